// A mission stepped from outside: the caller looks, reads the FOG, plans or makes its own path
// and executes it, in place of the built-in behaviour of RunMission. The robot, the maps, the
// end conditions and the report are the mission loop's own (the Python module's Mission).
#ifndef FOGNAV_SCENARIOS_MISSION_SESSION_H_
#define FOGNAV_SCENARIOS_MISSION_SESSION_H_

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "navigation/planner.h"
#include "perception/mapping.h"
#include "scenarios/mission.h"
#include "scenarios/params.h"
#include "scenarios/perception_cycle.h"
#include "scenarios/scenario.h"
#include "scenarios/views.h"

namespace fognav::scenarios {

class Behaviour;
namespace internal {
class MissionRobot;
struct MissionEnd;
}  // namespace internal

// One view the caller took: the stereo pair as rendered and what perception made of it.
struct SessionView {
  StereoView stereo;  // left, right, the renderer's depth and surfaces; X_WL the true camera
  ViewResult view;    // points (camera frame), planes, labelled points, X_GC (believed)
};

// What executing a path did.
struct SessionExecution {
  size_t blocked_at = 0;  // the first pose the body rules do not allow; path size if none
  size_t reached = 0;     // the index of the last pose executed to (0: none)
  int steps = 0;          // footsteps taken
  int collisions = 0;     // contacts that began
  bool ended = false;     // the mission ended during it (off the floor, or a collision)
};

class MissionSession {
 public:
  // The scenario's world with the robot at its start, its `params` and `seed` applied as
  // `fognav run` applies them; logs and pictures go to out_dir (created). Throws OutputError
  // if out_dir cannot be written, sim::SimError if the simulator cannot run.
  MissionSession(const Scenario& scenario, const std::string& out_dir);
  ~MissionSession();
  MissionSession(const MissionSession&) = delete;
  MissionSession& operator=(const MissionSession&) = delete;

  // The start sweep of views (StartSweep), each perceived into the maps.
  void LookAround();
  // Turns the head to (pan, tilt) (rad, the neck's angles) and perceives the view.
  SessionView Look(double pan, double tilt);
  // The FOG the built-in planner plans on (floor under the feet, walked cells marked).
  perception::Fog Fog() const;
  // The built-in planner from the believed pose in the robot's posture to `goal_G` (grid
  // frame; the scenario's goal if unset), as the mission plans (PlanToGoal).
  navigation::PlanResult Plan(const std::optional<Eigen::Vector2d>& goal_G = std::nullopt);
  // Executes `path` (path[0] the believed pose, then lattice poses with the moves that reach
  // them, as Plan gives) up to the first pose the planner's body rules do not allow on Fog(),
  // run by run (SegmentPath), stopping if the mission ends. One call is one cycle.
  SessionExecution Execute(const std::vector<navigation::PathPose>& path);

  // One cycle with the built-in behaviour, as RunMission runs it: the first call looks around
  // (the start of RunMission), every call first checks whether the mission has ended. Returns
  // false once it has (Done); stepping until then gives RunMission's mission and report.
  bool Step();

  perception::Pose2 BelievedPose() const;  // grid frame (odometry corrected by localization)
  perception::Pose2 TruePose() const;      // world frame
  double BelievedFloorZ() const;           // the floor under the robot, grid frame, metres
  navigation::Posture posture() const;
  // Whether the mission has ended (goal reached, off the floor, collision when the scenario
  // expects none, limits), or was reported.
  bool Done();
  // Ends the mission: scores it, writes the pictures and report.json into out_dir and
  // returns its outcome. Later calls return the same outcome.
  const MissionOutcome& Report();

  const Scenario& scenario() const { return scenario_; }
  const RunParams& params() const { return params_; }
  const navigation::PlannerParams& planner() const { return planner_; }
  int cycles() const;

 private:
  void CheckOpen() const;

  const Scenario scenario_;
  const RunParams params_;
  navigation::PlannerParams planner_;
  MissionOptions options_;
  std::unique_ptr<internal::MissionRobot> robot_;
  std::unique_ptr<internal::MissionEnd> end_;
  std::unique_ptr<Behaviour> behaviour_;  // made by the first Step
  bool ended_ = false;                    // Done() has been true: end_ holds the failure
  std::optional<MissionOutcome> outcome_;
};

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_MISSION_SESSION_H_

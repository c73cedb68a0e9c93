// The mission's behaviour: an explicit state and a decision step from that state and the latest
// FOG to the robot's next action. No simulator, renderer or controller here: the mission loop
// (scenarios/mission.cc) senses and acts, this decides. docs/behaviour.md lists the modes and
// the transitions.
#ifndef FOGNAV_SCENARIOS_BEHAVIOUR_H_
#define FOGNAV_SCENARIOS_BEHAVIOUR_H_

#include <cstddef>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "navigation/planner.h"
#include "perception/mapping.h"
#include "scenarios/params.h"

namespace fognav::scenarios {

// Where the mission ends: the goal's position (grid frame, metres) and how near counts as there.
struct MissionGoal {
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  double tolerance = 0.2;
};

// The robot's mode between cycles.
enum class Mode {
  kFollow,   // following plans to the goal, or toward it
  kExplore,  // going on past where the map window's way to the goal seemed to end
  kGoLook,   // going to a pose to look from (an inspection or a peek)
};

// What the robot does this cycle.
enum class Action {
  kFollow,      // execute Decision::run of Decision::plan
  kLookAround,  // the start sweep, then a look at the floor at Decision::peek_at if set
  kFreshLook,   // weaken the grid's evidence (ExecutionLimits::fresh_look_keep), look around
  kReplan,      // nothing: plan again next cycle (an exploration ended)
  kGiveUp,      // end the mission with no_path
};

struct Decision {
  Action action = Action::kFollow;
  const char* name = "follow";  // cycles.csv's decision column
  // the cycle's plan: the one followed, else the one the map gave
  navigation::PlanResult plan;
  navigation::PathSegment run;            // kFollow: the moves to execute, cut to about two strides
  std::optional<Eigen::Vector2d> target;  // where it explores or looks from, if it does
  std::optional<Eigen::Vector2d> peek_at;  // kLookAround: the floor to look at afterwards
  std::string failure_detail;              // kGiveUp: no_progress or the planner's reason
  // the map's own plan to the goal, for cycles.csv: goal, toward (a way short of it), here (no
  // move) or why there is none; its cost and length; the time it took (ms)
  const char* found = "";
  double found_cost = 0, found_length = 0, plan_ms = 0;
};

// Everything the behaviour remembers between cycles.
struct MissionState {
  double nearest_to_goal = std::numeric_limits<double>::infinity();  // believed, so far
  // exploring or going to look: until within `reach` of `target` or stalled (`stalls` cycles
  // without getting min_approach nearer than `best`)
  struct Exploration {
    Eigen::Vector2d target = Eigen::Vector2d::Zero();
    double reach = 0;
    bool to_look = false;  // an inspection or a peek: it looks around once there
    double best = 0;
    int stalls = 0;
  };
  std::optional<Exploration> explore;
  int explorations = 0;                    // begun so far (ExecutionLimits::max_explorations)
  std::optional<Eigen::Vector2d> peek_at;  // where to look at the floor at the next look around
  // believed positions of the last thrash_cycles cycles, each with nearest_to_goal then
  std::deque<std::pair<Eigen::Vector2d, double>> recent;
  // the last thrash_cycles poses come to by moving, each with nearest_to_goal then
  std::deque<std::pair<perception::Pose2, double>> arrivals;
  int thrashes = 0;  // times it went back and forth
  std::optional<perception::Pose2> fresh_at;  // where the grid was last weakened
  perception::Pose2 looked_at;                // where it last looked around
  bool just_looked = true;                    // no move since it looked around
  // crawling with no way on, it chose to get up under headroom not seen: until it stands again
  bool getting_up_unseen = false;
  navigation::PlanResult last_plan;  // the plan last followed and the pose its run ended at
  size_t last_plan_at = 0;
};

class Behaviour {
 public:
  // `planner` as the mission's planner runs (its goal_tolerance is the one plans aim at);
  // the robot has just looked around at `start`.
  Behaviour(const MissionGoal& goal, const navigation::PlannerParams& planner,
            const ExecutionLimits& limits, const perception::Pose2& start);

  // One decision on `fog` (walked cells and the floor under the feet marked) and `maps` (their
  // obstacle ranges) from the believed pose in the given posture. Updates the state for the
  // decision's action (a look around counts as done).
  Decision Decide(const perception::Fog& fog, const perception::MapState& maps,
                  const perception::Pose2& believed, navigation::Posture posture);
  // After a kFollow: the robot executed decision.plan up to path[reached].
  void Moved(const navigation::PlanResult& plan, size_t reached);
  // The robot looked around at `at` by itself (it moved into cells it had not seen).
  void LookedAround(const perception::Pose2& at);

  const MissionState& state() const { return state_; }
  MissionState& mutable_state() { return state_; }
  Mode mode() const;
  // The planner's parameters as the behaviour uses them now.
  navigation::PlannerParams planner() const;

 private:
  bool NoteArrival(const perception::Pose2& believed, double resolution);
  void KeepLastPlan(const perception::Fog& fog, const perception::Pose2& believed,
                    navigation::Posture posture, const navigation::PlannerParams& used,
                    navigation::PlanResult* plan) const;
  bool ExplorationEnds(const Eigen::Vector2d& position, Decision* d);
  Decision WhenBlocked(const perception::Fog& fog, const perception::MapState& maps,
                       const perception::Pose2& believed, navigation::Posture posture,
                       Decision d);
  bool FindLookout(const perception::Fog& fog, const perception::MapState& maps,
                   const perception::Pose2& believed, navigation::Posture posture,
                   navigation::PlanResult* toward, const char** why);
  bool BackOff(const perception::Fog& fog, const perception::Pose2& believed,
               navigation::Posture posture, navigation::PlanResult* toward, const char** why);
  void StartExploring(const Eigen::Vector2d& target, double reach, bool to_look,
                      const Eigen::Vector2d& from);
  Decision LookAround(const char* name, const perception::Pose2& at, Decision d);
  Decision Follow(const char* name, navigation::PlanResult plan, Decision d) const;
  bool LeadsNearer(const navigation::PlanResult& p, const Eigen::Vector2d& target,
                   double distance) const;

  MissionGoal goal_;
  navigation::PlannerParams planner_;
  ExecutionLimits limits_;
  MissionState state_;
};

// Plans to within planner.goal_tolerance; where no pose lies that near (a goal at the foot of a
// wall), to any pose within the goal's tolerance, with half a cell to spare for the cell
// centres. `used` gets the parameters of the plan returned.
navigation::PlanResult PlanToGoal(const perception::Fog& fog, const perception::Pose2& start,
                                  const MissionGoal& goal,
                                  const navigation::PlannerParams& planner,
                                  navigation::Posture posture,
                                  navigation::PlannerParams* used = nullptr);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_BEHAVIOUR_H_

// The robot of a mission as the loop senses and acts with it: the MuJoCo world, the stepping
// controller, the head's renderer, the maps built from its views, and the logs of what it did.
#ifndef FOGNAV_SCENARIOS_INTERNAL_MISSION_ROBOT_H_
#define FOGNAV_SCENARIOS_INTERNAL_MISSION_ROBOT_H_

#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "navigation/planner.h"
#include "perception/localization.h"
#include "perception/mapping.h"
#include "perception/step_edge.h"
#include "scenarios/mission.h"
#include "scenarios/params.h"
#include "scenarios/perception_cycle.h"
#include "scenarios/video.h"
#include "sim/controller.h"
#include "sim/render.h"
#include "sim/world.h"

namespace fognav::scenarios::internal {

// The measured edge of a step ahead (grid frame): a point on it, the heading it was measured
// along, and the two levels.
struct StepEdge {
  Eigen::Vector2d point_G = Eigen::Vector2d::Zero();
  double yaw = 0;
  double floor_z = 0, target_z = 0;
  // distance along `yaw` from `from` to the edge, if the edge is the one between these levels
  // (within h_floor) and was measured along about this heading; NaN otherwise
  double Ahead(const perception::Pose2& from, double from_z, double to_z, double h_floor) const;
};

class MissionRobot {
 public:
  // The world of `scenario` with the robot at its start; `planner` as the mission plans
  // (its kneel offset and step limits are set from the controller's).
  MissionRobot(const Scenario& scenario, const RunParams& params, const MissionOptions& options,
               navigation::PlannerParams* planner);

  perception::Pose2 believed() const;
  double believed_floor_z() const { return believed_floor_z_; }
  navigation::Posture posture() const;
  double TrueGoalDistance() const;
  // what the robot stands on (soles; knees and hands crawling) beyond the edge of the floor:
  // "right sole at (x, y) beyond the floor's edge", or empty
  std::string SupportOffFloor() const;
  const std::vector<sim::Collision>& collisions() const { return controller_.collisions(); }
  int steps() const { return controller_.steps(); }

  // The FOG for planning: the maps' FOG with the floor under the standing feet and the cells
  // walked on marked.
  perception::Fog PlanningFog() const;
  const perception::MapState& maps() const { return maps_; }
  // Weakens the grid's evidence to `keep` of its log-odds (a fresh look follows).
  void FadeGrid(double keep);

  void LookAround();
  // turns the head to `view` and perceives
  void Look(const sim::HeadAngles& view);
  // a look at the floor at `target`, floor_z high, the head panned toward it as far as it turns
  void LookAtFloor(const Eigen::Vector2d& target, double floor_z);
  // Executes `run` of `plan` (believed pose `from`, `fog` the plan's map); returns the index of
  // the path pose it went to (past run.last where a walk up to a step took the step at once).
  size_t Execute(const navigation::PlanResult& plan, const navigation::PathSegment& run,
                 const perception::Fog& fog);
  // After a move: looks where the plan goes, measures the step edges ahead on `plan` from
  // path[reached] on; crawling unsure of the heading, looks to both sides. Where the run's end
  // lay in cells never seen and the robot is 0.5 m from `looked_at`, it also looks around, and
  // returns where it believed it was then.
  std::optional<perception::Pose2> LookAfterMove(const navigation::PlanResult& plan, const navigation::PathSegment& run,
                     size_t reached, const perception::Fog& fog,
                     const perception::Pose2& looked_at);

  // the logs: a cycles.csv row, and flushing both logs (OutputError if the disk is full)
  void LogCycle(const std::string& row);
  void FlushLogs();
  void CloseLogs();
  const std::string& move() const { return current_move_; }  // the last move commanded
  void set_cycle(int cycle) { cycle_ = cycle; }  // for the looks' order and the video
  // the video's plan panel (drawn only when a video is made)
  void ShowPlan(const perception::Fog& fog, const navigation::PlanResult& plan);
  void NoteTiming(const char* stage, double ms) { timing_[stage].push_back(ms); }
  // frames/ and maps/ pictures of this cycle, the plan drawn from `from`
  void WriteCycleFrames(const std::string& name, const perception::Fog& fog,
                        const perception::Pose2& from, const navigation::PlanResult& plan);

  // what the report needs
  const sim::Controller& controller() const { return controller_; }
  perception::Pose2 TruePose() const;
  const std::map<std::string, int>& actions() const { return actions_; }
  const std::map<std::string, std::vector<double>>& timing() const { return timing_; }
  double path_length() const { return path_length_; }
  const StereoView& last_stereo() const { return last_stereo_; }
  // the believed pose's error at each settled footstep: position (m), heading (rad), and the
  // path walked by then (m)
  struct PoseError {
    double position = 0, yaw = 0, walked = 0;
  };
  const std::vector<PoseError>& settled_errors() const { return settled_errors_; }
  const perception::LocalizationState& localization() const { return localization_; }
  const ViewResult& last_view() const { return last_view_; }

 private:
  void OnTick();
  void NoteWalked(const perception::Pose2& at);  // Fog::walked: the standing footprint at `at`
  void RunController();
  void Predict();
  Eigen::Matrix3d IncrementCovariance(const perception::Pose2& before,
                                      const perception::Pose2& after, int steps) const;
  void Perceive();
  sim::HeadAngles HeadAtElevation(double pan, double wanted_elevation) const;
  void LookUpBeforeCrawling(const navigation::PlanResult& plan, size_t first);
  void AddVideoFrame();
  double EdgeAhead(const perception::Pose2& from, double from_z, double to_z, double reach) const;
  template <typename Which>
  void ForgetEdges(Which which);
  bool MeasureEdge(const navigation::PlanResult& plan, size_t j, const perception::Pose2& now);
  void MeasureEdges(const navigation::PlanResult& plan, size_t reached);
  void StepOnto(const perception::Pose2& from, double from_z, const navigation::PathPose& onto,
                double dx_plan, double dy_plan);
  void WalkUpTo(const navigation::PlanResult& plan, const navigation::PathSegment& run,
                size_t* reached);

  const Scenario& scenario_;
  const MissionOptions& options_;
  const PerceptionParams& perception_;
  const ExecutionLimits& limits_;
  const perception::StepEdgeParams& edge_params_;
  const navigation::PlannerParams& planner_;
  // the logs come first: a folder that cannot take them fails before the simulator starts
  std::ofstream trajectory_, cycles_;
  sim::ControllerParams controller_params_;
  sim::World world_;
  sim::Controller controller_;
  sim::Renderer renderer_;
  const sim::Humanoid& humanoid_;

  perception::MapState maps_;
  perception::LocalizationState localization_;
  perception::Pose2 predicted_from_;  // the believed pose the filter last predicted to
  int predicted_steps_ = 0;           // the footsteps then
  Eigen::Matrix3d step_covariance_;  // the odometry's noise: the covariance one footstep adds
  double believed_floor_z_ = 0;      // odometry: the sum of the commanded rises
  std::vector<StepEdge> edges_;      // of the next steps up or down on the plan, measured
  double step_reach_ = 0;            // a step's edge lies within this of the pose before it
  std::set<std::pair<int, int>> walked_;  // global cells the standing robot covered

  std::map<std::string, int> actions_;
  std::map<std::string, std::vector<double>> timing_;
  double path_length_ = 0;
  std::vector<PoseError> settled_errors_;
  perception::Pose2 last_true_;
  std::string current_move_ = "look";
  int last_step_logged_ = 0;
  int cycle_ = 0;
  std::unique_ptr<MissionVideo> video_;
  int video_every_ = 1;
  perception::RgbImage video_plan_picture_;
  StereoView last_stereo_;
  ViewResult last_view_;
};

}  // namespace fognav::scenarios::internal

#endif  // FOGNAV_SCENARIOS_INTERNAL_MISSION_ROBOT_H_

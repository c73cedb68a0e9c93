#include "scenarios/mission_session.h"

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "scenarios/behaviour.h"
#include "scenarios/internal/mission_loop.h"
#include "scenarios/internal/mission_robot.h"
#include "scenarios/output.h"

namespace fognav::scenarios {
namespace {

namespace nav = navigation;
using Clock = std::chrono::steady_clock;

// the planner as the mission runs it: plans aim at half the goal's tolerance
nav::PlannerParams MissionPlanner(const Scenario& scenario, const RunParams& params) {
  nav::PlannerParams p = params.planner;
  p.goal_tolerance = 0.5 * scenario.goal_tolerance;
  return p;
}

MissionOptions SessionOptions(const std::string& out_dir) {
  MissionOptions options;
  options.out_dir = out_dir;
  options.quiet = true;
  return options;
}

}  // namespace

MissionSession::MissionSession(const Scenario& scenario, const std::string& out_dir)
    : scenario_(scenario),
      params_(ResolveParams(scenario.params)),
      planner_(MissionPlanner(scenario, params_)),
      options_(SessionOptions(out_dir)),
      end_(std::make_unique<internal::MissionEnd>()) {
  end_->wall_start = Clock::now();
  MakeOutputFolder(out_dir);
  std::error_code error;
  std::filesystem::remove(out_dir + "/report.json", error);
  robot_ = std::make_unique<internal::MissionRobot>(scenario_, params_, options_, &planner_);
}

MissionSession::~MissionSession() = default;

void MissionSession::CheckOpen() const {
  if (outcome_) throw std::logic_error("the mission has ended: its report was made");
}

void MissionSession::LookAround() {
  CheckOpen();
  robot_->LookAround();
}

SessionView MissionSession::Look(double pan, double tilt) {
  CheckOpen();
  robot_->Look({pan, tilt});
  return {robot_->last_stereo(), robot_->last_view()};
}

perception::Fog MissionSession::Fog() const { return robot_->PlanningFog(); }

nav::PlanResult MissionSession::Plan(const std::optional<Eigen::Vector2d>& goal_G) {
  const auto start = Clock::now();
  const MissionGoal goal{goal_G.value_or(scenario_.goal), scenario_.goal_tolerance};
  nav::PlanResult plan =
      PlanToGoal(robot_->PlanningFog(), robot_->believed(), goal, planner_, robot_->posture());
  robot_->NoteTiming("planning",
                     std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  return plan;
}

SessionExecution MissionSession::Execute(const std::vector<nav::PathPose>& path) {
  CheckOpen();
  robot_->set_cycle(++end_->cycles);
  SessionExecution result;
  const int steps_before = robot_->steps();
  const size_t collisions_before = robot_->collisions().size();
  const perception::Fog fog = robot_->PlanningFog();
  nav::PlanResult plan;
  plan.status = nav::PlanStatus::kOk;
  plan.path = path;
  plan.reaches_goal = false;
  result.blocked_at =
      path.size() < 2 ? path.size() : nav::FirstBlockedPose(fog, plan, scenario_.goal, planner_);
  plan.path.resize(result.blocked_at);
  end_->plan = plan;
  std::string failure, detail;
  for (const nav::PathSegment& run : nav::SegmentPath(plan)) {
    result.reached = robot_->Execute(plan, run, fog);
    if (!robot_->SupportOffFloor().empty() || robot_->collisions().size() > collisions_before) {
      result.ended = internal::MissionEnds(scenario_, options_, *robot_, 0, &failure, &detail);
      if (result.ended) break;
    }
  }
  result.steps = robot_->steps() - steps_before;
  result.collisions = int(robot_->collisions().size() - collisions_before);
  robot_->FlushLogs();
  return result;
}

perception::Pose2 MissionSession::BelievedPose() const { return robot_->believed(); }
perception::Pose2 MissionSession::TruePose() const { return robot_->TruePose(); }
double MissionSession::BelievedFloorZ() const { return robot_->believed_floor_z(); }
nav::Posture MissionSession::posture() const { return robot_->posture(); }
int MissionSession::cycles() const { return end_->cycles; }

bool MissionSession::Done() {
  if (outcome_) return true;
  if (!ended_) {
    ended_ = internal::MissionEnds(scenario_, options_, *robot_, end_->cycles, &end_->failure,
                                   &end_->failure_detail);
  }
  return ended_;
}

bool MissionSession::Step() {
  if (outcome_) return false;
  if (!behaviour_) {
    robot_->LookAround();
    behaviour_ = std::make_unique<Behaviour>(MissionGoal{scenario_.goal, scenario_.goal_tolerance},
                                             planner_, params_.mission, robot_->believed());
  }
  if (Done()) return false;
  if (internal::RunCycle(options_, params_, *robot_, *behaviour_, end_.get()) ==
      internal::CycleEnd::kGaveUp) {
    ended_ = true;
    return false;
  }
  return true;
}

const MissionOutcome& MissionSession::Report() {
  if (!outcome_) {
    Done();  // sets the failure, if any
    robot_->FlushLogs();
    outcome_ = internal::Report(scenario_, options_, params_, planner_, *robot_, *end_);
  }
  return *outcome_;
}

}  // namespace fognav::scenarios

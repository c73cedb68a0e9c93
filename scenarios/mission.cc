#include "scenarios/mission.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "navigation/planner.h"
#include "scenarios/behaviour.h"
#include "scenarios/internal/mission_loop.h"
#include "scenarios/internal/mission_robot.h"
#include "scenarios/output.h"
#include "scenarios/params.h"
#include "scenarios/perception_cycle.h"
#include "scenarios/views.h"
#include "viz/pages.h"
#include "viz/pictures.h"

namespace fognav::scenarios {
namespace {

using Clock = std::chrono::steady_clock;
namespace nav = navigation;
using internal::MissionRobot;

double Ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// cycles.csv's row: where the robot believed it was, what the planner found there, what the
// behaviour decided (a target: where it went to explore or look from), and the explorations and
// times it went back and forth so far, after the decision
std::string CycleRow(int cycle, int step, const perception::Pose2& believed, nav::Posture posture,
                     const Decision& d, const MissionState& state) {
  char target[64] = ",";
  if (d.target) std::snprintf(target, sizeof(target), "%.5f,%.5f", d.target->x(), d.target->y());
  char row[384];
  std::snprintf(row, sizeof(row), "%d,%d,%.5f,%.5f,%.5f,%s,%s,%.4f,%.4f,%s,%s,%d,%d\n", cycle,
                step, believed.x, believed.y, believed.yaw, nav::PostureName(posture), d.found,
                d.found_cost, d.found_length, d.name, target, state.explorations, state.thrashes);
  return row;
}

}  // namespace

namespace internal {

bool MissionEnds(const Scenario& scenario, const MissionOptions& options,
                 const MissionRobot& robot, int cycle, std::string* failure,
                 std::string* detail) {
  if (const std::string off = robot.SupportOffFloor(); !off.empty()) {
    *failure = "off_floor";
    *detail = off;
  } else if (robot.TrueGoalDistance() <= scenario.goal_tolerance) {
    return true;
  } else if (scenario.expect.no_collision.value_or(false) && !robot.collisions().empty()) {
    const sim::Collision& c = robot.collisions().front();
    *failure = "collision";
    *detail = c.robot_name + " hit " + c.world_name;
  } else if (cycle >= scenario.max_cycles || robot.steps() >= scenario.max_steps) {
    *failure = "timeout";
  } else if (options.stop && options.stop->load()) {
    *failure = "interrupted";
  }
  return !failure->empty();
}

}  // namespace internal

namespace {

// Whether the mission met the scenario's expectations.
bool MetExpectations(const Expectations& expect, const MissionRobot& robot, bool reached_goal,
                     const std::string& failure) {
  bool success = true;
  if (expect.reach_goal && *expect.reach_goal != reached_goal) success = false;
  for (const auto& action : expect.actions_used) success = success && robot.actions().at(action) > 0;
  if (expect.no_collision.value_or(false) && !robot.collisions().empty()) success = false;
  // reach_goal: false alone expects the mission to end short of the goal, whatever the failure;
  // `failure` names the one it must end with; an interrupted mission never succeeds
  if (expect.failure) {
    success = success && failure == *expect.failure;
  } else if (!failure.empty() && expect.reach_goal.value_or(true) &&
             !(failure == "collision" && !expect.no_collision.value_or(false))) {
    success = false;
  }
  return success && failure != "interrupted";
}

// The ground-truth FOG of the whole floor.
perception::Fog WorldFog(const Scenario& scenario, const PerceptionParams& params) {
  perception::GridWindow whole;
  whole.resolution = params.map.grid.resolution;
  const Eigen::Vector2d lo = scenario.floor_center - scenario.floor_size / 2;
  whole.origin_ix = int(std::floor(lo.x() / whole.resolution)) - 2;
  whole.origin_iy = int(std::floor(lo.y() / whole.resolution)) - 2;
  whole.size_x = int(std::ceil(scenario.floor_size.x() / whole.resolution)) + 4;
  whole.size_y = int(std::ceil(scenario.floor_size.y() / whole.resolution)) + 4;
  return TruthFog(scenario, whole, params.map.fog);
}

}  // namespace

namespace internal {

MissionOutcome Report(const Scenario& scenario, const MissionOptions& options,
                      const RunParams& run_params, const nav::PlannerParams& planner,
                      MissionRobot& robot, const MissionEnd& end) {
  const std::string& out = options.out_dir;
  const PerceptionParams& perception_params = run_params.perception;
  const double goal_distance = robot.TrueGoalDistance();
  const bool reached_goal = goal_distance <= scenario.goal_tolerance;
  const perception::Pose2 believed = robot.believed();
  const perception::Pose2 truth_pose = robot.TruePose();
  const Eigen::Isometry3d X_GW =
      perception::Planar(believed) * perception::Planar(truth_pose).inverse();
  const perception::Fog fog = perception::ComputeFog(perception_params.map, robot.maps());
  const perception::Fog truth_fog = TruthFog(scenario, fog.window, perception_params.map.fog, X_GW);
  const perception::FogScore fog_score =
      perception::ScoreFog(fog, truth_fog, perception_params.map.fog);
  // the planner's path on the ground-truth FOG of the whole floor, for SPL
  const perception::Fog world_fog = WorldFog(scenario, perception_params);
  const nav::PlanResult optimal = PlanToGoal(world_fog, scenario.start,
                                             {scenario.goal, scenario.goal_tolerance}, planner,
                                             nav::Posture::kUpright);
  const double optimal_length =
      optimal.status == nav::PlanStatus::kOk && optimal.reaches_goal ? optimal.length : 0.0;
  const double spl = reached_goal && optimal_length > 0
                         ? optimal_length / std::max(robot.path_length(), optimal_length)
                         : 0.0;

  // pictures of the end state
  MakeOutputFolder(out + "/frames");
  WriteViewFrames(robot.last_stereo(), robot.last_view(), out + "/frames", "final");
  viz::WriteMapPictures(out + "/maps", fog, robot.maps(), perception_params.map, believed);
  WritePng(viz::DrawPlanPicture(fog, believed, end.plan, scenario.goal),
           out + "/maps/final_plan.png");
  WritePng(viz::DrawFog(truth_fog, believed), out + "/maps/fog_truth.png");
  WritePng(viz::DrawFogErrors(fog, truth_fog, perception_params.map.fog, believed),
           out + "/maps/fog_errors.png");
  viz::WriteFogTypes(out + "/maps/fog_truth_types.png", truth_fog);
  WritePng(viz::DrawPlanPicture(world_fog, scenario.start, optimal, scenario.goal),
           out + "/maps/optimal_plan.png");

  nlohmann::json collisions = nlohmann::json::array();
  for (const sim::Collision& c : robot.collisions()) {
    collisions.push_back({{"tick", c.tick}, {"robot", c.robot_name}, {"world", c.world_name},
                          {"depth", c.depth}});
  }
  nlohmann::json timing_ms = nlohmann::json::object();
  auto samples = [&](const char* stage) {
    const auto it = robot.timing().find(stage);
    return it == robot.timing().end() ? std::vector<double>{} : it->second;
  };
  for (const char* stage : {"render", "stereo", "segmentation", "mapping", "planning", "control"}) {
    timing_ms[stage] = perception::Median(samples(stage));
  }
  // the slow plans: the planning stage's 95th percentile (nearest rank) and maximum
  std::vector<double> plan_ms = samples("planning");
  std::sort(plan_ms.begin(), plan_ms.end());
  timing_ms["planning_p95"] =
      plan_ms.empty() ? 0.0 : plan_ms[size_t(std::ceil(0.95 * double(plan_ms.size()))) - 1];
  timing_ms["planning_max"] = plan_ms.empty() ? 0.0 : plan_ms.back();
  // the believed pose against the truth at settled footsteps (docs/localization.md)
  std::vector<double> position_errors, yaw_errors;
  for (const auto& e : robot.settled_errors()) {
    position_errors.push_back(e.position);
    yaw_errors.push_back(e.yaw);
  }
  auto spread = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const auto rank = [&](double q) { return v.empty() ? 0.0 : v[size_t(std::ceil(q * double(v.size()))) - 1]; };
    return nlohmann::json{{"median", perception::Median(v)}, {"p95", rank(0.95)},
                          {"max", v.empty() ? 0.0 : v.back()}};
  };
  const auto& settled = robot.settled_errors();
  const double drift = settled.empty() || settled.back().walked <= 0
                           ? 0.0
                           : settled.back().position / settled.back().walked;
  const perception::VisualOdometryState& vo = robot.localization().visual;
  const nlohmann::json localization = {
      {"mode", FormatParamValue(*FindParam("localization.mode"),
                                double(run_params.perception.localization.mode))},
      {"position_error", spread(position_errors)},
      {"yaw_error", spread(yaw_errors)},
      {"settled_footsteps", settled.size()},
      {"drift_per_m", drift},
      {"visual_views", vo.views},
      {"visual_tracked", vo.views == 0 ? 0.0 : double(vo.tracked) / double(vo.views)},
      {"visual_outcomes", vo.outcomes},
      {"keyframes", vo.keyframes.size()}};
  timing_ms["localization"] = perception::Median(samples("localization"));
  auto null_if_empty = [](const std::string& s) {
    return s.empty() ? nlohmann::json(nullptr) : nlohmann::json(s);
  };
  MissionOutcome outcome;
  outcome.success = MetExpectations(scenario.expect, robot, reached_goal, end.failure);
  outcome.reached_goal = reached_goal;
  outcome.failure = end.failure;
  const nlohmann::json report = {
      {"scenario", scenario.name},
      {"success", outcome.success},
      {"reached_goal", reached_goal},
      {"goal_distance", goal_distance},
      {"failure", null_if_empty(end.failure)},
      {"failure_detail", null_if_empty(end.failure_detail)},
      {"cycles", end.cycles},
      {"steps", robot.steps()},
      {"actions", robot.actions()},
      {"collisions", robot.collisions().size()},
      {"collision_list", collisions},
      {"path_length", robot.path_length()},
      {"optimal_path_length", optimal_length},
      {"spl", spl},
      {"fog", FogScoreJson(fog_score)},
      {"fog_accuracy", fog_score.accuracy},
      {"floor_height_error",
       {{"median", fog_score.height_error_median}, {"max", fog_score.height_error_max}}},
      {"final_pose", {{"true", {truth_pose.x, truth_pose.y, truth_pose.yaw}},
                      {"odometry", {believed.x, believed.y, believed.yaw}}}},
      {"localization", localization},
      {"wall_time_s", Ms(end.wall_start) / 1000},
      {"timing_ms", timing_ms},
      {"params", ParamsJson(run_params)}};
  outcome.report_json = report.dump(2);
  WriteFileAtomically(out + "/report.json", outcome.report_json + "\n");
  // the page reads the tables back: they must be complete
  robot.CloseLogs();
  viz::WriteMissionPage(out, world_fog, optimal, scenario.start, scenario.goal,
                        options.video_path);
  return outcome;
}

CycleEnd RunCycle(const MissionOptions& options, const RunParams& run_params,
                  MissionRobot& robot, Behaviour& behaviour, MissionEnd* end) {
  robot.set_cycle(++end->cycles);
  const perception::Pose2 believed = robot.believed();
  const perception::Fog fog = robot.PlanningFog();
  const nav::Posture posture = robot.posture();
  const Decision decision = behaviour.Decide(fog, robot.maps(), believed, posture);
  robot.NoteTiming("planning", decision.plan_ms);
  end->plan = decision.plan;
  robot.ShowPlan(fog, end->plan);
  robot.LogCycle(
      CycleRow(end->cycles, robot.steps(), believed, posture, decision, behaviour.state()));
  if (decision.action == Action::kGiveUp) {
    end->failure = "no_path";
    end->failure_detail = decision.failure_detail;
    return CycleEnd::kGaveUp;
  }
  if (decision.action == Action::kFreshLook) robot.FadeGrid(run_params.mission.fresh_look_keep);
  if (decision.action == Action::kFreshLook || decision.action == Action::kLookAround) {
    robot.LookAround();
    if (decision.peek_at) robot.LookAtFloor(*decision.peek_at, robot.believed_floor_z());
  }
  if (decision.action != Action::kFollow) return CycleEnd::kLooked;

  const size_t reached = robot.Execute(end->plan, decision.run, fog);
  behaviour.Moved(end->plan, reached);
  if (const auto looked = robot.LookAfterMove(end->plan, decision.run, reached, fog,
                                              behaviour.state().looked_at)) {
    behaviour.LookedAround(*looked);
  }
  if (options.dump_every > 0 && end->cycles % options.dump_every == 0) {
    char name[32];
    std::snprintf(name, sizeof(name), "cycle%04d", end->cycles);
    robot.WriteCycleFrames(name, fog, believed, end->plan);
  }
  return CycleEnd::kMoved;
}

}  // namespace internal

using internal::CycleEnd;
using internal::MissionEnd;
using internal::MissionEnds;
using internal::Report;
using internal::RunCycle;

// The loop: sense (the robot's views update its maps), decide (Behaviour), act (the robot
// executes the decision), log (RunCycle); until the mission ends (MissionEnds).
MissionOutcome RunMission(const Scenario& scenario, const MissionOptions& options) {
  MissionEnd end;
  end.wall_start = Clock::now();
  MakeOutputFolder(options.out_dir);
  // a report left from an earlier run must not pass for this run's
  std::error_code error;
  std::filesystem::remove(options.out_dir + "/report.json", error);
  const RunParams run_params = ResolveParams(scenario.params);
  nav::PlannerParams planner = run_params.planner;
  // plan to within half the tolerance, so the robot ends inside it despite odometry and cells
  planner.goal_tolerance = 0.5 * scenario.goal_tolerance;
  MissionRobot robot(scenario, run_params, options, &planner);
  const bool progress = !options.quiet && isatty(STDERR_FILENO);

  robot.LookAround();
  Behaviour behaviour({scenario.goal, scenario.goal_tolerance}, planner, run_params.mission,
                      robot.believed());
  while (!MissionEnds(scenario, options, robot, end.cycles, &end.failure, &end.failure_detail)) {
    const CycleEnd cycle = RunCycle(options, run_params, robot, behaviour, &end);
    if (cycle == CycleEnd::kGaveUp) break;
    if (progress && cycle == CycleEnd::kMoved) {
      std::fprintf(stderr, "\rcycle %4d  goal %5.2f m  %-11s  %6.1f s", end.cycles,
                   robot.TrueGoalDistance(), robot.move().c_str(),
                   Ms(end.wall_start) / 1000);
    }
  }
  robot.FlushLogs();
  if (progress) std::fprintf(stderr, "\n");
  return Report(scenario, options, run_params, planner, robot, end);
}

}  // namespace fognav::scenarios

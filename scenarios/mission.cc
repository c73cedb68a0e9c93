#include "scenarios/mission.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "navigation/planner.h"
#include "perception/step_edge.h"
#include "scenarios/output.h"
#include "scenarios/params.h"
#include "scenarios/perception_cycle.h"
#include "scenarios/video.h"
#include "sim/controller.h"
#include "viz/pages.h"
#include "viz/pictures.h"

namespace fognav::scenarios {
namespace {

using Clock = std::chrono::steady_clock;
namespace nav = navigation;

double Ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

// displacement (dx, dy in the frame of `from`, dyaw) from one planar pose to another
Eigen::Vector3d Relative(const perception::Pose2& from, const perception::Pose2& to) {
  double c = std::cos(from.yaw), s = std::sin(from.yaw);
  double dx = to.x - from.x, dy = to.y - from.y;
  return {c * dx + s * dy, -s * dx + c * dy, WrapAngle(to.yaw - from.yaw)};
}

perception::Pose2 ToPerception(const sim::Pose2& p) { return {p.x, p.y, p.yaw}; }

// The measured edge of a step ahead (grid frame): a point on it, the heading it was measured
// along, and the two levels.
struct StepEdge {
  Eigen::Vector2d point_G = Eigen::Vector2d::Zero();
  double yaw = 0;
  double floor_z = 0, target_z = 0;
  // distance along `yaw` from `from` to the edge, if the edge is the one between these levels
  // (within h_floor) and was measured along about this heading; NaN otherwise
  double Ahead(const perception::Pose2& from, double from_z, double to_z, double h_floor) const {
    if (!(std::abs(from_z - floor_z) <= h_floor && std::abs(to_z - target_z) <= h_floor &&
          std::abs(WrapAngle(from.yaw - yaw)) <= 0.2)) {
      return std::numeric_limits<double>::quiet_NaN();
    }
    const Eigen::Vector2d d = point_G - Eigen::Vector2d(from.x, from.y);
    const Eigen::Vector2d along(std::cos(from.yaw), std::sin(from.yaw));
    if (std::abs(along.x() * d.y() - along.y() * d.x()) > 0.2) {
      return std::numeric_limits<double>::quiet_NaN();
    }
    return along.dot(d);
  }
};

// head views of the cycles while moving: ahead and to both sides of the path, near and far
const std::vector<sim::HeadAngles> kCycleViews = {
    {0.0, 0.75}, {0.45, 0.6}, {0.0, 0.4}, {-0.45, 0.6}, {0.0, 0.15}};
// while crawling: the camera's elevation above the horizon (rad), up to see an underside
// overhead (0.3 is about the neck's limit in the crawl posture; the head's top is then at
// 0.30 m, the lowest ceiling of a tunnel), down to see the floor ahead
const std::vector<double> kCrawlElevations = {0.3, -0.6};

// Whether a tunnel cell within `range` of `at` has its ceiling at least `height` above floor_z.
bool HighCeilingNear(const perception::Fog& fog, const perception::Pose2& at, double floor_z,
                     double range, double height) {
  const perception::GridWindow& w = fog.window;
  if (fog.ceiling.size() != fog.type.size()) return false;
  int ix0, iy0, ix1, iy1;
  w.CellOf(at.x - range, at.y - range, &ix0, &iy0);
  w.CellOf(at.x + range, at.y + range, &ix1, &iy1);
  for (int iy = std::max(0, iy0); iy <= std::min(w.size_y - 1, iy1); ++iy) {
    for (int ix = std::max(0, ix0); ix <= std::min(w.size_x - 1, ix1); ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      if (fog.type[i] != perception::CellType::kTunnel || fog.ceiling[i] - floor_z < height) {
        continue;
      }
      const Eigen::Vector2d c = w.CellCenter(ix, iy);
      if (std::hypot(c.x() - at.x, c.y() - at.y) <= range) return true;
    }
  }
  return false;
}

// Whether a pose of path[first..] within `range` of `at` (up to the first beyond it) lies on an
// unknown cell or outside the window.
bool UnknownAhead(const perception::Fog& fog, const nav::PlanResult& plan, size_t first,
                  const perception::Pose2& at, double range) {
  for (size_t k = first; k < plan.path.size(); ++k) {
    const perception::Pose2& q = plan.path[k].pose_G;
    if (std::hypot(q.x - at.x, q.y - at.y) > range) break;
    int ix, iy;
    fog.window.CellOf(q.x, q.y, &ix, &iy);
    if (!fog.window.Contains(ix, iy) || fog.TypeAt(ix, iy) == perception::CellType::kUnknown) {
      return true;
    }
  }
  return false;
}

// The pan (relative to `from`'s heading) toward the first pose of path[first..] that lies
// `ahead` or farther from `from`, among those that `take` accepts (up to the first it rejects);
// the last accepted pose if none lies so far, 0 if none is accepted.
template <typename Take>
double PanToward(const nav::PlanResult& plan, size_t first, const perception::Pose2& from,
                 double ahead, Take take) {
  double pan = 0;
  for (size_t k = first; k < plan.path.size() && take(plan.path[k]); ++k) {
    const perception::Pose2& q = plan.path[k].pose_G;
    const double d = std::hypot(q.x - from.x, q.y - from.y);
    if (d < 0.01) continue;
    pan = WrapAngle(std::atan2(q.y - from.y, q.x - from.x) - from.yaw);
    if (d >= ahead) break;
  }
  return pan;
}

// Calls fn(gx, gy) for each global grid cell (indices at `resolution`) whose centre lies in the
// rectangle centred on `robot` that reaches `along` either way on its heading and `across` to
// either side.
template <typename Fn>
void ForCellsUnder(const perception::Pose2& robot, double along, double across,
                   double resolution, Fn fn) {
  const double c = std::cos(robot.yaw), s = std::sin(robot.yaw);
  const double reach = std::hypot(along, across);
  const int ix0 = int(std::floor((robot.x - reach) / resolution));
  const int iy0 = int(std::floor((robot.y - reach) / resolution));
  const int ix1 = int(std::floor((robot.x + reach) / resolution));
  const int iy1 = int(std::floor((robot.y + reach) / resolution));
  for (int iy = iy0; iy <= iy1; ++iy) {
    for (int ix = ix0; ix <= ix1; ++ix) {
      const double dx = (ix + 0.5) * resolution - robot.x, dy = (iy + 0.5) * resolution - robot.y;
      if (std::abs(c * dx + s * dy) <= along && std::abs(-s * dx + c * dy) <= across) fn(ix, iy);
    }
  }
}

// The global grid cells (indices at `resolution`) that the standing robot covers at `robot`
// (Fog::walked): those whose centres lie in its footprint, the depth along the heading by the
// shoulders' width across, without the planner's margin.
void AddWalkedCells(const nav::PlannerParams& p, const perception::Pose2& robot, double resolution,
                    std::set<std::pair<int, int>>* walked) {
  ForCellsUnder(robot, 0.5 * p.depth, 0.5 * p.shoulder_width, resolution,
                [&](int gx, int gy) { walked->insert({gx, gy}); });
}

// Fog::walked for the window from the global cells the standing robot covered
void MarkWalked(const std::set<std::pair<int, int>>& walked, perception::Fog* fog) {
  const perception::GridWindow& w = fog->window;
  fog->walked.assign(size_t(w.NumCells()), 0);
  for (const auto& [gx, gy] : walked) {
    const int ix = gx - w.origin_ix, iy = gy - w.origin_iy;
    if (w.Contains(ix, iy)) fog->walked[size_t(w.Index(ix, iy))] = 1;
  }
}

// The floor under the standing robot is known without looking: it stands on it. The body hides
// it from the eyes, so where the robot came by a way it did not look at, unknown cells lay
// around its feet and barred the moves the eyes do not look along (a side-step out of a narrow
// gap's mouth). Unknown cells that the standing footprint covers
// (centres inside it grown by half a cell) become floor at the believed floor height, except
// beside a floor or stairs cell on another level (more than h_floor off): the toes may reach
// past a step's edge there, and a cell marked on the robot's level would move the edge under
// the landing of the step down (the plan stepped back and forth before it).
void MarkFloorUnderFeet(const nav::PlannerParams& p, const perception::Pose2& robot, double floor_z,
                        perception::Fog* fog) {
  const perception::GridWindow& w = fog->window;
  const double along = 0.5 * p.depth + p.margin + 0.5 * w.resolution;
  const double across = 0.5 * p.shoulder_width + p.margin + 0.5 * w.resolution;
  ForCellsUnder(robot, along, across, w.resolution, [&](int gx, int gy) {
    const int ix = gx - w.origin_ix, iy = gy - w.origin_iy;
    if (!w.Contains(ix, iy)) return;
    const size_t i = size_t(w.Index(ix, iy));
    if (fog->type[i] != perception::CellType::kUnknown) return;
    bool edge = false;
    for (int jy = std::max(0, iy - 1); jy <= std::min(w.size_y - 1, iy + 1); ++jy) {
      for (int jx = std::max(0, ix - 1); jx <= std::min(w.size_x - 1, ix + 1); ++jx) {
        const perception::CellType t = fog->TypeAt(jx, jy);
        edge |= (t == perception::CellType::kFloor || t == perception::CellType::kStairs) &&
                std::abs(fog->HeightAt(jx, jy) - floor_z) > p.h_floor;
      }
    }
    if (edge) return;
    fog->type[i] = perception::CellType::kFloor;
    fog->height[i] = float(floor_z);
  });
}

// Plans to within params' tolerance (half the scenario's, so the robot ends inside it despite
// odometry and cells); where no pose lies that near (a goal at the foot of a wall), to any pose
// within the scenario's tolerance, with half a cell to spare for the cell centres.
// `used` gets the parameters of the plan returned.
nav::PlanResult PlanToGoal(const perception::Fog& fog, const perception::Pose2& start,
                           const Scenario& scenario, const nav::PlannerParams& params,
                           nav::Posture posture, nav::PlannerParams* used = nullptr) {
  if (used) *used = params;
  nav::PlanResult plan = nav::Plan(fog, start, scenario.goal, params, posture);
  if (plan.status == nav::PlanStatus::kOk || plan.reason != nav::NoPathReason::kGoalBlocked) {
    return plan;
  }
  nav::PlannerParams wider = params;
  wider.goal_tolerance = std::max(params.goal_tolerance,
                                  scenario.goal_tolerance - 0.5 * fog.window.resolution);
  if (used) *used = wider;
  return nav::Plan(fog, start, scenario.goal, wider, posture);
}

// Where to look from at obstacle evidence seen only from farther than `range`
// (ExecutionLimits::inspect_range), in obstacle and tunnel cells and on the rims of raised
// tops: the map with those cells unknown may have a way on; the robot looks from the last pose
// of that way before the real map stops it. Left as they are:
// cells within the body's reach of where the robot stands (it has looked from here; they lie
// where its eyes do not reach, behind a low wall it stands at) and cells beside obstacle
// evidence seen from nearer (the hidden inside of a wall whose face was seen from nearby; no
// look shows it). Nothing if there is no such way or it stays where it is.
std::optional<Eigen::Vector2d> InspectionPose(const perception::Fog& fog,
                                              const perception::MapState& maps,
                                              const perception::Pose2& believed,
                                              const Scenario& scenario,
                                              const nav::PlannerParams& params,
                                              nav::Posture posture, double range) {
  if (maps.obstacle_range.size() != fog.type.size()) return std::nullopt;
  const perception::GridWindow& w = fog.window;
  auto solid = [&](int ix, int iy) {
    const perception::CellType t = fog.TypeAt(ix, iy);
    return t == perception::CellType::kObstacle || t == perception::CellType::kTunnel;
  };
  auto seen_near = [&](int ix, int iy) {
    return w.Contains(ix, iy) && solid(ix, iy) &&
           !(maps.obstacle_range[size_t(w.Index(ix, iy))] > range);
  };
  // the body's reach: the shoulders standing, head and hands crawling
  const double reach =
      std::max(0.5 * params.shoulder_width, params.crawl_offset + 0.5 * params.crawl_length) +
      params.margin;
  const Eigen::Vector2d here(believed.x, believed.y);
  // the rim of a raised top: a floor or border cell more than h_stairs above a 4-neighbour's
  // floor (a top seen from afar may reach a cell too far, and two such rims close a narrow way)
  const float h_stairs = float(params.h_stairs);
  auto known_floor = [&](int jx, int jy, float* h) {
    if (!w.Contains(jx, jy)) return false;
    const perception::CellType t = fog.TypeAt(jx, jy);
    *h = fog.HeightAt(jx, jy);
    return (t == perception::CellType::kFloor || t == perception::CellType::kBorder ||
            t == perception::CellType::kStairs) && std::isfinite(*h);
  };
  auto top_rim = [&](int ix, int iy) {
    float h = 0, g = 0;
    if (!known_floor(ix, iy, &h)) return false;
    const int nx[4] = {ix + 1, ix - 1, ix, ix}, ny[4] = {iy, iy, iy + 1, iy - 1};
    for (int k = 0; k < 4; ++k) {
      if (known_floor(nx[k], ny[k], &g) && g < h - h_stairs) return true;
    }
    return false;
  };
  perception::Fog hopeful = fog;
  int suspects = 0;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      if (!(solid(ix, iy) || top_rim(ix, iy)) || !(maps.obstacle_range[i] > range) ||
          (w.CellCenter(ix, iy) - here).norm() <= reach || seen_near(ix - 1, iy) ||
          seen_near(ix + 1, iy) || seen_near(ix, iy - 1) || seen_near(ix, iy + 1)) {
        continue;
      }
      hopeful.type[i] = perception::CellType::kUnknown;
      hopeful.height[i] = -std::numeric_limits<float>::infinity();
      ++suspects;
    }
  }
  if (suspects == 0) return std::nullopt;
  const nav::PlanResult plan = PlanToGoal(hopeful, believed, scenario, params, posture);
  if (plan.status != nav::PlanStatus::kOk) return std::nullopt;
  const size_t k = nav::FirstBlockedPose(fog, plan, scenario.goal, params);
  if (k >= plan.path.size()) return std::nullopt;
  const perception::Pose2& before = plan.path[k - 1].pose_G;
  return Eigen::Vector2d(before.x, before.y);
}

// The map with every unknown cell made floor at height `z`.
perception::Fog OpenUnknown(const perception::Fog& fog, float z) {
  perception::Fog open = fog;
  for (size_t i = 0; i < open.type.size(); ++i) {
    if (open.type[i] != perception::CellType::kUnknown) continue;
    open.type[i] = perception::CellType::kFloor;
    open.height[i] = z;
  }
  return open;
}

// Where to look from at the unseen cells a plan would move into blind: the robot may not
// side-step or back into cells its eyes have not seen (PlannerParams::blind_moves_stay_known),
// so a gap that only a side-step passes stays closed while the floor behind it is hidden (a
// 0.25 m gap in a divider the robot came to at an angle). The map with blind moves allowed may
// have a way on; the robot looks from the last pose of that way before its first blind move,
// at `lead` beyond the pose that move goes to, in its direction. If `open_unseen` and there is
// no such way, the same on the map with the unseen cells open floor (OpenUnknown): the first
// move the real map stops may then be a walk as well. `toward` is the real map's plan toward
// the goal (nav::PlanToward with `params`). Nothing if there is no such way or it stays where
// it is.
struct Peek {
  Eigen::Vector2d from, at;
};

std::optional<Peek> PeekPose(const perception::Fog& fog, const perception::Pose2& believed,
                             const Scenario& scenario, const nav::PlannerParams& params,
                             nav::Posture posture, const nav::PlanResult& toward,
                             double min_approach, double lead, bool open_unseen) {
  if (!params.blind_moves_stay_known) return std::nullopt;
  nav::PlannerParams blind = params;
  blind.blind_moves_stay_known = false;
  int gx = 0, gy = 0;
  fog.window.CellOf(scenario.goal.x(), scenario.goal.y(), &gx, &gy);
  auto end_distance = [&](const nav::PlanResult& p) {
    return (Eigen::Vector2d(p.path.back().pose_G.x, p.path.back().pose_G.y) - scenario.goal)
        .norm();
  };
  // to the goal; else to where its region meets the window's edge; with the goal beyond the
  // window, min_approach nearer it than the real map leads
  auto blind_way = [&](const perception::Fog& map) {
    nav::PlanResult plan = PlanToGoal(map, believed, scenario, blind, posture);
    if (plan.status == nav::PlanStatus::kOk && !plan.reaches_goal) {
      if (fog.window.Contains(gx, gy)) {
        plan = nav::PlanBeyond(map, believed, scenario.goal, blind, posture);
      } else if (toward.status == nav::PlanStatus::kOk &&
                 end_distance(plan) >= end_distance(toward) - min_approach) {
        plan = nav::PlanResult{};
      }
    }
    return plan;
  };
  auto first_blocked = [&](const nav::PlanResult& plan) {
    return plan.status == nav::PlanStatus::kOk
               ? nav::FirstBlockedPose(fog, plan, scenario.goal, params)
               : plan.path.size();
  };
  nav::PlanResult plan = blind_way(fog);
  size_t k = first_blocked(plan);
  if (k >= plan.path.size() && open_unseen) {
    // the unseen cells open at the height of the floor the robot stands on
    int rx = 0, ry = 0;
    fog.window.CellOf(believed.x, believed.y, &rx, &ry);
    const float z = fog.window.Contains(rx, ry) && std::isfinite(fog.HeightAt(rx, ry))
                        ? fog.HeightAt(rx, ry)
                        : 0.0f;
    plan = blind_way(OpenUnknown(fog, z));
    k = first_blocked(plan);
  }
  if (k >= plan.path.size()) return std::nullopt;
  const perception::Pose2& before = plan.path[k - 1].pose_G;
  const perception::Pose2& blind_to = plan.path[k].pose_G;
  const Eigen::Vector2d from(before.x, before.y), to(blind_to.x, blind_to.y);
  const Eigen::Vector2d step = to - from;
  return Peek{from, step.norm() > 1e-9 ? Eigen::Vector2d(to + step.normalized() * lead) : to};
}

}  // namespace

MissionOutcome RunMission(const Scenario& scenario, const MissionOptions& options) {
  const auto wall_start = Clock::now();
  MakeOutputFolder(options.out_dir);
  // a report left from an earlier run must not pass for this run's
  std::error_code error;
  std::filesystem::remove(options.out_dir + "/report.json", error);
  std::ofstream trajectory(options.out_dir + "/trajectory.csv");
  if (!trajectory) throw OutputError(options.out_dir + "/trajectory.csv: cannot write");
  trajectory << "step,tick,true_x,true_y,true_yaw,odom_x,odom_y,odom_yaw,action\n";
  std::ofstream cycles_csv(options.out_dir + "/cycles.csv");
  if (!cycles_csv) throw OutputError(options.out_dir + "/cycles.csv: cannot write");
  cycles_csv << "cycle,step,odom_x,odom_y,odom_yaw,posture,plan,plan_cost,plan_length,decision,"
                "target_x,target_y,explorations,thrashes\n";
  // the logs reach the disk every cycle: a full disk ends the run there, and they can be read
  // while it runs
  auto flush_logs = [&]() {
    const std::pair<std::ofstream*, const char*> logs[] = {{&trajectory, "trajectory.csv"},
                                                           {&cycles_csv, "cycles.csv"}};
    for (const auto& [log, name] : logs) {
      errno = 0;
      if (!log->flush()) {
        throw OutputError(options.out_dir + "/" + name + ": cannot write: " +
                          (errno != 0 ? std::strerror(errno) : "the stream failed"));
      }
    }
  };
  flush_logs();
  const bool progress = !options.quiet && isatty(STDERR_FILENO);
  std::unique_ptr<MissionVideo> video;
  if (!options.video_path.empty()) {
    video = std::make_unique<MissionVideo>(options.video_path, options.video_fps);
  }

  // world, robot, renderer
  const RunParams run_params = ResolveParams(scenario.params);
  const PerceptionParams& perception_params = run_params.perception;
  nav::PlannerParams planner_params = run_params.planner;
  // plan to within half the tolerance, so the robot ends inside it despite odometry and cells
  planner_params.goal_tolerance = 0.5 * scenario.goal_tolerance;
  const ExecutionLimits& limits = run_params.mission;
  sim::World world(MakeWorldSpec(scenario));
  const mjModel* m = world.model();
  mjData* d = world.data();
  sim::ControllerParams controller_params;
  controller_params.odometry_noise_xy = scenario.odometry_noise_xy;
  controller_params.odometry_noise_yaw = scenario.odometry_noise_yaw;
  controller_params.seed = unsigned(scenario.seed);
  sim::Controller controller(m, controller_params);
  planner_params.kneel_offset = controller.KneelOffset();
  // steps up and down as long and as far aside as the controller takes them
  planner_params.max_step_length = controller_params.limits.max_climb_forward;
  planner_params.max_step_sideways = controller_params.limits.max_climb_sideways;
  const bool seen_headroom_to_get_up = planner_params.get_up_under_seen_headroom;
  const sim::Humanoid& humanoid = controller.humanoid();
  controller.Reset({scenario.start.x, scenario.start.y, scenario.start.yaw}, 0.0, m, d);
  sim::Renderer renderer(m);

  perception::MapState maps;
  // the odometry's own noise model: the covariance one footstep adds
  perception::LocalizationState localization;
  const Eigen::Matrix3d step_covariance =
      Eigen::Vector3d(scenario.odometry_noise_xy * scenario.odometry_noise_xy,
                      scenario.odometry_noise_xy * scenario.odometry_noise_xy,
                      scenario.odometry_noise_yaw * scenario.odometry_noise_yaw).asDiagonal();
  double believed_floor_z = 0;  // odometry: the sum of the commanded rises
  std::map<std::string, int> actions;
  for (const auto& name : ActionNames()) actions[name] = 0;
  std::map<std::string, std::vector<double>> timing;
  double path_length = 0;
  perception::Pose2 last_true = ToPerception(controller.TruePose(d));
  std::string current_move = "look";
  int cycle = 0;
  int last_step_logged = 0;
  std::set<std::pair<int, int>> walked;  // global cells the standing robot covered (Fog::walked)

  // the video's frames: the chase camera now, the last head image, the last plan picture
  perception::RgbImage video_plan_picture;
  StereoView last_stereo;
  const int video_every =
      std::max(1, int(std::lround(options.video_period_s * controller_params.control_rate_hz)));
  auto add_video_frame = [&]() {
    const sim::Pose2 t = controller.TruePose(d);
    const sim::PinholeCamera chase = sim::PinholeCamera::FromFov(
        ChaseCamera(t.x, t.y, t.yaw, believed_floor_z), MissionVideo::kPanelWidth,
        MissionVideo::kPanelHeight, 1.0);
    const sim::RenderedView view = renderer.Render(m, d, chase, {false, false});
    perception::RgbImage chase_image(view.width, view.height);
    for (size_t i = 0; i < chase_image.data.size(); ++i) {
      chase_image.data[i] = {view.rgb[3 * i], view.rgb[3 * i + 1], view.rgb[3 * i + 2]};
    }
    char status[160];
    std::snprintf(status, sizeof(status), "%s   cycle %d   %s   goal %.2f m   t %.1f s",
                  scenario.name.c_str(), cycle, current_move.c_str(),
                  std::hypot(t.x - scenario.goal.x(), t.y - scenario.goal.y()),
                  controller.ticks() * controller.dt());
    video->Add(chase_image, last_stereo.left, video_plan_picture, status);
  };

  // logs every footstep and accumulates the ground-truth path
  auto on_tick = [&](int) {
    if (video && controller.ticks() % video_every == 0) add_video_frame();
    if (controller.steps() == last_step_logged) return;
    last_step_logged = controller.steps();
    perception::Pose2 t = ToPerception(controller.TruePose(d));
    perception::Pose2 o = ToPerception(controller.believed_pose());
    path_length += std::hypot(t.x - last_true.x, t.y - last_true.y);
    last_true = t;
    char row[256];
    std::snprintf(row, sizeof(row), "%d,%d,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%s\n", controller.steps(),
                  controller.ticks(), t.x, t.y, t.yaw, o.x, o.y, o.yaw, current_move.c_str());
    trajectory << row;
    if (controller.mode() == sim::Mode::kStanding) {
      AddWalkedCells(planner_params, o, perception_params.map.grid.resolution, &walked);
    }
  };
  auto run_controller = [&]() {
    auto start = Clock::now();
    const perception::Pose2 before = ToPerception(controller.believed_pose());
    const int steps_before = controller.steps();
    controller.RunUntilIdle(m, d, on_tick);
    perception::PredictPose(before, ToPerception(controller.believed_pose()),
                            (controller.steps() - steps_before) * step_covariance, &localization);
    timing["control"].push_back(Ms(start));
  };

  // one perception cycle at the head's current pose
  ViewResult last_view;
  auto perceive = [&]() {
    auto start = Clock::now();
    last_stereo = RenderStereo(&renderer, world, sim::HeadCameraPoseInWorld(humanoid, d, sim::Eye::kLeft),
                               scenario.sensor);
    timing["render"].push_back(Ms(start));
    last_view = PerceiveView(perception_params, scenario.sensor.depth, last_stereo, humanoid,
                             ToPerception(controller.believed_pose()), believed_floor_z,
                             sim::HeadCameraPose(humanoid, d, sim::Eye::kLeft),
                             sim::RobotBodyBoxes(humanoid, m, d), &maps, &localization);
    timing["stereo"].push_back(last_view.stereo_ms);
    timing["segmentation"].push_back(last_view.segmentation_ms);
    timing["mapping"].push_back(last_view.mapping_ms);
    const perception::Pose2& localized = last_view.robot_G;
    controller.CorrectBelievedPose({localized.x, localized.y, localized.yaw});
  };
  // turns the head to `view` and perceives
  auto look = [&](const sim::HeadAngles& view) {
    controller.MoveHead(view);
    run_controller();
    perceive();
  };
  auto look_around = [&]() {
    current_move = "look";
    for (const sim::HeadAngles& view : StartSweep()) look(view);
  };

  // the neck angles that give the camera the wanted pan and elevation above the horizon, from
  // its kinematic pose
  auto head_at_elevation = [&](double pan, double wanted_elevation) {
    const Eigen::Vector3d forward_R =
        sim::HeadCameraPose(humanoid, d, sim::Eye::kLeft).rotation().col(2);
    const double elevation = std::asin(std::clamp(forward_R.z(), -1.0, 1.0));
    const double tilt = d->qpos[humanoid.joint_qpos(sim::kNeckTilt)];
    return sim::HeadAngles{pan, tilt + elevation - wanted_elevation};
  };

  // a look at the floor at `target`, floor_z high, the head panned toward it as far as the
  // neck turns
  auto look_at_floor = [&](const Eigen::Vector2d& target, double floor_z) {
    const Eigen::Vector3d to =
        Relative(ToPerception(controller.believed_pose()), {target.x(), target.y(), 0});
    const Eigen::Vector3d camera_R = sim::HeadCameraPose(humanoid, d, sim::Eye::kLeft).translation();
    const double below = camera_R.z() + believed_floor_z - floor_z;
    const double run_out = std::hypot(to.x() - camera_R.x(), to.y() - camera_R.y());
    look(head_at_elevation(std::atan2(to.y(), to.x()), -std::atan2(below, run_out)));
  };

  // Before getting down for the plan's crawl from path[first]: the standing eyes look up
  // (ExecutionLimits::underside_elevation) toward the crawl's pose look_ahead on (or its last)
  // and to both sides of it.
  auto look_up_before_crawling = [&](const nav::PlanResult& p, size_t first,
                                     const perception::Pose2& from) {
    const double toward =
        PanToward(p, first + 1, from, limits.look_ahead,
                  [](const nav::PathPose& q) { return q.posture == nav::Posture::kCrawling; });
    const std::string move = current_move;
    current_move = "look";
    const double side = limits.side_look_pan;
    for (const double pan : {toward, toward + side, toward - side}) {
      look(head_at_elevation(pan, limits.underside_elevation));
    }
    current_move = move;
  };

  auto true_goal_distance = [&]() {
    sim::Pose2 t = controller.TruePose(d);
    return std::hypot(t.x - scenario.goal.x(), t.y - scenario.goal.y());
  };

  // what the robot stands on (soles; knees and hands crawling) beyond the edge of the floor: it
  // would fall. "right sole at (x, y)", or empty.
  auto support_off_floor = [&]() -> std::string {
    using sim::Side;
    std::vector<std::pair<std::string, int>> supports;
    for (const Side s : {Side::kLeft, Side::kRight}) {
      const std::string side = s == Side::kLeft ? "left " : "right ";
      if (controller.mode() == sim::Mode::kCrawling) {
        supports.push_back({side + "knee", humanoid.knee_geom(s)});
        supports.push_back({side + "hand", humanoid.hand_geom(s)});
      } else {
        supports.push_back({side + "sole", humanoid.sole_geom(s)});
      }
    }
    for (const auto& [name, geom] : supports) {
      const Eigen::Vector2d p(d->geom_xpos[3 * geom], d->geom_xpos[3 * geom + 1]);
      if (!OverFloor(scenario, p)) {
        char where[64];
        std::snprintf(where, sizeof(where), " at (%.2f, %.2f)", p.x(), p.y());
        return name + where + " beyond the floor's edge";
      }
    }
    return "";
  };

  // the closed loop
  std::string failure;
  std::string failure_detail;  // why: the planner's no-path reason, the colliding geoms
  nav::PlanResult plan;
  nav::PlanResult last_plan;  // the plan of the last cycle and the pose its run ended at
  size_t last_plan_at = 0;
  perception::Fog fog;
  // the edges of the next steps up or down on the plan, measured from the views
  std::vector<StepEdge> edges;
  const perception::StepEdgeParams& edge_params = run_params.step_edge;
  const double h_floor = planner_params.h_floor;
  // a step's edge lies within the longest step (plus the walk closer) of the pose before it
  const double step_reach = controller_params.limits.max_climb_forward + limits.edge_correction;
  auto forget_edges = [&](auto&& which) {
    edges.erase(std::remove_if(edges.begin(), edges.end(), which), edges.end());
  };
  // the distance along from.yaw to the nearest measured edge between these levels within
  // `reach` ahead (or 5 cm behind), or NaN
  auto edge_ahead = [&](const perception::Pose2& from, double from_z, double to_z,
                        double reach) {
    double nearest = std::numeric_limits<double>::quiet_NaN();
    for (const StepEdge& e : edges) {
      const double ahead = e.Ahead(from, from_z, to_z, h_floor);
      if (ahead >= -0.05 && ahead <= reach &&
          (std::isnan(nearest) || std::abs(ahead) < std::abs(nearest))) {
        nearest = ahead;
      }
    }
    return nearest;
  };
  auto measure_edges = [&]() {
    if (last_plan.status != nav::PlanStatus::kOk) return;
    const std::vector<nav::PathPose>& path = last_plan.path;
    const perception::Pose2 now = ToPerception(controller.believed_pose());
    // edges left far behind or aside (the plan went another way) are forgotten
    forget_edges([&](const StepEdge& edge) {
      return (edge.point_G - Eigen::Vector2d(now.x, now.y)).norm() > 2.0;
    });
    // the edge of the step into path[j] from the last view, if it is in view and not too near
    auto from_view = [&](size_t j) {
      const nav::PathPose& pre = path[j - 1];
      const double e = perception::MeasureStepEdge(edge_params, last_view.labelled_G, pre.pose_G,
                                                   pre.floor_z, path[j].floor_z);
      if (!std::isfinite(e)) return false;
      const Eigen::Vector2d point = Eigen::Vector2d(pre.pose_G.x, pre.pose_G.y) +
                                    e * Eigen::Vector2d(std::cos(pre.pose_G.yaw),
                                                        std::sin(pre.pose_G.yaw));
      if ((point - Eigen::Vector2d(now.x, now.y)).norm() < limits.edge_min_range) return false;
      const StepEdge measured{point, pre.pose_G.yaw, pre.floor_z, path[j].floor_z};
      // a new measurement of an edge replaces the old one
      forget_edges([&](const StepEdge& old) {
        return std::abs(old.Ahead(pre.pose_G, pre.floor_z, path[j].floor_z, h_floor) - e) < 0.1;
      });
      edges.push_back(measured);
      return true;
    };
    double ahead = 0;  // path length from the robot
    size_t first_step = 0;
    for (size_t j = last_plan_at + 1; j < path.size(); ++j) {
      ahead += std::hypot(path[j].pose_G.x - path[j - 1].pose_G.x,
                          path[j].pose_G.y - path[j - 1].pose_G.y);
      if (ahead > limits.edge_lookahead) break;
      if (path[j].move != nav::Move::kStairsUp && path[j].move != nav::Move::kStairsDown) continue;
      const bool measured = from_view(j);
      if (first_step == 0 && !measured &&
          !std::isfinite(edge_ahead(path[j - 1].pose_G, path[j - 1].floor_z, path[j].floor_z,
                                    step_reach))) {
        first_step = j;
      }
    }
    if (first_step == 0) return;
    // the next step is not measured yet: look at where the plan puts its riser, as the paper's
    // robot stops to look at the stairs, while it is far enough for the body not to hide it
    const nav::PathPose& pre = path[first_step - 1];
    const nav::PathPose& post = path[first_step];
    const Eigen::Vector2d riser(0.5 * (pre.pose_G.x + post.pose_G.x),
                                0.5 * (pre.pose_G.y + post.pose_G.y));
    const double range = (riser - Eigen::Vector2d(now.x, now.y)).norm();
    if (range < limits.edge_min_range || range > limits.edge_look_range) return;
    look_at_floor(riser, std::max(pre.floor_z, post.floor_z));
    from_view(first_step);
  };

  // One step up or down from `from` (facing the step, on a floor from_z high) onto the level
  // of `onto`, planned dx_plan forward and dy_plan to the left: with the step's measured edge
  // the heel lands heel_margin past it (stepping down, at least that far), at most
  // edge_correction from the plan's landing, walking closer first where that is beyond the
  // longest step.
  auto step_onto = [&](const perception::Pose2& from, double from_z, const nav::PathPose& onto,
                       double dx_plan, double dy_plan) {
    const sim::StepLimits& step_limits = controller_params.limits;
    double dz = std::isfinite(onto.floor_z) ? onto.floor_z - believed_floor_z : 0.0;
    dz = std::clamp(dz, -step_limits.max_climb_height, step_limits.max_climb_height);
    double dx = dx_plan;
    const double e = edge_ahead(from, from_z, onto.floor_z, step_reach);
    if (std::isfinite(e)) {
      const double heel = e + humanoid.sole_half_length() + limits.heel_margin;
      dx = std::clamp(heel, onto.floor_z > from_z ? dx - limits.edge_correction : dx,
                      dx + limits.edge_correction);
      // beyond the longest step: walk up to the edge first, the toes toe_margin short of it
      const double toes = e - humanoid.sole_half_length() - limits.toe_margin;
      const double closer = std::min(dx - step_limits.max_climb_forward, toes);
      if (closer > 0.002) {
        const std::string step_move = current_move;
        current_move = nav::MoveName(nav::Move::kWalk);
        controller.Walk(closer, 0, 0);
        ++actions[current_move];
        run_controller();
        current_move = step_move;
        dx -= closer;
      }
    }
    dx = std::clamp(dx, 0.02, step_limits.max_climb_forward);
    controller.StepOnto(
        dx, dz,
        std::clamp(dy_plan, -step_limits.max_climb_sideways, step_limits.max_climb_sideways));
    believed_floor_z += dz;
    // the edge stepped over is behind now
    forget_edges([&](const StepEdge& edge) {
      const double ahead = edge.Ahead(from, from_z, onto.floor_z, h_floor);
      return ahead >= -0.05 && ahead <= step_reach;
    });
  };

  AddWalkedCells(planner_params, ToPerception(controller.believed_pose()),
                 perception_params.map.grid.resolution, &walked);
  look_around();
  perception::Pose2 looked_at = ToPerception(controller.believed_pose());
  bool just_looked = true;
  std::optional<perception::Pose2> fresh_at;  // where the grid was last weakened
  // where the robot explores to, beyond the window's edge that nav::PlanBeyond led to
  std::optional<Eigen::Vector2d> explore_to;
  double nearest_to_goal = std::numeric_limits<double>::infinity();  // believed, so far
  int explorations = 0;
  double explore_best = 0;  // the distance to explore_to when it last got min_approach nearer
  double explore_reach = 0;  // exploring ends within this distance of explore_to
  bool inspecting = false;   // explore_to is where to look from (InspectionPose, PeekPose)
  // where to look once there (PeekPose), if peek_pending
  bool peek_pending = false;
  Eigen::Vector2d peek_at = Eigen::Vector2d::Zero();
  // looks around where the robot stands (`here`), then at the floor of a pending peek
  auto look_around_and_peek = [&](const perception::Pose2& here) {
    look_around();
    if (peek_pending) look_at_floor(peek_at, believed_floor_z);
    peek_pending = false;
    looked_at = here;
    just_looked = true;
  };
  // believed positions of the last cycles (thrash_cycles) and the nearest to the goal so far
  std::deque<std::pair<Eigen::Vector2d, double>> recent;
  // the last thrash_cycles poses it came to by moving, with the nearest to the goal it had
  // been by then
  std::deque<std::pair<perception::Pose2, double>> arrivals;
  int thrashes = 0;         // times it went back and forth (thrash_cycles)
  int explore_stalls = 0;   // cycles since it last got min_approach nearer
  // whether a plan moves the robot at all, and whether it leads min_approach nearer to `target`
  // than `distance`
  auto moves = [](const nav::PlanResult& p) {
    return p.status == nav::PlanStatus::kOk && p.path.size() >= 2;
  };
  auto leads_nearer = [&](const nav::PlanResult& p, const Eigen::Vector2d& target,
                          double distance) {
    if (!moves(p)) return false;
    const Eigen::Vector2d end(p.path.back().pose_G.x, p.path.back().pose_G.y);
    return (end - target).norm() < distance - limits.min_approach;
  };
  // exploring (to a window edge, or to inspect): until within `reach` of `target` or stalled
  auto start_exploring = [&](const Eigen::Vector2d& target, double reach, bool inspect,
                             const Eigen::Vector2d& from) {
    explore_to = target;
    explore_reach = reach;
    inspecting = inspect;
    explore_best = (target - from).norm();
    explore_stalls = 0;
    ++explorations;
  };
  // cycles.csv: per cycle where the robot believed it was, what the planner found there and
  // what the robot did about it (a target: where it went to explore or look from), with the
  // explorations and the times it went back and forth so far, after the decision
  struct CycleRow {
    int cycle, step;
    perception::Pose2 believed;
    const char* posture;
    const char* plan;  // goal, toward (a way short of it), here (no move) or why there is none
    double cost, length;
    const char* decision;
    std::optional<Eigen::Vector2d> target;
  };
  std::optional<CycleRow> log_row;
  auto log_cycle = [&]() {
    if (!log_row) return;
    const CycleRow& r = *log_row;
    char target[64] = ",";
    if (r.target) std::snprintf(target, sizeof(target), "%.5f,%.5f", r.target->x(), r.target->y());
    char row[384];
    std::snprintf(row, sizeof(row), "%d,%d,%.5f,%.5f,%.5f,%s,%s,%.4f,%.4f,%s,%s,%d,%d\n",
                  r.cycle, r.step, r.believed.x, r.believed.y, r.believed.yaw, r.posture, r.plan,
                  r.cost, r.length, r.decision, target, explorations, thrashes);
    cycles_csv << row;
    log_row.reset();
    flush_logs();
  };
  auto decide = [&](const char* decision,
                    const std::optional<Eigen::Vector2d>& target = std::nullopt) {
    if (!log_row) return;
    log_row->decision = decision;
    log_row->target = target;
  };
  while (true) {
    log_cycle();
    if (const std::string off = support_off_floor(); !off.empty()) {
      failure = "off_floor";
      failure_detail = off;
      break;
    }
    if (true_goal_distance() <= scenario.goal_tolerance) break;
    if (scenario.expect.no_collision.value_or(false) && !controller.collisions().empty()) {
      failure = "collision";
      const sim::Collision& c = controller.collisions().front();
      failure_detail = c.robot_name + " hit " + c.world_name;
      break;
    }
    if (cycle >= scenario.max_cycles || controller.steps() >= scenario.max_steps) {
      failure = "timeout";
      break;
    }
    if (options.stop && options.stop->load()) {
      failure = "interrupted";
      break;
    }
    ++cycle;

    // plan from where odometry says the robot is
    const perception::Pose2 believed = ToPerception(controller.believed_pose());
    const Eigen::Vector2d position(believed.x, believed.y);
    nearest_to_goal = std::min(nearest_to_goal, (position - scenario.goal).norm());
    fog = perception::ComputeFog(perception_params.map, maps);
    if (controller.mode() == sim::Mode::kStanding) {
      MarkFloorUnderFeet(planner_params, believed, believed_floor_z, &fog);
    }
    MarkWalked(walked, &fog);
    auto start = Clock::now();
    const nav::Posture posture = controller.mode() == sim::Mode::kCrawling
                                     ? nav::Posture::kCrawling
                                     : nav::Posture::kUpright;
    if (posture == nav::Posture::kUpright) {
      planner_params.get_up_under_seen_headroom = seen_headroom_to_get_up;
    }
    nav::PlannerParams used = planner_params;
    plan = PlanToGoal(fog, believed, scenario, planner_params, posture, &used);
    auto same_pose = [&](const perception::Pose2& a, const perception::Pose2& b) {
      return std::hypot(a.x - b.x, a.y - b.y) < 0.5 * fog.window.resolution &&
             std::abs(WrapAngle(a.yaw - b.yaw)) < 0.05;
    };
    // come to this pose by moving for the circling_arrivals-th time (see there)
    const bool moved_here = arrivals.empty() || !same_pose(arrivals.back().first, believed);
    int times_here = 0;
    double nearest_then = 0;  // at the first time
    for (const auto& [pose, nearest] : arrivals) {
      if (!same_pose(pose, believed)) continue;
      if (times_here++ == 0) nearest_then = nearest;
    }
    const bool circling = moved_here && times_here + 1 >= limits.circling_arrivals &&
                          nearest_to_goal > nearest_then - limits.min_approach;
    if (moved_here) arrivals.push_back({believed, nearest_to_goal});
    if (int(arrivals.size()) > limits.thrash_cycles) arrivals.pop_front();
    // keep to the last plan where the robot got to its end of the run and the rest of it is
    // still allowed and about as cheap
    if (plan.status == nav::PlanStatus::kOk && last_plan.status == nav::PlanStatus::kOk &&
        last_plan_at < last_plan.path.size()) {
      const nav::PathPose& at = last_plan.path[last_plan_at];
      if (at.posture == posture && same_pose(at.pose_G, believed)) {
        nav::PlanResult rest =
            nav::ContinuePlan(fog, last_plan, last_plan_at, believed, scenario.goal, used);
        if (moves(rest) && rest.cost <= plan.cost + std::max(limits.keep_plan_margin,
                                                             limits.keep_plan_share * plan.cost)) {
          plan = std::move(rest);
        }
      }
    }
    timing["planning"].push_back(Ms(start));
    if (video) video_plan_picture = viz::DrawPlanPicture(fog, believed, plan, scenario.goal);
    log_row = CycleRow{cycle, controller.steps(), believed, nav::PostureName(posture),
                       moves(plan) ? (plan.reaches_goal ? "goal" : "toward")
                       : plan.status == nav::PlanStatus::kOk ? "here"
                                                             : nav::NoPathReasonName(plan.reason),
                       plan.cost, plan.length, "follow", std::nullopt};
    // exploring goes on while the map's ways to the goal come and go (they may lead through
    // cells not yet seen), until the robot is within explore_beyond of where it explores to or
    // has not got min_approach nearer to it for explore_patience cycles (nearer than where it
    // last did: turns toward it and looks make cycles without a step, and a robot that gains a
    // few centimetres a cycle is on its way)
    if (explore_to) {
      const double d = (position - *explore_to).norm();
      if (d < explore_best - limits.min_approach) {
        explore_stalls = 0;
        explore_best = d;
      } else {
        ++explore_stalls;
      }
      if (d < explore_reach || explore_stalls > limits.explore_patience) {
        // come to look, the robot looks around (and for a peek, at the floor beyond the blind
        // move) at once: following a way that opened elsewhere on the way there, its eyes
        // would see only where that way goes (come side-stepping, they face the wall beside
        // the passage it came to look along)
        const bool there_to_look = inspecting && d < explore_reach;
        if (there_to_look) decide("look_on_arrival", explore_to);
        explore_to.reset();
        inspecting = false;
        if (there_to_look) {
          look_around_and_peek(believed);
          continue;
        }
      }
    }
    recent.push_back({position, nearest_to_goal});
    if (int(recent.size()) > limits.thrash_cycles) recent.pop_front();
    const bool thrashing = !plan.reaches_goal && int(recent.size()) == limits.thrash_cycles &&
                           nearest_to_goal > recent.front().second - limits.min_approach &&
                           std::all_of(recent.begin(), recent.end(), [&](const auto& r) {
                             return (r.first - recent.front().first).norm() < limits.thrash_radius;
                           });
    if (thrashing) {
      recent.clear();
      ++thrashes;
    }
    if (thrashing || circling) arrivals.clear();
    if (thrashes > 1) {  // the ways it finds take it back and forth
      decide("give_up");
      failure = "no_path";
      failure_detail = "no_progress";
      break;
    }
    // exploring or inspecting, only a plan to the goal itself takes over (a goal outside the
    // window has plans toward it that lead to where the way seemed to end, and the goal passes
    // in and out of the window as the robot goes)
    // once it went back and forth, a plan short of the goal must lead nearer than it has been
    const bool stuck = thrashes > 0 && !explore_to && !plan.reaches_goal &&
                       !leads_nearer(plan, scenario.goal, nearest_to_goal);
    // circling on plans that reach the goal, it looks around; it does not give up for it
    // (counted as going back and forth, a room it took through gave up: it had gone back and
    // forth once before)
    if (circling && !just_looked && !explore_to && moves(plan) && plan.reaches_goal) {
      decide("circling_look");
      look_around_and_peek(believed);
      continue;
    }
    if (!moves(plan) || thrashing || stuck || (explore_to && !plan.reaches_goal)) {
      // exploring, the robot looks ahead each cycle; it looks around, goes nearer and looks
      // afresh only once that way ends (below)
      if (!just_looked && !explore_to) {
        decide("look_around");
        look_around_and_peek(believed);
        continue;
      }
      // no way even after looking around: get as near the goal as the map allows and look
      // again from there (what was seen from afar may be wrong), unless that gains nothing
      // (once it has explored: over the nearest it has been, else it would only go back)
      const double here = (position - scenario.goal).norm();
      nav::PlanResult toward;
      bool nearer = false;
      const char* why = "toward_goal";  // the decision, once a way is found
      bool why_explores = false;         // ... and whether it explores to explore_to
      if (!explore_to) {
        toward = nav::PlanToward(fog, believed, scenario.goal, planner_params, posture);
        nearer =
            leads_nearer(toward, scenario.goal,
                         explorations > 0 || thrashes > 0 ? std::min(nearest_to_goal, here) : here);
      }
      // crawling with no way on: beyond a table top as thick as the eyes are high the headroom
      // stays unseen from below, so the robot may get up where the map holds no ceiling, until
      // it stands again; with no way to the goal even so, it gets up where that leads nearer
      if (!nearer && posture == nav::Posture::kCrawling &&
          planner_params.get_up_under_seen_headroom) {
        nav::PlannerParams unseen = planner_params;
        unseen.get_up_under_seen_headroom = false;
        nav::PlanResult up = PlanToGoal(fog, believed, scenario, unseen, posture);
        if (!moves(up)) {
          up = nav::PlanToward(fog, believed, scenario.goal, unseen, posture);
          if (!leads_nearer(up, scenario.goal, here)) up = nav::PlanResult{};
        }
        if (moves(up)) {
          planner_params = unseen;
          toward = std::move(up);
          nearer = true;
          why = "get_up";
        }
      }
      if (!nearer && !explore_to &&
          (!fresh_at || std::hypot(believed.x - fresh_at->x, believed.y - fresh_at->y) >
                            limits.fresh_look_distance)) {
        decide("fresh_look");
        perception::FadeGrid(perception_params.map, limits.fresh_look_keep, &maps);
        look_around();
        looked_at = believed;
        fresh_at = believed;
        just_looked = true;
        continue;
      }
      // still no way: the goal's region may be joined beyond the map window (a wall whose end
      // lies outside it), so explore: to the window's edge where that region meets it, then on
      // to explore_beyond past where that edge was (the window moves with the robot and forgets
      // what it leaves behind, so a new choice each cycle would go back and forth). Where that
      // way ends, the robot looks around (as above) and chooses again, or gives up.
      if (!nearer && explore_to) {
        toward = nav::PlanToward(fog, believed, *explore_to, planner_params, posture);
        nearer = leads_nearer(toward, *explore_to, (position - *explore_to).norm());
        why = "explore";
        why_explores = true;
        if (!nearer) {
          decide("explore_ends", explore_to);
          explore_to.reset();
          inspecting = false;
          continue;
        }
      } else if (!nearer && explorations < limits.max_explorations) {
        // or go and look, at obstacle evidence seen from afar or into the unseen cells a blind
        // move needs (of the two, the one reached by the cheaper way), where that way is
        // shorter than the one to the window's edge: exploring beyond the window with a gap on
        // the way unseen, the robot went back and forth along a divider until it gave up
        std::optional<Eigen::Vector2d> suspect = InspectionPose(
            fog, maps, believed, scenario, planner_params, posture, limits.inspect_range);
        if (!suspect) {
          suspect = InspectionPose(fog, maps, believed, scenario, planner_params, posture,
                                   limits.inspect_near_range);
        }
        // (`toward` holds the real map's plan toward the goal here: not exploring, not nearer)
        const std::optional<Peek> peek =
            PeekPose(fog, believed, scenario, planner_params, posture, toward, limits.min_approach,
                     limits.peek_lead, !suspect);
        const std::optional<Eigen::Vector2d> candidates[2] = {
            suspect, peek ? std::optional<Eigen::Vector2d>(peek->from) : std::nullopt};
        const double reaches[2] = {limits.inspect_reach, limits.peek_reach};
        int chosen = -1;  // the candidate to look from
        nav::PlanResult look_way;
        peek_pending = false;
        for (int c = 0; c < 2; ++c) {
          const std::optional<Eigen::Vector2d>& at = candidates[c];
          if (!at) continue;
          nav::PlanResult way = nav::PlanToward(fog, believed, *at, planner_params, posture);
          if (leads_nearer(way, *at, (position - *at).norm()) &&
              (chosen < 0 || way.cost < look_way.cost)) {
            chosen = c;
            look_way = std::move(way);
          }
        }
        nav::PlanResult edge =
            nav::PlanBeyond(fog, believed, scenario.goal, planner_params, posture);
        if (chosen >= 0 && (!moves(edge) || look_way.length < edge.length)) {
          start_exploring(*candidates[chosen], reaches[chosen], true, position);
          toward = std::move(look_way);
          nearer = true;
          peek_pending = chosen == 1;
          if (peek_pending) peek_at = peek->at;
          why = peek_pending ? "peek" : "inspect";
          why_explores = true;
        } else if (moves(edge)) {
          const Eigen::Vector2d end(edge.path.back().pose_G.x, edge.path.back().pose_G.y);
          start_exploring(end + (end - position).normalized() * limits.explore_beyond,
                          limits.explore_beyond, false, position);
          toward = std::move(edge);
          nearer = true;
          why = "explore_edge";
          why_explores = true;
        }
      }
      if (!nearer) {
        decide("give_up");
        failure = "no_path";
        // a plan that ends where it starts: the best reachable state toward the goal is here
        failure_detail = plan.status == nav::PlanStatus::kOk ? "no_progress"
                                                             : nav::NoPathReasonName(plan.reason);
        break;
      }
      decide(why, why_explores ? explore_to : std::nullopt);
      plan = std::move(toward);
      if (video) video_plan_picture = viz::DrawPlanPicture(fog, believed, plan, scenario.goal);
    }

    // the first run of moves, cut to about two strides
    const std::vector<nav::PathSegment> segments = nav::SegmentPath(plan);
    const nav::PathSegment& run = segments.front();
    int target = run.last;
    double limit = run.move == nav::Move::kWalk       ? limits.walk
                   : run.move == nav::Move::kSidestep ? limits.sidestep
                   : run.move == nav::Move::kCrawl    ? limits.crawl
                                                      : 1e9;
    double travelled = 0;
    for (int k = run.first + 1; k <= run.last; ++k) {
      const auto& a = plan.path[k - 1].pose_G;
      const auto& b = plan.path[k].pose_G;
      travelled += std::hypot(b.x - a.x, b.y - a.y);
      if (travelled >= limit) {
        target = k;
        break;
      }
    }
    const nav::PathPose& goal_pose = plan.path[target];
    last_plan = plan;
    last_plan_at = size_t(target);
    const Eigen::Vector3d delta = Relative(believed, goal_pose.pose_G);
    current_move = nav::MoveName(run.move);
    switch (run.move) {
      case nav::Move::kStairsUp:
      case nav::Move::kStairsDown: {
        // face the step first; a step aside within the climb's own limit (and 5 mm of the
        // believed pose's offset from the plan's cell, which step_onto clamps) is taken with it
        const bool aside =
            std::abs(delta.y()) <= controller_params.limits.max_climb_sideways + 0.005;
        if (std::abs(delta.z()) > 0.05 || !aside) {
          controller.Walk(0, aside ? 0.0 : delta.y(), delta.z());
        }
        step_onto({believed.x, believed.y, goal_pose.pose_G.yaw},
                  plan.path[size_t(run.first)].floor_z, goal_pose, delta.x(),
                  aside ? delta.y() : 0.0);
        break;
      }
      case nav::Move::kCrawl:
        if (run.posture == nav::Posture::kCrawling && controller.mode() == sim::Mode::kStanding) {
          if (HighCeilingNear(fog, believed, believed_floor_z, limits.high_ceiling_range,
                              limits.high_ceiling)) {
            look_up_before_crawling(plan, size_t(run.first), believed);
          }
          controller.GetDown();
        } else if (run.posture == nav::Posture::kUpright &&
                   controller.mode() == sim::Mode::kCrawling) {
          controller.GetUp();
        } else {
          controller.Crawl(delta.x(), delta.z());
        }
        break;
      case nav::Move::kTurn:
        if (controller.mode() == sim::Mode::kCrawling) {
          controller.Crawl(0, delta.z());
        } else {
          controller.Walk(0, 0, delta.z());
        }
        break;
      default: {
        // walking up to a step whose edge was measured: the toes stop toe_margin short of it
        // (the walk is cut by at most edge_correction), and where that is short of the plan's
        // pose the step follows from there at once
        double dx = delta.x();
        const size_t next = size_t(target) + 1;
        double e = std::numeric_limits<double>::quiet_NaN();
        if (run.move == nav::Move::kWalk && next < plan.path.size() && dx > 0 &&
            plan.path[next].move == nav::Move::kStairsUp && std::abs(delta.y()) < 0.02 &&
            std::abs(delta.z()) < 0.05) {
          e = edge_ahead(believed, goal_pose.floor_z, plan.path[next].floor_z,
                         dx + step_reach);
        }
        const double toes = e - humanoid.sole_half_length() - limits.toe_margin;
        if (!std::isfinite(e) || toes >= dx) {
          controller.Walk(dx, delta.y(), delta.z());
          break;
        }
        dx = std::max({0.0, toes, dx - limits.edge_correction});
        if (dx > 0) {
          controller.Walk(dx, delta.y(), delta.z());
          ++actions[current_move];
          run_controller();
        }
        current_move = nav::MoveName(nav::Move::kStairsUp);
        last_plan_at = next;
        const Eigen::Vector3d step = Relative(goal_pose.pose_G, plan.path[next].pose_G);
        step_onto(ToPerception(controller.believed_pose()), goal_pose.floor_z, plan.path[next],
                  step.x() + delta.x() - dx, step.y());
        break;
      }
    }
    ++actions[current_move];
    run_controller();

    // look where the robot is going, then perceive
    const perception::Pose2 at = ToPerception(controller.believed_pose());
    if (controller.mode() == sim::Mode::kCrawling) {
      look(head_at_elevation(0.0, kCrawlElevations[size_t(cycle) % kCrawlElevations.size()]));
    } else if (limits.level_views && cycle % 2 == 0 &&
               !UnknownAhead(fog, plan, size_t(target), at, limits.look_ahead) &&
               HighCeilingNear(fog, at, believed_floor_z, limits.high_ceiling_range,
                               limits.high_ceiling)) {
      look(head_at_elevation(PanToward(plan, size_t(target), at, limits.look_ahead,
                                       [](const nav::PathPose&) { return true; }),
                             0.0));
    } else {
      look(kCycleViews[size_t(cycle) % kCycleViews.size()]);
    }
    just_looked = false;
    measure_edges();

    // crawling, the forward views rarely hold a wall: once unsure of the heading (noisy
    // odometry only; noise-free odometry is exact), look to both sides for one
    if (controller.mode() == sim::Mode::kCrawling &&
        std::sqrt(localization.PoseCovariance()(2, 2)) > limits.lost_yaw) {
      for (const double pan : {limits.side_look_pan, -limits.side_look_pan}) {
        look(head_at_elevation(pan, 0.0));
      }
    }

    // a plan into cells never seen: look around once the robot has moved on
    int ix, iy;
    fog.window.CellOf(goal_pose.pose_G.x, goal_pose.pose_G.y, &ix, &iy);
    const perception::Pose2 now = ToPerception(controller.believed_pose());
    if (fog.window.Contains(ix, iy) && fog.TypeAt(ix, iy) == perception::CellType::kUnknown &&
        std::hypot(now.x - looked_at.x, now.y - looked_at.y) > 0.5) {
      look_around();
      looked_at = now;
      just_looked = true;
    }

    if (options.dump_every > 0 && cycle % options.dump_every == 0) {
      char name[32];
      std::snprintf(name, sizeof(name), "cycle%04d", cycle);
      WriteViewFrames(last_stereo, last_view, options.out_dir + "/frames", name);
      MakeOutputFolder(options.out_dir + "/maps");
      WritePng(viz::DrawPlanPicture(fog, believed, plan, scenario.goal),
               options.out_dir + "/maps/" + name + "_plan.png");
    }
    if (progress) {
      std::fprintf(stderr, "\rcycle %4d  goal %5.2f m  %-11s  %6.1f s", cycle, true_goal_distance(),
                   current_move.c_str(), Ms(wall_start) / 1000);
    }
  }
  log_cycle();
  flush_logs();
  if (progress) std::fprintf(stderr, "\n");

  // scores against the ground truth
  const double goal_distance = true_goal_distance();
  const bool reached_goal = goal_distance <= scenario.goal_tolerance;
  const perception::Pose2 believed = ToPerception(controller.believed_pose());
  const perception::Pose2 truth_pose = ToPerception(controller.TruePose(d));
  const Eigen::Isometry3d X_GW =
      perception::Planar(believed) * perception::Planar(truth_pose).inverse();
  fog = perception::ComputeFog(perception_params.map, maps);
  const perception::Fog truth_fog = TruthFog(scenario, fog.window, perception_params.map.fog, X_GW);
  const perception::FogScore fog_score =
      perception::ScoreFog(fog, truth_fog, perception_params.map.fog);

  // the planner's path on the ground-truth FOG of the whole floor, for SPL
  perception::GridWindow whole;
  whole.resolution = perception_params.map.grid.resolution;
  Eigen::Vector2d lo = scenario.floor_center - scenario.floor_size / 2;
  whole.origin_ix = int(std::floor(lo.x() / whole.resolution)) - 2;
  whole.origin_iy = int(std::floor(lo.y() / whole.resolution)) - 2;
  whole.size_x = int(std::ceil(scenario.floor_size.x() / whole.resolution)) + 4;
  whole.size_y = int(std::ceil(scenario.floor_size.y() / whole.resolution)) + 4;
  const perception::Fog world_fog = TruthFog(scenario, whole, perception_params.map.fog);
  const nav::PlanResult optimal =
      PlanToGoal(world_fog, scenario.start, scenario, planner_params, nav::Posture::kUpright);
  const double optimal_length =
      optimal.status == nav::PlanStatus::kOk && optimal.reaches_goal ? optimal.length : 0.0;
  const double spl = reached_goal && optimal_length > 0
                         ? optimal_length / std::max(path_length, optimal_length)
                         : 0.0;

  // expectations
  bool success = true;
  const Expectations& expect = scenario.expect;
  if (expect.reach_goal && *expect.reach_goal != reached_goal) success = false;
  for (const auto& action : expect.actions_used) success = success && actions[action] > 0;
  if (expect.no_collision.value_or(false) && !controller.collisions().empty()) success = false;
  // reach_goal: false alone expects the mission to end short of the goal, whatever the failure;
  // `failure` names the one it must end with; an interrupted mission never succeeds
  if (expect.failure) {
    success = success && failure == *expect.failure;
  } else if (!failure.empty() && expect.reach_goal.value_or(true) &&
             !(failure == "collision" && !expect.no_collision.value_or(false))) {
    success = false;
  }
  if (failure == "interrupted") success = false;

  // pictures of the end state
  MakeOutputFolder(options.out_dir + "/frames");
  WriteViewFrames(last_stereo, last_view, options.out_dir + "/frames", "final");
  viz::WriteMapPictures(options.out_dir + "/maps", fog, maps, perception_params.map, believed);
  WritePng(viz::DrawPlanPicture(fog, believed, plan, scenario.goal),
           options.out_dir + "/maps/final_plan.png");
  WritePng(viz::DrawFog(truth_fog, believed), options.out_dir + "/maps/fog_truth.png");
  WritePng(viz::DrawFogErrors(fog, truth_fog, perception_params.map.fog, believed),
           options.out_dir + "/maps/fog_errors.png");
  viz::WriteFogTypes(options.out_dir + "/maps/fog_truth_types.png", truth_fog);
  WritePng(viz::DrawPlanPicture(world_fog, scenario.start, optimal, scenario.goal),
           options.out_dir + "/maps/optimal_plan.png");

  nlohmann::json collisions = nlohmann::json::array();
  for (const sim::Collision& c : controller.collisions()) {
    collisions.push_back({{"tick", c.tick}, {"robot", c.robot_name}, {"world", c.world_name},
                          {"depth", c.depth}});
  }
  nlohmann::json timing_ms = nlohmann::json::object();
  for (const char* stage : {"render", "stereo", "segmentation", "mapping", "planning", "control"}) {
    timing_ms[stage] = perception::Median(timing[stage]);
  }
  // the slow plans: the planning stage's 95th percentile (nearest rank) and maximum
  std::vector<double> plan_ms = timing["planning"];
  std::sort(plan_ms.begin(), plan_ms.end());
  timing_ms["planning_p95"] =
      plan_ms.empty() ? 0.0 : plan_ms[size_t(std::ceil(0.95 * double(plan_ms.size()))) - 1];
  timing_ms["planning_max"] = plan_ms.empty() ? 0.0 : plan_ms.back();
  nlohmann::json report = {
      {"scenario", scenario.name},
      {"success", success},
      {"reached_goal", reached_goal},
      {"goal_distance", goal_distance},
      {"failure", failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(failure)},
      {"failure_detail", failure_detail.empty() ? nlohmann::json(nullptr)
                                                : nlohmann::json(failure_detail)},
      {"cycles", cycle},
      {"steps", controller.steps()},
      {"actions", actions},
      {"collisions", controller.collisions().size()},
      {"collision_list", collisions},
      {"path_length", path_length},
      {"optimal_path_length", optimal_length},
      {"spl", spl},
      {"fog", FogScoreJson(fog_score)},
      {"fog_accuracy", fog_score.accuracy},
      {"floor_height_error",
       {{"median", fog_score.height_error_median}, {"max", fog_score.height_error_max}}},
      {"final_pose", {{"true", {truth_pose.x, truth_pose.y, truth_pose.yaw}},
                      {"odometry", {believed.x, believed.y, believed.yaw}}}},
      {"wall_time_s", Ms(wall_start) / 1000},
      {"timing_ms", timing_ms},
      {"params", ParamsJson(run_params)}};
  MissionOutcome outcome;
  outcome.success = success;
  outcome.reached_goal = reached_goal;
  outcome.failure = failure;
  outcome.report_json = report.dump(2);
  WriteFileAtomically(options.out_dir + "/report.json", outcome.report_json + "\n");
  // the page reads the tables back: they must be complete
  trajectory.close();
  cycles_csv.close();
  viz::WriteMissionPage(options.out_dir, world_fog, optimal, scenario.start, scenario.goal,
                        options.video_path);
  return outcome;
}

}  // namespace fognav::scenarios

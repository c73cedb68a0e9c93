#include "scenarios/internal/mission_robot.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "scenarios/output.h"
#include "scenarios/views.h"
#include "viz/pictures.h"

namespace fognav::scenarios::internal {
namespace {

namespace nav = navigation;
using Clock = std::chrono::steady_clock;
using perception::Pose2;

double Ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// displacement (dx, dy in the frame of `from`, dyaw) from one planar pose to another
Eigen::Vector3d Relative(const Pose2& from, const Pose2& to) {
  double c = std::cos(from.yaw), s = std::sin(from.yaw);
  double dx = to.x - from.x, dy = to.y - from.y;
  return {c * dx + s * dy, -s * dx + c * dy, WrapAngle(to.yaw - from.yaw)};
}

// head views of the cycles while moving: ahead and to both sides of the path, near and far
const std::vector<sim::HeadAngles> kCycleViews = {
    {0.0, 0.75}, {0.45, 0.6}, {0.0, 0.4}, {-0.45, 0.6}, {0.0, 0.15}};
// while crawling: the camera's elevation above the horizon (rad), up to see an underside
// overhead (0.3 is about the neck's limit in the crawl posture; the head's top is then at
// 0.30 m, the lowest ceiling of a tunnel), down to see the floor ahead
const std::vector<double> kCrawlElevations = {0.3, -0.6};

// Whether a tunnel cell within `range` of `at` has its ceiling at least `height` above floor_z.
bool HighCeilingNear(const perception::Fog& fog, const Pose2& at, double floor_z, double range,
                     double height) {
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
                  const Pose2& at, double range) {
  for (size_t k = first; k < plan.path.size(); ++k) {
    const Pose2& q = plan.path[k].pose_G;
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
double PanToward(const nav::PlanResult& plan, size_t first, const Pose2& from, double ahead,
                 Take take) {
  double pan = 0;
  for (size_t k = first; k < plan.path.size() && take(plan.path[k]); ++k) {
    const Pose2& q = plan.path[k].pose_G;
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
void ForCellsUnder(const Pose2& robot, double along, double across, double resolution, Fn fn) {
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

// The floor under the standing robot is known without looking: it stands on it. The body hides
// it from the eyes, so where the robot came by a way it did not look at, unknown cells lay
// around its feet and barred the moves the eyes do not look along (a side-step out of a narrow
// gap's mouth). Unknown cells that the standing footprint covers (centres inside it grown by
// half a cell) become floor at the believed floor height, except beside a floor or stairs cell
// on another level (more than h_floor off): the toes may reach past a step's edge there, and a
// cell marked on the robot's level would move the edge under the landing of the step down.
void MarkFloorUnderFeet(const nav::PlannerParams& p, const Pose2& robot, double floor_z,
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

// a log with its header line, on the disk
std::ofstream OpenLog(const std::string& path, const char* header) {
  std::ofstream log(path);
  if (!log) throw OutputError(path + ": cannot write");
  errno = 0;
  if (!(log << header).flush()) {
    throw OutputError(path + ": cannot write: " +
                      (errno != 0 ? std::strerror(errno) : "the stream failed"));
  }
  return log;
}

}  // namespace

double StepEdge::Ahead(const Pose2& from, double from_z, double to_z, double h_floor) const {
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

namespace {
sim::ControllerParams ControllerParamsFor(const Scenario& scenario) {
  sim::ControllerParams p;
  p.odometry_noise_xy = scenario.odometry_noise_xy;
  p.odometry_noise_yaw = scenario.odometry_noise_yaw;
  p.odometry_stride_scale = scenario.odometry_stride_scale;
  p.odometry_yaw_bias = scenario.odometry_yaw_bias;
  p.seed = unsigned(scenario.seed);
  return p;
}
}  // namespace

MissionRobot::MissionRobot(const Scenario& scenario, const RunParams& params,
                           const MissionOptions& options, nav::PlannerParams* planner)
    : scenario_(scenario),
      options_(options),
      perception_(params.perception),
      limits_(params.mission),
      edge_params_(params.step_edge),
      planner_(*planner),
      trajectory_(OpenLog(options.out_dir + "/trajectory.csv",
                          "step,tick,true_x,true_y,true_yaw,odom_x,odom_y,odom_yaw,action,"
                          "settled\n")),
      cycles_(OpenLog(options.out_dir + "/cycles.csv",
                      "cycle,step,odom_x,odom_y,odom_yaw,posture,plan,plan_cost,plan_length,"
                      "decision,target_x,target_y,explorations,thrashes\n")),
      controller_params_(ControllerParamsFor(scenario)),
      world_(MakeWorldSpec(scenario)),
      controller_(world_.model(), controller_params_),
      renderer_(world_.model()),
      humanoid_(controller_.humanoid()) {
  if (!options.video_path.empty()) {
    video_ = std::make_unique<MissionVideo>(options.video_path, options.video_fps);
  }
  video_every_ =
      std::max(1, int(std::lround(options.video_period_s * controller_params_.control_rate_hz)));
  planner->kneel_offset = controller_.KneelOffset();
  // steps up and down as long and as far aside as the controller takes them
  planner->max_step_length = controller_params_.limits.max_climb_forward;
  planner->max_step_sideways = controller_params_.limits.max_climb_sideways;
  step_reach_ = controller_params_.limits.max_climb_forward + limits_.edge_correction;
  controller_.Reset(scenario.start, 0.0, world_.model(), world_.data());
  const double xy = scenario.odometry_noise_xy, yaw = scenario.odometry_noise_yaw;
  step_covariance_ = Eigen::Vector3d(xy * xy, xy * xy, yaw * yaw).asDiagonal();
  for (const auto& name : ActionNames()) actions_[name] = 0;
  last_true_ = TruePose();
  predicted_from_ = believed();
  NoteWalked(believed());
}

void MissionRobot::NoteWalked(const Pose2& at) {
  ForCellsUnder(at, 0.5 * planner_.depth, 0.5 * planner_.shoulder_width,
                perception_.map.grid.resolution, [&](int gx, int gy) { walked_.insert({gx, gy}); });
}

Pose2 MissionRobot::believed() const { return controller_.believed_pose(); }

Pose2 MissionRobot::TruePose() const { return controller_.TruePose(world_.data()); }

nav::Posture MissionRobot::posture() const {
  return controller_.mode() == sim::Mode::kCrawling ? nav::Posture::kCrawling
                                                    : nav::Posture::kUpright;
}

double MissionRobot::TrueGoalDistance() const {
  const Pose2 t = TruePose();
  return std::hypot(t.x - scenario_.goal.x(), t.y - scenario_.goal.y());
}

std::string MissionRobot::SupportOffFloor() const {
  using sim::Side;
  const mjData* d = world_.data();
  std::vector<std::pair<std::string, int>> supports;
  for (const Side s : {Side::kLeft, Side::kRight}) {
    const std::string side = s == Side::kLeft ? "left " : "right ";
    if (controller_.mode() == sim::Mode::kCrawling) {
      supports.push_back({side + "knee", humanoid_.knee_geom(s)});
      supports.push_back({side + "hand", humanoid_.hand_geom(s)});
    } else {
      supports.push_back({side + "sole", humanoid_.sole_geom(s)});
    }
  }
  for (const auto& [name, geom] : supports) {
    const Eigen::Vector2d p(d->geom_xpos[3 * geom], d->geom_xpos[3 * geom + 1]);
    if (!OverFloor(scenario_, p)) {
      char where[64];
      std::snprintf(where, sizeof(where), " at (%.2f, %.2f)", p.x(), p.y());
      return name + where + " beyond the floor's edge";
    }
  }
  return "";
}

perception::Fog MissionRobot::PlanningFog() const {
  perception::Fog fog = perception::ComputeFog(perception_.map, maps_);
  if (controller_.mode() == sim::Mode::kStanding) {
    MarkFloorUnderFeet(planner_, believed(), believed_floor_z_, &fog);
  }
  const perception::GridWindow& w = fog.window;
  fog.walked.assign(size_t(w.NumCells()), 0);
  for (const auto& [gx, gy] : walked_) {
    const int ix = gx - w.origin_ix, iy = gy - w.origin_iy;
    if (w.Contains(ix, iy)) fog.walked[size_t(w.Index(ix, iy))] = 1;
  }
  return fog;
}

void MissionRobot::FadeGrid(double keep) { perception::FadeGrid(perception_.map, keep, &maps_); }

void MissionRobot::FlushLogs() {
  const std::pair<std::ofstream*, const char*> logs[] = {{&trajectory_, "trajectory.csv"},
                                                         {&cycles_, "cycles.csv"}};
  for (const auto& [log, name] : logs) {
    errno = 0;
    if (!log->flush()) {
      throw OutputError(options_.out_dir + "/" + name + ": cannot write: " +
                        (errno != 0 ? std::strerror(errno) : "the stream failed"));
    }
  }
}

void MissionRobot::LogCycle(const std::string& row) {
  cycles_ << row;
  FlushLogs();
}

void MissionRobot::CloseLogs() {
  FlushLogs();
  trajectory_.close();
  cycles_.close();
}

void MissionRobot::ShowPlan(const perception::Fog& fog, const nav::PlanResult& plan) {
  if (video_) video_plan_picture_ = viz::DrawPlanPicture(fog, believed(), plan, scenario_.goal);
}

void MissionRobot::WriteCycleFrames(const std::string& name, const perception::Fog& fog,
                                    const Pose2& from, const nav::PlanResult& plan) {
  WriteViewFrames(last_stereo_, last_view_, options_.out_dir + "/frames", name);
  MakeOutputFolder(options_.out_dir + "/maps");
  WritePng(viz::DrawPlanPicture(fog, from, plan, scenario_.goal),
           options_.out_dir + "/maps/" + name + "_plan.png");
}

// the video's frame: the chase camera now, the last head image, the last plan picture
void MissionRobot::AddVideoFrame() {
  const Pose2 t = TruePose();
  const sim::PinholeCamera chase = sim::PinholeCamera::FromFov(
      ChaseCamera(t.x, t.y, t.yaw, believed_floor_z_), MissionVideo::kPanelWidth,
      MissionVideo::kPanelHeight, 1.0);
  const sim::RenderedView view = renderer_.Render(world_.model(), world_.data(), chase,
                                                  {false, false});
  perception::RgbImage chase_image(view.width, view.height);
  for (size_t i = 0; i < chase_image.data.size(); ++i) {
    chase_image.data[i] = {view.rgb[3 * i], view.rgb[3 * i + 1], view.rgb[3 * i + 2]};
  }
  char status[160];
  std::snprintf(status, sizeof(status), "%s   cycle %d   %s   goal %.2f m   t %.1f s",
                scenario_.name.c_str(), cycle_, current_move_.c_str(),
                std::hypot(t.x - scenario_.goal.x(), t.y - scenario_.goal.y()),
                controller_.ticks() * controller_.dt());
  video_->Add(chase_image, last_stereo_.left, video_plan_picture_, status);
}

// logs every footstep and accumulates the ground-truth path
void MissionRobot::OnTick() {
  if (video_ && controller_.ticks() % video_every_ == 0) AddVideoFrame();
  if (controller_.steps() == last_step_logged_) return;
  last_step_logged_ = controller_.steps();
  const Pose2 t = TruePose(), o = believed();
  path_length_ += std::hypot(t.x - last_true_.x, t.y - last_true_.y);
  last_true_ = t;
  char row[256];
  const bool settled = controller_.settled();
  std::snprintf(row, sizeof(row), "%d,%d,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%s,%d\n",
                controller_.steps(), controller_.ticks(), t.x, t.y, t.yaw, o.x, o.y, o.yaw,
                current_move_.c_str(), settled ? 1 : 0);
  trajectory_ << row;
  if (settled) {
    settled_errors_.push_back({std::hypot(o.x - t.x, o.y - t.y), std::abs(WrapAngle(o.yaw - t.yaw)),
                               path_length_});
  }
  if (controller_.mode() == sim::Mode::kStanding) NoteWalked(o);
}

void MissionRobot::RunController() {
  const auto start = Clock::now();
  // views while walking feed the visual odometry; with exact odometry there is nothing to track
  const bool tracking = perception_.localization.mode == perception::LocalizationMode::kVisual &&
                        (step_covariance_.trace() > 0 || scenario_.odometry_stride_scale > 0 ||
                         scenario_.odometry_yaw_bias > 0);
  const int every = tracking ? perception_.view_every_steps : 0;
  int last_view_steps = controller_.steps();
  double perceive_ms = 0;
  controller_.RunUntilIdle(world_.model(), world_.data(), [&](int) {
    OnTick();
    // views while walking, where a stride has just ended (the believed pose holds then)
    if (every > 0 && controller_.settled() && controller_.steps() - last_view_steps >= every &&
        !controller_.Idle()) {
      last_view_steps = controller_.steps();
      const auto perceive_start = Clock::now();
      Perceive();
      perceive_ms += Ms(perceive_start);
    }
  });
  Predict();
  timing_["control"].push_back(Ms(start) - perceive_ms);
}

// Propagates the filter over the footsteps since the last prediction; in mode truth the belief
// is the truth.
void MissionRobot::Predict() {
  const Pose2 now = believed();
  perception::PredictPose(predicted_from_, now,
                          IncrementCovariance(predicted_from_, now,
                                              controller_.steps() - predicted_steps_),
                          &localization_);
  if (perception_.localization.mode == perception::LocalizationMode::kTruth) {
    controller_.CorrectBelievedPose(TruePose());
  }
  predicted_from_ = believed();
  predicted_steps_ = controller_.steps();
}

// The odometry's covariance over `steps` footsteps from `before` to `after`, in the robot frame
// of `before`: the random walk per footstep and the systematic part, whole over the increment
// (the stride scale along the displacement, the yaw bias for every footstep).
Eigen::Matrix3d MissionRobot::IncrementCovariance(const Pose2& before, const Pose2& after,
                                                  int steps) const {
  Eigen::Matrix3d covariance = steps * step_covariance_;
  const Eigen::Vector3d d_R = Relative(before, {after.x, after.y, 0});
  const Eigen::Vector2d d(d_R.x(), d_R.y());
  const double s = scenario_.odometry_stride_scale, b = scenario_.odometry_yaw_bias * steps;
  covariance.topLeftCorner<2, 2>() += s * s * d * d.transpose();
  covariance(2, 2) += b * b;
  return covariance;
}

// one perception cycle at the head's current pose
void MissionRobot::Perceive() {
  Predict();
  const auto start = Clock::now();
  const mjData* d = world_.data();
  last_stereo_ = RenderStereo(&renderer_, world_,
                              sim::HeadCameraPoseInWorld(humanoid_, d, sim::Eye::kLeft),
                              scenario_.sensor);
  timing_["render"].push_back(Ms(start));
  last_view_ = PerceiveView(perception_, scenario_.sensor.depth, last_stereo_, humanoid_,
                            believed(), believed_floor_z_,
                            sim::HeadCameraPose(humanoid_, d, sim::Eye::kLeft),
                            sim::RobotBodyBoxes(humanoid_, world_.model(), d), &maps_,
                            &localization_);
  timing_["stereo"].push_back(last_view_.stereo_ms);
  timing_["segmentation"].push_back(last_view_.segmentation_ms);
  timing_["mapping"].push_back(last_view_.mapping_ms);
  timing_["localization"].push_back(last_view_.localization_ms);
  controller_.CorrectBelievedPose(last_view_.robot_G);
  predicted_from_ = believed();
}

// turns the head to `view` and perceives
void MissionRobot::Look(const sim::HeadAngles& view) {
  controller_.MoveHead(view);
  RunController();
  Perceive();
}

void MissionRobot::LookAround() {
  current_move_ = "look";
  for (const sim::HeadAngles& view : StartSweep()) Look(view);
}

// the neck angles that give the camera the wanted pan and elevation above the horizon, from its
// kinematic pose
sim::HeadAngles MissionRobot::HeadAtElevation(double pan, double wanted_elevation) const {
  const mjData* d = world_.data();
  const Eigen::Vector3d forward_R =
      sim::HeadCameraPose(humanoid_, d, sim::Eye::kLeft).rotation().col(2);
  const double elevation = std::asin(std::clamp(forward_R.z(), -1.0, 1.0));
  const double tilt = d->qpos[humanoid_.joint_qpos(sim::kNeckTilt)];
  return sim::HeadAngles{pan, tilt + elevation - wanted_elevation};
}

void MissionRobot::LookAtFloor(const Eigen::Vector2d& target, double floor_z) {
  const Eigen::Vector3d to = Relative(believed(), {target.x(), target.y(), 0});
  const Eigen::Vector3d camera_R =
      sim::HeadCameraPose(humanoid_, world_.data(), sim::Eye::kLeft).translation();
  const double below = camera_R.z() + believed_floor_z_ - floor_z;
  const double run_out = std::hypot(to.x() - camera_R.x(), to.y() - camera_R.y());
  Look(HeadAtElevation(std::atan2(to.y(), to.x()), -std::atan2(below, run_out)));
}

// Before getting down for the plan's crawl from path[first]: the standing eyes look up
// (ExecutionLimits::underside_elevation) toward the crawl's pose look_ahead on (or its last)
// and to both sides of it.
void MissionRobot::LookUpBeforeCrawling(const nav::PlanResult& plan, size_t first) {
  const double toward =
      PanToward(plan, first + 1, believed(), limits_.look_ahead,
                [](const nav::PathPose& q) { return q.posture == nav::Posture::kCrawling; });
  const std::string move = current_move_;
  current_move_ = "look";
  const double side = limits_.side_look_pan;
  for (const double pan : {toward, toward + side, toward - side}) {
    Look(HeadAtElevation(pan, limits_.underside_elevation));
  }
  current_move_ = move;
}

template <typename Which>
void MissionRobot::ForgetEdges(Which which) {
  edges_.erase(std::remove_if(edges_.begin(), edges_.end(), which), edges_.end());
}

// the distance along from.yaw to the nearest measured edge between these levels within `reach`
// ahead (or 5 cm behind), or NaN
double MissionRobot::EdgeAhead(const Pose2& from, double from_z, double to_z,
                               double reach) const {
  double nearest = std::numeric_limits<double>::quiet_NaN();
  for (const StepEdge& e : edges_) {
    const double ahead = e.Ahead(from, from_z, to_z, planner_.h_floor);
    if (ahead >= -0.05 && ahead <= reach &&
        (std::isnan(nearest) || std::abs(ahead) < std::abs(nearest))) {
      nearest = ahead;
    }
  }
  return nearest;
}

// the edge of the step into path[j] from the last view, if it is in view and not too near
// `now`; a new measurement of an edge replaces the old one
bool MissionRobot::MeasureEdge(const nav::PlanResult& plan, size_t j, const Pose2& now) {
  const nav::PathPose& pre = plan.path[j - 1];
  const double floor_z = pre.floor_z, to_z = plan.path[j].floor_z;
  const double e = perception::MeasureStepEdge(edge_params_, last_view_.labelled_G, pre.pose_G,
                                               floor_z, to_z);
  if (!std::isfinite(e)) return false;
  const Eigen::Vector2d point = Eigen::Vector2d(pre.pose_G.x, pre.pose_G.y) +
                                e * Eigen::Vector2d(std::cos(pre.pose_G.yaw),
                                                    std::sin(pre.pose_G.yaw));
  if ((point - Eigen::Vector2d(now.x, now.y)).norm() < limits_.edge_min_range) return false;
  const StepEdge measured{point, pre.pose_G.yaw, floor_z, to_z};
  ForgetEdges([&](const StepEdge& old) {
    return std::abs(old.Ahead(pre.pose_G, floor_z, to_z, planner_.h_floor) - e) < 0.1;
  });
  edges_.push_back(measured);
  return true;
}

// Measures the step edges on `plan` within edge_lookahead of path[reached]; where the next step
// is not measured yet, looks at where the plan puts its riser, as the paper's robot stops to
// look at the stairs, while it is far enough for the body not to hide it.
void MissionRobot::MeasureEdges(const nav::PlanResult& plan, size_t reached) {
  if (plan.status != nav::PlanStatus::kOk) return;
  const std::vector<nav::PathPose>& path = plan.path;
  const Pose2 now = believed();
  // edges left far behind or aside (the plan went another way) are forgotten
  ForgetEdges([&](const StepEdge& edge) {
    return (edge.point_G - Eigen::Vector2d(now.x, now.y)).norm() > 2.0;
  });
  double ahead = 0;  // path length from the robot
  size_t first_step = 0;
  for (size_t j = reached + 1; j < path.size(); ++j) {
    ahead += std::hypot(path[j].pose_G.x - path[j - 1].pose_G.x,
                        path[j].pose_G.y - path[j - 1].pose_G.y);
    if (ahead > limits_.edge_lookahead) break;
    if (path[j].move != nav::Move::kStairsUp && path[j].move != nav::Move::kStairsDown) continue;
    const bool measured = MeasureEdge(plan, j, now);
    if (first_step == 0 && !measured &&
        !std::isfinite(EdgeAhead(path[j - 1].pose_G, path[j - 1].floor_z, path[j].floor_z,
                                 step_reach_))) {
      first_step = j;
    }
  }
  if (first_step == 0) return;
  const nav::PathPose& pre = path[first_step - 1];
  const nav::PathPose& post = path[first_step];
  const Eigen::Vector2d riser(0.5 * (pre.pose_G.x + post.pose_G.x),
                              0.5 * (pre.pose_G.y + post.pose_G.y));
  const double range = (riser - Eigen::Vector2d(now.x, now.y)).norm();
  if (range < limits_.edge_min_range || range > limits_.edge_look_range) return;
  LookAtFloor(riser, std::max(pre.floor_z, post.floor_z));
  MeasureEdge(plan, first_step, now);
}

// One step up or down from `from` (facing the step, on a floor from_z high) onto the level of
// `onto`, planned dx_plan forward and dy_plan to the left: with the step's measured edge the
// heel lands heel_margin past it (stepping down, at least that far), at most edge_correction
// from the plan's landing, walking closer first where that is beyond the longest step.
void MissionRobot::StepOnto(const Pose2& from, double from_z, const nav::PathPose& onto,
                            double dx_plan, double dy_plan) {
  const sim::StepLimits& step_limits = controller_params_.limits;
  double dz = std::isfinite(onto.floor_z) ? onto.floor_z - believed_floor_z_ : 0.0;
  dz = std::clamp(dz, -step_limits.max_climb_height, step_limits.max_climb_height);
  double dx = dx_plan;
  const double e = EdgeAhead(from, from_z, onto.floor_z, step_reach_);
  if (std::isfinite(e)) {
    const double heel = e + humanoid_.sole_half_length() + limits_.heel_margin;
    dx = std::clamp(heel, onto.floor_z > from_z ? dx - limits_.edge_correction : dx,
                    dx + limits_.edge_correction);
    // beyond the longest step: walk up to the edge first, the toes toe_margin short of it
    const double toes = e - humanoid_.sole_half_length() - limits_.toe_margin;
    const double closer = std::min(dx - step_limits.max_climb_forward, toes);
    if (closer > 0.002) {
      const std::string step_move = current_move_;
      current_move_ = nav::MoveName(nav::Move::kWalk);
      controller_.Walk(closer, 0, 0);
      ++actions_[current_move_];
      RunController();
      current_move_ = step_move;
      dx -= closer;
    }
  }
  dx = std::clamp(dx, 0.02, step_limits.max_climb_forward);
  controller_.StepOnto(
      dx, dz, std::clamp(dy_plan, -step_limits.max_climb_sideways, step_limits.max_climb_sideways));
  believed_floor_z_ += dz;
  // the edge stepped over is behind now
  ForgetEdges([&](const StepEdge& edge) {
    const double ahead = edge.Ahead(from, from_z, onto.floor_z, planner_.h_floor);
    return ahead >= -0.05 && ahead <= step_reach_;
  });
}

// A walk to path[target]; up to a step whose edge was measured, the toes stop toe_margin short
// of it (the walk is cut by at most edge_correction), and where that is short of the plan's
// pose the step follows from there at once (*reached becomes the step's pose).
void MissionRobot::WalkUpTo(const nav::PlanResult& plan, const nav::PathSegment& run,
                            size_t* reached) {
  const size_t target = size_t(run.last);
  const Pose2 from = believed();
  const nav::PathPose& goal_pose = plan.path[target];
  const Eigen::Vector3d delta = Relative(from, goal_pose.pose_G);
  double dx = delta.x();
  const size_t next = target + 1;
  double e = std::numeric_limits<double>::quiet_NaN();
  if (run.move == nav::Move::kWalk && next < plan.path.size() && dx > 0 &&
      plan.path[next].move == nav::Move::kStairsUp && std::abs(delta.y()) < 0.02 &&
      std::abs(delta.z()) < 0.05) {
    e = EdgeAhead(from, goal_pose.floor_z, plan.path[next].floor_z, dx + step_reach_);
  }
  const double toes = e - humanoid_.sole_half_length() - limits_.toe_margin;
  if (!std::isfinite(e) || toes >= dx) {
    controller_.Walk(dx, delta.y(), delta.z());
    return;
  }
  dx = std::max({0.0, toes, dx - limits_.edge_correction});
  if (dx > 0) {
    controller_.Walk(dx, delta.y(), delta.z());
    ++actions_[current_move_];
    RunController();
  }
  current_move_ = nav::MoveName(nav::Move::kStairsUp);
  *reached = next;
  const Eigen::Vector3d step = Relative(goal_pose.pose_G, plan.path[next].pose_G);
  StepOnto(believed(), goal_pose.floor_z, plan.path[next], step.x() + delta.x() - dx, step.y());
}

size_t MissionRobot::Execute(const nav::PlanResult& plan, const nav::PathSegment& run,
                             const perception::Fog& fog) {
  const size_t target = size_t(run.last);
  size_t reached = target;
  const Pose2 from = believed();
  const nav::PathPose& goal_pose = plan.path[target];
  const Eigen::Vector3d delta = Relative(from, goal_pose.pose_G);
  current_move_ = nav::MoveName(run.move);
  switch (run.move) {
    case nav::Move::kStairsUp:
    case nav::Move::kStairsDown: {
      // face the step first; a step aside within the climb's own limit (and 5 mm of the
      // believed pose's offset from the plan's cell, which StepOnto clamps) is taken with it
      const bool aside = std::abs(delta.y()) <= controller_params_.limits.max_climb_sideways + 0.005;
      if (std::abs(delta.z()) > 0.05 || !aside) controller_.Walk(0, aside ? 0.0 : delta.y(), delta.z());
      StepOnto({from.x, from.y, goal_pose.pose_G.yaw}, plan.path[size_t(run.first)].floor_z,
               goal_pose, delta.x(), aside ? delta.y() : 0.0);
      break;
    }
    case nav::Move::kCrawl:
      if (run.posture == nav::Posture::kCrawling && controller_.mode() == sim::Mode::kStanding) {
        if (HighCeilingNear(fog, from, believed_floor_z_, limits_.high_ceiling_range,
                            limits_.high_ceiling)) {
          LookUpBeforeCrawling(plan, size_t(run.first));
        }
        controller_.GetDown();
      } else if (run.posture == nav::Posture::kUpright &&
                 controller_.mode() == sim::Mode::kCrawling) {
        controller_.GetUp();
      } else {
        controller_.Crawl(delta.x(), delta.z());
      }
      break;
    case nav::Move::kTurn:
      if (controller_.mode() == sim::Mode::kCrawling) {
        controller_.Crawl(0, delta.z());
      } else {
        controller_.Walk(0, 0, delta.z());
      }
      break;
    default:
      WalkUpTo(plan, run, &reached);
      break;
  }
  ++actions_[current_move_];
  RunController();
  return reached;
}

std::optional<Pose2> MissionRobot::LookAfterMove(const nav::PlanResult& plan, const nav::PathSegment& run,
                                 size_t reached, const perception::Fog& fog,
                                 const Pose2& looked_at) {
  const size_t target = size_t(run.last);
  const Pose2 at = believed();
  if (controller_.mode() == sim::Mode::kCrawling) {
    Look(HeadAtElevation(0.0, kCrawlElevations[size_t(cycle_) % kCrawlElevations.size()]));
  } else if (limits_.level_views && cycle_ % 2 == 0 &&
             !UnknownAhead(fog, plan, target, at, limits_.look_ahead) &&
             HighCeilingNear(fog, at, believed_floor_z_, limits_.high_ceiling_range,
                             limits_.high_ceiling)) {
    Look(HeadAtElevation(PanToward(plan, target, at, limits_.look_ahead,
                                   [](const nav::PathPose&) { return true; }),
                         0.0));
  } else {
    Look(kCycleViews[size_t(cycle_) % kCycleViews.size()]);
  }
  MeasureEdges(plan, reached);
  // crawling, the forward views rarely hold a wall: once unsure of the heading (noisy odometry
  // only; noise-free odometry is exact), look to both sides for one
  if (controller_.mode() == sim::Mode::kCrawling &&
      std::sqrt(localization_.PoseCovariance()(2, 2)) > limits_.lost_yaw) {
    for (const double pan : {limits_.side_look_pan, -limits_.side_look_pan}) {
      Look(HeadAtElevation(pan, 0.0));
    }
  }
  // a plan into cells never seen: look around once the robot has moved on
  const Pose2& end = plan.path[target].pose_G;
  int ix, iy;
  fog.window.CellOf(end.x, end.y, &ix, &iy);
  const Pose2 now = believed();
  if (fog.window.Contains(ix, iy) && fog.TypeAt(ix, iy) == perception::CellType::kUnknown &&
      std::hypot(now.x - looked_at.x, now.y - looked_at.y) > 0.5) {
    LookAround();
    return now;
  }
  return std::nullopt;
}

}  // namespace fognav::scenarios::internal

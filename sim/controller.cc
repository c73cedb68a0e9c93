#include "sim/controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/internal/box_overlap.h"
#include "sim/render.h"

namespace fognav::sim {
namespace {

using internal::FootPlacement;
using internal::GroundFrame;
using internal::SmoothRamp;

Eigen::Matrix3d Rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
Eigen::Matrix3d Ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }

// the robot frame of two feet: midway between them, mean heading, on the lower surface
GroundFrame FeetFrame(const std::array<FootPlacement, 2>& feet) {
  const Eigen::Vector3d mid = 0.5 * (feet[0].p + feet[1].p);
  return {mid.x(), mid.y(), internal::LerpAngle(feet[0].yaw, feet[1].yaw, 0.5),
          std::min(feet[0].p.z(), feet[1].p.z())};
}

// flat feet side by side at a frame, stance_width apart
std::array<FootPlacement, 2> FeetAt(const GroundFrame& frame, double stance_width) {
  std::array<FootPlacement, 2> feet;
  for (int s = 0; s < 2; ++s) {
    feet[s].p = frame.PointAt(0, (s == 0 ? 0.5 : -0.5) * stance_width, 0);
    feet[s].yaw = frame.yaw;
  }
  return feet;
}

Pose2 Compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.yaw), s = std::sin(a.yaw);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, internal::WrapAngle(a.yaw + b.yaw)};
}

// relative displacement from frame a to frame b, in a
Pose2 Between(const GroundFrame& a, const GroundFrame& b) {
  const double c = std::cos(a.yaw), s = std::sin(a.yaw);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, internal::WrapAngle(b.yaw - a.yaw)};
}

// the n-th of `count` equal parts of the way from a to a.Then(dx, dy, dyaw), as a displacement
// from the (n-1)-th: straight in x, y with the heading turning evenly
Pose2 StrideDelta(double dx, double dy, double dyaw, int n, int count) {
  const GroundFrame start{};
  const GroundFrame goal = start.Then(dx, dy, dyaw);
  auto at = [&](int i) {
    const double s = double(i) / count;
    return GroundFrame{s * goal.x, s * goal.y, s * dyaw, 0};
  };
  return Between(at(n - 1), at(n));
}

std::string ContactName(const mjModel* m, int g) {
  if (const char* name = mj_id2name(m, mjOBJ_GEOM, g)) return name;
  if (const char* name = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g])) return name;
  return "geom " + std::to_string(g);
}

}  // namespace

std::vector<HeadAngles> LookAroundSweep(const LookAroundParams& params) {
  std::vector<HeadAngles> views;
  for (size_t t = 0; t < params.tilts.size(); ++t) {
    for (size_t i = 0; i < params.pans.size(); ++i) {
      const size_t k = t % 2 == 0 ? i : params.pans.size() - 1 - i;
      const double pan =
          t == 0 ? std::clamp(params.pans[k], -params.near_pan_limit, params.near_pan_limit)
                 : params.pans[k];
      views.push_back({pan, params.tilts[t]});
    }
  }
  views.push_back({0.0, params.tilts.empty() ? 0.0 : params.tilts.back()});
  return views;
}

Controller::Controller(const mjModel* m, const ControllerParams& params)
    : humanoid_(m), params_(params), rng_(params.seed) {}

void Controller::Reset(const Pose2& start, double surface_z, const mjModel* m, mjData* d) {
  Reset(start, surface_z, start, m, d);
}

void Controller::Reset(const Pose2& start, double surface_z, const Pose2& believed, const mjModel* m,
                       mjData* d) {
  queue_.clear();
  segment_tick_ = 0;
  collisions_.clear();
  touching_.clear();
  rng_.seed(params_.seed);
  // the systematic part has a generator of its own: the per-step stream stays as it was
  std::mt19937 systematic(params_.seed ^ 0x5eedu);
  std::normal_distribution<double> unit(0.0, 1.0);
  stride_scale_error_ = params_.odometry_stride_scale * unit(systematic);
  yaw_bias_error_ = params_.odometry_yaw_bias * unit(systematic);
  settled_ = true;
  steps_ = 0;
  tick_ = 0;
  believed_ = believed;
  mode_ = Mode::kStanding;
  head_ = {};
  const GroundFrame frame{start.x, start.y, start.yaw, surface_z};
  plan_ = Plan{};
  plan_.feet = FeetAt(frame, params_.stance_width);
  current_ = StandingPosture(plan_.feet);
  current_.q[kNeckPan] = head_.pan;
  current_.q[kNeckTilt] = head_.tilt;
  SetPosture(humanoid_, current_, d);
  mj_kinematics(m, d);
  mj_camlight(m, d);
  mj_collision(m, d);
  CheckContacts(m, d);
}

void Controller::RequireMode(Mode mode, const char* command) const {
  if (plan_.mode != mode) {
    throw std::logic_error(std::string("Controller::") + command + " needs the robot " +
                           (mode == Mode::kStanding ? "standing" : "crawling"));
  }
}

FootPlacement Controller::NoisyFoot(const GroundFrame& frame, int side) {
  FootPlacement f;
  f.p = frame.PointAt(0, (side == 0 ? 0.5 : -0.5) * params_.stance_width, 0);
  f.yaw = frame.yaw;
  std::normal_distribution<double> unit(0.0, 1.0);
  const double ex = unit(rng_), ey = unit(rng_), eyaw = unit(rng_);
  f.p.x() += params_.odometry_noise_xy * ex;
  f.p.y() += params_.odometry_noise_xy * ey;
  f.yaw = internal::WrapAngle(f.yaw + params_.odometry_noise_yaw * eyaw);
  return f;
}

void Controller::PushStride(double dx, double dy, double dyaw, double dz) {
  const GroundFrame from = FeetFrame(plan_.feet);
  // executed: the commanded stride with the systematic error (two footsteps of yaw bias)
  const double scale = 1 + stride_scale_error_;
  GroundFrame to = from.Then(scale * dx, scale * dy, dyaw + 2 * yaw_bias_error_);
  to.z = plan_.feet[0].p.z() + dz;
  // the foot on the side of the motion leads
  int lead = 0;
  if (dy < -1e-9 || (std::abs(dy) <= 1e-9 && dyaw < -1e-9)) lead = 1;
  const int step_ticks = std::max(1, int(std::lround(params_.step_time * params_.control_rate_hz)));
  // a side-step or a turn in place on one level (corrections for the odometry may move it a
  // few mm along)
  const bool sideways = dz == 0 && std::abs(dx) < std::max(std::abs(dy), 0.01);
  for (int k = 0; k < 2; ++k) {
    const int side = k == 0 ? lead : 1 - lead;
    Segment seg;
    seg.kind = Kind::kStep;
    seg.ticks = step_ticks;
    seg.feet_from = plan_.feet;
    seg.feet_to = plan_.feet;
    seg.feet_to[side] = NoisyFoot(to, side);
    seg.swing = side;
    seg.lift_z = std::max(seg.feet_from[side].p.z(), seg.feet_to[side].p.z()) +
                 (sideways ? params_.side_clearance : params_.swing_clearance);
    if (k == 1) seg.odometry = {dx, dy, dyaw};
    seg.settles = k == 1;
    seg.steps = 1;
    plan_.feet = seg.feet_to;
    queue_.push_back(seg);
  }
}

void Controller::Walk(double dx, double dy, double dyaw) {
  RequireMode(Mode::kStanding, "Walk");
  const StepLimits& l = params_.limits;
  const int n = internal::StrideCount(dx, dy, dyaw, l.max_forward, l.max_backward, l.max_sideways,
                                      l.max_turn);
  for (int i = 1; i <= n; ++i) {
    const Pose2 delta = StrideDelta(dx, dy, dyaw, i, n);
    PushStride(delta.x, delta.y, delta.yaw, 0);
  }
}

void Controller::StepOnto(double dx, double dz, double dy) {
  RequireMode(Mode::kStanding, "StepOnto");
  const StepLimits& l = params_.limits;
  if (!(dx >= 0 && dx <= l.max_climb_forward + 1e-9 && std::abs(dz) <= l.max_climb_height + 1e-9 &&
        std::abs(dy) <= l.max_climb_sideways + 1e-9)) {
    throw std::invalid_argument("StepOnto(" + std::to_string(dx) + ", " + std::to_string(dz) +
                                ", " + std::to_string(dy) + "): forward must be in [0, " +
                                std::to_string(l.max_climb_forward) + "] m, |height| at most " +
                                std::to_string(l.max_climb_height) + " m and |sideways| at most " +
                                std::to_string(l.max_climb_sideways) + " m");
  }
  PushStride(dx, dy, 0, dz);
}

void Controller::MoveHead(const HeadAngles& target) {
  Segment seg;
  seg.kind = Kind::kHead;
  seg.mode_after = plan_.mode;
  seg.head_from = plan_.head;
  seg.head_to = {std::clamp(target.pan, humanoid_.joint_min(kNeckPan), humanoid_.joint_max(kNeckPan)),
                 std::clamp(target.tilt, humanoid_.joint_min(kNeckTilt), humanoid_.joint_max(kNeckTilt))};
  const double angle = std::max(std::abs(seg.head_to.pan - seg.head_from.pan),
                                std::abs(seg.head_to.tilt - seg.head_from.tilt));
  seg.ticks = std::max(1, int(std::ceil(angle / params_.head_speed * params_.control_rate_hz)));
  plan_.head = seg.head_to;
  queue_.push_back(seg);
}

void Controller::GetDown() {
  RequireMode(Mode::kStanding, "GetDown");
  Segment seg;
  seg.kind = Kind::kTransition;
  seg.ticks = std::max(1, int(std::lround(params_.transition_time * params_.control_rate_hz)));
  seg.mode_after = Mode::kCrawling;
  seg.stand = FeetFrame(plan_.feet);
  seg.head_from = plan_.head;
  seg.head_to = {0.0, params_.crawl.neck_tilt};
  seg.odometry = {KneelOffset(), 0, 0};
  plan_.mode = Mode::kCrawling;
  plan_.crawl = seg.stand.Then(KneelOffset(), 0, 0);
  plan_.head = seg.head_to;
  queue_.push_back(seg);
}

void Controller::GetUp() {
  RequireMode(Mode::kCrawling, "GetUp");
  Segment seg;
  seg.kind = Kind::kTransition;
  seg.ticks = std::max(1, int(std::lround(params_.transition_time * params_.control_rate_hz)));
  seg.mode_after = Mode::kStanding;
  seg.getting_up = true;
  seg.stand = plan_.crawl.Then(-KneelOffset(), 0, 0);
  seg.head_from = plan_.head;
  seg.head_to = {0.0, 0.0};
  seg.odometry = {-KneelOffset(), 0, 0};
  plan_.feet = FeetAt(seg.stand, params_.stance_width);
  plan_.mode = Mode::kStanding;
  plan_.head = seg.head_to;
  queue_.push_back(seg);
}

void Controller::Crawl(double dx, double dyaw) {
  RequireMode(Mode::kCrawling, "Crawl");
  const StepLimits& l = params_.limits;
  const int n = internal::StrideCount(dx, 0, dyaw, l.max_crawl_forward, 0.5 * l.max_crawl_forward, 1,
                                      l.max_crawl_turn);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int i = 1; i <= n; ++i) {
    const Pose2 delta = StrideDelta(dx, 0, dyaw, i, n);
    Segment seg;
    seg.kind = Kind::kCrawlCycle;
    seg.mode_after = Mode::kCrawling;
    seg.ticks = std::max(1, int(std::lround(params_.crawl_cycle_time * params_.control_rate_hz)));
    seg.crawl_from = plan_.crawl;
    const double scale = 1 + stride_scale_error_;
    seg.crawl_to =
        plan_.crawl.Then(scale * delta.x, scale * delta.y, delta.yaw + 4 * yaw_bias_error_);
    // the executed cycle drifts like four footsteps would
    const double ex = unit(rng_), ey = unit(rng_), eyaw = unit(rng_);
    seg.crawl_to.x += 2 * params_.odometry_noise_xy * ex;
    seg.crawl_to.y += 2 * params_.odometry_noise_xy * ey;
    seg.crawl_to.yaw = internal::WrapAngle(seg.crawl_to.yaw + 2 * params_.odometry_noise_yaw * eyaw);
    seg.odometry = delta;
    seg.steps = 4;
    seg.settles = true;
    plan_.crawl = seg.crawl_to;
    queue_.push_back(seg);
  }
}

namespace {

JointPosture StandingOver(const Humanoid& h, const ControllerParams& params,
                     const std::array<FootPlacement, 2>& feet) {
  const GroundFrame f = FeetFrame(feet);
  const Eigen::Vector2d p_xy(f.x, f.y);
  const internal::LegGeometry& leg = h.leg(Side::kLeft);
  double z = f.z + leg.ankle_height + params.hip_height - leg.p_BH.z();
  z = std::min(z, internal::MaxBaseHeight(h, feet, p_xy, f.yaw, params.max_leg));
  JointPosture posture;
  internal::SetStandingArms(&posture);
  internal::SolveStance(h, feet, p_xy, z, f.yaw, &posture);
  return posture;
}

}  // namespace

JointPosture StandingPostureAt(const Humanoid& h, const Pose2& pose, double surface_z,
                          const ControllerParams& params) {
  return StandingOver(h, params, FeetAt({pose.x, pose.y, pose.yaw, surface_z}, params.stance_width));
}

JointPosture Controller::StandingPosture(const std::array<FootPlacement, 2>& feet) const {
  return StandingOver(humanoid_, params_, feet);
}

JointPosture Controller::StepPosture(const Segment& seg, double u) const {
  const double half_ds = 0.5 * params_.double_support;
  std::array<FootPlacement, 2> feet = seg.feet_from;
  const int sw = seg.swing;
  if (u >= 1 - half_ds) {
    feet[sw] = seg.feet_to[sw];
  } else if (u > half_ds) {
    feet[sw] = internal::SwingFoot(seg.feet_from[sw], seg.feet_to[sw], seg.lift_z,
                                   (u - half_ds) / (1 - 2 * half_ds));
  }

  // pelvis: from over the old feet to over the new ones, swaying towards the stance foot
  const GroundFrame a = FeetFrame(seg.feet_from), b = FeetFrame(seg.feet_to);
  const double s = SmoothRamp(u, 0, 1);
  Eigen::Vector2d p_xy(a.x + s * (b.x - a.x), a.y + s * (b.y - a.y));
  const Eigen::Vector2d to_stance = seg.feet_from[1 - sw].p.head<2>() - Eigen::Vector2d(a.x, a.y);
  if (to_stance.norm() > 1e-6) {
    const double bump = std::pow(std::sin(M_PI * u), 2);
    p_xy += params_.pelvis_sway * bump * to_stance.normalized();
  }
  const double yaw = internal::LerpAngle(a.yaw, b.yaw, s);

  // height: nominal over the lower foot, lowered where a leg would stretch too far
  const internal::LegGeometry& leg = humanoid_.leg(Side::kLeft);
  const double lift = leg.ankle_height + params_.hip_height - leg.p_BH.z();
  const double z_a = std::min(a.z + lift, internal::MaxBaseHeight(humanoid_, seg.feet_from,
                                                                   {a.x, a.y}, a.yaw, params_.max_leg));
  const double z_b = std::min(b.z + lift, internal::MaxBaseHeight(humanoid_, seg.feet_to, {b.x, b.y},
                                                                   b.yaw, params_.max_leg));
  double z = z_a + s * (z_b - z_a);
  z = std::min(z, internal::MaxBaseHeight(humanoid_, feet, p_xy, yaw, params_.max_leg));

  JointPosture posture;
  internal::SetStandingArms(&posture);
  internal::SolveStance(humanoid_, feet, p_xy, z, yaw, &posture);
  return posture;
}

JointPosture Controller::CrawlPostureAt(const GroundFrame& frame) const {
  const internal::CrawlShape& c = params_.crawl;
  std::array<Eigen::Vector3d, 2> knees, hands;
  for (int s = 0; s < 2; ++s) {
    const double sign = s == 0 ? 1 : -1;
    knees[s] = frame.PointAt(0, sign * c.knee_y, humanoid_.knee_radius());
    hands[s] = frame.PointAt(c.hand_x, sign * c.hand_y, humanoid_.hand_radius());
  }
  return internal::CrawlPosture(humanoid_, c, frame, knees, hands, {true, true});
}

JointPosture Controller::CrawlCyclePosture(const Segment& seg, double u) const {
  const internal::CrawlShape& c = params_.crawl;
  const GroundFrame& a = seg.crawl_from;
  const GroundFrame& b = seg.crawl_to;
  // limbs swing one at a time: left hand, right knee, right hand, left knee
  auto limb = [&](double dx, double dy, double dz, double slot) {
    const double s = SmoothRamp(u, slot, slot + 0.25);
    const Eigen::Vector3d p = (1 - s) * a.PointAt(dx, dy, dz) + s * b.PointAt(dx, dy, dz);
    return Eigen::Vector3d(p + Eigen::Vector3d(0, 0, c.limb_lift * std::sin(M_PI * s)));
  };
  const double kr = humanoid_.knee_radius(), hr = humanoid_.hand_radius();
  const std::array<Eigen::Vector3d, 2> hands = {limb(c.hand_x, c.hand_y, hr, 0.0),
                                                limb(c.hand_x, -c.hand_y, hr, 0.5)};
  const std::array<Eigen::Vector3d, 2> knees = {limb(0, c.knee_y, kr, 0.75),
                                                limb(0, -c.knee_y, kr, 0.25)};
  const std::array<bool, 2> planted = {u <= 0.75 || u >= 1.0, u <= 0.25 || u >= 0.5};
  const double s = SmoothRamp(u, 0, 1);
  const GroundFrame f{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), internal::LerpAngle(a.yaw, b.yaw, s),
                      a.z};
  return internal::CrawlPosture(humanoid_, c, f, knees, hands, planted);
}

namespace {

// sole pose of a foot pivoted by theta (heel up) about its toe edge at p_toe, heading yaw
Eigen::Isometry3d TiptoeSole(const Eigen::Vector3d& p_toe, double yaw, double theta, double half_length) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = p_toe;
  X.linear() = Rz(yaw) * Ry(theta);
  return X * Eigen::Translation3d(-half_length, 0, 0);
}

void SolveLegs(const Humanoid& h, const std::array<Eigen::Isometry3d, 2>& X_WS, JointPosture* posture) {
  for (int s = 0; s < 2; ++s) {
    const auto ik = internal::SolveLegIk(h.leg(Side(s)), posture->X_WB.inverse() * X_WS[s]);
    const int first = s == 0 ? kLeftHipYaw : kRightHipYaw;
    for (int i = 0; i < 6; ++i) posture->q[first + i] = ik.q[i];
  }
}

}  // namespace

double Controller::KneelOffset() const {
  // the knees land one shin length ahead of the ankles of the tiptoed feet
  const internal::LegGeometry& leg = humanoid_.leg(Side::kLeft);
  const double half = humanoid_.sole_half_length(), theta = params_.kneel_toe_angle;
  const Eigen::Vector3d p_ankle = Eigen::Vector3d(half, 0, 0) + Ry(theta) * Eigen::Vector3d(-half, 0, leg.ankle_height);
  const double dz = p_ankle.z() - humanoid_.knee_radius();
  return p_ankle.x() + std::sqrt(leg.shin * leg.shin - dz * dz);
}

JointPosture Controller::TransitionPosture(const GroundFrame& stand, double s) const {
  const internal::LegGeometry& leg = humanoid_.leg(Side::kLeft);
  const double half = humanoid_.sole_half_length();
  const std::array<FootPlacement, 2> feet = FeetAt(stand, params_.stance_width);
  std::array<Eigen::Vector3d, 2> toes;
  for (int k = 0; k < 2; ++k) toes[k] = stand.PointAt(half, (k == 0 ? 0.5 : -0.5) * params_.stance_width, 0);
  const Eigen::Isometry3d X_WS = stand.Isometry();

  // key poses of the pelvis: standing, squatting, knees touching down (thighs vertical)
  const JointPosture standing = StandingPosture(feet);
  JointPosture squat;
  squat.X_WB = X_WS * Eigen::Translation3d(-0.01, 0, params_.squat_height) *
               Eigen::AngleAxisd(params_.squat_pitch, Eigen::Vector3d::UnitY());
  squat.q[kLeftShoulderPitch] = squat.q[kRightShoulderPitch] = -1.0;
  squat.q[kLeftShoulderRoll] = 0.1;
  squat.q[kRightShoulderRoll] = -0.1;
  squat.q[kLeftElbow] = squat.q[kRightElbow] = -0.3;
  const double knee_x = KneelOffset();
  const Eigen::Matrix3d R_kneel = Ry(params_.kneel_pitch);
  const Eigen::Vector3d p_hip(knee_x, 0, humanoid_.knee_radius() + leg.thigh);
  JointPosture kneel;
  kneel.X_WB = X_WS * Eigen::Translation3d(p_hip - R_kneel * Eigen::Vector3d(leg.p_BH.x(), 0, leg.p_BH.z())) *
               Eigen::AngleAxisd(params_.kneel_pitch, Eigen::Vector3d::UnitY());
  kneel.q = squat.q;
  SolveLegs(humanoid_, {TiptoeSole(toes[0], stand.yaw, params_.kneel_toe_angle, half),
                        TiptoeSole(toes[1], stand.yaw, params_.kneel_toe_angle, half)},
            &kneel);

  // crawl shape at touch-down: the kneeling pelvis, legs as they land, hands raised
  const GroundFrame crawl = stand.Then(knee_x, 0, 0);
  const internal::CrawlShape& shape = params_.crawl;
  auto crawl_at = [&](double c) {
    internal::CrawlShape sh = shape;
    const double base_x = (crawl.Isometry().inverse() * kneel.X_WB.translation()).x();
    sh.base_x = base_x + c * (shape.base_x - base_x);
    sh.base_pitch = params_.kneel_pitch + c * (shape.base_pitch - params_.kneel_pitch);
    sh.knee_angle = kneel.q[kLeftKnee] + c * (shape.knee_angle - kneel.q[kLeftKnee]);
    sh.ankle_pitch = kneel.q[kLeftAnklePitch] + c * (shape.ankle_pitch - kneel.q[kLeftAnklePitch]);
    // knee pads move out from under the hips to the crawl width, hands come down
    std::array<Eigen::Vector3d, 2> knees, hands;
    for (int k = 0; k < 2; ++k) {
      const double sign = k == 0 ? 1 : -1;
      const double y = std::abs(leg.p_BH.y()) + c * (shape.knee_y - std::abs(leg.p_BH.y()));
      knees[k] = crawl.PointAt(0, sign * y, humanoid_.knee_radius());
      const Eigen::Vector3d raised = crawl.PointAt(0.10, sign * shape.hand_y, 0.12);
      const Eigen::Vector3d down = crawl.PointAt(shape.hand_x, sign * shape.hand_y, humanoid_.hand_radius());
      hands[k] = raised + SmoothRamp(c, 0.3, 1.0) * (down - raised);
    }
    return internal::CrawlPosture(humanoid_, sh, crawl, knees, hands, {true, true});
  };

  if (s <= 0.3) {
    // squat down over flat feet
    JointPosture p = internal::LerpPosture(standing, squat, SmoothRamp(s, 0, 0.3));
    std::array<Eigen::Isometry3d, 2> soles;
    for (int k = 0; k < 2; ++k) {
      soles[k] = Eigen::Translation3d(feet[k].p) * Eigen::AngleAxisd(stand.yaw, Eigen::Vector3d::UnitZ());
    }
    SolveLegs(humanoid_, soles, &p);
    return p;
  }
  if (s <= 0.65) {
    // knees forward and down while the feet pivot onto their toes
    const double b = SmoothRamp(s, 0.3, 0.65);
    JointPosture p = internal::LerpPosture(squat, kneel, b);
    const JointPosture start_c = crawl_at(0);
    for (int j : {kLeftShoulderPitch, kLeftShoulderRoll, kLeftElbow, kRightShoulderPitch,
                  kRightShoulderRoll, kRightElbow}) {
      p.q[j] = squat.q[j] + b * (start_c.q[j] - squat.q[j]);
    }
    const double theta = params_.kneel_toe_angle * b;
    SolveLegs(humanoid_, {TiptoeSole(toes[0], stand.yaw, theta, half), TiptoeSole(toes[1], stand.yaw, theta, half)},
              &p);
    return p;
  }
  // hands down, pelvis over to the crawl pitch
  return crawl_at(SmoothRamp(s, 0.65, 1.0));
}

JointPosture Controller::Evaluate(const Segment& seg, double u, HeadAngles* head) const {
  switch (seg.kind) {
    case Kind::kStep:
      return StepPosture(seg, u);
    case Kind::kHead: {
      const double s = SmoothRamp(u, 0, 1);
      *head = {seg.head_from.pan + s * (seg.head_to.pan - seg.head_from.pan),
               seg.head_from.tilt + s * (seg.head_to.tilt - seg.head_from.tilt)};
      return current_;
    }
    case Kind::kTransition: {
      const double s = SmoothRamp(u, 0, 1);
      *head = {seg.head_from.pan + s * (seg.head_to.pan - seg.head_from.pan),
               seg.head_from.tilt + s * (seg.head_to.tilt - seg.head_from.tilt)};
      return TransitionPosture(seg.stand, seg.getting_up ? 1 - u : u);
    }
    case Kind::kCrawlCycle:
      return CrawlCyclePosture(seg, u);
  }
  return current_;
}

void Controller::Tick(const mjModel* m, mjData* d) {
  if (!queue_.empty()) {
    const Segment& seg = queue_.front();
    ++segment_tick_;
    current_ = Evaluate(seg, double(segment_tick_) / seg.ticks, &head_);
    if (segment_tick_ >= seg.ticks) {
      mode_ = seg.mode_after;
      steps_ += seg.steps;
      if (seg.steps > 0) settled_ = seg.settles;
      believed_ = Compose(believed_, seg.odometry);
      queue_.pop_front();
      segment_tick_ = 0;
    }
  }
  current_.q[kNeckPan] = head_.pan;
  current_.q[kNeckTilt] = head_.tilt;
  SetPosture(humanoid_, current_, d);
  mj_kinematics(m, d);
  mj_camlight(m, d);
  mj_collision(m, d);
  ++tick_;
  CheckContacts(m, d);
}

int Controller::RunUntilIdle(const mjModel* m, mjData* d, const std::function<void(int)>& on_tick,
                             int max_ticks) {
  int n = 0;
  while (!Idle() && n < max_ticks) {
    Tick(m, d);
    ++n;
    if (on_tick) on_tick(tick_);
  }
  return n;
}

Pose2 Controller::TruePose(const mjData* d) const {
  const Eigen::Isometry3d X_WR = RobotFrameInWorld(humanoid_, d);
  const Eigen::Matrix3d R = X_WR.linear();
  return {X_WR.translation().x(), X_WR.translation().y(), std::atan2(R(1, 0), R(0, 0))};
}

namespace {

// A box geom's pose and half extents in the world.
internal::Box GeomBox(const mjModel* m, const mjData* d, int geom) {
  internal::Box box;
  for (int k = 0; k < 3; ++k) {
    box.center[k] = d->geom_xpos[3 * geom + k];
    box.half[k] = m->geom_size[3 * geom + k];
    for (int j = 0; j < 3; ++j) box.axes(k, j) = d->geom_xmat[9 * geom + 3 * k + j];
  }
  return box;
}

}  // namespace

void Controller::CheckContacts(const mjModel* m, const mjData* d) {
  const bool on_all_fours = mode_ == Mode::kCrawling ||
                            (!queue_.empty() && queue_.front().kind == Kind::kTransition);
  // pairs touching this tick; a pair already touching last tick continues its collision
  std::map<std::pair<int, int>, int> now;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const bool robot1 = humanoid_.IsRobotGeom(c.geom1), robot2 = humanoid_.IsRobotGeom(c.geom2);
    if (robot1 == robot2) continue;
    const int r = robot1 ? c.geom1 : c.geom2, w = robot1 ? c.geom2 : c.geom1;
    double depth = -c.dist;
    // MuJoCo 2.2's box-box collider may report a phantom contact far deeper than the boxes
    // overlap when faces rest flush (a sole on a tread: 0.48 m for 3 micrometres; see
    // BoxPenetration's tests): for two boxes the separating-axis depth bounds it
    if (m->geom_type[r] == mjGEOM_BOX && m->geom_type[w] == mjGEOM_BOX) {
      depth = std::min(depth, internal::BoxPenetration(GeomBox(m, d, r), GeomBox(m, d, w)));
    }
    if (depth <= params_.collision_depth) continue;
    // supports: soles on what they stand on, hands and knees on the floor while crawling
    bool support = r == humanoid_.sole_geom(Side::kLeft) || r == humanoid_.sole_geom(Side::kRight);
    if (on_all_fours) {
      for (int s = 0; s < 2; ++s) {
        support = support || r == humanoid_.hand_geom(Side(s)) || r == humanoid_.knee_geom(Side(s));
      }
    }
    if (support && std::abs(c.frame[2]) > 0.9 && depth <= params_.support_depth) continue;
    const auto key = std::make_pair(r, w);
    auto it = now.find(key);
    if (it == now.end()) {
      auto old = touching_.find(key);
      int index = int(collisions_.size());
      if (old != touching_.end()) {
        index = old->second;
      } else {
        collisions_.push_back({tick_, r, w, ContactName(m, r), ContactName(m, w), depth});
      }
      it = now.emplace(key, index).first;
    }
    collisions_[it->second].depth = std::max(collisions_[it->second].depth, depth);
  }
  touching_ = std::move(now);
}

ClipRecorder::ClipRecorder(const mjModel* m, const Humanoid& humanoid, ClipParams params)
    : humanoid_(&humanoid), params_(std::move(params)), renderer_(std::make_unique<Renderer>(m)) {
  std::error_code error;
  std::filesystem::create_directories(params_.dir, error);
  if (error) throw std::runtime_error("cannot create clip directory '" + params_.dir + "': " + error.message());
}

ClipRecorder::~ClipRecorder() = default;

void ClipRecorder::operator()(const mjModel* m, const mjData* d, int tick) {
  if (params_.every <= 0 || tick % params_.every != 0) return;
  const Eigen::Isometry3d X_WR = RobotFrameInWorld(*humanoid_, d);
  if (!anchored_) {
    eye_offset_W_ = X_WR.linear() * params_.eye_R;
    target_offset_W_ = X_WR.linear() * params_.target_R;
    anchored_ = true;
  }
  // look from the eye at the target, OpenCV axes: z forward, x right, y down
  const Eigen::Vector3d eye = X_WR.translation() + eye_offset_W_;
  const Eigen::Vector3d z = (X_WR.translation() + target_offset_W_ - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() << x, z.cross(x), z;
  X_WC.translation() = eye;
  const RenderedView view = renderer_->Render(
      m, d, PinholeCamera::FromFov(X_WC, params_.width_px, params_.height_px, params_.hfov),
      {/*depth=*/false, /*surfaces=*/false});
  cv::Mat rgb(view.height, view.width, CV_8UC3, const_cast<uint8_t*>(view.rgb.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  char name[32];
  std::snprintf(name, sizeof(name), "_%05d.png", frames_);
  const std::string path = params_.dir + "/" + params_.prefix + name;
  if (!cv::imwrite(path, bgr)) throw std::runtime_error("cannot write clip frame '" + path + "'");
  ++frames_;
}

}  // namespace fognav::sim

#include "sim/internal/gait.h"

#include <algorithm>
#include <cmath>

namespace fognav::sim::internal {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

Eigen::Matrix3d Rz(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix(); }
Eigen::Matrix3d Ry(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitY()).toRotationMatrix(); }

Eigen::Isometry3d FootPose(const FootPlacement& f) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Rz(f.yaw);
  X.translation() = f.p;
  return X;
}

int CeilCount(double value, double limit) { return int(std::ceil(value / limit - 1e-9)); }

}  // namespace

GroundFrame GroundFrame::Then(double dx, double dy, double dyaw) const {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {x + c * dx - s * dy, y + s * dx + c * dy, WrapAngle(yaw + dyaw), z};
}

Eigen::Vector3d GroundFrame::PointAt(double dx, double dy, double dz) const {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {x + c * dx - s * dy, y + s * dx + c * dy, z + dz};
}

Eigen::Isometry3d GroundFrame::Isometry() const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Rz(yaw);
  X.translation() = Vector3d(x, y, z);
  return X;
}

double SmoothRamp(double t, double a, double b) {
  const double s = std::clamp((t - a) / (b - a), 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

double WrapAngle(double a) { return std::remainder(a, 2 * M_PI); }

double LerpAngle(double a, double b, double s) { return a + s * WrapAngle(b - a); }

FootPlacement SwingFoot(const FootPlacement& from, const FootPlacement& to, double lift_z, double u) {
  FootPlacement f;
  const double s = SmoothRamp(u, 0.25, 0.75);
  f.p.head<2>() = from.p.head<2>() + s * (to.p.head<2>() - from.p.head<2>());
  f.yaw = LerpAngle(from.yaw, to.yaw, s);
  if (u < 0.7) {
    f.p.z() = from.p.z() + (lift_z - from.p.z()) * SmoothRamp(u, 0.0, 0.3);
  } else {
    f.p.z() = lift_z + (to.p.z() - lift_z) * SmoothRamp(u, 0.7, 1.0);
  }
  return f;
}

int StrideCount(double dx, double dy, double dyaw, double max_forward, double max_backward,
                double max_sideways, double max_turn) {
  int n = dx >= 0 ? CeilCount(dx, max_forward) : CeilCount(-dx, max_backward);
  n = std::max(n, CeilCount(std::abs(dy), max_sideways));
  n = std::max(n, CeilCount(std::abs(dyaw), max_turn));
  return n;
}

void SetStandingArms(JointPosture* posture) {
  auto& q = posture->q;
  q[kWaist] = 0;
  q[kLeftShoulderPitch] = q[kRightShoulderPitch] = 0.05;
  q[kLeftShoulderRoll] = 0.12;
  q[kRightShoulderRoll] = -0.12;
  q[kLeftElbow] = q[kRightElbow] = -0.25;
}

bool SolveStance(const Humanoid& h, const std::array<FootPlacement, 2>& feet, const Vector2d& p_xy,
                 double base_z, double yaw, JointPosture* posture) {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.linear() = Rz(yaw);
  X_WB.translation() = Vector3d(p_xy.x(), p_xy.y(), base_z);
  posture->X_WB = X_WB;
  bool ok = true;
  for (int s = 0; s < 2; ++s) {
    const LegIkResult ik = SolveLegIk(h.leg(Side(s)), X_WB.inverse() * FootPose(feet[s]));
    ok = ok && ik.reachable;
    const int first = s == 0 ? kLeftHipYaw : kRightHipYaw;
    for (int i = 0; i < 6; ++i) posture->q[first + i] = ik.q[i];
  }
  return ok;
}

double MaxBaseHeight(const Humanoid& h, const std::array<FootPlacement, 2>& feet, const Vector2d& p_xy,
                     double yaw, double max_leg) {
  double z = INFINITY;
  for (int s = 0; s < 2; ++s) {
    const LegGeometry& leg = h.leg(Side(s));
    const Vector3d p_hip = Rz(yaw) * leg.p_BH;
    const double dh = (p_xy + p_hip.head<2>() - feet[s].p.head<2>()).norm();
    const double rise = std::sqrt(std::max(max_leg * max_leg - dh * dh, 0.0));
    z = std::min(z, feet[s].p.z() + leg.ankle_height + rise - p_hip.z());
  }
  return z;
}

JointPosture CrawlPosture(const Humanoid& h, const CrawlShape& shape, const GroundFrame& frame,
                     const std::array<Vector3d, 2>& knees_W, const std::array<Vector3d, 2>& hands_W,
                     const std::array<bool, 2>& knee_planted) {
  JointPosture posture;
  const Eigen::Matrix3d R_WB = Rz(frame.yaw) * Ry(shape.base_pitch);
  const Vector3d p_base = frame.PointAt(shape.base_x, 0, 0);

  // base height: a planted knee pad rests on its target, the thigh pointing at it
  double base_z = -INFINITY;
  for (int s = 0; s < 2; ++s) {
    if (!knee_planted[s] && (knee_planted[0] || knee_planted[1])) continue;
    const LegGeometry& leg = h.leg(Side(s));
    const Vector3d p_hip = R_WB * leg.p_BH;
    const double dh = (p_base.head<2>() + p_hip.head<2>() - knees_W[s].head<2>()).norm();
    const double drop = std::sqrt(std::max(leg.thigh * leg.thigh - dh * dh, 0.0));
    base_z = std::max(base_z, knees_W[s].z() + drop - p_hip.z());
  }
  posture.X_WB.linear() = R_WB;
  posture.X_WB.translation() = Vector3d(p_base.x(), p_base.y(), base_z);
  const Eigen::Isometry3d X_BW = posture.X_WB.inverse();

  // legs: thighs point at the knee targets; the knee makes up the thigh's forward lean, so
  // shins and feet keep their slope over the floor while a knee swings
  const Vector3d forward(std::cos(frame.yaw), std::sin(frame.yaw), 0);
  for (int s = 0; s < 2; ++s) {
    const Vector3d p_BK = X_BW * knees_W[s];
    const auto hip = PointThigh(h.leg(Side(s)).p_BH, p_BK);
    const Vector3d thigh_W = knees_W[s] - posture.X_WB * h.leg(Side(s)).p_BH;
    const double lean = std::atan2(thigh_W.dot(forward), -thigh_W.z());
    const int first = s == 0 ? kLeftHipYaw : kRightHipYaw;
    posture.q[first + 0] = 0;
    posture.q[first + 1] = hip[0];
    posture.q[first + 2] = hip[1];
    posture.q[first + 3] = shape.knee_angle + lean;
    posture.q[first + 4] = shape.ankle_pitch;
    posture.q[first + 5] = 0;
  }

  // arms reach the hands' targets from the torso (waist straight)
  const Eigen::Isometry3d X_TW = (posture.X_WB * Eigen::Translation3d(h.p_BT())).inverse();
  for (int s = 0; s < 2; ++s) {
    const ArmAngles arm = SolveArmIk(h.arm(Side(s)), X_TW * hands_W[s]);
    const int first = s == 0 ? kLeftShoulderPitch : kRightShoulderPitch;
    for (int i = 0; i < 3; ++i) posture.q[first + i] = arm[i];
  }
  posture.q[kWaist] = 0;
  posture.q[kNeckPan] = 0;
  posture.q[kNeckTilt] = shape.neck_tilt;
  return posture;
}

JointPosture LerpPosture(const JointPosture& a, const JointPosture& b, double s) {
  JointPosture p;
  p.X_WB.translation() = (1 - s) * a.X_WB.translation() + s * b.X_WB.translation();
  p.X_WB.linear() = Eigen::Quaterniond(a.X_WB.linear())
                        .slerp(s, Eigen::Quaterniond(b.X_WB.linear()))
                        .toRotationMatrix();
  for (int j = 0; j < kNumJoints; ++j) p.q[j] = (1 - s) * a.q[j] + s * b.q[j];
  return p;
}

}  // namespace fognav::sim::internal

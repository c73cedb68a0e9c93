#include "sim/internal/leg_ik.h"

#include <algorithm>
#include <cmath>

namespace fognav::sim::internal {
namespace {

using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d Rx(double a) { return AngleAxisd(a, Vector3d::UnitX()).toRotationMatrix(); }
Matrix3d Ry(double a) { return AngleAxisd(a, Vector3d::UnitY()).toRotationMatrix(); }
Matrix3d Rz(double a) { return AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix(); }

double Clamp1(double x) { return std::clamp(x, -1.0, 1.0); }

}  // namespace

LegIkResult SolveLegIk(const LegGeometry& leg, const Eigen::Isometry3d& X_BS) {
  LegIkResult result;
  const double a = leg.thigh, b = leg.shin;
  const Matrix3d R_BF = X_BS.linear();
  const Vector3d p_BA = X_BS.translation() + R_BF * Vector3d(0, 0, leg.ankle_height);

  // hip seen from the ankle, in the foot frame
  const Vector3d r = R_BF.transpose() * (leg.p_BH - p_BA);
  double c = r.norm();
  if (c > a + b) {
    result.reachable = false;
    c = a + b;
  }

  // knee from the law of cosines: c^2 = a^2 + b^2 + 2ab cos(knee)
  const double knee = std::acos(Clamp1((c * c - a * a - b * b) / (2 * a * b)));

  // ankle roll turns the hip into the foot's xz-plane, ankle pitch aligns the shin chain
  const double ankle_roll = std::atan2(r.y(), r.z());
  const double rho = std::sqrt(r.y() * r.y() + r.z() * r.z());
  const double ankle_pitch =
      std::atan2(-a * std::sin(knee), b + a * std::cos(knee)) - std::atan2(r.x(), rho);

  // hip angles from the thigh orientation: R = Rz(yaw) Rx(roll) Ry(pitch)
  const Matrix3d M = R_BF * Rx(-ankle_roll) * Ry(-(knee + ankle_pitch));
  const double hip_roll = std::atan2(M(2, 1), std::hypot(M(0, 1), M(1, 1)));
  const double hip_yaw = std::atan2(-M(0, 1), M(1, 1));
  const double hip_pitch = std::atan2(-M(2, 0), M(2, 2));

  result.q = {hip_yaw, hip_roll, hip_pitch, knee, ankle_pitch, ankle_roll};
  return result;
}

Eigen::Isometry3d LegForwardKinematics(const LegGeometry& leg, const LegAngles& q) {
  const Matrix3d R_thigh = Rz(q[0]) * Rx(q[1]) * Ry(q[2]);
  const Vector3d p_knee = leg.p_BH + R_thigh * Vector3d(0, 0, -leg.thigh);
  const Matrix3d R_shin = R_thigh * Ry(q[3]);
  const Vector3d p_ankle = p_knee + R_shin * Vector3d(0, 0, -leg.shin);
  const Matrix3d R_foot = R_shin * Ry(q[4]) * Rx(q[5]);
  Eigen::Isometry3d X_BS = Eigen::Isometry3d::Identity();
  X_BS.linear() = R_foot;
  X_BS.translation() = p_ankle + R_foot * Vector3d(0, 0, -leg.ankle_height);
  return X_BS;
}

ArmAngles SolveArmIk(const ArmGeometry& arm, const Eigen::Vector3d& p_TH) {
  const double u = arm.upper, f = arm.fore;
  const Vector3d v = p_TH - arm.p_TS;
  const double d = std::clamp(v.norm(), std::abs(u - f) + 1e-9, u + f);

  // elbow from the law of cosines, flexed forward (negative)
  const double elbow = -std::acos(Clamp1((d * d - u * u - f * f) / (2 * u * f)));
  // hand in the upper-arm frame
  const Vector3d w(-f * std::sin(elbow), 0, -u - f * std::cos(elbow));

  // roll brings the hand to the target's y, pitch turns it in the xz-plane
  const Vector3d v_d = v.normalized() * d;
  const double roll = std::asin(Clamp1(v_d.y() / -w.z()));
  const double pitch = std::atan2(v_d.x(), v_d.z()) -
                       std::atan2(w.x(), w.z() * std::cos(roll));
  return {pitch, roll, elbow};
}

Eigen::Vector3d ArmForwardKinematics(const ArmGeometry& arm, const ArmAngles& q) {
  const Matrix3d R_upper = Ry(q[0]) * Rx(q[1]);
  const Vector3d p_elbow = arm.p_TS + R_upper * Vector3d(0, 0, -arm.upper);
  return p_elbow + R_upper * Ry(q[2]) * Vector3d(0, 0, -arm.fore);
}

std::array<double, 2> PointThigh(const Eigen::Vector3d& p_BH, const Eigen::Vector3d& p_BK) {
  // R = Rx(roll) Ry(pitch) maps -z to (-cos(r) sin(p), sin(r), -cos(r) cos(p))
  const Vector3d v = (p_BK - p_BH).normalized();
  const double roll = std::asin(Clamp1(v.y()));
  const double pitch = std::atan2(-v.x(), -v.z());
  return {roll, pitch};
}

}  // namespace fognav::sim::internal

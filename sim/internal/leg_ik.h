// Closed-form inverse kinematics of the humanoid's limbs: the 6-DOF legs (hip yaw, roll,
// pitch, knee, ankle pitch, roll) and the 3-DOF arms (shoulder pitch, roll, elbow).
// Axes follow models/humanoid.xml: yaw about z, roll about x, pitch about y of the parent
// body; in the zero pose limbs hang straight down (-z).
#ifndef FOGNAV_SIM_INTERNAL_LEG_IK_H_
#define FOGNAV_SIM_INTERNAL_LEG_IK_H_

#include <array>

#include <Eigen/Geometry>

namespace fognav::sim::internal {

// Leg dimensions, metres, in the base (pelvis) frame B.
struct LegGeometry {
  Eigen::Vector3d p_BH = Eigen::Vector3d(0, 0.045, -0.03);  // hip joint centre in B
  double thigh = 0.10;         // hip to knee
  double shin = 0.10;          // knee to ankle
  double ankle_height = 0.035;  // ankle joint above the sole
};

// Joint angles, radians, in chain order: hip yaw, hip roll, hip pitch, knee, ankle pitch,
// ankle roll.
using LegAngles = std::array<double, 6>;

struct LegIkResult {
  LegAngles q{};
  bool reachable = true;  // false: the sole was too far and the knee was clamped straight
};

// Angles that put the sole (bottom centre of the foot, frame S) at X_BS, the sole pose in the
// base frame. If the hip-to-ankle distance exceeds the leg, the knee is straightened and the
// leg points at the target.
LegIkResult SolveLegIk(const LegGeometry& leg, const Eigen::Isometry3d& X_BS);

// Forward kinematics: the sole pose in the base frame for the given angles.
Eigen::Isometry3d LegForwardKinematics(const LegGeometry& leg, const LegAngles& q);

// Arm dimensions, metres, in the torso frame T.
struct ArmGeometry {
  Eigen::Vector3d p_TS = Eigen::Vector3d(0, 0.095, 0.125);  // shoulder joint centre in T
  double upper = 0.08;    // shoulder to elbow
  double fore = 0.085;    // elbow to the hand's centre
};

// Shoulder pitch, shoulder roll, elbow (elbow <= 0 flexes the arm forward).
using ArmAngles = std::array<double, 3>;

// Angles that put the hand's centre at p_TH (torso frame), elbow flexed forward; an out-of-reach
// target straightens the arm towards it.
ArmAngles SolveArmIk(const ArmGeometry& arm, const Eigen::Vector3d& p_TH);

// Forward kinematics: the hand's centre in the torso frame.
Eigen::Vector3d ArmForwardKinematics(const ArmGeometry& arm, const ArmAngles& q);

// Hip roll and pitch (yaw 0) that point the thigh from the hip at p_BH towards p_BK (base
// frame); the knee lands on that ray, one thigh length from the hip.
std::array<double, 2> PointThigh(const Eigen::Vector3d& p_BH, const Eigen::Vector3d& p_BK);

}  // namespace fognav::sim::internal

#endif  // FOGNAV_SIM_INTERNAL_LEG_IK_H_

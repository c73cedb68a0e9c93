#include "sim/internal/leg_ik.h"

#include <random>

#include <gtest/gtest.h>

#include "sim/humanoid.h"
#include "sim/model.h"

namespace fognav::sim {
namespace {

using internal::LegAngles;

// random leg angles in a walking/climbing range, away from the straight-knee singularity
LegAngles RandomLeg(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  return {0.5 * u(rng), 0.3 * u(rng), -0.6 + 0.6 * u(rng), 1.2 + 0.9 * u(rng), -0.5 + 0.5 * u(rng),
          0.3 * u(rng)};
}

TEST(LegIk, RecoversTheAnglesOfReachableSolePoses) {
  std::mt19937 rng(7);
  internal::LegGeometry leg;
  for (int i = 0; i < 1000; ++i) {
    const LegAngles q = RandomLeg(rng);
    const Eigen::Isometry3d X_BS = internal::LegForwardKinematics(leg, q);
    const internal::LegIkResult ik = internal::SolveLegIk(leg, X_BS);
    ASSERT_TRUE(ik.reachable);
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(ik.q[j], q[j], 1e-9) << "joint " << j << " sample " << i;
  }
}

TEST(LegIk, ClampsAnOutOfReachTargetWithTheKneeStraight) {
  internal::LegGeometry leg;
  Eigen::Isometry3d X_BS = Eigen::Isometry3d::Identity();
  X_BS.translation() = leg.p_BH + Eigen::Vector3d(0.05, 0, -0.3);
  const internal::LegIkResult ik = internal::SolveLegIk(leg, X_BS);
  EXPECT_FALSE(ik.reachable);
  EXPECT_NEAR(ik.q[3], 0.0, 1e-9);
}

TEST(ArmIk, ReachesPointsInsideTheArmsWorkspace) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  internal::ArmGeometry arm;
  for (int i = 0; i < 1000; ++i) {
    const internal::ArmAngles q = {-0.8 + 0.8 * u(rng), 0.2 + 0.3 * u(rng), -1.0 + 0.9 * u(rng)};
    const Eigen::Vector3d p = internal::ArmForwardKinematics(arm, q);
    const internal::ArmAngles ik = internal::SolveArmIk(arm, p);
    EXPECT_LT((internal::ArmForwardKinematics(arm, ik) - p).norm(), 1e-9) << "sample " << i;
    EXPECT_LE(ik[2], 0.0);
  }
}

// the closed-form chains agree with MuJoCo's kinematics of models/humanoid.xml
TEST(LegIk, ForwardKinematicsMatchesTheModel) {
  ModelPtr m = LoadModelFromXml(ShippedModel("humanoid.xml"));
  DataPtr d = MakeData(m.get());
  const Humanoid h(m.get());
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    JointPosture posture;
    posture.X_WB.translation() = Eigen::Vector3d(0.3, -0.2, 0.25);
    posture.X_WB.linear() =
        Eigen::AngleAxisd(0.4 * trial, Eigen::Vector3d(0.2, 0.3, 1).normalized()).toRotationMatrix();
    const LegAngles left = RandomLeg(rng), right = RandomLeg(rng);
    for (int i = 0; i < 6; ++i) {
      posture.q[kLeftHipYaw + i] = left[i];
      posture.q[kRightHipYaw + i] = right[i];
    }
    posture.q[kLeftShoulderPitch] = -0.7;
    posture.q[kLeftShoulderRoll] = 0.3;
    posture.q[kLeftElbow] = -0.9;
    SetPosture(h, posture, d.get());
    mj_kinematics(m.get(), d.get());
    for (int s = 0; s < 2; ++s) {
      const int site = h.sole_site(Side(s));
      const Eigen::Isometry3d X_WS =
          posture.X_WB * internal::LegForwardKinematics(h.leg(Side(s)), s == 0 ? left : right);
      const Eigen::Vector3d p_mj(d->site_xpos[3 * site], d->site_xpos[3 * site + 1],
                                 d->site_xpos[3 * site + 2]);
      const Eigen::Matrix3d R_mj =
          Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * site);
      EXPECT_LT((X_WS.translation() - p_mj).norm(), 1e-9);
      EXPECT_LT((X_WS.linear() - R_mj).norm(), 1e-9);
    }
    const int hand = h.hand_geom(Side::kLeft);
    const Eigen::Vector3d p_hand =
        posture.X_WB * Eigen::Translation3d(h.p_BT()) *
        internal::ArmForwardKinematics(h.arm(Side::kLeft), {-0.7, 0.3, -0.9});
    EXPECT_LT((p_hand - Eigen::Vector3d(d->geom_xpos[3 * hand], d->geom_xpos[3 * hand + 1],
                                        d->geom_xpos[3 * hand + 2]))
                  .norm(),
              1e-9);
  }
}

}  // namespace
}  // namespace fognav::sim

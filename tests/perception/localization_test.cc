// Localization against walls: analytic planes seen from known poses in a corridor.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "perception/internal/map_synthetic.h"
#include "perception/localization.h"

namespace fognav::perception {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr int kPixels = 176 * 144;

// The head camera 0.5 m above the floor, looking along the robot's x (OpenCV axes).
Eigen::Isometry3d CameraInRobot() { return internal::LookAt({0, 0, 0.5}, {1, 0, 0.5}); }

// A corridor 1.2 m wide along x with a wall across it at x = 2.2.
std::vector<Plane> CorridorSeenFrom(const Pose2& robot_W) {
  const Eigen::Isometry3d X_WC = Planar(robot_W) * CameraInRobot();
  const double x0 = robot_W.x + 1.0, x1 = robot_W.x + 2.0;
  return {internal::WallPlane({x0, 0.6}, {x1, 0.6}, 0.3, X_WC),
          internal::WallPlane({x0, -0.6}, {x1, -0.6}, 0.3, X_WC),
          internal::WallPlane({2.2, -0.5}, {2.2, 0.5}, 0.3, X_WC)};
}

TEST(Localization, NoiseFreeOdometryRecordsWallsButNeverMovesThePose) {
  LocalizationState state;
  const Pose2 start;
  Pose2 pose = CorrectPose({}, CorridorSeenFrom(start), kPixels, CameraInRobot(), start, &state);
  EXPECT_EQ(pose.x, 0);
  EXPECT_EQ(pose.y, 0);
  EXPECT_EQ(pose.yaw, 0);
  ASSERT_EQ(state.landmarks.size(), 3u);
  EXPECT_NEAR(std::abs(state.landmarks[0].angle), 90 * kDeg, 1e-9);
  EXPECT_NEAR(state.landmarks[0].offset, -0.6, 1e-9);  // n = (0, -1): -y = -0.6
  // the walls again from a believed pose that is 3 cm off: still no correction
  const Pose2 moved{0.5, 0, 0}, believed{0.5, 0.03, 0};
  PredictPose(start, believed, Eigen::Matrix3d::Zero(), &state);
  pose = CorrectPose({}, CorridorSeenFrom(moved), kPixels, CameraInRobot(), believed, &state);
  EXPECT_EQ(pose.y, 0.03);
  EXPECT_EQ(pose.yaw, 0);
  // the walls were matched (not added again), and only the landmarks moved
  ASSERT_EQ(state.landmarks.size(), 3u);
  for (const WallLandmark& landmark : state.landmarks) EXPECT_EQ(landmark.matches, 1);
  EXPECT_EQ(state.PoseCovariance().norm(), 0);
}

TEST(Localization, PiecesOfOneWallInOneViewCountOnce) {
  LocalizationState state;
  const Eigen::Isometry3d X_WC = Planar({}) * CameraInRobot();
  // the left wall seen as two planes: one landmark, not matched by its own second piece
  CorrectPose({},
              {internal::WallPlane({1.0, 0.6}, {1.5, 0.6}, 0.3, X_WC),
               internal::WallPlane({1.5, 0.6}, {2.0, 0.6}, 0.3, X_WC)},
              kPixels, CameraInRobot(), {}, &state);
  ASSERT_EQ(state.landmarks.size(), 1u);
  EXPECT_EQ(state.landmarks[0].matches, 0);
  // the next view's two pieces update it once
  PredictPose({}, {}, Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal(), &state);
  CorrectPose({},
              {internal::WallPlane({1.0, 0.6}, {1.5, 0.6}, 0.3, X_WC),
               internal::WallPlane({1.5, 0.6}, {2.0, 0.6}, 0.3, X_WC)},
              kPixels, CameraInRobot(), {}, &state);
  EXPECT_EQ(state.landmarks[0].matches, 1);
}

TEST(Localization, WallsSeenBeforeCorrectADriftedPose) {
  LocalizationState state;
  CorrectPose({}, CorridorSeenFrom({}), kPixels, CameraInRobot(), {}, &state);
  // odometry says (1, 0, 0), uncertain by 20 cm and 10 deg (far more than the walls, which
  // were seen from a known pose); the robot is elsewhere
  const Pose2 truth{1.02, 0.05, 3 * kDeg}, believed{1.0, 0.0, 0.0};
  const Eigen::Matrix3d prior = Eigen::Vector3d(0.04, 0.04, std::pow(10 * kDeg, 2)).asDiagonal();
  PredictPose({}, believed, prior, &state);
  const Pose2 pose =
      CorrectPose({}, CorridorSeenFrom(truth), kPixels, CameraInRobot(), believed, &state);
  EXPECT_NEAR(pose.x, truth.x, 0.005);
  EXPECT_NEAR(pose.y, truth.y, 0.005);
  EXPECT_NEAR(pose.yaw, truth.yaw, 0.3 * kDeg);
  // and the filter is surer than before in every direction
  const Eigen::Matrix3d P = state.PoseCovariance();
  for (int i = 0; i < 3; ++i) EXPECT_LT(P(i, i), prior(i, i) / 10) << i;
  EXPECT_EQ(state.landmarks.size(), 3u);  // nothing new: the same three walls
}

TEST(Localization, OneWallCorrectsOnlyWhatItSees) {
  LocalizationState state;
  const Eigen::Isometry3d X_WC = Planar({}) * CameraInRobot();
  CorrectPose({}, {internal::WallPlane({1, 0.6}, {2, 0.6}, 0.3, X_WC)}, kPixels, CameraInRobot(),
              {}, &state);
  const Pose2 truth{0.1, 0.04, 0}, believed{0.0, 0.0, 0.0};
  PredictPose({}, believed, Eigen::Vector3d(0.04, 0.04, std::pow(2 * kDeg, 2)).asDiagonal(),
              &state);
  const Eigen::Isometry3d X_WC_true = Planar(truth) * CameraInRobot();
  const Pose2 pose = CorrectPose({}, {internal::WallPlane({1, 0.6}, {2, 0.6}, 0.3, X_WC_true)},
                                 kPixels, CameraInRobot(), believed, &state);
  EXPECT_NEAR(pose.y, truth.y, 0.01);  // across the wall
  EXPECT_NEAR(pose.x, 0.0, 1e-6);      // along it: no information
}

TEST(Localization, AWallFarFromEveryLandmarkIsNewAndMovesNothing) {
  LocalizationState state;
  CorrectPose({}, CorridorSeenFrom({}), kPixels, CameraInRobot(), {}, &state);
  PredictPose({}, {}, Eigen::Vector3d(0.0004, 0.0004, 0.0004).asDiagonal(), &state);
  // a wall 0.4 m inside the left one: beyond the gate of a 2 cm pose uncertainty
  const Eigen::Isometry3d X_WC = Planar({}) * CameraInRobot();
  const Pose2 pose = CorrectPose({}, {internal::WallPlane({1, 0.2}, {2, 0.2}, 0.3, X_WC)}, kPixels,
                                 CameraInRobot(), {}, &state);
  EXPECT_EQ(pose.y, 0);
  EXPECT_EQ(state.landmarks.size(), 4u);
  EXPECT_EQ(state.covariance.rows(), 3 + 2 * 4);
}

TEST(Localization, FloorsSmallAndRoughPlanesAreNoLandmarks) {
  LocalizationState state;
  const Eigen::Isometry3d X_WC = Planar({}) * CameraInRobot();
  // the floor ahead (horizontal)
  Plane floor;
  for (int i = 0; i < 50; ++i) {
    for (int k = 0; k < 50; ++k) {
      const Eigen::Vector3d p_C =
          X_WC.inverse() * Eigen::Vector3d(1 + i * 0.02, -0.5 + k * 0.02, 0);
      ++floor.num_points;
      floor.b += p_C;
      floor.A += p_C * p_C.transpose();
    }
  }
  floor.n = X_WC.linear().transpose() * Eigen::Vector3d::UnitZ();
  floor.d = floor.n.dot(floor.Centroid());
  // a wall too short (0.2 m), and a wall too rough
  Plane short_wall = internal::WallPlane({1, 0.6}, {1.2, 0.6}, 0.3, X_WC);
  Plane rough_wall = internal::WallPlane({1, -0.6}, {2, -0.6}, 0.3, X_WC);
  rough_wall.rms = 0.02;
  CorrectPose({}, {floor, short_wall, rough_wall}, kPixels, CameraInRobot(), {}, &state);
  EXPECT_TRUE(state.landmarks.empty());
  // too few points for this image size
  CorrectPose({}, CorridorSeenFrom({}), 100 * kPixels, CameraInRobot(), {}, &state);
  EXPECT_TRUE(state.landmarks.empty());
}

TEST(Localization, PredictionGrowsTheSidewaysUncertaintyWithTheHeadingsLeverArm) {
  LocalizationState state;
  state.covariance(2, 2) = std::pow(2 * kDeg, 2);
  const Eigen::Matrix3d step = Eigen::Vector3d(1e-6, 1e-6, 0).asDiagonal();
  PredictPose({}, {1.0, 0, 0}, step, &state);
  // 1 m forward with a heading uncertain by 2 deg: sideways by about 1 m * 2 deg
  EXPECT_NEAR(std::sqrt(state.covariance(1, 1)), std::hypot(1.0 * 2 * kDeg, 1e-3), 1e-6);
  EXPECT_NEAR(state.covariance(0, 0), 1e-6, 1e-12);
  EXPECT_NEAR(state.covariance(1, 2), std::pow(2 * kDeg, 2), 1e-12);
}

// A state whose pose has the given standard deviations (x, y, yaw) and no landmarks.
LocalizationState UncertainPose(double sigma_xy, double sigma_yaw) {
  LocalizationState state;
  state.covariance = Eigen::Vector3d(sigma_xy * sigma_xy, sigma_xy * sigma_xy,
                                     sigma_yaw * sigma_yaw).asDiagonal();
  return state;
}

TEST(PoseFusion, AnExactMeasurementWeighsAgainstTheOdometryByTheirCovariances) {
  LocalizationState state = UncertainPose(0.02, 0.02);
  const Pose2 odometry{1.0, 0.0, 0.0}, measured{1.03, -0.01, 0.01};
  // equal variances: the fused pose lies half way, and its variance halves
  const Eigen::Matrix3d R = state.PoseCovariance();
  bool accepted = false;
  const Pose2 fused = FusePose(odometry, measured, R, 3.0, &state, &accepted);
  EXPECT_TRUE(accepted);
  EXPECT_NEAR(fused.x, 1.015, 1e-9);
  EXPECT_NEAR(fused.y, -0.005, 1e-9);
  EXPECT_NEAR(fused.yaw, 0.005, 1e-9);
  EXPECT_NEAR(state.PoseCovariance()(0, 0), 0.5 * 0.02 * 0.02, 1e-12);
}

TEST(PoseFusion, AMeasurementBeyondTheGateIsRejected) {
  LocalizationState state = UncertainPose(0.01, 0.01);
  const Eigen::Matrix3d before = state.PoseCovariance();
  bool accepted = true;
  const Pose2 pose{1.0, 0.0, 0.0};
  // 10 cm off against 1 cm of odometry and 4 mm of registration noise
  const Pose2 fused = FusePose(pose, {1.1, 0.0, 0.0},
                               Eigen::Vector3d(1.6e-5, 1.6e-5, 1.6e-5).asDiagonal(), 3.0, &state,
                               &accepted);
  EXPECT_FALSE(accepted);
  EXPECT_EQ(fused.x, pose.x);
  EXPECT_TRUE(state.PoseCovariance().isApprox(before));
}

// A view localized against keyframes of its own making: the keyframe's pose is cloned into the
// state, so that registering again and again to a keyframe taken with the same error does not
// make the filter believe it knows its pose better than when the keyframe was taken.
TEST(PoseFusion, RegistrationsToAClonedKeyframeDoNotShrinkTheUncertaintyBelowIts) {
  LocalizationState state = UncertainPose(0.02, 0.01);
  Keyframe kf;
  kf.robot_G = {1.0, 0.0, 0.0};
  kf.column = 3;
  state.covariance.conservativeResize(6, 6);
  state.covariance.bottomRightCorner<3, 3>() = state.covariance.topLeftCorner<3, 3>();
  state.covariance.topRightCorner<3, 3>() = state.covariance.topLeftCorner<3, 3>();
  state.covariance.bottomLeftCorner<3, 3>() = state.covariance.topLeftCorner<3, 3>();
  state.visual.keyframes.push_back(kf);
  const double sigma_before = std::sqrt(state.PoseCovariance()(0, 0));
  Pose2 pose{1.0, 0.0, 0.0};
  const Eigen::Matrix3d R = Eigen::Vector3d(1.6e-5, 1.6e-5, 1.6e-5).asDiagonal();
  for (int i = 0; i < 20; ++i) {
    bool accepted = false;
    pose = FusePose(pose, {1.0, 0.0, 0.0}, R, 3.0, &state, &accepted, 0);
    EXPECT_TRUE(accepted);
  }
  // the pose's own uncertainty stays the keyframe's: within 1 %
  EXPECT_GT(std::sqrt(state.PoseCovariance()(0, 0)), 0.99 * sigma_before);
  // while an exact keyframe (no column) pins it down to the registration's noise
  state.visual.keyframes[0].column = -1;
  pose = FusePose(pose, {1.0, 0.0, 0.0}, R, 3.0, &state, nullptr, 0);
  EXPECT_LT(std::sqrt(state.PoseCovariance()(0, 0)), 0.005);
}

// A registration relative to a cloned keyframe corrects the keyframe's pose too: the clone
// moves with the correction in proportion to its correlation with the pose.
TEST(PoseFusion, ACorrectionMovesTheCorrelatedKeyframe) {
  LocalizationState state = UncertainPose(0.02, 0.01);
  Keyframe kf;
  kf.robot_G = {0.5, 0.0, 0.0};
  kf.column = 3;
  // the keyframe was taken before 0.5 m of odometry that added (1 cm)^2
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6, 6);
  const Eigen::Matrix3d P_kf = Eigen::Vector3d(3e-4, 3e-4, 1e-4).asDiagonal();
  P.topLeftCorner<3, 3>() = P_kf + Eigen::Vector3d(1e-4, 1e-4, 0).asDiagonal().toDenseMatrix();
  P.bottomRightCorner<3, 3>() = P_kf;
  P.topRightCorner<3, 3>() = P_kf;
  P.bottomLeftCorner<3, 3>() = P_kf;
  state.covariance = P;
  state.visual.keyframes.push_back(kf);
  // the registration says the pose is 1 cm further along than the odometry
  bool accepted = false;
  const Pose2 fused = FusePose({1.0, 0.0, 0.0}, {1.01, 0.0, 0.0},
                               Eigen::Vector3d(1e-6, 1e-6, 1e-6).asDiagonal(), 3.0, &state,
                               &accepted, 0);
  ASSERT_TRUE(accepted);
  // only the odometry since the keyframe is in doubt: the pose takes the correction, the
  // keyframe hardly moves
  EXPECT_NEAR(fused.x, 1.01, 1e-3);
  EXPECT_NEAR(state.visual.keyframes[0].robot_G.x, 0.5, 1e-3);
}

}  // namespace
}  // namespace fognav::perception

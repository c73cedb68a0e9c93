// Visual odometry on rendered stereo pairs of the course with known motion: the keyframe is
// taken at a known pose, the view after a motion, and the registration, seeded with the true
// pose off by 1 cm and 1 degree, must recover the view's pose.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "perception/localization.h"
#include "perception/segmentation.h"
#include "perception/visual_odometry.h"
#include "scenarios/params.h"
#include "scenarios/scenario.h"
#include "scenarios/views.h"
#include "sim/render.h"
#include "sim/world.h"

namespace fognav::scenarios {
namespace {

using perception::Pose2;

constexpr double kDeg = M_PI / 180.0;

struct Frame {
  perception::GrayImage gray;
  perception::DepthImage depth;
  perception::CameraIntrinsics K;
};

class VisualOdometryRender : public ::testing::Test {
 protected:
  void SetUp() override {
    scenario_ = LoadScenario("scenarios/stairs_and_table.yaml");
    world_ = std::make_unique<sim::World>(MakeWorldSpec(scenario_));
    renderer_ = std::make_unique<sim::Renderer>(world_->model());
    // the head camera of the standing robot in its frame, tilted down by `tilt_`
    X_RC_level_ = PlaceRobot(world_.get(), Pose2{0, 0, 0});
  }
  Eigen::Isometry3d CameraInRobot(double tilt) const {
    return X_RC_level_ * Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitX());
  }
  // the robot stands at `pose` on the floor (or a tread, `z` high) and looks with `tilt`
  Frame View(const Pose2& pose, double tilt, bool stereo, double z = 0) {
    PlaceRobot(world_.get(), Pose2{-0.3, 0.0, 0});  // the body out of the way, behind
    const Eigen::Isometry3d X_WC = perception::Planar(pose, z) * CameraInRobot(tilt);
    const StereoView view = RenderStereo(renderer_.get(), *world_, X_WC, scenario_.sensor);
    Frame f;
    f.gray = perception::ToGray(view.left);
    f.K = view.intrinsics;
    f.depth = stereo ? perception::DepthOf(perception::StereoPointImage(
                           view.left, view.right, view.intrinsics, PerceptionParams{}.stereo))
                     : view.depth;
    return f;
  }
  // registers `b` (taken at pose_b) against a keyframe `a` (at pose_a); returns the position
  // error of the recovered pose, or infinity if it was not tracked
  double Register(const Frame& a, const Pose2& pose_a, const Frame& b, const Pose2& pose_b,
                  double tilt, double z_b = 0, double* yaw_error = nullptr) {
    perception::VisualOdometryState state;
    perception::Keyframe kf;
    kf.gray = a.gray;
    kf.depth = a.depth;
    kf.intrinsics = a.K;
    kf.X_GC = perception::Planar(pose_a) * CameraInRobot(tilt);
    state.keyframes.push_back(kf);
    const Pose2 seed{pose_b.x + 0.01, pose_b.y - 0.007, pose_b.yaw + 1 * kDeg};
    const perception::VisualOdometryResult r = perception::RegisterView(
        params_, b.gray, b.depth, b.K, CameraInRobot(tilt), seed, z_b, state);
    if (!r.tracked) {
      std::printf("not tracked: %s (overlap %.2f)\n", r.why.c_str(), r.overlap);
      return INFINITY;
    }
    if (yaw_error != nullptr) *yaw_error = std::abs(r.robot_G.yaw - pose_b.yaw);
    return std::hypot(r.robot_G.x - pose_b.x, r.robot_G.y - pose_b.y);
  }

  Scenario scenario_;
  std::unique_ptr<sim::World> world_;
  std::unique_ptr<sim::Renderer> renderer_;
  Eigen::Isometry3d X_RC_level_;
  perception::VisualOdometryParams params_;
};

TEST_F(VisualOdometryRender, RecoversMotionsWithStereoDepth) {
  struct Case {
    const char* name;
    Pose2 a, b;
    double tilt;
  };
  const Case cases[] = {
      {"straight, level", {0, 0, 0}, {0.16, 0, 0}, 0.15},
      {"straight, toward the floor", {0, 0, 0}, {0.16, 0, 0}, 0.6},
      {"turn", {0, 0, 0}, {0, 0, 0.35}, 0.4},
      {"side-step", {0.2, 0, 0}, {0.2, 0.1, 0}, 0.4},
      {"turn and walk", {0.3, -0.1, 0.2}, {0.45, -0.05, 0.0}, 0.4},
      {"onto a tread (3 cm up)", {1.1, 0, 0}, {1.27, 0, 0}, 0.6},
  };
  for (const Case& c : cases) {
    const double z_b = c.b.x > 1.25 ? 0.03 : 0.0;  // the course's first tread starts at 1.4 m
    const Frame a = View(c.a, c.tilt, true), b = View(c.b, c.tilt, true, z_b);
    double yaw_error = 0;
    const double error = Register(a, c.a, b, c.b, c.tilt, z_b, &yaw_error);
    std::printf("%s: %.4f m, %.3f deg\n", c.name, error, yaw_error / kDeg);
    EXPECT_LT(error, 0.006) << c.name;
    EXPECT_LT(yaw_error, 0.4 * kDeg) << c.name;
  }
}

// Crawling: the eyes 0.24 m high and tilted up, a crawl cycle forward.
TEST_F(VisualOdometryRender, RecoversACrawlCycle) {
  const Eigen::Isometry3d X_RC = LookAt({0.12, 0.0, 0.24}, {1.1, 0.0, 0.45});
  const Pose2 a{2.9, 0.0, 0.0}, b{2.96, 0.0, 0.02};
  auto view = [&](const Pose2& pose) {
    PlaceRobot(world_.get(), Pose2{-0.3, 0.0, 0});
    const StereoView v =
        RenderStereo(renderer_.get(), *world_, perception::Planar(pose) * X_RC, scenario_.sensor);
    Frame f;
    f.gray = perception::ToGray(v.left);
    f.K = v.intrinsics;
    f.depth = perception::DepthOf(perception::StereoPointImage(v.left, v.right, v.intrinsics,
                                                               PerceptionParams{}.stereo));
    return f;
  };
  const Frame fa = view(a), fb = view(b);
  perception::VisualOdometryState state;
  perception::Keyframe kf;
  kf.gray = fa.gray;
  kf.depth = fa.depth;
  kf.intrinsics = fa.K;
  kf.X_GC = perception::Planar(a) * X_RC;
  state.keyframes.push_back(kf);
  const perception::VisualOdometryResult r = perception::RegisterView(
      params_, fb.gray, fb.depth, fb.K, X_RC, Pose2{b.x - 0.01, b.y + 0.01, b.yaw - kDeg}, 0,
      state);
  ASSERT_TRUE(r.tracked) << r.why;
  EXPECT_LT(std::hypot(r.robot_G.x - b.x, r.robot_G.y - b.y), 0.006);
  EXPECT_LT(std::abs(r.robot_G.yaw - b.yaw), 0.4 * kDeg);
}

// The estimator over a walk: a keyframe at the start (exact), views every 8 cm with 2 % longer
// strides than the odometry says; views that no keyframe overlaps become keyframes, and the
// believed pose stays within a centimetre of the truth where the odometry alone drifts.
TEST_F(VisualOdometryRender, AWalkSwitchesKeyframesAndKeepsThePose) {
  const double tilt = 0.4;
  const Eigen::Isometry3d X_RC = CameraInRobot(tilt);
  perception::LocalizationParams lp;
  perception::LocalizationState state;
  Pose2 truth{0, 0, 0}, believed{0, 0, 0};
  double odometry_error = 0;
  for (int i = 0; i <= 12; ++i) {
    if (i > 0) {
      truth.x += 0.08 * 1.02;
      const Pose2 before = believed;
      believed.x += 0.08;
      PredictPose(before, believed, Eigen::Vector3d(2.5e-5, 2.5e-5, 1e-5).asDiagonal(), &state);
      odometry_error += 0.0016;
    }
    const Frame f = View(truth, tilt, true);
    perception::LocalizationView in;
    in.gray = &f.gray;
    in.depth = &f.depth;
    in.intrinsics = f.K;
    in.X_RC = X_RC;
    const perception::LocalizationReport r = LocalizeView(lp, params_, in, believed, &state);
    believed = r.pose_G;
  }
  std::printf("keyframes %zu, tracked %d of %d, error %.4f m (odometry alone %.4f m)\n",
              state.visual.keyframes.size(), state.visual.tracked, state.visual.views,
              std::hypot(believed.x - truth.x, believed.y - truth.y), odometry_error);
  EXPECT_GE(state.visual.keyframes.size(), 2u);  // the walk left the first one behind
  EXPECT_GE(state.visual.tracked, 10);
  EXPECT_LT(std::hypot(believed.x - truth.x, believed.y - truth.y), 0.006);
  EXPECT_GT(odometry_error, 0.015);
}

}  // namespace
}  // namespace fognav::scenarios

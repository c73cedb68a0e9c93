// Visual odometry on rendered stereo pairs of the course with known motion: the keyframe is
// taken at a known pose, the view after a motion, and the registration, seeded with the true
// pose off by 1 cm and 1 degree, must recover the view's pose.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

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
  };
  for (const Case& c : cases) {
    const Frame a = View(c.a, c.tilt, true), b = View(c.b, c.tilt, true);
    double yaw_error = 0;
    const double error = Register(a, c.a, b, c.b, c.tilt, 0, &yaw_error);
    std::printf("%s: %.4f m, %.3f deg\n", c.name, error, yaw_error / kDeg);
    EXPECT_LT(error, 0.006) << c.name;
    EXPECT_LT(yaw_error, 0.4 * kDeg) << c.name;
  }
}

}  // namespace
}  // namespace fognav::scenarios

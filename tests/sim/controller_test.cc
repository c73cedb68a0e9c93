#include "sim/controller.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "sim/model.h"

namespace fognav::sim {
namespace {

constexpr double kDeg = M_PI / 180;

std::string World(const std::string& bodies) {
  return R"(<mujoco model="test_world">
  <include file="humanoid.xml"/>
  <worldbody>
    <geom name="floor" type="plane" size="4 4 0.1"/>
    )" + bodies + R"(
  </worldbody>
</mujoco>)";
}

// height of the surface under a point (the tests' worlds know their geometry)
using SurfaceFn = std::function<double(double x, double y)>;
double Flat(double, double) { return 0.0; }

// Ground-truth checks on every tick: stance feet neither slide nor tilt nor sink, and the
// head camera's height.
class Monitor {
 public:
  Monitor(const Controller& c, const mjData* d, SurfaceFn surface)
      : c_(&c), d_(d), surface_(std::move(surface)) {}

  void operator()(int) {
    const Humanoid& h = c_->humanoid();
    for (int s = 0; s < 2; ++s) {
      const int site = h.sole_site(Side(s));
      const Eigen::Vector3d p(d_->site_xpos[3 * site], d_->site_xpos[3 * site + 1], d_->site_xpos[3 * site + 2]);
      const double ground = surface_(p.x(), p.y());
      const double yaw = std::atan2(d_->site_xmat[9 * site + 3], d_->site_xmat[9 * site]);
      const bool level = d_->site_xmat[9 * site + 8] > std::cos(1 * kDeg);
      sink_ = std::max(sink_, ground - p.z());
      if (c_->mode() == Mode::kStanding && p.z() - ground < 5e-4) {
        // a foot on the ground: compare with where it touched down
        if (!grounded_[s]) {
          grounded_[s] = true;
          anchor_[s] = p;
          anchor_yaw_[s] = yaw;
        }
        slide_ = std::max(slide_, (p - anchor_[s]).norm());
        twist_ = std::max(twist_, std::abs(std::remainder(yaw - anchor_yaw_[s], 2 * M_PI)));
        if (!level) ++tilted_ticks_;
      } else {
        grounded_[s] = false;
      }
    }
    const double z_cam = HeadCameraPoseInWorld(h, d_, Eye::kLeft).translation().z();
    cam_min_ = std::min(cam_min_, z_cam);
    cam_max_ = std::max(cam_max_, z_cam);
  }

  double slide() const { return slide_; }
  double twist() const { return twist_; }
  double sink() const { return sink_; }
  int tilted_ticks() const { return tilted_ticks_; }
  double camera_range() const { return cam_max_ - cam_min_; }

 private:
  const Controller* c_;
  const mjData* d_;
  SurfaceFn surface_;
  bool grounded_[2] = {false, false};
  Eigen::Vector3d anchor_[2];
  double anchor_yaw_[2] = {0, 0};
  double slide_ = 0, twist_ = 0, sink_ = -1;
  int tilted_ticks_ = 0;
  double cam_min_ = std::numeric_limits<double>::infinity(), cam_max_ = -cam_min_;
};

class ControllerTest : public ::testing::Test {
 protected:
  void Load(const std::string& bodies, const ControllerParams& params = {}) {
    m_ = LoadModelFromXml(World(bodies));
    d_ = MakeData(m_.get());
    c_ = std::make_unique<Controller>(m_.get(), params);
    c_->Reset({0, 0, 0}, 0.0, m_.get(), d_.get());
  }
  Monitor Run(SurfaceFn surface = Flat) {
    Monitor monitor(*c_, d_.get(), std::move(surface));
    c_->RunUntilIdle(m_.get(), d_.get(), std::ref(monitor));
    return monitor;
  }
  void ExpectTruePose(double x, double y, double yaw) {
    const Pose2 p = c_->TruePose(d_.get());
    EXPECT_NEAR(p.x, x, 0.01);
    EXPECT_NEAR(p.y, y, 0.01);
    EXPECT_NEAR(std::remainder(p.yaw - yaw, 2 * M_PI), 0.0, 1 * kDeg);
  }
  void ExpectStanceFeetFirm(const Monitor& monitor) {
    EXPECT_LT(monitor.slide(), 1e-3);
    EXPECT_LT(monitor.twist(), 1 * kDeg);
    EXPECT_EQ(monitor.tilted_ticks(), 0);
    EXPECT_LT(monitor.sink(), 2e-3);
  }
  void ExpectNoCollisions() {
    for (const Collision& c : c_->collisions()) {
      ADD_FAILURE() << "collision at tick " << c.tick << ": " << c.robot_name << " with " << c.world_name
                    << ", " << c.depth * 1000 << " mm";
    }
  }
  ModelPtr m_;
  DataPtr d_;
  std::unique_ptr<Controller> c_;
};

TEST_F(ControllerTest, WalksOneMetreStraight) {
  Load("");
  c_->Walk(1.0, 0, 0);
  const Monitor monitor = Run();
  ExpectTruePose(1.0, 0, 0);
  ExpectStanceFeetFirm(monitor);
  EXPECT_LT(monitor.camera_range(), 0.02);
  ExpectNoCollisions();
  EXPECT_EQ(c_->steps(), 2 * 13);  // 13 strides of 7.7 cm
  EXPECT_NEAR(c_->believed_pose().x, 1.0, 1e-9);
  RecordProperty("camera_height_range_mm", std::to_string(monitor.camera_range() * 1000));
}

TEST_F(ControllerTest, SideStepsHalfAMetre) {
  Load("");
  c_->Walk(0, 0.5, 0);
  Monitor monitor = Run();
  ExpectTruePose(0, 0.5, 0);
  c_->Walk(0, -0.5, 0);
  monitor = Run();
  ExpectTruePose(0, 0, 0);
  ExpectStanceFeetFirm(monitor);
  EXPECT_LT(monitor.camera_range(), 0.02);
  ExpectNoCollisions();
}

TEST_F(ControllerTest, TurnsNinetyDegreesOnTheSpot) {
  Load("");
  c_->Walk(0, 0, M_PI / 2);
  Monitor monitor = Run();
  ExpectTruePose(0, 0, M_PI / 2);
  ExpectStanceFeetFirm(monitor);
  c_->Walk(0, 0, -M_PI / 2);
  monitor = Run();
  ExpectTruePose(0, 0, 0);
  ExpectStanceFeetFirm(monitor);
  EXPECT_LT(monitor.camera_range(), 0.02);
  ExpectNoCollisions();
}

TEST_F(ControllerTest, WalksACombinedDisplacement) {
  Load("");
  c_->Walk(0.4, -0.2, 60 * kDeg);
  const Monitor monitor = Run();
  ExpectTruePose(0.4, -0.2, 60 * kDeg);
  ExpectStanceFeetFirm(monitor);
  EXPECT_NEAR(c_->believed_pose().x, 0.4, 1e-9);
  EXPECT_NEAR(c_->believed_pose().y, -0.2, 1e-9);
  EXPECT_NEAR(c_->believed_pose().yaw, 60 * kDeg, 1e-9);
}

TEST_F(ControllerTest, OdometryDriftsFromTheTruthWithSeededNoise) {
  ControllerParams params;
  params.odometry_noise_xy = 0.005;
  params.odometry_noise_yaw = 1 * kDeg;
  params.seed = 42;
  Load("", params);
  c_->Walk(1.0, 0, 0);
  Run();
  const Pose2 truth = c_->TruePose(d_.get());
  // belief integrates the commands; the truth went elsewhere
  EXPECT_NEAR(c_->believed_pose().x, 1.0, 1e-9);
  EXPECT_NEAR(c_->believed_pose().y, 0.0, 1e-9);
  const double drift = std::hypot(truth.x - 1.0, truth.y);
  EXPECT_GT(drift, 0.005);
  EXPECT_LT(drift, 0.3);
  // the same seed drifts the same way
  c_->Reset({0, 0, 0}, 0.0, m_.get(), d_.get());
  c_->Walk(1.0, 0, 0);
  Run();
  EXPECT_DOUBLE_EQ(c_->TruePose(d_.get()).x, truth.x);
  EXPECT_DOUBLE_EQ(c_->TruePose(d_.get()).y, truth.y);
}

// The systematic part: every stride scaled by the same drawn factor, a heading that creeps
// by the same drawn angle each footstep; the per-step stream is untouched by it.
TEST_F(ControllerTest, SystematicOdometryErrorScalesStridesAndCreepsTheHeading) {
  ControllerParams params;
  params.odometry_stride_scale = 0.03;
  params.odometry_yaw_bias = 0.2 * kDeg;
  params.seed = 7;
  Load("", params);
  const double s = c_->stride_scale_error(), b = c_->yaw_bias_error();
  EXPECT_NE(s, 0.0);
  EXPECT_LT(std::abs(s), 0.15);  // 5 sigma
  c_->Walk(0.8, 0, 0);
  Run();
  EXPECT_TRUE(c_->settled());
  const Pose2 truth = c_->TruePose(d_.get());
  EXPECT_NEAR(c_->believed_pose().x, 0.8, 1e-9);
  // 10 strides of 8 cm, 20 footsteps of yaw bias
  EXPECT_NEAR(truth.yaw, 20 * b, 1e-6);
  const double along = truth.x * std::cos(10 * b) + truth.y * std::sin(10 * b);
  EXPECT_NEAR(along, 0.8 * (1 + s), 0.004);
  // without the systematic part the same seed walks exactly
  ControllerParams exact;
  exact.seed = 7;
  Load("", exact);
  c_->Walk(0.8, 0, 0);
  Run();
  EXPECT_NEAR(c_->TruePose(d_.get()).x, 0.8, 1e-6);
}

// treads as on the course: 3 cm, 6 cm, 3 cm, each a box from the floor up
const char* kStairs = R"(
    <geom name="tread_1" type="box" pos="0.425 0 0.015" size="0.125 0.5 0.015"/>
    <geom name="tread_2" type="box" pos="0.725 0 0.03" size="0.175 0.5 0.03"/>
    <geom name="tread_3" type="box" pos="1.025 0 0.015" size="0.125 0.5 0.015"/>)";

double StairsSurface(double x, double) {
  if (x >= 0.3 && x < 0.55) return 0.03;
  if (x >= 0.55 && x < 0.9) return 0.06;
  if (x >= 0.9 && x < 1.15) return 0.03;
  return 0.0;
}

TEST_F(ControllerTest, ClimbsUpAndDownTreadsOfThreeAndSixCentimetres) {
  Load(kStairs);
  // toes 2 cm before each riser, then one stride onto the tread (heights from perception)
  c_->Walk(0.225, 0, 0);    // sole centres at 0.225, toes at 0.28
  c_->StepOnto(0.155, 0.03);  // onto tread 1 at 0.38
  c_->Walk(0.095, 0, 0);    // 0.475, toes at 0.53
  c_->StepOnto(0.16, 0.03);   // onto tread 2 at 0.635
  c_->Walk(0.19, 0, 0);     // 0.825, toes 2 cm before its end
  c_->StepOnto(0.155, -0.03);  // down onto tread 3 at 0.98
  c_->Walk(0.095, 0, 0);    // 1.075
  c_->StepOnto(0.155, -0.03);  // down to the floor at 1.23
  const Monitor monitor = Run(StairsSurface);
  ExpectTruePose(1.23, 0, 0);
  ExpectStanceFeetFirm(monitor);
  ExpectNoCollisions();
  const double z = RobotFrameInWorld(c_->humanoid(), d_.get()).translation().z();
  EXPECT_NEAR(z, 0.0, 1e-3);
}

// a step onto a tread a little aside (stairs turned between the planner's headings): the lead
// foot is the one on the side of the motion, so the feet never cross
TEST_F(ControllerTest, StepsUpAndDownATreadALittleAside) {
  Load(kStairs);
  const double aside = ControllerParams().limits.max_climb_sideways;
  c_->Walk(0.225, 0, 0);
  c_->StepOnto(0.155, 0.03, -aside);  // onto tread 1, to the right
  c_->Walk(0.095, 0, 0);
  c_->StepOnto(0.16, 0.03, aside);  // onto tread 2, back to the left
  c_->Walk(0.19, 0, 0);
  c_->StepOnto(0.155, -0.03, aside);  // down onto tread 3, to the left
  const Monitor monitor = Run(StairsSurface);
  ExpectTruePose(0.98, aside, 0);
  ExpectStanceFeetFirm(monitor);
  ExpectNoCollisions();
  EXPECT_THROW(c_->StepOnto(0.1, 0.03, 1.5 * aside), std::invalid_argument);
}

TEST_F(ControllerTest, StandsOnATreadAtItsHeight) {
  Load(kStairs);
  c_->Walk(0.225, 0, 0);
  c_->StepOnto(0.155, 0.03);
  c_->Walk(0.095, 0, 0);
  c_->StepOnto(0.16, 0.03);
  Run(StairsSurface);
  EXPECT_NEAR(RobotFrameInWorld(c_->humanoid(), d_.get()).translation().z(), 0.06, 1e-3);
  // standing height is measured from the tread
  EXPECT_NEAR(RobotVerticalExtent(c_->humanoid(), m_.get(), d_.get())[1], 0.06 + 0.58, 0.01);
}

TEST_F(ControllerTest, RejectsATreadTooHighOrTooFar) {
  Load("");
  EXPECT_THROW(c_->StepOnto(0.1, 0.08), std::invalid_argument);
  EXPECT_THROW(c_->StepOnto(0.3, 0.03), std::invalid_argument);
  EXPECT_THROW(c_->Crawl(0.1, 0), std::logic_error);
}

// a table with its underside at 0.35 m: top 3 cm thick, legs outside the robot's way
const char* kTable = R"(
    <body name="desk">
      <geom name="desk_top" type="box" pos="0.85 0 0.365" size="0.3 0.5 0.015"/>
      <geom name="desk_leg_1" type="box" pos="0.57 0.47 0.175" size="0.02 0.02 0.175"/>
      <geom name="desk_leg_2" type="box" pos="0.57 -0.47 0.175" size="0.02 0.02 0.175"/>
      <geom name="desk_leg_3" type="box" pos="1.13 0.47 0.175" size="0.02 0.02 0.175"/>
      <geom name="desk_leg_4" type="box" pos="1.13 -0.47 0.175" size="0.02 0.02 0.175"/>
    </body>)";

TEST_F(ControllerTest, CrawlsUnderATableWithItsUndersideAt35Centimetres) {
  Load(kTable);
  c_->GetDown();
  c_->Crawl(1.26, 0);
  Monitor monitor(*c_, d_.get(), Flat);
  double top = 0;
  int crawl_ticks = 0;
  c_->RunUntilIdle(m_.get(), d_.get(), [&](int tick) {
    monitor(tick);
    if (c_->mode() == Mode::kCrawling) {
      top = std::max(top, RobotVerticalExtent(c_->humanoid(), m_.get(), d_.get())[1]);
      ++crawl_ticks;
    }
  });
  EXPECT_GT(crawl_ticks, 0);
  EXPECT_LT(top, 0.30);
  EXPECT_LT(monitor.sink(), 5e-3);
  c_->GetUp();
  Run();
  EXPECT_EQ(c_->mode(), Mode::kStanding);
  ExpectTruePose(1.26, 0, 0);
  ExpectNoCollisions();
  RecordProperty("crawl_height_m", std::to_string(top));
}

// The planner (navigation::PlannerParams::kneel_clear_reach) lets tunnel cells lie under the
// crawling footprint more than 0.46 m ahead of the standing origin when the robot gets down: the
// body must stay below the lowest tunnel ceiling (0.30 m) there throughout.
TEST_F(ControllerTest, GettingDownKeepsTheBodyLowBeyondTheKneelClearReach) {
  Load("");
  double highest_beyond = 0, highest = 0;
  auto envelope = [&](int) {
    const Eigen::Isometry3d X_WR0 = Eigen::Isometry3d::Identity();  // the start: world = robot
    const Eigen::Isometry3d X_WR = RobotFrameInWorld(c_->humanoid(), d_.get());
    for (const RobotBox& box : RobotBodyBoxes(c_->humanoid(), m_.get(), d_.get())) {
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d corner((k & 1 ? 1 : -1) * box.half_size.x(),
                                     (k & 2 ? 1 : -1) * box.half_size.y(),
                                     (k & 4 ? 1 : -1) * box.half_size.z());
        const Eigen::Vector3d p = X_WR0.inverse() * X_WR * (box.X_RB * corner);
        highest = std::max(highest, p.z());
        if (p.x() > 0.46) highest_beyond = std::max(highest_beyond, p.z());
      }
    }
  };
  c_->GetDown();
  c_->RunUntilIdle(m_.get(), d_.get(), envelope);
  c_->GetUp();
  c_->RunUntilIdle(m_.get(), d_.get(), envelope);
  EXPECT_GT(highest, 0.55);  // it does stand up and get down
  EXPECT_LT(highest_beyond, 0.30);
}

TEST_F(ControllerTest, CrawlTurnsAndKeepsItsBelief) {
  Load("");
  c_->GetDown();
  c_->Crawl(0.2, 45 * kDeg);
  c_->GetUp();
  Run();
  const Pose2 believed = c_->believed_pose();
  const Pose2 truth = c_->TruePose(d_.get());
  EXPECT_NEAR(truth.x, believed.x, 0.01);
  EXPECT_NEAR(truth.y, believed.y, 0.01);
  EXPECT_NEAR(std::remainder(truth.yaw - believed.yaw, 2 * M_PI), 0.0, 1 * kDeg);
  EXPECT_NEAR(believed.yaw, 45 * kDeg, 1e-9);
  ExpectNoCollisions();
}

// two blocks 0.22 m apart across the way: narrower than the shoulders (0.26 m with the arms),
// wider than the robot's depth. They are 0.5 m tall: below the hands (0.22 m) the robot is only
// 0.16 m wide and would pass a 0.22 m gap front on.
const char* kGap = R"(
    <geom name="block_left" type="box" pos="0.6 0.31 0.25" size="0.1 0.2 0.25"/>
    <geom name="block_right" type="box" pos="0.6 -0.31 0.25" size="0.1 0.2 0.25"/>)";

TEST_F(ControllerTest, SideStepsThroughAGapOf22Centimetres) {
  Load(kGap);
  c_->Walk(0, 0, M_PI / 2);
  c_->Walk(0, -1.2, 0);  // facing +y, the robot's right is +x
  c_->Walk(0, 0, -M_PI / 2);
  const Monitor monitor = Run();
  ExpectTruePose(1.2, 0, 0);
  ExpectStanceFeetFirm(monitor);
  ExpectNoCollisions();
}

TEST_F(ControllerTest, NamesTheGeomsOfACollision) {
  Load(kGap);
  c_->Walk(1.2, 0, 0);  // front on, the shoulders do not fit
  Run();
  ASSERT_FALSE(c_->collisions().empty());
  bool arm_hit_block = false;
  for (const Collision& c : c_->collisions()) {
    EXPECT_GT(c.depth, 0.005);
    EXPECT_EQ(c.robot_name.rfind("robot_", 0), 0u);
    arm_hit_block = arm_hit_block || (c.robot_name.find("arm") != std::string::npos &&
                                      c.world_name.rfind("block_", 0) == 0);
  }
  EXPECT_TRUE(arm_hit_block);
}

TEST_F(ControllerTest, LooksAroundAtTheFloorNearAndAhead) {
  Load("");
  const std::vector<HeadAngles> views = LookAroundSweep();
  ASSERT_GE(views.size(), 6u);
  double nearest = 1e9, farthest = 0, left = 0, right = 0;
  for (const HeadAngles& view : views) {
    c_->MoveHead(view);
    Run();
    const Eigen::Isometry3d X_RC = HeadCameraPose(c_->humanoid(), d_.get(), Eye::kLeft);
    EXPECT_NEAR(d_->qpos[c_->humanoid().joint_qpos(kNeckPan)], view.pan, 1e-9);
    // where the optical axis meets the floor, in the robot frame
    const Eigen::Vector3d axis = X_RC.linear().col(2);
    ASSERT_LT(axis.z(), 0);
    const Eigen::Vector3d hit = X_RC.translation() - X_RC.translation().z() / axis.z() * axis;
    nearest = std::min(nearest, hit.head<2>().norm());
    farthest = std::max(farthest, hit.head<2>().norm());
    left = std::max(left, hit.y());
    right = std::min(right, hit.y());
  }
  EXPECT_LT(nearest, 0.35);
  EXPECT_GT(farthest, 0.8);
  EXPECT_GT(left, 0.2);
  EXPECT_LT(right, -0.2);
  EXPECT_NEAR(views.back().pan, 0.0, 1e-9);
}

// The near ring stops short of the far ring's pans, where arm and shoulder hide the floor from
// one eye; both rings keep their order and the far ring pans as far as asked.
TEST(LookAroundSweep, NearRingPansNoFurtherThanItsLimit) {
  LookAroundParams params;
  params.pans = {-1.4, -0.7, 0.0, 0.7, 1.4};
  params.tilts = {1.0, 0.5};
  params.near_pan_limit = 0.9;
  const std::vector<HeadAngles> views = LookAroundSweep(params);
  ASSERT_EQ(views.size(), 11u);
  const std::vector<double> near = {-0.9, -0.7, 0.0, 0.7, 0.9}, far = {1.4, 0.7, 0.0, -0.7, -1.4};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(views[i].pan, near[i]);
    EXPECT_DOUBLE_EQ(views[i].tilt, 1.0);
    EXPECT_DOUBLE_EQ(views[5 + i].pan, far[i]);
    EXPECT_DOUBLE_EQ(views[5 + i].tilt, 0.5);
  }
  EXPECT_DOUBLE_EQ(views.back().pan, 0.0);
}

// renders off-screen through OSMesa
TEST_F(ControllerTest, ClipRecorderWritesAFrameEveryFewTicks) {
  Load("");
  ClipParams params;
  params.dir = ::testing::TempDir() + "/fognav_clip_test";
  params.every = 10;
  params.width_px = 160;
  params.height_px = 120;
  std::filesystem::remove_all(params.dir);
  ClipRecorder clip(m_.get(), c_->humanoid(), params);
  c_->Walk(0.08, 0, 0);  // one stride: 100 ticks
  c_->RunUntilIdle(m_.get(), d_.get(), [&](int tick) { clip(m_.get(), d_.get(), tick); });
  EXPECT_EQ(clip.frames(), 10);
  EXPECT_TRUE(std::filesystem::exists(params.dir + "/frame_00000.png"));
  EXPECT_TRUE(std::filesystem::exists(params.dir + "/frame_00009.png"));
  EXPECT_GT(std::filesystem::file_size(params.dir + "/frame_00009.png"), 1000u);
}

// Crawling, the head is raised to look straight ahead (so the robot sees where it crawls and
// the ceiling it crawls under), and it can look up and down without rising to a 0.30 m ceiling.
TEST_F(ControllerTest, CrawlingHeadLooksAheadAndStaysBelowATunnelCeiling) {
  Load("");
  c_->GetDown();
  Run();
  auto elevation = [&]() {
    const Eigen::Vector3d f =
        HeadCameraPoseInWorld(c_->humanoid(), d_.get(), Eye::kLeft).rotation().col(2);
    return std::asin(f.z());
  };
  EXPECT_NEAR(elevation(), 0.0, 0.05);
  double highest = -1, lowest = 1;
  for (double tilt = -1.55; tilt <= -0.8; tilt += 0.05) {
    c_->MoveHead({0.0, tilt});
    Run();
    // the head's corner passes 0.3 mm above 0.30 m near tilt -1.0: within a millimetre
    EXPECT_LT(RobotVerticalExtent(c_->humanoid(), m_.get(), d_.get())[1], 0.301) << tilt;
    highest = std::max(highest, elevation());
    lowest = std::min(lowest, elevation());
  }
  EXPECT_GT(highest, 0.1);
  EXPECT_LT(lowest, -0.5);
  ExpectNoCollisions();
}

}  // namespace
}  // namespace fognav::sim

namespace fognav::sim {
namespace {

// The planner keeps obstacles off the body it assumes (navigation::PlannerParams): soles 0.12 m
// long, knees from 0.055 m behind the origin to 0.09 m ahead, shoulders 0.13 m to either side
// (margin 0.015 m on top), the tilted head 0.12 m from the origin. The body must stay inside
// those, margin included, whatever the controller does.
TEST_F(ControllerTest, BodyStaysWithinWhatThePlannerAssumes) {
  Load("");
  std::array<double, 4> reach = {0, 0, 0, 0};  // behind, ahead, right, left
  auto track = [&](int) {
    const auto e = RobotPlanarExtent(c_->humanoid(), m_.get(), d_.get());
    reach = {std::max(reach[0], -e[0]), std::max(reach[1], e[1]), std::max(reach[2], -e[2]),
             std::max(reach[3], e[3])};
  };
  auto run = [&]() {
    reach = {0, 0, 0, 0};
    c_->RunUntilIdle(m_.get(), d_.get(), track);
  };
  constexpr double kMargin = 0.015;
  // at rest the soles and knees lie within the soles' footprint, the arms within the shoulders
  c_->Walk(0.04, 0, 0);
  run();
  const auto rest = RobotPlanarExtent(c_->humanoid(), m_.get(), d_.get());
  EXPECT_LT(-rest[0], 0.06 + kMargin);
  EXPECT_LT(rest[1], 0.09 + kMargin);
  EXPECT_LT(std::max(-rest[2], rest[3]), 0.13 + kMargin);
  // side-steps and turns in place: the knees come forward as a foot lifts, less than in a walk,
  // as these lift it less (ControllerParams::side_clearance): they pass between blocks facing
  // one, and keep the knees 7 mm further back than the planner's body_front
  c_->Walk(0.3, 0, 0);
  run();
  EXPECT_GT(reach[1], 0.09 - 0.002) << "a walk lifts the sole higher";
  for (const Eigen::Vector3d& move :
       {Eigen::Vector3d(0, 0.3, 0), Eigen::Vector3d(0, -0.3, 0), Eigen::Vector3d(0, 0, 1.0)}) {
    c_->Walk(move.x(), move.y(), move.z());
    run();
    EXPECT_LT(reach[0], 0.055 + kMargin) << move.transpose();
    EXPECT_LT(reach[1], 0.09 - 0.007) << move.transpose();
    EXPECT_GT(reach[1], 0.06 + kMargin) << "the knees pass the soles' footprint";
    // the arms swing out a little beyond the shoulders' margin (see PlannerParams)
    EXPECT_LT(std::max(reach[2], reach[3]), 0.13 + kMargin + 0.01) << move.transpose();
  }
  // looking down ahead and to the side, the head reaches no further than head_reach + margin
  for (const HeadAngles& view : {HeadAngles{0.0, 1.1}, HeadAngles{1.2, 1.1}}) {
    c_->MoveHead(view);
    run();
    EXPECT_LT(std::max({reach[1], reach[2], reach[3]}), 0.12 + kMargin + 0.01);
  }
}

}  // namespace
}  // namespace fognav::sim

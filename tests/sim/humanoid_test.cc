#include "sim/humanoid.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sim/controller.h"
#include "sim/model.h"

namespace fognav::sim {
namespace {

constexpr double kDeg = M_PI / 180;

// a world of its own defaults and a floor, including the robot
const char* kWorld = R"(
<mujoco model="floor_world">
  <default><geom rgba="0.5 0.5 0.5 1"/></default>
  <include file="humanoid.xml"/>
  <worldbody>
    <light pos="0 0 3"/>
    <geom name="floor" type="plane" size="3 3 0.1"/>
  </worldbody>
</mujoco>)";

double TotalMass(const mjModel* m, int root) {
  double mass = 0;
  for (int b = 0; b < m->nbody; ++b) {
    if (m->body_rootid[b] == root) mass += m->body_mass[b];
  }
  return mass;
}

TEST(Humanoid, LoadsAloneAndInsideAWorld) {
  ModelPtr alone = LoadModelFromXml(ShippedModel("humanoid.xml"));
  ModelPtr world = LoadModelFromXml(kWorld);
  const Humanoid h_alone(alone.get()), h(world.get());
  EXPECT_EQ(h_alone.geom_ids().size(), h.geom_ids().size());
  EXPECT_NEAR(TotalMass(world.get(), h.base_body()), 7.0, 0.3);
  // world geoms keep their own defaults and are not robot geoms
  const int floor = mj_name2id(world.get(), mjOBJ_GEOM, "floor");
  EXPECT_FALSE(h.IsRobotGeom(floor));
  EXPECT_FLOAT_EQ(world->geom_rgba[4 * floor], 0.5f);
  EXPECT_EQ(world->geom_contype[floor], 1);
  // robot geoms collide with the world but not with each other
  for (int g : h.geom_ids()) {
    EXPECT_EQ(world->geom_contype[g] & world->geom_conaffinity[g], 0) << JointName(kWaist);
    EXPECT_TRUE(world->geom_contype[floor] & world->geom_conaffinity[g]);
  }
}

class StandingRobot : public ::testing::Test {
 protected:
  void SetUp() override {
    m_ = LoadModelFromXml(kWorld);
    d_ = MakeData(m_.get());
    controller_ = std::make_unique<Controller>(m_.get());
    controller_->Reset({0.4, -0.3, 30 * kDeg}, 0.0, m_.get(), d_.get());
  }
  const Humanoid& h() const { return controller_->humanoid(); }
  ModelPtr m_;
  DataPtr d_;
  std::unique_ptr<Controller> controller_;
};

TEST_F(StandingRobot, Is58CentimetresTallWithNothingBelowTheFloor) {
  const auto extent = RobotVerticalExtent(h(), m_.get(), d_.get());
  EXPECT_NEAR(extent[1], 0.58, 0.01);
  EXPECT_GE(extent[0], -1e-6);
}

TEST_F(StandingRobot, StandsWithBothSolesFlatOnTheFloor) {
  for (int s = 0; s < 2; ++s) {
    const int site = h().sole_site(Side(s));
    EXPECT_NEAR(d_->site_xpos[3 * site + 2], 0.0, 1e-3);
    EXPECT_GT(d_->site_xmat[9 * site + 8], std::cos(1 * kDeg));  // sole normal up within 1 deg
    // the sole plate's bottom face is the site
    const int g = h().sole_geom(Side(s));
    EXPECT_NEAR(d_->geom_xpos[3 * g + 2] - m_->geom_size[3 * g + 2], 0.0, 1e-3);
  }
  EXPECT_TRUE(controller_->collisions().empty());
}

TEST_F(StandingRobot, HasAForwardLookingStereoPairFiveCentimetresApart) {
  const Eigen::Isometry3d X_RL = HeadCameraPose(h(), d_.get(), Eye::kLeft);
  const Eigen::Isometry3d X_RR = HeadCameraPose(h(), d_.get(), Eye::kRight);
  // OpenCV camera: z forward = robot x, x right = robot -y, y down = robot -z
  EXPECT_GT(X_RL.linear().col(2).dot(Eigen::Vector3d::UnitX()), 0.999);
  EXPECT_GT(X_RL.linear().col(0).dot(-Eigen::Vector3d::UnitY()), 0.999);
  EXPECT_GT(X_RL.linear().col(1).dot(-Eigen::Vector3d::UnitZ()), 0.999);
  // the right eye sits 5 cm along the left camera's x axis
  const Eigen::Vector3d baseline = X_RL.inverse() * X_RR.translation();
  EXPECT_NEAR(baseline.x(), 0.05, 1e-9);
  EXPECT_NEAR(baseline.y(), 0.0, 1e-9);
  EXPECT_NEAR(baseline.z(), 0.0, 1e-9);
  EXPECT_NEAR(X_RL.translation().z(), 0.52, 0.01);
  EXPECT_NEAR(m_->cam_fovy[h().camera(Eye::kLeft)], 37.45, 0.01);
  // 45 deg horizontally at 176x144
  const double hfov = 2 * std::atan(std::tan(37.45 / 2 * kDeg) * 176.0 / 144.0);
  EXPECT_NEAR(hfov / kDeg, 45.0, 0.05);
}

TEST_F(StandingRobot, HeadCameraPoseComesFromTheJointsNotTheBasePose) {
  const Eigen::Isometry3d before = HeadCameraPose(h(), d_.get(), Eye::kLeft);
  // same joints, base elsewhere: the pose in the robot frame does not change
  JointPosture p = GetPosture(h(), d_.get());
  p.X_WB = Eigen::Translation3d(1.0, 2.0, 0.3) * Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ()) * p.X_WB;
  SetPosture(h(), p, d_.get());
  mj_kinematics(m_.get(), d_.get());
  mj_camlight(m_.get(), d_.get());
  const Eigen::Isometry3d after = HeadCameraPose(h(), d_.get(), Eye::kLeft);
  EXPECT_LT((before.matrix() - after.matrix()).norm(), 1e-9);
  // and it agrees with the world poses of robot and camera
  const Eigen::Isometry3d X_WC = RobotFrameInWorld(h(), d_.get()) * after;
  EXPECT_LT((X_WC.matrix() - HeadCameraPoseInWorld(h(), d_.get(), Eye::kLeft).matrix()).norm(), 1e-9);
}

TEST_F(StandingRobot, BodyBoxesCoverTheBody) {
  const auto boxes = RobotBodyBoxes(h(), m_.get(), d_.get());
  ASSERT_EQ(boxes.size(), h().geom_ids().size());
  double top = 0, half_width = 0, front = -1, back = 1;
  for (const RobotBox& box : boxes) {
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d c(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
      const Eigen::Vector3d p = box.X_RB * c.cwiseProduct(box.half_size);
      top = std::max(top, p.z());
      half_width = std::max(half_width, std::abs(p.y()));
      front = std::max(front, p.x());
      back = std::min(back, p.x());
    }
  }
  EXPECT_NEAR(top, 0.58, 0.01);
  // wider at the shoulders than deep: a 0.22 m gap needs side-stepping
  EXPECT_GT(2 * half_width, 0.22);
  EXPECT_LT(front - back, 0.16);
  RecordProperty("shoulder_width_m", std::to_string(2 * half_width));
  RecordProperty("depth_m", std::to_string(front - back));
}

TEST_F(StandingRobot, CrawlPostureFitsUnder30Centimetres) {
  controller_->GetDown();
  controller_->RunUntilIdle(m_.get(), d_.get());
  EXPECT_EQ(controller_->mode(), Mode::kCrawling);
  const auto extent = RobotVerticalExtent(h(), m_.get(), d_.get());
  EXPECT_LT(extent[1], 0.30);
  EXPECT_GE(extent[0], -2e-3);
  EXPECT_TRUE(controller_->collisions().empty());
  // hands and knees carry the robot
  for (int s = 0; s < 2; ++s) {
    for (int g : {h().hand_geom(Side(s)), h().knee_geom(Side(s))}) {
      EXPECT_NEAR(d_->geom_xpos[3 * g + 2], m_->geom_size[3 * g], 2e-3) << mj_id2name(m_.get(), mjOBJ_GEOM, g);
    }
  }
}

}  // namespace
}  // namespace fognav::sim

// Separating-axis penetration of two boxes, and the MuJoCo 2.2 box-box contact it checks.
#include "sim/internal/box_overlap.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "sim/controller.h"
#include "sim/model.h"

namespace fognav::sim {
namespace {

using internal::Box;
using internal::BoxPenetration;

Box MakeBox(const Eigen::Vector3d& center, const Eigen::Vector3d& half, double yaw = 0.0) {
  Box box;
  box.center = center;
  box.half = half;
  box.axes = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return box;
}

TEST(BoxPenetration, IsTheOverlapAlongTheShallowestAxis) {
  const Box floor = MakeBox({0, 0, -0.05}, {1, 1, 0.05});
  // a sole 3 mm into the floor, turned by any yaw: 3 mm
  for (double yaw : {0.0, 0.35, 1.0}) {
    EXPECT_NEAR(BoxPenetration(floor, MakeBox({0.2, 0.1, 0.007}, {0.055, 0.032, 0.01}, yaw)),
                0.003, 1e-12);
  }
  // 2 cm above it: separated by 2 cm
  EXPECT_NEAR(BoxPenetration(floor, MakeBox({0, 0, 0.03}, {0.055, 0.032, 0.01})), -0.02, 1e-12);
  // pushed 1 cm sideways into a wall's face: 1 cm, whatever its height
  const Box wall = MakeBox({0.5, 0, 0.15}, {0.05, 1, 0.15});
  EXPECT_NEAR(BoxPenetration(wall, MakeBox({0.405, 0, 0.01}, {0.055, 0.032, 0.01})), 0.01, 1e-12);
  // symmetric in its arguments
  const Box sole = MakeBox({0.43, 0.2, 0.05}, {0.055, 0.032, 0.01}, 0.7);
  EXPECT_NEAR(BoxPenetration(wall, sole), BoxPenetration(sole, wall), 1e-12);
}

// Two boxes turned 45 degrees about x and about z: they touch edge to edge, where only the
// cross product of the edges separates them (face axes alone report an overlap).
TEST(BoxPenetration, EdgeToEdgeUsesTheCrossAxes) {
  Box a = MakeBox({0, 0, 0}, {0.1, 0.1, 0.1});
  a.axes = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  Box b = MakeBox({0, 0, 0}, {0.1, 0.1, 0.1});
  b.axes = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double reach = 0.1 * std::sqrt(2.0);  // each box's edge from its centre along z
  b.center.z() = 2 * reach + 0.01;
  EXPECT_NEAR(BoxPenetration(a, b), -0.01, 1e-9);
  b.center.z() = 2 * reach - 0.01;
  EXPECT_NEAR(BoxPenetration(a, b), 0.01, 1e-9);
}

// MuJoCo 2.2.2's box-box collider reports a contact 0.48 m deep for a sole resting flush on
// a tread (the poses of a mission's sole and tread, to the last bit: 3 micrometres of overlap;
// google-deepmind/mujoco#3476 reports the same kind of phantom in MuJoCo 3.10). The separating
// axes say 3 micrometres; Controller::CheckContacts takes the smaller of the two, no collision.
TEST(BoxPenetration, ReadsAFlushSoleOnATreadAsShallowWhereMujocoDoesNot) {
  const Eigen::Vector3d sole_center(1.3120717840719736, -0.21188903074534129, 0.079997102022170988);
  Eigen::Matrix3d sole_axes;  // row-major, as MuJoCo's geom_xmat
  sole_axes << 0.9402325594864267, -0.3405330146720047, -5.4502811934676745e-17,
      0.3405330146720047, 0.9402325594864267, -1.3088345659061388e-17, 5.570233216889788e-17,
      -6.2539181177544344e-18, 1.0000000000000004;
  const ModelPtr model = LoadModelFromXml(R"(
<mujoco>
  <worldbody>
    <geom name="tread" type="box" pos="1.3 -0.26 0.035" size="0.2 0.43 0.035"/>
    <body name="foot">
      <freejoint/>
      <geom name="sole" type="box" size="0.055 0.032 0.01"/>
    </body>
  </worldbody>
</mujoco>)");
  const DataPtr data = MakeData(model.get());
  for (int k = 0; k < 3; ++k) data->qpos[k] = sole_center[k];
  mj_kinematics(model.get(), data.get());
  // the sole's pose exactly as the mission's kinematic chain left it
  for (int k = 0; k < 3; ++k) data->geom_xpos[3 + k] = sole_center[k];
  for (int k = 0; k < 9; ++k) data->geom_xmat[9 + k] = sole_axes(k / 3, k % 3);
  mj_collision(model.get(), data.get());
  double deepest = 0;
  for (int i = 0; i < data->ncon; ++i) deepest = std::max(deepest, -data->contact[i].dist);

  Box sole = MakeBox(sole_center, {0.055, 0.032, 0.01});
  sole.axes = sole_axes;
  const double separating = BoxPenetration(MakeBox({1.3, -0.26, 0.035}, {0.2, 0.43, 0.035}), sole);
  EXPECT_NEAR(separating, 0.070 - (sole_center.z() - 0.01), 1e-9);
  // MuJoCo's own depth is recorded, not asserted: 0.48 m with Debian 12's libmujoco 2.2.2 on
  // x86-64, and a MuJoCo that fixes it leaves the rule right
  RecordProperty("mujoco_depth_m", std::to_string(deepest));
  EXPECT_LT(std::min(deepest, separating), ControllerParams{}.collision_depth);
}

}  // namespace
}  // namespace fognav::sim

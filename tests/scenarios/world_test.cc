#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "scenarios/scenario.h"
#include "scenarios/views.h"
#include "sim/render.h"

namespace fognav::scenarios {
namespace {

TEST(WorldFromScenario, HoldsExactlyTheListedObjects) {
  Scenario scenario = LoadScenario("scenarios/stairs_and_table.yaml");
  std::vector<Solid> solids = WorldSolids(scenario);
  sim::World world(MakeWorldSpec(scenario));
  const mjModel* m = world.model();
  const mjData* d = world.data();

  // every geom is the floor, a part of the robot or one of the scenario's solids or its skin,
  // once; a skin coincides with its solid, is seen in colour only and never touches anything
  std::set<int> solid_geoms;
  for (size_t i = 0; i < solids.size(); ++i) {
    int geom = world.box_geom(i);
    ASSERT_GE(geom, 0) << solids[i].name;
    EXPECT_TRUE(solid_geoms.insert(geom).second);
    EXPECT_EQ(m->geom_type[geom], mjGEOM_BOX);
    Eigen::Map<const Eigen::Vector3d> p(d->geom_xpos + 3 * geom);
    Eigen::Map<const Eigen::Vector3d> half(m->geom_size + 3 * geom);
    EXPECT_TRUE(p.isApprox(solids[i].box.X_FB.translation(), 1e-9)) << solids[i].name;
    EXPECT_TRUE(half.isApprox(solids[i].box.half_size, 1e-9)) << solids[i].name;
    EXPECT_EQ(m->geom_group[geom], sim::kSolidGroup);
    int skin = world.skin_geom(i);
    ASSERT_GE(skin, 0) << solids[i].name;
    EXPECT_TRUE(solid_geoms.insert(skin).second);
    EXPECT_EQ(m->geom_type[skin], mjGEOM_MESH);
    EXPECT_EQ(m->geom_group[skin], sim::kSkinGroup);
    EXPECT_EQ(m->geom_contype[skin] | m->geom_conaffinity[skin], 0);
    Eigen::Map<const Eigen::Vector3d> skin_p(d->geom_xpos + 3 * skin);
    EXPECT_TRUE(skin_p.isApprox(p, 1e-9)) << solids[i].name;
    // the skin's mesh spans the box: its bounding half extents are the box's in some order
    const int mesh = m->geom_dataid[skin];
    Eigen::Vector3d extent = Eigen::Vector3d::Zero();
    for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
      for (int a = 0; a < 3; ++a) {
        extent[a] = std::max(extent[a],
                             double(std::abs(m->mesh_vert[3 * (m->mesh_vertadr[mesh] + v) + a])));
      }
    }
    Eigen::Vector3d sorted_half = half, sorted_extent = extent;
    std::sort(sorted_half.data(), sorted_half.data() + 3);
    std::sort(sorted_extent.data(), sorted_extent.data() + 3);
    EXPECT_TRUE(sorted_extent.isApprox(sorted_half, 1e-5)) << solids[i].name;
  }
  int robot_geoms = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (g == world.floor_geom()) continue;
    if (world.IsRobotGeom(g)) {
      ++robot_geoms;
      continue;
    }
    EXPECT_TRUE(solid_geoms.count(g)) << "unexpected geom " << g;
  }
  EXPECT_GT(robot_geoms, 10);
  EXPECT_EQ(m->geom_type[world.floor_geom()], mjGEOM_PLANE);
  // 4 walls, 2 blocks, 3 treads, 3 gap blocks, a table top and 4 legs
  EXPECT_EQ(solids.size(), 17u);
}

// `fognav render` shows what the robot's left eye sees standing at the start: the eye sits in
// the head above the start pose (a stale camera pose once rendered from behind the robot)
TEST(WorldFromScenario, PlaceRobotPutsTheEyeInTheHeadAtTheStart) {
  Scenario scenario = LoadScenario("scenarios/stairs_and_table.yaml");
  sim::World world(MakeWorldSpec(scenario));
  const perception::Pose2 start{1.0, 0.1, M_PI / 2};
  const Eigen::Isometry3d X_WL = PlaceRobot(&world, start);
  EXPECT_NEAR(X_WL.translation().x(), start.x, 0.06);
  EXPECT_NEAR(X_WL.translation().y(), start.y, 0.06);
  EXPECT_GT(X_WL.translation().z(), 0.45);
  EXPECT_LT(X_WL.translation().z(), 0.58);
  // looking ahead along the start heading (OpenCV: camera z forward)
  const Eigen::Vector3d forward = X_WL.rotation().col(2);
  EXPECT_GT(forward.dot(Eigen::Vector3d(std::cos(start.yaw), std::sin(start.yaw), 0)), 0.8);
}

}  // namespace
}  // namespace fognav::scenarios

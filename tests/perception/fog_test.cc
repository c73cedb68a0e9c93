#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "perception/internal/map_classify.h"
#include "perception/internal/map_synthetic.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

using internal::AlignedBox;
using internal::Fig9Cameras;
using internal::LookAt;
using internal::Fig9World;
using internal::MakeIntrinsics;
using internal::RenderBoxes;

constexpr float kNegInf = -std::numeric_limits<float>::infinity();

// Runs the perception cycle of a perfect sensor over the camera poses (robot at the origin).
Fog Perceive(const std::vector<OrientedBox>& world, const std::vector<Eigen::Isometry3d>& cameras,
             const MapParams& params, MapState* state) {
  const CameraIntrinsics K = MakeIntrinsics(176, 144, 45.0);
  for (const Eigen::Isometry3d& X_GC : cameras) {
    const internal::SyntheticFrame frame = RenderBoxes(world, X_GC, K);
    MapInput in;
    in.p_GC = X_GC.translation();
    in.points = LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_GC, {});
    UpdateMaps(params, in, state);
  }
  return ComputeFog(params, *state);
}

Fog Perceive(const std::vector<OrientedBox>& world, const std::vector<Eigen::Isometry3d>& cameras,
             const MapParams& params = {}) {
  MapState state;
  return Perceive(world, cameras, params, &state);
}

CellType TypeAt(const Fog& fog, double x, double y) {
  int ix, iy;
  fog.window.CellOf(x, y, &ix, &iy);
  return fog.TypeAt(ix, iy);
}

float HeightAt(const Fog& fog, double x, double y) {
  int ix, iy;
  fog.window.CellOf(x, y, &ix, &iy);
  return fog.HeightAt(ix, iy);
}

// Fog::headroom_seen and Fog::ceiling of the cell at (x, y)
int HeadroomSeenAt(const Fog& fog, double x, double y) {
  int ix, iy;
  fog.window.CellOf(x, y, &ix, &iy);
  return fog.headroom_seen[size_t(fog.window.Index(ix, iy))];
}

float CeilingAt(const Fog& fog, double x, double y) {
  int ix, iy;
  fog.window.CellOf(x, y, &ix, &iy);
  return fog.ceiling[size_t(fog.window.Index(ix, iy))];
}

OrientedBox Floor() { return AlignedBox(-2, 2, -2, 2, -0.01, 0.0); }

// Cameras at `height` on two rings around a target (radius and 1.7 times it), looking at it.
std::vector<Eigen::Isometry3d> Around(const Eigen::Vector3d& target, double radius, double height) {
  std::vector<Eigen::Isometry3d> cameras;
  for (double r : {radius, 1.7 * radius}) {
    for (int k = 0; k < 8; ++k) {
      const double a = 2.0 * M_PI * (k + 0.5) / 8.0;
      const Eigen::Vector3d eye =
          target + Eigen::Vector3d(r * std::cos(a), r * std::sin(a), height - target.z());
      cameras.push_back(LookAt(eye, target));
    }
  }
  return cameras;
}

// Every cell of `fog` whose truth is not unknown and whose estimate is known agrees.
void ExpectMatchesTruth(const Fog& fog, const std::vector<OrientedBox>& world,
                        const MapParams& params) {
  const Fog truth = GroundTruthFog(world, fog.window, params.fog);
  const FogScore s = ScoreFog(fog, truth, params.fog);
  EXPECT_EQ(s.correct, s.observed);
  int shown = 0;
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      const CellType e = fog.TypeAt(ix, iy), t = truth.TypeAt(ix, iy);
      if (e == CellType::kUnknown || e == t || ++shown > 12) continue;
      const Eigen::Vector2d c = fog.window.CellCenter(ix, iy);
      ADD_FAILURE() << "cell (" << c.x() << ", " << c.y() << "): truth " << CellTypeName(t) << " "
                    << truth.HeightAt(ix, iy) << ", estimate " << CellTypeName(e) << " "
                    << fog.HeightAt(ix, iy);
    }
  }
  EXPECT_LE(s.height_error_max, 1e-4);
}

TEST(Fog, ThreeCentimetreStepIsStairs) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.30, 1.10, -0.5, 0.5, 0.0, 0.03)};
  const Fog fog = Perceive(world, Around({0.3, 0.0, 0.0}, 1.0, 0.5));
  EXPECT_EQ(TypeAt(fog, 0.26, 0.02), CellType::kStairs);  // floor cell beside the edge
  EXPECT_EQ(TypeAt(fog, 0.30, 0.02), CellType::kStairs);  // cell across the edge
  EXPECT_NEAR(HeightAt(fog, 0.30, 0.02), 0.03, 1e-5);     // the highest floor in the cell
  EXPECT_EQ(TypeAt(fog, 0.70, 0.02), CellType::kFloor);
  EXPECT_NEAR(HeightAt(fog, 0.70, 0.02), 0.03, 1e-5);
  EXPECT_EQ(TypeAt(fog, -0.20, 0.02), CellType::kFloor);
  EXPECT_NEAR(HeightAt(fog, -0.20, 0.02), 0.0, 1e-5);
  ExpectMatchesTruth(fog, world, {});
}

TEST(Fog, EightCentimetreStepIsBorder) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.30, 1.10, -0.5, 0.5, 0.0, 0.08)};
  const Fog fog = Perceive(world, Around({0.3, 0.0, 0.0}, 1.0, 0.5));
  EXPECT_EQ(TypeAt(fog, 0.26, 0.02), CellType::kBorder);
  EXPECT_EQ(TypeAt(fog, 0.30, 0.02), CellType::kBorder);
  EXPECT_EQ(TypeAt(fog, 0.70, 0.02), CellType::kFloor);
  EXPECT_NEAR(HeightAt(fog, 0.70, 0.02), 0.08, 1e-5);
  ExpectMatchesTruth(fog, world, {});
}

TEST(Fog, RiserOnACellBoundaryDoesNotMakeAnObstacle) {
  // the step face at x = 0.32 lies on a cell boundary: its points may land in the lower column
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.32, 1.12, -0.5, 0.5, 0.0, 0.03)};
  const Fog fog = Perceive(world, Around({0.3, 0.0, 0.0}, 1.0, 0.5));
  EXPECT_EQ(TypeAt(fog, 0.30, 0.02), CellType::kStairs);
  EXPECT_EQ(TypeAt(fog, 0.34, 0.02), CellType::kStairs);
  ExpectMatchesTruth(fog, world, {});
}

// A block from `underside` to 0.56 m (its top above the standing camera height, so it is no
// floor) over the floor, seen from `camera_height` looking at the floor and straight ahead.
Fog Ceiling(double underside, double camera_height, const MapParams& params,
            std::vector<OrientedBox>* world, MapState* state) {
  *world = {Floor(), AlignedBox(0.42, 1.02, -0.3, 0.3, underside, std::max(0.56, underside + 0.04))};
  std::vector<Eigen::Isometry3d> cameras = Around({0.72, 0.02, 0.0}, 1.0, camera_height);
  for (const Eigen::Isometry3d& X : Around({0.72, 0.02, camera_height}, 1.0, camera_height)) {
    cameras.push_back(X);
  }
  return Perceive(*world, cameras, params, state);
}

TEST(Fog, CeilingAt40cmIsTunnel) {
  std::vector<OrientedBox> world;
  MapState state;
  const Fog fog = Ceiling(0.40, 0.2, {}, &world, &state);
  EXPECT_EQ(TypeAt(fog, 0.72, 0.02), CellType::kTunnel);
  EXPECT_NEAR(HeightAt(fog, 0.72, 0.02), 0.0, 1e-5);  // eq. (25): the floor height
  ExpectMatchesTruth(fog, world, {});
}

TEST(Fog, CeilingAt25cmIsObstacle) {
  std::vector<OrientedBox> world;
  MapState state;
  const Fog fog = Ceiling(0.25, 0.12, {}, &world, &state);
  EXPECT_EQ(TypeAt(fog, 0.72, 0.02), CellType::kObstacle);
  ExpectMatchesTruth(fog, world, {});
}

TEST(Fog, CeilingAt70cmIsFloor) {
  // with a grid tall enough to hold the ceiling: c > f + h_robot
  MapParams tall;
  tall.grid.size_z = 24;
  std::vector<OrientedBox> world;
  MapState state;
  const Fog fog = Ceiling(0.70, 0.5, tall, &world, &state);
  EXPECT_GT(state.ProbabilityAt({0.72, 0.02, 0.71}), tall.grid.p_occ);
  EXPECT_EQ(TypeAt(fog, 0.72, 0.02), CellType::kFloor);
  ExpectMatchesTruth(fog, world, tall);
  // with the paper's 16 layers the ceiling is above the grid: floor as well
  MapState state16;
  const Fog fog16 = Ceiling(0.70, 0.5, {}, &world, &state16);
  EXPECT_EQ(TypeAt(fog16, 0.72, 0.02), CellType::kFloor);
}

TEST(Fog, BoxTopIsNotWalkableFromTheFloorAround) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.42, 0.82, -0.22, 0.22, 0.0, 0.2)};
  const Fog fog = Perceive(world, Around({0.62, 0.0, 0.0}, 1.1, 0.5));
  EXPECT_EQ(TypeAt(fog, 0.62, 0.02), CellType::kFloor);
  EXPECT_NEAR(HeightAt(fog, 0.62, 0.02), 0.2, 1e-5);
  // every way in from the floor crosses border cells on both sides of the edge
  for (double y = -0.14; y <= 0.14; y += 0.04) {
    EXPECT_EQ(TypeAt(fog, 0.38, y), CellType::kBorder) << y;
    EXPECT_EQ(TypeAt(fog, 0.42, y), CellType::kBorder) << y;
    EXPECT_EQ(TypeAt(fog, 0.82, y), CellType::kBorder) << y;
    EXPECT_EQ(TypeAt(fog, 0.86, y), CellType::kBorder) << y;
  }
  ExpectMatchesTruth(fog, world, {});
}

TEST(Fog, ThinPostIsObstacleWithTheTopOfItsHighestLayer) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.61, 0.65, 0.01, 0.05, 0.0, 0.25)};
  const Fog fog = Perceive(world, Around({0.63, 0.03, 0.0}, 0.9, 0.5));
  EXPECT_EQ(TypeAt(fog, 0.63, 0.03), CellType::kObstacle);
  // eq. (25): 0.25 lies in layer [0.22, 0.26)
  EXPECT_NEAR(HeightAt(fog, 0.63, 0.03), 0.26, 1e-5);
  ExpectMatchesTruth(fog, world, {});
}

TEST(Fog, RimOfATopWhoseFarSideIsUnseenIsUnknownNotFloor) {
  // a 0.3 m wall, broad enough to be floor on top, seen from one side only: the floor behind
  // it lies in its shadow, so eq. (24) cannot see the drop at its far rim
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.32, 0.52, -0.5, 0.5, 0.0, 0.3)};
  std::vector<Eigen::Isometry3d> cameras;
  for (double y : {-0.3, 0.0, 0.3}) {
    for (double x : {0.1, 0.42, 0.8}) cameras.push_back(LookAt({-0.5, y, 0.5}, {x, y, 0.0}));
  }
  MapParams params;
  const Fog fog = Perceive(world, cameras, params);
  EXPECT_EQ(TypeAt(fog, 0.50, 0.02), CellType::kUnknown);  // far rim
  EXPECT_EQ(TypeAt(fog, 0.54, 0.02), CellType::kUnknown);  // in the shadow
  EXPECT_EQ(TypeAt(fog, 0.42, 0.02), CellType::kFloor);    // the middle of the top
  EXPECT_NEAR(HeightAt(fog, 0.42, 0.02), 0.3, 1e-4);
  EXPECT_EQ(TypeAt(fog, 0.34, 0.02), CellType::kBorder);  // near rim
  ExpectMatchesTruth(fog, world, params);

  // the paper: the far rim is floor, where the truth (a drop behind it) is border
  params.fog.require_known_neighbourhood = false;
  const Fog paper = Perceive(world, cameras, params);
  EXPECT_EQ(TypeAt(paper, 0.50, 0.02), CellType::kFloor);
  const Fog truth = GroundTruthFog(world, paper.window, params.fog);
  EXPECT_EQ(TypeAt(truth, 0.50, 0.02), CellType::kBorder);
}

// Index in the state's 2D arrays of the cell holding grid-frame (x, y).
size_t CellIndex(const MapState& state, double x, double y) {
  int ix, iy;
  state.window.CellOf(x, y, &ix, &iy);
  return size_t(state.window.Index(ix, iy));
}

// A 0.1 m wide, 0.3 m high wall along x (y from 0.41 to 0.51) whose top strip segmentation
// missed (at a metre, stereo sees it as two or three pixels): its points carry no plane, so no
// cell of it has a floor.
std::vector<OrientedBox> WallWorld() {
  return {Floor(), AlignedBox(-0.5, 0.5, 0.41, 0.51, 0.0, 0.3)};
}

void PerceiveWallWithoutTopPlane(const MapParams& params, MapState* state) {
  const std::vector<OrientedBox> world = WallWorld();
  const CameraIntrinsics K = MakeIntrinsics(176, 144, 45.0);
  for (const Eigen::Isometry3d& X_GC : Around({0.0, 0.46, 0.0}, 1.0, 0.5)) {
    internal::SyntheticFrame frame = RenderBoxes(world, X_GC, K);
    for (size_t i = 0; i < frame.points_C.points.size(); ++i) {
      const Eigen::Vector3f p_G = X_GC.cast<float>() * frame.points_C.points[i];
      if (PointImage::Valid(frame.points_C.points[i]) && p_G.z() > 0.299f) {
        frame.planes.labels.data[i] = -1;
      }
    }
    MapInput in;
    in.p_GC = X_GC.translation();
    in.points = LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_GC, {});
    UpdateMaps(params, in, state);
  }
}

TEST(Fog, WallTopThatNoPlaneCoveredIsBorderNotObstacle) {
  auto perceive = [&](const MapParams& params) {
    MapState state;
    PerceiveWallWithoutTopPlane(params, &state);
    return ComputeFog(params, state);
  };
  MapParams params;
  const Fog fog = perceive(params);
  const Fog truth = GroundTruthFog(WallWorld(), fog.window, params.fog);
  for (double x = -0.38; x <= 0.38; x += 0.04) {
    for (double y : {0.42, 0.46, 0.50}) {  // the cells whose centre lies on the wall
      EXPECT_EQ(TypeAt(fog, x, y), TypeAt(truth, x, y)) << x << " " << y;
      EXPECT_NEAR(HeightAt(fog, x, y), 0.3, 0.02) << x << " " << y;  // the middle of its layer
    }
    EXPECT_EQ(TypeAt(fog, x, 0.42), CellType::kBorder) << x;
    // the floor at its foot on both sides is border too (a drop in U), on the floor's level
    for (double y : {0.38, 0.54}) {
      EXPECT_EQ(TypeAt(fog, x, y), CellType::kBorder) << x << " " << y;
      EXPECT_NEAR(HeightAt(fog, x, y), 0.0, 1e-4) << x << " " << y;
    }
    EXPECT_EQ(TypeAt(fog, x, 0.30), CellType::kFloor) << x;
  }
  // the paper's classification: occupied layers above the floor make the wall an obstacle
  params.fog.infer_tops = false;
  EXPECT_EQ(TypeAt(perceive(params), 0.0, 0.46), CellType::kObstacle);
}

TEST(Fog, WallTopWithALowerRimIsStillATop) {
  // the wall above, but along part of its near side the eyes saw the face only up to one and
  // two layers below the wall's highest layer (a far wall's rim): its tops span three layers
  MapParams params;
  MapState state;
  PerceiveWallWithoutTopPlane(params, &state);
  auto highest_layer = [&](size_t i) {
    int k = -1;
    for (int iz = 0; iz < state.size_z; ++iz) {
      if (state.log_odds[i * size_t(state.size_z) + size_t(iz)] > 0) k = iz;
    }
    return k;
  };
  const int top = highest_layer(CellIndex(state, 0.0, 0.42));
  ASSERT_GT(top, 2);
  for (int k = 0; k < 4; ++k) {  // the cells centred at x = -0.26 ... -0.14
    const size_t i = CellIndex(state, -0.26 + 0.04 * k, 0.42);
    for (int iz = top - k / 2; iz < state.size_z; ++iz) {
      state.log_odds[i * size_t(state.size_z) + size_t(iz)] = -2.0f;
    }
  }
  ASSERT_EQ(highest_layer(CellIndex(state, -0.14, 0.42)), top - 2);
  Fog fog = ComputeFog(params, state);
  const Fog truth = GroundTruthFog(WallWorld(), fog.window, params.fog);
  for (double x = -0.38; x <= 0.38; x += 0.04) {
    for (double y : {0.42, 0.46, 0.50}) {  // the lower rim too: its face reaches the top unseen
      EXPECT_EQ(TypeAt(fog, x, y), TypeAt(truth, x, y)) << x << " " << y;
      EXPECT_NEAR(HeightAt(fog, x, y), 0.3, 0.02) << x << " " << y;
    }
  }
  // without the band every cell of the wall is an obstacle
  params.fog.top_band_share = 1.0;
  fog = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(fog, 0.0, 0.46), CellType::kObstacle);
  // nor is a wall wider than top_band_max_width a top with a lower rim
  params.fog.top_band_share = 2.0 / 3.0;
  params.fog.top_band_max_width = 0.08;
  fog = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(fog, 0.0, 0.46), CellType::kObstacle);
  // nor one with a lower cell inside it, off its rim (a rough top)
  params.fog.top_band_max_width = 0.20;
  const size_t inner = CellIndex(state, -0.22, 0.46);
  for (int iz = top - 1; iz < state.size_z; ++iz) {
    state.log_odds[inner * size_t(state.size_z) + size_t(iz)] = -2.0f;
  }
  state.log_odds[inner * size_t(state.size_z) + size_t(top - 2)] = 2.0f;
  fog = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(fog, 0.0, 0.46), CellType::kObstacle);
}

TEST(Fog, TableSeenFromBelowStaysTunnelWithInferredTops) {
  // a table whose top is below the eyes, seen only from crawling height: its columns hold the
  // floor, free space and the occupied underside, no solid from the floor up, so no top is
  // inferred and eq. (23) makes them tunnel
  const std::vector<OrientedBox> world = {Floor(),
                                          AlignedBox(-0.3, 0.3, -0.3, 0.3, 0.40, 0.44),
                                          AlignedBox(-0.3, -0.26, -0.3, -0.26, 0.0, 0.40),
                                          AlignedBox(0.26, 0.3, -0.3, -0.26, 0.0, 0.40),
                                          AlignedBox(-0.3, -0.26, 0.26, 0.3, 0.0, 0.40),
                                          AlignedBox(0.26, 0.3, 0.26, 0.3, 0.0, 0.40)};
  const Fog fog = Perceive(world, Around({0.0, 0.0, 0.3}, 0.9, 0.2));
  for (double x = -0.18; x <= 0.18; x += 0.04) {
    for (double y = -0.18; y <= 0.18; y += 0.04) {
      EXPECT_EQ(TypeAt(fog, x, y), CellType::kTunnel) << x << " " << y;
    }
  }
}

TEST(Fog, UnreliableHeightIsUnknownAndMakesNoStepAround) {
  // a flat floor seen by a perfect sensor; one cell then holds a height 2 cm off with a sigma
  // of 2 cm, as a far noisy plane leaves it
  const std::vector<OrientedBox> world = {Floor()};
  MapParams params;
  MapState state;
  Perceive(world, Around({0.6, 0.0, 0.0}, 1.0, 0.5), params, &state);
  const size_t i = CellIndex(state, 0.62, 0.02);
  ASSERT_NEAR(state.floor[i], 0.0, 1e-5);
  ASSERT_LE(state.floor_var[i], params.fog.max_height_sigma * params.fog.max_height_sigma);
  state.floor[i] = 0.02f;
  state.floor_var[i] = 4e-4f;

  const Fog fog = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(fog, 0.62, 0.02), CellType::kUnknown);
  EXPECT_EQ(HeightAt(fog, 0.62, 0.02), kNegInf);
  EXPECT_EQ(TypeAt(fog, 0.58, 0.02), CellType::kFloor);  // its neighbours see no step
  EXPECT_EQ(TypeAt(fog, 0.66, 0.06), CellType::kFloor);

  // the paper (no sigma test) takes the height: the cell and its neighbours are stairs
  params.fog.max_height_sigma = std::numeric_limits<double>::infinity();
  const Fog paper = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(paper, 0.62, 0.02), CellType::kStairs);
  EXPECT_EQ(TypeAt(paper, 0.58, 0.02), CellType::kStairs);
}

TEST(Fog, ObstacleAboveAnUnreliableHeightIsStillAnObstacle) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.61, 0.65, 0.01, 0.05, 0.0, 0.25)};
  MapParams params;
  MapState state;
  Perceive(world, Around({0.63, 0.03, 0.0}, 0.9, 0.5), params, &state);
  const size_t i = CellIndex(state, 0.63, 0.03);
  state.floor[i] = 0.0f;
  state.floor_var[i] = 4e-4f;

  const Fog fog = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(fog, 0.63, 0.03), CellType::kObstacle);
}

TEST(Fog, LowOccupancyInACellWithoutFloorBesideAFloorIsUnknownNotObstacle) {
  // a flat floor seen by a perfect sensor; then one cell loses its floor height but keeps its
  // floor layer occupied (hidden behind a step down, hit by smeared points), another also has
  // an occupied layer 10 cm up
  const std::vector<OrientedBox> world = {Floor()};
  MapParams params;
  MapState state;
  Perceive(world, Around({0.6, 0.0, 0.0}, 1.0, 0.5), params, &state);
  const size_t low = CellIndex(state, 0.62, 0.02), high = CellIndex(state, 0.62, -0.14);
  for (size_t i : {low, high}) {
    state.floor[i] = kNegInf;
    state.floor_var[i] = 0;
    state.log_odds[i * size_t(state.size_z)] = 2.0f;  // layer 0 occupied
  }
  state.log_odds[high * size_t(state.size_z) + 3] = 2.0f;  // layer 3: [0.10, 0.14)

  const Fog fog = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(fog, 0.62, 0.02), CellType::kUnknown);
  EXPECT_EQ(TypeAt(fog, 0.62, -0.14), CellType::kObstacle);
  EXPECT_NEAR(HeightAt(fog, 0.62, -0.14), 0.14, 1e-5);

  // the paper: any occupied layer of a cell without floor is an obstacle
  params.fog.ignore_low_unknown = false;
  const Fog paper = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(paper, 0.62, 0.02), CellType::kObstacle);
}

TEST(Fog, EveryLayerCountsInAGridWhoseHeightIsNoMultipleOfEight) {
  // a flat floor of known height everywhere and, in a few columns of a 13-layer grid, occupied
  // layers (ComputeFog reads a column's layers eight at a time, the last five apart)
  MapParams params;
  params.grid.size_z = 13;  // layers from -0.02 m up to 0.50 m
  MapState state;
  ResetMaps(params, Pose2{}, &state);
  std::fill(state.floor.begin(), state.floor.end(), 0.0f);
  auto occupy = [&](double x, double y, std::initializer_list<int> layers) {
    for (int iz : layers) state.log_odds[CellIndex(state, x, y) * 13 + size_t(iz)] = 2.0f;
  };
  occupy(0.02, 0.02, {12});     // [0.46, 0.50): a ceiling for a tunnel
  occupy(0.42, 0.02, {9, 12});  // the lower of the two: [0.34, 0.38)
  occupy(0.02, 0.42, {7});      // [0.26, 0.30): too low to crawl under
  occupy(0.42, 0.42, {3, 12});  // an obstacle up to the top of layer 12
  const Fog fog = ComputeFog(params, state);
  EXPECT_EQ(TypeAt(fog, 0.02, 0.02), CellType::kTunnel);
  EXPECT_NEAR(CeilingAt(fog, 0.02, 0.02), 0.46, 1e-5);
  EXPECT_EQ(TypeAt(fog, 0.42, 0.02), CellType::kTunnel);
  EXPECT_NEAR(CeilingAt(fog, 0.42, 0.02), 0.34, 1e-5);
  EXPECT_EQ(TypeAt(fog, 0.02, 0.42), CellType::kObstacle);
  EXPECT_NEAR(HeightAt(fog, 0.02, 0.42), 0.30, 1e-5);
  EXPECT_EQ(TypeAt(fog, 0.42, 0.42), CellType::kObstacle);
  EXPECT_NEAR(HeightAt(fog, 0.42, 0.42), 0.50, 1e-5);
  EXPECT_EQ(TypeAt(fog, 0.82, 0.82), CellType::kFloor);
}

TEST(Fog, ClassifyFollowsThePaperAlgorithm) {
  const FogParams p;
  auto classify = [&](float f, float o, float c, float dh) {
    internal::CellQuantities q;
    q.f = f;
    q.o = o;
    q.c = c;
    q.dh = dh;
    return internal::Classify(p, q);
  };
  EXPECT_EQ(classify(kNegInf, kNegInf, kNegInf, 0), CellType::kUnknown);
  EXPECT_EQ(classify(kNegInf, 0.1f, 0.0f, 0), CellType::kObstacle);
  EXPECT_EQ(classify(0.0f, 0.8f, 0.7f, 0), CellType::kFloor);     // c > f + h_robot
  EXPECT_EQ(classify(0.0f, 0.5f, 0.4f, 0), CellType::kTunnel);    // c > f + h_tunnel
  EXPECT_EQ(classify(0.0f, 0.3f, 0.25f, 0), CellType::kObstacle);
  EXPECT_EQ(classify(0.0f, kNegInf, kNegInf, 0.01f), CellType::kFloor);
  EXPECT_EQ(classify(0.0f, kNegInf, kNegInf, 0.03f), CellType::kStairs);
  EXPECT_EQ(classify(0.0f, kNegInf, kNegInf, 0.08f), CellType::kBorder);
  internal::CellQuantities q;
  q.f = 0.1f;
  q.o = 0.3f;
  EXPECT_EQ(internal::FogHeight(CellType::kObstacle, q), 0.3f);
  EXPECT_EQ(internal::FogHeight(CellType::kTunnel, q), 0.1f);
  EXPECT_EQ(internal::FogHeight(CellType::kUnknown, q), kNegInf);
}

TEST(Fog, FloorChangeIsTheLargestDifferenceToKnownNeighbours) {
  GridWindow w;
  w.size_x = 3;
  w.size_y = 3;
  std::vector<float> floor(9, kNegInf);
  floor[4] = 0.05f;  // centre
  floor[0] = 0.0f;
  floor[8] = 0.12f;
  std::vector<float> dh, highest;
  internal::FloorChange(w, floor, 1, &dh, &highest);
  EXPECT_NEAR(dh[4], 0.07f, 1e-6);  // eq. (24)
  EXPECT_NEAR(highest[4], 0.12f, 1e-6);
  EXPECT_NEAR(dh[0], 0.05f, 1e-6);  // its only known neighbour is the centre
  EXPECT_EQ(dh[2], 0.0f);           // no floor of its own
}

void PrintScore(const FogScore& s) {
  std::printf("observed %d correct %d accuracy %.4f height cells %d median %.4f max %.4f\n",
              s.observed, s.correct, s.accuracy, s.height_cells, s.height_error_median,
              s.height_error_max);
  std::printf("truth \\ estimate: unknown floor stairs border tunnel obstacle\n");
  for (int t = 0; t < kNumCellTypes; ++t) {
    std::printf("%9s:", CellTypeName(CellType(t)));
    for (int e = 0; e < kNumCellTypes; ++e) std::printf(" %6d", s.confusion[t][e]);
    std::printf("\n");
  }
}

TEST(FogFig9, PerfectSensorMatchesGroundTruth) {
  const std::vector<OrientedBox> world = Fig9World();
  const CameraIntrinsics K = MakeIntrinsics(176, 144, 45.0);
  MapParams params;
  MapState state;
  const Pose2 robot;
  for (const Eigen::Isometry3d& X_GC : Fig9Cameras()) {
    const internal::SyntheticFrame frame = RenderBoxes(world, X_GC, K);
    MapInput in;
    in.robot_G = robot;
    in.p_GC = X_GC.translation();
    in.points = LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_GC, {});
    UpdateMaps(params, in, &state);
  }
  const Fog fog = ComputeFog(params, state);
  const Fog truth = GroundTruthFog(world, fog.window, params.fog);
  const FogScore s = ScoreFog(fog, truth, params.fog);
  PrintScore(s);
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      const CellType e = fog.TypeAt(ix, iy), t = truth.TypeAt(ix, iy);
      if (e == CellType::kUnknown || e == t) continue;
      const Eigen::Vector2d c = fog.window.CellCenter(ix, iy);
      std::printf("cell (%.2f, %.2f): truth %s %.3f estimate %s %.3f\n", c.x(), c.y(),
                  CellTypeName(t), truth.HeightAt(ix, iy), CellTypeName(e), fog.HeightAt(ix, iy));
    }
  }
  EXPECT_GE(s.accuracy, 0.99);
  EXPECT_LE(s.height_error_max, 0.005);
}

// Fog::headroom_seen: a floor cell whose layers from h_tunnel to h_robot rays have crossed is
// seen; one without rays above its floor is not, nor is one whose column holds a ceiling.
TEST(Fog, HeadroomIsSeenWhereRaysCrossedEveryLayerAboveTheFloor) {
  MapParams params;
  MapState state;
  MapInput in;
  in.p_GC = Eigen::Vector3d(0.0, 0.0, 0.56);
  // a wall at x = 2 from the floor to 0.6 m across y in [-0.2, 0.2]: at x = 1 the rays to it
  // span z from 0.28 to 0.58
  for (double y = -0.2; y <= 0.2; y += 0.01) {
    for (double z = 0.0; z <= 0.6; z += 0.01) {
      in.points.push_back({Eigen::Vector3f(2.0f, float(y), float(z))});
    }
  }
  // floor patches at x = 1 (under those rays) and at y = 1 (no ray above them but their own)
  for (double x = 0.9; x <= 1.1; x += 0.01) {
    for (double y : {-0.05, -0.03, -0.01, 0.01, 0.03, 0.05, 0.95, 0.97, 0.99, 1.01, 1.03, 1.05}) {
      in.points.push_back({Eigen::Vector3f(float(x), float(y), 0.0f), 0.0f});
    }
  }
  // a ceiling at 0.45 m over a floor patch at x = 1.5
  for (double x = 1.45; x <= 1.55; x += 0.01) {
    for (double y = -0.05; y <= 0.05; y += 0.01) {
      in.points.push_back({Eigen::Vector3f(float(x), float(y), 0.45f)});
      in.points.push_back({Eigen::Vector3f(float(x), float(y), 0.0f), 0.0f});
    }
  }
  for (int k = 0; k < 2; ++k) UpdateMaps(params, in, &state);
  const Fog fog = ComputeFog(params, state);
  ASSERT_EQ(fog.headroom_seen.size(), fog.type.size());
  auto seen = [&](double x, double y) { return HeadroomSeenAt(fog, x, y); };
  EXPECT_EQ(TypeAt(fog, 1.0, 0.0), CellType::kFloor);
  EXPECT_EQ(seen(1.0, 0.0), 1);
  EXPECT_EQ(TypeAt(fog, 1.0, 1.0), CellType::kFloor);
  EXPECT_EQ(seen(1.0, 1.0), 0);
  EXPECT_EQ(TypeAt(fog, 1.5, 0.0), CellType::kTunnel);
  EXPECT_EQ(seen(1.5, 0.0), 0);
  EXPECT_EQ(seen(-1.0, -1.0), 0);  // never observed
}

// FogParams::ceiling_gap: an underside seen in some columns only (a grazing view of a table top)
// makes tunnel cells with floor cells between them. The floor cells of a gap of at most
// ceiling_gap cells between ceilings of one layer become tunnel, unless rays have seen their
// headroom free; a wider gap, or one between ceilings of different layers, stays floor.
TEST(Fog, CeilingGapsBetweenTunnelCellsOfOneLayerAreTunnel) {
  MapParams params;
  const int gap = params.fog.ceiling_gap;
  ASSERT_GE(gap, 2);
  // the wide gap: one cell more than ceiling_gap, from x = 1.24 on
  const double wide_end = 1.24 + 0.04 * (gap + 1);
  auto perceive = [&](const MapParams& p, bool headroom_seen_over_gap) {
    MapState state;
    MapInput in;
    in.p_GC = Eigen::Vector3d(0.0, 0.0, 0.56);
    for (double x = 0.805; x < wide_end + 0.6; x += 0.01) {
      for (double y = -0.055; y < 0.06; y += 0.01) {
        in.points.push_back({Eigen::Vector3f(float(x), float(y), 0.0f), 0.0f});
      }
    }
    // undersides over the cells x in [0.80, 0.84) and [0.92, 0.96) (a gap of two cells),
    // [1.20, 1.24) and [wide_end, wide_end + 0.04) (ceiling_gap + 1 cells), all at 0.48 m;
    // 0.2 m further at 0.36 m and 0.32 m further at 0.52 m (two cells between ceilings four
    // layers apart)
    const std::vector<std::pair<double, float>> undersides = {
        {0.80, 0.48f},           {0.92, 0.48f},           {1.20, 0.48f},
        {wide_end, 0.48f},       {wide_end + 0.2, 0.36f}, {wide_end + 0.32, 0.52f}};
    for (const auto& [x0, z] : undersides) {
      for (double x = x0 + 0.005; x < x0 + 0.04; x += 0.01) {
        for (double y = -0.055; y < 0.06; y += 0.01) {
          in.points.push_back({Eigen::Vector3f(float(x), float(y), z)});
        }
      }
    }
    for (int k = 0; k < 2; ++k) UpdateMaps(p, in, &state);
    if (headroom_seen_over_gap) {
      // seen from straight above the gap: rays cross its columns from 0.62 m down
      MapInput above;
      above.p_GC = Eigen::Vector3d(0.88, 0.0, 0.62);
      for (double x = 0.845; x < 0.92; x += 0.01) {
        for (double y = -0.035; y < 0.04; y += 0.01) {
          above.points.push_back({Eigen::Vector3f(float(x), float(y), 0.0f), 0.0f});
        }
      }
      for (int k = 0; k < 2; ++k) UpdateMaps(p, above, &state);
    }
    return ComputeFog(p, state);
  };
  const Fog fog = perceive(params, false);
  const double low = wide_end + 0.22, high = wide_end + 0.34;  // the two ceilings' cell centres
  for (double x : {0.82, 0.94, 1.22, wide_end + 0.02, low, high}) {
    EXPECT_EQ(TypeAt(fog, x, 0.0), CellType::kTunnel) << x;
  }
  for (double x : {0.86, 0.90}) {
    EXPECT_EQ(TypeAt(fog, x, 0.0), CellType::kTunnel) << x;
    EXPECT_NEAR(HeightAt(fog, x, 0.0), 0.0, 1e-5) << x;  // the floor's height, as eq. (25)
    // the ceiling of the cells beside: the bottom of the layer [0.46, 0.50) holding 0.48 m
    EXPECT_NEAR(CeilingAt(fog, x, 0.0), 0.46, 1e-5) << x;
  }
  EXPECT_NEAR(CeilingAt(fog, low, 0.0), 0.34, 1e-5);
  EXPECT_NEAR(CeilingAt(fog, high, 0.0), 0.50, 1e-5);
  EXPECT_EQ(CeilingAt(fog, low + 0.04, 0.0), kNegInf);
  for (double x = 1.26; x < wide_end; x += 0.04) {
    EXPECT_EQ(TypeAt(fog, x, 0.0), CellType::kFloor) << x;
  }
  for (double x : {low + 0.04, low + 0.08}) {
    EXPECT_EQ(TypeAt(fog, x, 0.0), CellType::kFloor) << x;
  }
  // the paper: the gap is floor
  MapParams paper;
  paper.fog.ceiling_gap = 0;
  const Fog plain = perceive(paper, false);
  for (double x : {0.86, 0.90}) {
    EXPECT_EQ(TypeAt(plain, x, 0.0), CellType::kFloor) << x;
    EXPECT_EQ(HeadroomSeenAt(plain, x, 0.0), 0) << x;
  }
  // headroom seen free over the gap: floor
  const Fog looked = perceive(params, true);
  for (double x : {0.86, 0.90}) {
    EXPECT_EQ(HeadroomSeenAt(looked, x, 0.0), 1) << x;
    EXPECT_EQ(TypeAt(looked, x, 0.0), CellType::kFloor) << x;
  }
  EXPECT_EQ(TypeAt(looked, 0.94, 0.0), CellType::kTunnel);
}

}  // namespace
}  // namespace fognav::perception

// 3D occupancy grid: eq. (18), exact traversal, clipping, scrolling, convergence, outliers.
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "perception/mapping.h"

namespace fognav::perception {
namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();

MapInput Frame(const Pose2& robot, const Eigen::Vector3d& camera,
               const std::vector<Eigen::Vector3f>& points) {
  MapInput in;
  in.robot_G = robot;
  in.p_GC = camera;
  for (const Eigen::Vector3f& p : points) in.points.push_back({p, kNegInf});
  return in;
}

// Eq. (18) with the sensor model P(p|c) = p_hit, P(p|!c) = 1 - p_hit.
double Eq18(double prior, double p_hit) {
  return p_hit * prior / (p_hit * prior + (1.0 - p_hit) * (1.0 - prior));
}

TEST(OccupancyGrid, SingleRayMarksCrossedCellsFreeAndEndCellOccupied) {
  MapParams params;
  MapState state;
  // along x in the middle of layer 8 ([0.30, 0.34)) and of row y = [0, 0.04)
  UpdateMaps(params, Frame({}, {0.01, 0.02, 0.32}, {{0.81f, 0.02f, 0.32f}}), &state);
  for (double x = 0.01; x < 0.80; x += 0.04) {
    EXPECT_NEAR(state.ProbabilityAt({x, 0.02, 0.32}), params.grid.p_miss, 1e-6) << x;
  }
  EXPECT_NEAR(state.ProbabilityAt({0.81, 0.02, 0.32}), params.grid.p_hit, 1e-6);
  EXPECT_NEAR(state.ProbabilityAt({0.85, 0.02, 0.32}), 0.5, 1e-6);  // beyond the point
  EXPECT_NEAR(state.ProbabilityAt({0.41, 0.06, 0.32}), 0.5, 1e-6);  // beside the ray
  EXPECT_NEAR(state.ProbabilityAt({0.41, 0.02, 0.36}), 0.5, 1e-6);  // above the ray
}

TEST(OccupancyGrid, BayesUpdateFollowsEq18UntilClamped) {
  MapParams params;
  MapState state;
  const Eigen::Vector3f point(0.81f, 0.02f, 0.32f);
  double expected = 0.5;
  for (int k = 1; k <= 4; ++k) {
    UpdateMaps(params, Frame({}, {0.01, 0.02, 0.32}, {point}), &state);
    expected = Eq18(expected, params.grid.p_hit);
    EXPECT_NEAR(state.ProbabilityAt(point.cast<double>()), expected, 1e-5) << k;
  }
  for (int k = 0; k < 4; ++k) UpdateMaps(params, Frame({}, {0.01, 0.02, 0.32}, {point}), &state);
  EXPECT_NEAR(state.ProbabilityAt(point.cast<double>()), params.grid.p_max, 1e-5);
  EXPECT_NEAR(state.ProbabilityAt({0.41, 0.02, 0.32}), params.grid.p_min, 1e-5);
}

TEST(OccupancyGrid, OneUpdatePerCellAndFrameWithHitsWinning) {
  MapParams params;
  MapState state;
  // the second ray crosses the first ray's end cell: that cell is still updated as occupied once
  UpdateMaps(params,
             Frame({}, {0.01, 0.02, 0.32}, {{0.41f, 0.02f, 0.32f}, {0.81f, 0.02f, 0.32f}}),
             &state);
  EXPECT_NEAR(state.ProbabilityAt({0.41, 0.02, 0.32}), params.grid.p_hit, 1e-6);
  EXPECT_NEAR(state.ProbabilityAt({0.21, 0.02, 0.32}), params.grid.p_miss, 1e-6);
}

// The local cell of a grid-frame point, as (ix, iy, iz).
std::tuple<int, int, int> CellOf(const MapState& s, const Eigen::Vector3d& p) {
  int ix, iy;
  s.window.CellOf(p.x(), p.y(), &ix, &iy);
  return {ix, iy, s.LayerOf(p.z())};
}

TEST(OccupancyGrid, TraversalVisitsExactlyTheCellsTheSegmentCrosses) {
  MapParams params;
  params.grid.one_ray_per_end_cell = false;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-1.9, 1.9), z(-0.01, 0.61);
  const double res = params.grid.resolution;
  for (int trial = 0; trial < 60; ++trial) {
    const Eigen::Vector3d a(xy(rng), xy(rng), z(rng)), b(xy(rng), xy(rng), z(rng));
    MapState state;
    UpdateMaps(params, Frame({}, a, {b.cast<float>()}), &state);
    // cells the grid changed
    std::set<std::tuple<int, int, int>> visited;
    for (int iy = 0; iy < state.window.size_y; ++iy) {
      for (int ix = 0; ix < state.window.size_x; ++ix) {
        for (int iz = 0; iz < state.size_z; ++iz) {
          if (state.Probability(ix, iy, iz) != 0.5) visited.insert({ix, iy, iz});
        }
      }
    }
    // cells of dense samples along the segment, and cells the segment passes within 1e-4 of
    std::set<std::tuple<int, int, int>> sampled, near;
    const int n = int((b - a).norm() / res * 2000) + 2;
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector3d p = a + (b - a) * (double(k) / n);
      sampled.insert(CellOf(state, p));
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d o((c & 1) ? 1e-4 : -1e-4, (c & 2) ? 1e-4 : -1e-4,
                                (c & 4) ? 1e-4 : -1e-4);
        near.insert(CellOf(state, p + o));
      }
    }
    for (const auto& cell : sampled) EXPECT_TRUE(visited.count(cell)) << "trial " << trial;
    for (const auto& cell : visited) EXPECT_TRUE(near.count(cell)) << "trial " << trial;
    EXPECT_NEAR(state.ProbabilityAt(b), params.grid.p_hit, 1e-6);
  }
}

TEST(OccupancyGrid, NanPointsDoNothing) {
  MapParams params;
  MapState state;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  UpdateMaps(params, Frame({}, {0.01, 0.02, 0.32}, {{nan, 0.0f, 0.3f}, {nan, nan, nan}}), &state);
  for (float l : state.log_odds) ASSERT_EQ(l, 0.0f);
}

TEST(OccupancyGrid, PointsTooFarForFloatsDoNothing) {
  // the largest float, in grid cells, overflows to infinity: no ray, no floor, no cell index
  MapParams params;
  MapState state;
  const float big = std::numeric_limits<float>::max();
  MapInput in = Frame({}, {0.01, 0.02, 0.32}, {{big, 0.0f, 0.3f}, {0.0f, -big, 0.0f}});
  for (LabelledPoint& p : in.points) p.h = 0.0f;  // floor points, for the floor map too
  UpdateMaps(params, in, &state);
  for (float l : state.log_odds) ASSERT_EQ(l, 0.0f);
  for (float f : state.floor) ASSERT_EQ(f, kNegInf);
}

TEST(OccupancyGrid, FloorPointsOfNoWorldsPlaneGiveNoFloor) {
  // in the window, but their plane's height or spread overflows the fusion
  MapParams params;
  MapState state;
  const float big = std::numeric_limits<float>::max();
  MapInput in = Frame({}, {0.01, 0.02, 0.32}, {});
  in.points.push_back({{0.5f, 0.0f, 0.0f}, big, 0.01f});
  in.points.push_back({{0.6f, 0.0f, 0.0f}, 0.0f, big});
  for (int k = 0; k < 3; ++k) UpdateMaps(params, in, &state);
  for (float f : state.floor) ASSERT_EQ(f, kNegInf);
}

TEST(OccupancyGrid, RaysAreClippedToTheGrid) {
  MapParams params;
  MapState state;
  // camera above the grid's top (0.62 m), point beyond its x edge (2 m): only free cells inside
  UpdateMaps(params, Frame({}, {0.01, 0.02, 1.0}, {{3.01f, 0.02f, 0.0f}}), &state);
  int free = 0, occupied = 0;
  for (float l : state.log_odds) {
    free += l < 0.0f;
    occupied += l > 0.0f;
  }
  EXPECT_EQ(occupied, 0);
  EXPECT_GT(free, 10);
  // where the ray enters the grid: z = 0.62 at x = 0.01 + 3 * 0.38 = 1.15
  EXPECT_NEAR(state.ProbabilityAt({1.17, 0.02, 0.61}), params.grid.p_miss, 1e-6);
  EXPECT_NEAR(state.ProbabilityAt({1.97, 0.02, 0.35}), params.grid.p_miss, 1e-6);
}

TEST(OccupancyGrid, ScrollingKeepsWorldFixedContentAndErasesWhatLeaves) {
  MapParams params;
  MapState state;
  const Eigen::Vector3d p(0.53, 0.31, 0.21);
  UpdateMaps(params, Frame({}, {0.01, 0.01, 0.5}, {p.cast<float>()}), &state);
  ASSERT_NEAR(state.ProbabilityAt(p), params.grid.p_hit, 1e-6);
  const int ix0 = state.window.origin_ix, iy0 = state.window.origin_iy;

  // move by 0.9 m, -0.45 m: the window scrolls by whole cells, the cell stays on its global index
  const Pose2 moved{0.9, -0.45, 0.3};
  UpdateMaps(params, Frame(moved, {0.9, -0.45, 0.5}, {}), &state);
  EXPECT_EQ(state.window.origin_ix - ix0, 22);
  EXPECT_EQ(state.window.origin_iy - iy0, -12);
  EXPECT_NEAR(state.ProbabilityAt(p), params.grid.p_hit, 1e-6);
  int ix, iy;
  state.window.CellOf(p.x(), p.y(), &ix, &iy);
  EXPECT_EQ(ix + state.window.origin_ix, 13);
  EXPECT_EQ(iy + state.window.origin_iy, 7);

  // far away the cell leaves the window; back home it is unknown again
  UpdateMaps(params, Frame({3.0, 0.0, 0.0}, {3.0, 0.0, 0.5}, {}), &state);
  EXPECT_TRUE(std::isnan(state.ProbabilityAt(p)));
  UpdateMaps(params, Frame({}, {0.0, 0.0, 0.5}, {}), &state);
  EXPECT_NEAR(state.ProbabilityAt(p), 0.5, 1e-9);
}

TEST(OccupancyGrid, RepeatedObservationsConverge) {
  MapParams params;
  MapState state;
  // a wall at x = 1.01 m seen from the origin
  std::vector<Eigen::Vector3f> wall;
  for (double y = -0.5; y <= 0.5; y += 0.01) {
    for (double z = 0.0; z <= 0.5; z += 0.01) wall.push_back({1.01f, float(y), float(z)});
  }
  for (int k = 0; k < 10; ++k) UpdateMaps(params, Frame({}, {0.0, 0.0, 0.3}, wall), &state);
  EXPECT_NEAR(state.ProbabilityAt({1.01, 0.1, 0.2}), params.grid.p_max, 1e-5);
  EXPECT_NEAR(state.ProbabilityAt({0.5, 0.1, 0.2}), params.grid.p_min, 1e-5);
}

TEST(OccupancyGrid, OutliersAreFilteredByLaterRays) {
  MapParams params;
  MapState state;
  std::vector<Eigen::Vector3f> wall;
  for (double y = -0.3; y <= 0.3; y += 0.01) {
    for (double z = 0.0; z <= 0.5; z += 0.01) wall.push_back({1.01f, float(y), float(z)});
  }
  // one frame with a stray point in mid-air, then the wall behind it
  std::vector<Eigen::Vector3f> with_outlier = wall;
  const Eigen::Vector3f outlier(0.61f, 0.01f, 0.25f);
  with_outlier.push_back(outlier);
  UpdateMaps(params, Frame({}, {0.0, 0.0, 0.3}, with_outlier), &state);
  EXPECT_GT(state.ProbabilityAt(outlier.cast<double>()), params.grid.p_occ);
  for (int k = 0; k < 3; ++k) UpdateMaps(params, Frame({}, {0.0, 0.0, 0.3}, wall), &state);
  EXPECT_LT(state.ProbabilityAt(outlier.cast<double>()), params.grid.p_occ);
  const Fog fog = ComputeFog(params, state);
  int ix, iy;
  fog.window.CellOf(outlier.x(), outlier.y(), &ix, &iy);
  EXPECT_NE(fog.TypeAt(ix, iy), CellType::kObstacle);
}

// With min_hits_per_frame 2 a lone stray point in a frame is no hit (its cell stays unknown),
// while two points ending in one cell, and the wall's cells with dozens each, are.
TEST(OccupancyGrid, AStrayPointIsNoHitWithTwoHitsPerFrame) {
  MapParams params;
  params.grid.min_hits_per_frame = 2;
  MapState state;
  std::vector<Eigen::Vector3f> points;
  for (double y = -0.3; y <= 0.3; y += 0.01) {
    for (double z = 0.0; z <= 0.5; z += 0.01) points.push_back({1.01f, float(y), float(z)});
  }
  const Eigen::Vector3f stray(0.61f, 0.21f, 0.25f), pair(0.61f, -0.21f, 0.25f);
  points.push_back(stray);
  points.push_back(pair);
  points.push_back(pair + Eigen::Vector3f(0.01f, 0.005f, 0.0f));  // the same cell
  UpdateMaps(params, Frame({}, {0.0, 0.0, 0.3}, points), &state);
  EXPECT_EQ(state.ProbabilityAt(stray.cast<double>()), 0.5);
  EXPECT_GT(state.ProbabilityAt(pair.cast<double>()), params.grid.p_occ);
  EXPECT_GT(state.ProbabilityAt(Eigen::Vector3d(1.01, 0.0, 0.25)), params.grid.p_occ);
  // the paper's update: the stray point's cell is occupied
  MapParams paper;
  MapState paper_state;
  UpdateMaps(paper, Frame({}, {0.0, 0.0, 0.3}, points), &paper_state);
  EXPECT_GT(paper_state.ProbabilityAt(stray.cast<double>()), paper.grid.p_occ);
}

// With overrule_ratio, obstacle evidence seen only from afar (a phantom in front of a far wall,
// saturated over several frames) is set free by one ray that crosses it from less than half
// that range; evidence also seen from near is not, and the paper's update needs many misses.
TEST(OccupancyGrid, ANearMissOverrulesObstacleEvidenceSeenOnlyFromAfar) {
  auto wall_at = [](double x) {
    std::vector<Eigen::Vector3f> wall;
    for (double y = -0.3; y <= 0.3; y += 0.01) {
      for (double z = 0.0; z <= 0.5; z += 0.01) wall.push_back({float(x), float(y), float(z)});
    }
    return wall;
  };
  const Eigen::Vector3f phantom(1.41f, 0.01f, 0.25f), near_box(0.61f, -0.19f, 0.25f);
  auto run = [&](double ratio) {
    MapParams params;
    params.grid.overrule_ratio = ratio;
    MapState state;
    // from 2.6 m and 1.8 m away (camera at x = -1.2): the phantom and a real box, 10 frames
    std::vector<Eigen::Vector3f> far_view = {phantom, phantom, near_box, near_box};
    for (int k = 0; k < 10; ++k) {
      UpdateMaps(params, Frame({}, {-1.2, 0.0, 0.3}, far_view), &state);
    }
    // the box seen from near (0.5 m), then one view from x = 0.2 of the wall behind both,
    // whose rays cross the phantom (1.2 m from the camera) and, one of them, the box's cell
    // (0.45 m from it)
    UpdateMaps(params, Frame({}, {0.1, -0.19, 0.25}, {near_box, near_box}), &state);
    const Eigen::Vector3f camera(0.2f, 0.0f, 0.3f);
    std::vector<Eigen::Vector3f> behind = wall_at(2.5);
    behind.push_back(camera + (near_box - camera) * (2.3f / 0.41f));
    UpdateMaps(params, Frame({}, camera.cast<double>(), behind), &state);
    return std::make_pair(state.ProbabilityAt(phantom.cast<double>()),
                          state.ProbabilityAt(near_box.cast<double>()));
  };
  const auto [phantom_overruled, box_overruled] = run(2.0);
  const auto [phantom_paper, box_paper] = run(0.0);
  EXPECT_LT(phantom_overruled, 0.5);
  EXPECT_GT(phantom_paper, 0.6);                // one miss leaves saturated evidence occupied
  EXPECT_NEAR(box_overruled, box_paper, 1e-6);  // seen from near: the same update
  EXPECT_GT(box_overruled, 0.6);
  EXPECT_LT(run(0.01).second, 0.5);  // the last view does cross the box's cell
}

TEST(OccupancyGrid, MapsFitInFourMegabytes) {
  MapParams params;
  MapState state;
  ResetMaps(params, {}, &state);
  EXPECT_LE(state.MemoryBytes(), size_t(4) << 20);
  EXPECT_EQ(state.log_odds.size(), size_t(100 * 100 * 16));
}

}  // namespace
}  // namespace fognav::perception

// Where the floor ends (VoidParams): empty rays, the no-floor FOG cells and their ground truth.
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "perception/internal/map_synthetic.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

using internal::AlignedBox;
using internal::LookAt;
using internal::MakeIntrinsics;
using internal::RenderBoxes;

// A floor that ends at x = 0.8 (nothing beyond it), seen from the standing eye height.
const std::vector<OrientedBox> kFloorEndingAhead = {AlignedBox(-1.0, 0.8, -1.0, 1.0, -0.01, 0.0)};
const Eigen::Isometry3d kEye = LookAt({0.0, 0.0, 0.5}, {1.0, 0.0, 0.0});

Image<uint8_t> All(int width, int height, uint8_t value) { return {width, height, value}; }

// where ray d from the camera meets the floor plane z = 0 (x, y)
Eigen::Vector2d OnFloor(const Eigen::Isometry3d& X_GC, const Eigen::Vector3f& d) {
  const Eigen::Vector3d c = X_GC.translation();
  const double t = -c.z() / double(d.z());
  return {c.x() + t * d.x(), c.y() + t * d.y()};
}

// The map input of one view of `boxes` from `eye`: its labelled points and its empty rays to
// the floor plane z = 0.
MapInput ViewOf(const std::vector<OrientedBox>& boxes, const Eigen::Isometry3d& eye,
                const MapParams& params) {
  const CameraIntrinsics K = MakeIntrinsics(88, 72, 45.0);
  const internal::SyntheticFrame frame = RenderBoxes(boxes, eye, K);
  MapInput in;
  in.p_GC = eye.translation();
  in.points = LabelPoints(LabelParams{}, frame.points_C, frame.planes, eye, {});
  in.empty_rays_G = EmptyRays(params.no_floor, frame.points_C, All(88, 72, 255), K, eye, 0.0);
  in.floor_z = 0.0;
  return in;
}

TEST(NoFloor, EmptyRaysAreThoseBeyondTheEdgeOfTheFloor) {
  const CameraIntrinsics K = MakeIntrinsics(88, 72, 45.0);
  const internal::SyntheticFrame frame = RenderBoxes(kFloorEndingAhead, kEye, K);
  const VoidParams params;
  const std::vector<Eigen::Vector3f> rays =
      EmptyRays(params, frame.points_C, All(88, 72, 255), K, kEye, 0.0);
  ASSERT_GT(rays.size(), 100u);
  for (const Eigen::Vector3f& d : rays) {
    ASSERT_LT(d.z(), 0.0f);
    const Eigen::Vector2d p = OnFloor(kEye, d);
    EXPECT_TRUE(p.x() > 0.8 - 1e-6 || std::abs(p.y()) > 1.0 - 1e-6)  // never on the floor
        << p.transpose();
  }
  // stereo's holes on textured surfaces are no emptiness
  EXPECT_TRUE(EmptyRays(params, frame.points_C, All(88, 72, 0), K, kEye, 0.0).empty());
  // nor is what lies beyond a top (here the same surface seen 0.2 m above the robot's floor)
  EXPECT_TRUE(EmptyRays(params, frame.points_C, All(88, 72, 255), K, kEye, -0.2).empty());
  // nor a gap narrower than min_width_px: a hole two columns wide in a floor seen below it
  internal::SyntheticFrame holed = RenderBoxes({AlignedBox(-1.0, 3.0, -1.0, 1.0, -0.01, 0.0)},
                                               kEye, K);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 20; v < 50; ++v) {
    for (int u = 40; u < 42; ++u) holed.points_C.at(u, v) = Eigen::Vector3f::Constant(nan);
  }
  for (const Eigen::Vector3f& d :
       EmptyRays(params, holed.points_C, All(88, 72, 255), K, kEye, 0.0)) {
    const Eigen::Vector2d p = OnFloor(kEye, d);
    EXPECT_TRUE(p.x() > 3.0 - 1e-6 || std::abs(p.y()) > 1.0 - 1e-6)  // only beyond its edges
        << p.transpose();
  }
}

// At the floor's edge the eyes may look beyond it with no floor in view: every empty column
// counts then, but not empty pixels under a near wall's points (stereo's holes in its texture)
TEST(NoFloor, AViewOfNothingCountsButHolesBelowAWallDoNot) {
  const CameraIntrinsics K = MakeIntrinsics(88, 72, 45.0);
  const VoidParams params;
  const std::vector<OrientedBox> edge_below = {AlignedBox(-1.0, 0.1, -1.0, 1.0, -0.01, 0.0)};
  const internal::SyntheticFrame beyond = RenderBoxes(edge_below, kEye, K);
  const std::vector<Eigen::Vector3f> rays =
      EmptyRays(params, beyond.points_C, All(88, 72, 255), K, kEye, 0.0);
  EXPECT_GT(rays.size(), size_t(88 * 36));  // at least the lower half of the view
  for (const Eigen::Vector3f& d : rays) EXPECT_GT(OnFloor(kEye, d).x(), 0.1);

  std::vector<OrientedBox> wall = kFloorEndingAhead;
  wall.push_back(AlignedBox(0.3, 0.4, -1.0, 1.0, 0.0, 1.0));  // taller than the eyes, 0.3 m ahead
  internal::SyntheticFrame holed = RenderBoxes(wall, kEye, K);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 50; v < 72; ++v) {
    for (int u = 0; u < 88; ++u) holed.points_C.at(u, v) = Eigen::Vector3f::Constant(nan);
  }
  EXPECT_TRUE(EmptyRays(params, holed.points_C, All(88, 72, 255), K, kEye, 0.0).empty());
}

TEST(NoFloor, CellsBeyondTheEdgeBecomeBorderWithoutHeightAsTheTruthHasThem) {
  const MapParams params;
  MapState state;
  std::vector<int> void_cells_after;
  for (int frame_no = 0; frame_no < 2; ++frame_no) {
    UpdateMaps(params, ViewOf(kFloorEndingAhead, kEye, params), &state);
    const Fog fog = ComputeFog(params, state);
    int n = 0;
    for (size_t i = 0; i < fog.type.size(); ++i) {
      n += fog.type[i] == CellType::kBorder && fog.height[i] == -INFINITY;
    }
    void_cells_after.push_back(n);
  }
  EXPECT_EQ(void_cells_after[0], 0);  // one frame is not enough (min_frames 2)
  EXPECT_GT(void_cells_after[1], 50);

  const Fog fog = ComputeFog(params, state);
  const Fog truth = GroundTruthFog(kFloorEndingAhead, fog.window, params.fog);
  int seen_floor = 0;
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      const double x = (fog.window.origin_ix + ix + 0.5) * fog.window.resolution;
      const double y = (fog.window.origin_iy + iy + 0.5) * fog.window.resolution;
      if (x > 0.8 || std::abs(y) > 1.0) {
        EXPECT_EQ(truth.TypeAt(ix, iy), CellType::kBorder) << x << " " << y;
        EXPECT_EQ(truth.HeightAt(ix, iy), -INFINITY);
      }
      if (fog.TypeAt(ix, iy) == CellType::kBorder) {
        EXPECT_GT(x, 0.8) << "a no-floor cell on the floor at " << x << " " << y;
        EXPECT_LE(std::hypot(x, y), params.no_floor.range + fog.window.resolution);
      }
      if (fog.TypeAt(ix, iy) == CellType::kFloor) {
        ++seen_floor;
        EXPECT_LT(x, 0.8);
      }
    }
  }
  EXPECT_GT(seen_floor, 50);

  // min_frames 0 turns it off
  MapParams off = params;
  off.no_floor.min_frames = 0;
  const Fog without = ComputeFog(off, state);
  for (size_t i = 0; i < without.type.size(); ++i) {
    EXPECT_FALSE(without.type[i] == CellType::kBorder && without.height[i] == -INFINITY);
  }
}

// The robot's own body may be untextured and without range: it hides the floor behind it. The
// head box the eyes look out of hides nothing.
TEST(NoFloor, TheRobotsBodyHidesTheFloorButTheHeadAroundTheEyesDoesNot) {
  const CameraIntrinsics K = MakeIntrinsics(88, 72, 45.0);
  const VoidParams params;
  const std::vector<OrientedBox> edge_below = {AlignedBox(-1.0, 0.1, -1.0, 1.0, -0.01, 0.0)};
  const internal::SyntheticFrame beyond = RenderBoxes(edge_below, kEye, K);
  const size_t all = EmptyRays(params, beyond.points_C, All(88, 72, 255), K, kEye, 0.0).size();
  ASSERT_GT(all, size_t(88 * 36));
  const OrientedBox head = AlignedBox(-0.05, 0.05, -0.05, 0.05, 0.45, 0.55);
  EXPECT_EQ(EmptyRays(params, beyond.points_C, All(88, 72, 255), K, kEye, 0.0, {head}, 0.02)
                .size(),
            all);
  // an arm held out under the eyes, left of the view's middle (+y)
  const OrientedBox arm = AlignedBox(0.2, 0.4, 0.0, 0.3, 0.2, 0.25);
  const std::vector<Eigen::Vector3f> rays =
      EmptyRays(params, beyond.points_C, All(88, 72, 255), K, kEye, 0.0, {head, arm}, 0.02);
  EXPECT_LT(rays.size(), all - 88 * 5);
  for (const Eigen::Vector3f& d : rays) {
    // no kept ray passes through the arm grown by the margin: at its top it is off the arm
    const double t = (0.25 + 0.02 - 0.5) / double(d.z());
    const Eigen::Vector3d p = kEye.translation() + t * d.cast<double>();
    EXPECT_FALSE(p.x() > 0.2 - 0.02 + 1e-6 && p.x() < 0.4 + 0.02 - 1e-6 &&
                 p.y() > -0.02 + 1e-6 && p.y() < 0.32 - 1e-6)
        << p.transpose();
  }
}

// Within min_distance of the eyes a blob of the floor's texture may fill the texture window:
// empty rays that meet the floor nearer do not count.
TEST(NoFloor, RaysMeetingTheFloorNearTheEyesDoNotCount) {
  MapParams params;
  params.no_floor.min_distance = 0.8;
  // eyes 0.3 m up and the floor ending 0.3 m ahead: the rays meet the floor from 0.42 m on
  const Eigen::Isometry3d low = LookAt({0.0, 0.0, 0.3}, {0.6, 0.0, 0.0});
  const std::vector<OrientedBox> floor = {AlignedBox(-1.0, 0.3, -1.0, 1.0, -0.01, 0.0)};
  MapState state;
  for (int frame_no = 0; frame_no < 2; ++frame_no) {
    UpdateMaps(params, ViewOf(floor, low, params), &state);
  }
  const Fog fog = ComputeFog(params, state);
  int no_floor = 0;
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      if (fog.TypeAt(ix, iy) != CellType::kBorder) continue;
      ++no_floor;
      const Eigen::Vector2d c = fog.window.CellCenter(ix, iy);
      // a cell reached from at least 0.8 m: its far corner lies at least that far
      EXPECT_GT(std::hypot(std::hypot(std::abs(c.x()) + 0.02, std::abs(c.y()) + 0.02), 0.3),
                0.8)
          << c.transpose();
    }
  }
  EXPECT_GT(no_floor, 20);
}

// Stereo smears a far floor edge beyond it; nearer views whose rays see nothing there take the
// smeared heights back (VoidParams::drop_floor), but not the heights of a top.
TEST(NoFloor, EmptyRaysTakeBackAFloorSmearedBeyondItsEdge) {
  MapParams params;
  params.no_floor.drop_floor = true;
  const Eigen::Isometry3d far = LookAt({-0.6, 0.0, 0.5}, {1.0, 0.0, 0.0});
  // the far view: the floor seen up to 0.88 m right of the middle (y < 0), and a 0.3 m top
  // at 0.5-0.8 m left of it; the near eyes see y within +-0.3 m at x = 0.8 m
  const std::vector<OrientedBox> smeared = {AlignedBox(-1.0, 0.88, -0.3, 0.0, -0.01, 0.0),
                                            AlignedBox(-1.0, 0.5, 0.0, 0.3, -0.01, 0.0),
                                            AlignedBox(0.5, 0.8, 0.0, 0.3, 0.29, 0.3)};
  // the true world: the floor ends at 0.8 m (beside the top at 0.5 m)
  const std::vector<OrientedBox> truth = {AlignedBox(-1.0, 0.8, -0.3, 0.0, -0.01, 0.0),
                                          AlignedBox(-1.0, 0.5, 0.0, 0.3, -0.01, 0.0),
                                          AlignedBox(0.5, 0.8, 0.0, 0.3, 0.29, 0.3)};
  auto types_after = [&](const MapParams& p) {
    MapState state;
    UpdateMaps(p, ViewOf(smeared, far, p), &state);
    for (int frame_no = 0; frame_no < 2; ++frame_no) UpdateMaps(p, ViewOf(truth, kEye, p), &state);
    return std::make_pair(ComputeFog(p, state), state);
  };
  const auto [fog, state] = types_after(params);
  MapParams kept = params;
  kept.no_floor.drop_floor = false;
  const auto [fog_kept, state_kept] = types_after(kept);

  int dropped = 0, smeared_cells = 0, tops = 0, kept_floor = 0;
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      const Eigen::Vector2d c = fog.window.CellCenter(ix, iy);
      const size_t i = size_t(fog.window.Index(ix, iy));
      if (!std::isfinite(state_kept.floor[i])) continue;
      if (c.y() > 0.02 && c.y() < 0.28 && c.x() > 0.52 && c.x() < 0.78) {
        ++tops;  // the top keeps its height, with or without the rule
        EXPECT_NEAR(state.floor[i], 0.3, 0.01) << c.transpose();
      } else if (c.y() < -0.02 && c.y() > -0.28 && c.x() > 0.8 && c.x() < 0.88) {
        ++smeared_cells;  // floor in the far view only
        EXPECT_EQ(fog_kept.TypeAt(ix, iy), CellType::kFloor) << c.transpose();
        EXPECT_FALSE(std::isfinite(state.floor[i])) << c.transpose();
        dropped += fog.TypeAt(ix, iy) == CellType::kBorder && fog.height[i] == -INFINITY;
      } else if (c.y() < -0.02 && c.y() > -0.28 && c.x() > 0.4 && c.x() < 0.76) {
        ++kept_floor;  // the floor the near views see keeps its height
        EXPECT_NEAR(state.floor[i], 0.0, 0.01) << c.transpose();
      }
    }
  }
  EXPECT_GT(tops, 20);
  EXPECT_GT(kept_floor, 20);
  EXPECT_GT(smeared_cells, 6);
  EXPECT_EQ(dropped, smeared_cells);
}

TEST(NoFloor, TexturelessPixelsAreThoseOfAnEvenImage) {
  RgbImage image(20, 10, Rgb{0, 0, 0});
  for (int v = 0; v < 10; ++v) {
    for (int u = 10; u < 20; ++u) {
      const uint8_t g = (u + v) % 2 ? 200 : 40;  // a checkerboard on the right half
      image.at(u, v) = Rgb{g, g, g};
    }
  }
  VoidParams params;  // 5 x 5 window
  const Image<uint8_t> mask = TexturelessPixels(params, image);
  for (int v = 0; v < 10; ++v) {
    for (int u = 0; u < 20; ++u) {
      EXPECT_EQ(mask.at(u, v), u < 8 ? 255 : 0) << u << " " << v;  // two columns short of it
    }
  }
}

}  // namespace
}  // namespace fognav::perception

// Stereo matching and point images on analytic textured scenes (no renderer).
#include <cmath>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "perception/internal/scanline_scenes.h"
#include "perception/segmentation.h"

namespace fognav::perception {
namespace {

using internal::RenderScene;
using internal::RenderStereoPair;
using internal::Scene;
using internal::SceneCamera;
using internal::SceneIntrinsics;
using internal::SceneView;

// A textured fronto-parallel wall at distance z_m in front of a level camera.
Scene Wall(double z_m) {
  Scene scene;
  scene.floor = false;
  scene.boxes.push_back({Eigen::Vector3d(z_m, -20, -20), Eigen::Vector3d(z_m + 1, 20, 20)});
  return scene;
}

struct DepthError {
  double rms = 0;   // metres, over valid pixels
  double valid = 0;  // share of pixels with a point
};

DepthError StereoWallError(double z_m) {
  const auto K = SceneIntrinsics(176, 144);
  RgbImage left, right;
  RenderStereoPair(Wall(z_m), K, SceneCamera(0, 0, 0, 0), &left, &right);
  Image<float> disparity;
  const PointImage points = StereoPointImage(left, right, K, StereoParams(), &disparity);
  double sum = 0;
  int n = 0;
  for (const Eigen::Vector3f& p : points.points) {
    if (!PointImage::Valid(p)) continue;
    sum += (p.z() - z_m) * (p.z() - z_m);
    ++n;
  }
  DepthError e;
  e.rms = n > 0 ? std::sqrt(sum / n) : NAN;
  e.valid = double(n) / double(points.points.size());
  return e;
}

TEST(Stereo, ErrorGrowsWithDistance) {
  const DepthError near = StereoWallError(1.0);
  const DepthError far = StereoWallError(3.0);
  RecordProperty("rms_1m_mm", int(1000 * near.rms));
  RecordProperty("rms_3m_mm", int(1000 * far.rms));
  std::printf("depth rms at 1 m %.1f mm (%.0f %% valid), at 3 m %.1f mm (%.0f %% valid)\n",
              1000 * near.rms, 100 * near.valid, 1000 * far.rms, 100 * far.valid);
  EXPECT_GE(near.valid, 0.9);
  EXPECT_GE(far.valid, 0.9);
  EXPECT_LT(near.rms, 0.01);
  EXPECT_GT(far.rms, 3 * near.rms);  // a constant disparity error gives 9x
}

TEST(Stereo, DisparityMatchesGeometry) {
  const auto K = SceneIntrinsics(176, 144);
  RgbImage left, right;
  RenderStereoPair(Wall(1.0), K, SceneCamera(0, 0, 0, 0), &left, &right);
  Image<float> disparity;
  StereoPointImage(left, right, K, StereoParams(), &disparity);
  const double expected = K.fx * K.baseline / 1.0;
  std::vector<float> valid;
  for (float d : disparity.data)
    if (std::isfinite(d)) valid.push_back(d);
  ASSERT_FALSE(valid.empty());
  std::nth_element(valid.begin(), valid.begin() + valid.size() / 2, valid.end());
  EXPECT_NEAR(valid[valid.size() / 2], expected, 0.05);
}

TEST(Stereo, RefinementRemovesPixelLocking) {
  // SGBM's own sub-pixel interpolation locks towards whole disparities (about 0.3 px off at
  // 10.6 px); the Gauss-Newton refinement brings the median back to the true value
  const auto K = SceneIntrinsics(176, 144);
  RgbImage left, right;
  RenderStereoPair(Wall(1.0), K, SceneCamera(0, 0, 0, 0), &left, &right);
  StereoParams sgbm_only;
  sgbm_only.refine_iterations = 0;
  auto median_error = [&](const StereoParams& p) {
    Image<float> disparity;
    StereoPointImage(left, right, K, p, &disparity);
    std::vector<float> err;
    for (float d : disparity.data)
      if (std::isfinite(d)) err.push_back(std::abs(d - float(K.fx * K.baseline)));
    std::nth_element(err.begin(), err.begin() + err.size() / 2, err.end());
    return err[err.size() / 2];
  };
  EXPECT_LT(median_error(StereoParams()), 0.5 * median_error(sgbm_only));
}

TEST(Stereo, LeftRightCheckRejectsMatchesBetweenUnrelatedImages) {
  // the right image shows another part of the wall (the camera 0.3 m higher): no pixel has a
  // true match, so every point is a mismatch
  const auto K = SceneIntrinsics(176, 144);
  RgbImage left, right, unused;
  RenderStereoPair(Wall(1.0), K, SceneCamera(0, 0, 0, 0), &left, &unused);
  RenderStereoPair(Wall(1.0), K, SceneCamera(0, 0, 0.3, 0), &unused, &right);
  auto valid_share = [&](const StereoParams& p) {
    const PointImage points = StereoPointImage(left, right, K, p);
    int valid = 0;
    for (const Eigen::Vector3f& q : points.points) valid += PointImage::Valid(q);
    return double(valid) / double(points.points.size());
  };
  StereoParams unchecked;
  unchecked.left_right_check = false;
  const double with_check = valid_share(StereoParams()), without = valid_share(unchecked);
  std::printf("unrelated pair: %.1f %% of pixels with points, %.1f %% without the check\n",
              100 * with_check, 100 * without);
  EXPECT_LT(with_check, 0.5 * without);
}

// Stereo of `scene` seen from X_WC against its rims: the pixels with a point off the nearer
// surface (surface ids from 7, the boxes after the first) whose disparity exceeds the truth by
// more than 1 px (fattened), and the pixels with a point on it, each with how many of them lie
// off the rims. The disparity image goes to *disparity.
struct RimCounts {
  int fattened = 0, fattened_off_rims = 0, nearer = 0, nearer_off_rims = 0;
};
RimCounts CountAgainstRims(const Scene& scene, const Eigen::Isometry3d& X_WC,
                           Image<float>* disparity) {
  const auto K = SceneIntrinsics(176, 144);
  RgbImage left, right;
  RenderStereoPair(scene, K, X_WC, &left, &right);
  const SceneView truth = RenderScene(scene, K, X_WC);
  StereoPointImage(left, right, K, StereoParams(), disparity);
  const Image<uint8_t> rims = DepthEdgeRims(*disparity);
  RimCounts c;
  for (size_t i = 0; i < disparity->data.size(); ++i) {
    if (!std::isfinite(disparity->data[i])) continue;
    const bool on_nearer = truth.surface.data[i] >= 7;
    const double d_true = K.fx * K.baseline / truth.depth.data[i];
    const bool fat = !on_nearer && disparity->data[i] > d_true + 1.0;
    c.fattened += fat;
    c.fattened_off_rims += fat && !rims.data[i];
    c.nearer += on_nearer;
    c.nearer_off_rims += on_nearer && !rims.data[i];
  }
  return c;
}

// Two posts 0.2 m apart at 1.2 m in front of a wall at 3 m, before a level camera at the origin.
Scene PostsBeforeAWall() {
  Scene scene;
  scene.floor = false;
  scene.boxes.push_back({Eigen::Vector3d(3.0, -20, -20), Eigen::Vector3d(4.0, 20, 20)});
  scene.boxes.push_back({Eigen::Vector3d(1.2, -0.4, -20), Eigen::Vector3d(1.3, -0.1, 20)});
  scene.boxes.push_back({Eigen::Vector3d(1.2, 0.1, -20), Eigen::Vector3d(1.3, 0.4, 20)});
  return scene;
}

// The posts before a wall: near the posts' sides the matching block covers post and wall, and
// the nearer post wins: wall pixels beside a post take its disparity (foreground fattening),
// which would put phantom obstacles into the gap. They lie on the posts' rims.
TEST(Stereo, FattenedPixelsBesideANearerSurfaceLieOnItsRim) {
  const Scene scene = PostsBeforeAWall();
  const auto K = SceneIntrinsics(176, 144);
  const Eigen::Isometry3d X_WC = SceneCamera(0, 0, 0, 0);
  Image<float> disparity;
  const RimCounts c = CountAgainstRims(scene, X_WC, &disparity);  // the posts are the nearer
  const int fattened = c.fattened, fattened_off_rims = c.fattened_off_rims, post = c.nearer,
            post_off_rims = c.nearer_off_rims;
  std::printf(
      "fattened wall pixels: %d, %d of them off the rims; post pixels with a point: %d, "
      "%d of them off the rims\n",
      fattened, fattened_off_rims, post, post_off_rims);
  EXPECT_GT(fattened, 50);  // the effect is there
  EXPECT_LE(fattened_off_rims, fattened / 20);
  EXPECT_GT(post_off_rims, post * 3 / 4);  // the posts' middles are no rims
  // no rims on the wall alone, nor without a margin
  RgbImage wall_left, wall_right;
  RenderStereoPair(Wall(3.0), K, X_WC, &wall_left, &wall_right);
  Image<float> wall_disparity;
  StereoPointImage(wall_left, wall_right, K, StereoParams(), &wall_disparity);
  int wall_rims = 0;
  for (uint8_t r : DepthEdgeRims(wall_disparity).data) wall_rims += r != 0;
  EXPECT_LT(wall_rims, 176 * 144 / 100);
  // a side wall 0.25 m beside the eye, seen at a slant from 0.2 m to 3 m away: its disparity
  // falls by 0.2 px per pixel along the rows, in terraces; most of it is no rim
  Scene corridor = Wall(3.0);
  corridor.boxes.push_back({Eigen::Vector3d(0.2, 0.25, -20), Eigen::Vector3d(3.0, 0.5, 20)});
  const SceneView corridor_truth = RenderScene(corridor, K, X_WC);
  RgbImage corridor_left, corridor_right;
  RenderStereoPair(corridor, K, X_WC, &corridor_left, &corridor_right);
  Image<float> corridor_disparity;
  StereoPointImage(corridor_left, corridor_right, K, StereoParams(), &corridor_disparity);
  const Image<uint8_t> corridor_rims = DepthEdgeRims(corridor_disparity);
  int side = 0, side_rims = 0;
  for (size_t i = 0; i < corridor_rims.data.size(); ++i) {
    if (corridor_truth.surface.data[i] < 7 || !std::isfinite(corridor_disparity.data[i])) continue;
    ++side;
    side_rims += corridor_rims.data[i] != 0;
  }
  std::printf("slanted side wall: %d of %d pixels on rims\n", side_rims, side);
  EXPECT_GT(side, 2000);
  EXPECT_LT(side_rims, side / 5);
  StereoParams no_margin;
  no_margin.edge_margin = 0;
  int unmarked = 0;
  for (uint8_t r : DepthEdgeRims(disparity, no_margin).data) unmarked += r;
  EXPECT_EQ(unmarked, 0);
}

// The search over the range a half-resolution matching finds (StereoParams::range_margin 16)
// against the whole range, on scenes from 0.15 m (70 px) to 3 m (3.5 px) away: as many points,
// and the same disparities where both have one.
TEST(Stereo, SearchRangeFromHalfResolutionKeepsNearAndFarSurfaces) {
  const auto K = SceneIntrinsics(176, 144);
  Scene posts = PostsBeforeAWall();  // posts 0.2 m away before a wall at 3 m
  for (internal::SceneBox& box : posts.boxes) {
    if (box.lo.x() < 2) box.lo.x() = 0.2, box.hi.x() = 0.3;
  }
  Scene near_step = internal::Staircase(0.3, 2, 0.25, 0.05);  // a floor with two treads
  for (const auto& [name, scene, X_WC] :
       {std::tuple<const char*, Scene, Eigen::Isometry3d>{"wall 0.15 m", Wall(0.15),
                                                          SceneCamera(0, 0, 0, 0)},
        {"wall 3 m", Wall(3.0), SceneCamera(0, 0, 0, 0)},
        {"posts 0.2 m before a wall at 3 m", posts, SceneCamera(0, 0, 0, 0)},
        {"floor and treads", near_step, SceneCamera(0, 0, 0.55, 0.6)}}) {
    RgbImage left, right;
    RenderStereoPair(scene, K, X_WC, &left, &right);
    StereoParams found, whole;
    found.range_margin = 16;
    whole.range_margin = -1;
    Image<float> d_range, d_whole;
    StereoPointImage(left, right, K, found, &d_range);
    StereoPointImage(left, right, K, whole, &d_whole);
    int n_range = 0, n_whole = 0, both = 0, differ = 0;
    for (size_t i = 0; i < d_range.data.size(); ++i) {
      const bool a = std::isfinite(d_range.data[i]), b = std::isfinite(d_whole.data[i]);
      n_range += a;
      n_whole += b;
      if (!a || !b) continue;
      ++both;
      differ += std::abs(d_range.data[i] - d_whole.data[i]) > 0.5f;
    }
    std::printf("%s: %d points with the found range, %d with the whole range, %d of %d differ\n",
                name, n_range, n_whole, differ, both);
    EXPECT_GT(n_whole, 176 * 144 / 2) << name;
    EXPECT_GT(n_range, 0.98 * n_whole) << name;
    EXPECT_LT(differ, both / 100) << name;
  }
}

// The refined left-right check (StereoParams::refine_left_right_tolerance) on the posts before
// a wall and on a floor seen from a standing robot's eyes: the share of points off by more than
// 0.3 px (on the posts' sides the matching block covers post and wall; a far floor's texture is
// finer than the pixels) falls, and the points of the plain surfaces stay.
TEST(Stereo, RefinedLeftRightCheckDropsPointsOffBySubPixels) {
  const Scene posts = PostsBeforeAWall();
  Scene floor;  // the floor plane only, the eyes 0.5 m above it looking 0.4 rad down
  const auto K = SceneIntrinsics(176, 144);
  struct Counts {
    int points = 0, off = 0;
  };
  auto count = [&](const Scene& scene, const Eigen::Isometry3d& X_WC, double tolerance) {
    RgbImage left, right;
    RenderStereoPair(scene, K, X_WC, &left, &right);
    const SceneView truth = RenderScene(scene, K, X_WC);
    StereoParams p;
    p.refine_left_right_tolerance = tolerance;
    const PointImage points = StereoPointImage(left, right, K, p);
    const double fB = K.fx * K.baseline;
    Counts c;
    for (size_t i = 0; i < points.points.size(); ++i) {
      const Eigen::Vector3f& q = points.points[i];
      if (!PointImage::Valid(q) || !std::isfinite(truth.depth.data[i])) continue;
      ++c.points;
      c.off += std::abs(fB / q.z() - fB / truth.depth.data[i]) > 0.3;
    }
    return c;
  };
  for (const auto& [name, scene, X_WC] :
       {std::tuple<const char*, Scene, Eigen::Isometry3d>{"posts", posts, SceneCamera(0, 0, 0, 0)},
        {"floor", floor, SceneCamera(0, 0, 0.5, 0.4)}}) {
    const Counts off = count(scene, X_WC, 0.0), on = count(scene, X_WC, 0.3);
    std::printf("%s: %d of %d points off by more than 0.3 px without the check, %d of %d with\n",
                name, off.off, off.points, on.off, on.points);
    EXPECT_GT(off.off, 50) << name;  // the effect is there
    EXPECT_LT(double(on.off) / on.points, 0.7 * double(off.off) / off.points) << name;
    EXPECT_GT(on.points, 0.9 * off.points) << name;
  }
}

// The same up and down the image: a crawling robot's eyes 0.15 m below a table top that ends
// 0.9 m ahead, a wall at 3 m beyond. Wall pixels just below the top's far edge take the top's
// disparity and would put phantom obstacles under the table's edge; they lie on its rim. The
// underside itself, whose disparity changes fast from row to row as it is seen at a grazing
// angle, is mostly no rim.
TEST(Stereo, FattenedPixelsBelowAnOverhangLieOnItsRim) {
  Scene scene;
  scene.boxes.push_back({Eigen::Vector3d(3.0, -20, 0), Eigen::Vector3d(4.0, 20, 20)});
  scene.boxes.push_back({Eigen::Vector3d(0.3, -2, 0.35), Eigen::Vector3d(0.9, 2, 0.6)});
  Image<float> disparity;
  const RimCounts c = CountAgainstRims(scene, SceneCamera(0, 0, 0.2, 0), &disparity);
  const int fattened = c.fattened, fattened_off_rims = c.fattened_off_rims, underside = c.nearer,
            underside_off_rims = c.nearer_off_rims;  // the top's
  std::printf(
      "fattened pixels below the edge: %d, %d of them off the rims; underside pixels with a "
      "point: %d, %d of them off the rims\n",
      fattened, fattened_off_rims, underside, underside_off_rims);
  EXPECT_GT(fattened, 50);
  EXPECT_LE(fattened_off_rims, fattened / 10);
  EXPECT_GT(underside, 2000);
  EXPECT_GT(underside_off_rims, underside * 3 / 4);
}

// A band a few rows high nearer than what lies above, below and beside it (a table top's edge
// seen edge-on): column rim in its middle, row rim at its ends, nothing on the background.
TEST(Stereo, RimsOfAThinBandAreColumnRimsButAtItsEnds) {
  Image<float> disparity(176, 144, 5.0f);
  for (int v = 60; v < 66; ++v)
    for (int u = 40; u < 120; ++u) disparity.at(u, v) = 10.0f;
  const Image<uint8_t> rims = DepthEdgeRims(disparity);
  for (int v = 60; v < 66; ++v) {
    EXPECT_EQ(rims.at(80, v), kColumnRim) << v;
    EXPECT_EQ(rims.at(41, v), kRowRim) << v;
    EXPECT_EQ(rims.at(118, v), kRowRim) << v;
  }
  EXPECT_EQ(rims.at(80, 50), 0);
  EXPECT_EQ(rims.at(20, 62), 0);
}

TEST(Stereo, UntexturedPairGivesNoPoints) {
  const auto K = SceneIntrinsics(176, 144);
  const RgbImage flat(176, 144, Rgb{128, 128, 128});
  const PointImage points = StereoPointImage(flat, flat, K);
  int valid = 0;
  for (const Eigen::Vector3f& p : points.points) valid += PointImage::Valid(p);
  EXPECT_LT(valid, 176 * 144 / 20);
}

// The range score in disparity pixels: a wall at 2 m seen with disparity errors of 0.1 px on
// most pixels, 2 px on a tenth of them, and no point on a fifth.
TEST(ScoreStereo, MeasuresDisparityErrorsValidShareAndOutliers) {
  CameraIntrinsics K;
  K.width_px = 10;
  K.height_px = 10;
  K.fx = K.fy = 200;
  K.cx = K.cy = 5;
  K.baseline = 0.05;
  const double fb = K.fx * K.baseline, z_true = 2.0;
  DepthImage truth(10, 10);
  PointImage points(10, 10);
  for (int i = 0; i < 100; ++i) {
    truth.data[size_t(i)] = float(z_true);
    if (i % 5 == 4) continue;  // no point
    const double d = fb / z_true + (i % 10 == 0 ? 2.0 : 0.1);
    points.points[size_t(i)] = Eigen::Vector3f(0, 0, float(fb / d));
  }
  truth.data[0] = std::numeric_limits<float>::quiet_NaN();  // not scored
  truth.data[1] = 3.0f;                                      // beyond max_depth_m
  const StereoScore s = ScoreStereo(points, truth, K, 2.5);
  EXPECT_EQ(s.pixels, 98);
  EXPECT_NEAR(s.valid, 78.0 / 98.0, 1e-9);
  EXPECT_NEAR(s.median_error_px, 0.1, 1e-4);
  EXPECT_NEAR(s.bad_1px, 9.0 / 78.0, 1e-9);
  EXPECT_NEAR(s.median_depth_error, z_true - fb / (fb / z_true + 0.1), 1e-5);
}

TEST(DepthPointImage, BackProjectsAlongTheOpticalAxis) {
  CameraIntrinsics K = SceneIntrinsics(8, 6);
  DepthImage depth(8, 6, 2.0f);
  depth.at(3, 2) = NAN;
  depth.at(4, 2) = 0.0f;
  const PointImage points = DepthPointImage(depth, K);
  EXPECT_FALSE(PointImage::Valid(points.at(3, 2)));
  EXPECT_FALSE(PointImage::Valid(points.at(4, 2)));
  const Eigen::Vector3f p = points.at(7, 5);
  EXPECT_NEAR(p.z(), 2.0, 1e-6);
  EXPECT_NEAR(p.x(), (7 - K.cx) / K.fx * 2.0, 1e-6);
  EXPECT_NEAR(p.y(), (5 - K.cy) / K.fy * 2.0, 1e-6);
}

TEST(Subsample2x, TakesEverySecondPixel) {
  PointImage points(176, 144);
  for (int v = 0; v < 144; ++v)
    for (int u = 0; u < 176; ++u) points.at(u, v) = Eigen::Vector3f(u, v, 1);
  const PointImage half = Subsample2x(points);
  ASSERT_EQ(half.width, 88);
  ASSERT_EQ(half.height, 72);
  EXPECT_EQ(half.at(10, 20).x(), 20);
  EXPECT_EQ(half.at(10, 20).y(), 40);
  const CameraIntrinsics K = Subsample2x(SceneIntrinsics(176, 144));
  EXPECT_EQ(K.width_px, 88);
  EXPECT_NEAR(K.fx, SceneIntrinsics(176, 144).fx / 2, 1e-12);
}

TEST(DepthEdgeRims, AnImageWithoutColumnsHasNoRims) {
  const Image<uint8_t> rims = DepthEdgeRims(Image<float>(0, 5, 1.0f));
  EXPECT_EQ(rims.width, 0);
  EXPECT_EQ(rims.height, 5);
  EXPECT_TRUE(rims.data.empty());
}

}  // namespace
}  // namespace fognav::perception

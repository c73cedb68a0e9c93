// Labelled points (paper Section 5 intro, 5.1): floor candidates, heights, self-filter.
#include <algorithm>
#include <cmath>
#include <limits>
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

const CameraIntrinsics kK = MakeIntrinsics(176, 144, 45.0);

OrientedBox Floor() { return AlignedBox(-3, 3, -3, 3, -0.01, 0.0); }

TEST(LabelPoints, HorizontalPlanesGetTheirHeightInTheGridFrame) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.6, 1.2, -0.3, 0.3, 0.0, 0.03)};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.5}, {1.0, 0, 0});
  const internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  // the grid frame is the world shifted: heights in it are 5 cm more
  Eigen::Isometry3d X_GW = Eigen::Isometry3d::Identity();
  X_GW.translation() = Eigen::Vector3d(0.1, -0.2, 0.05);
  const std::vector<LabelledPoint> points =
      LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_GW * X_WC, {});
  int floor = 0, step = 0, other = 0;
  for (const LabelledPoint& lp : points) {
    const double z_W = lp.p_G.z() - 0.05;
    if (std::abs(z_W) < 1e-4) {
      EXPECT_NEAR(lp.h, 0.05, 1e-5);
      ++floor;
    } else if (std::abs(z_W - 0.03) < 1e-4) {
      EXPECT_NEAR(lp.h, 0.08, 1e-5);
      ++step;
    } else {
      EXPECT_EQ(lp.h, -std::numeric_limits<float>::infinity()) << "riser point at z " << z_W;
      ++other;
    }
  }
  EXPECT_GT(floor, 1000);
  EXPECT_GT(step, 1000);
  EXPECT_GT(other, 10);  // the riser of the step
}

TEST(LabelPoints, FloorHeightsCarryTheirPlanesRmsAsSigma) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.6, 1.2, -0.3, 0.3, 0.0, 0.03)};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.5}, {1.0, 0, 0});
  internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  for (size_t k = 0; k < frame.planes.planes.size(); ++k)
    frame.planes.planes[k].rms = 0.004 * double(k + 1);
  LabelParams params;
  params.min_height_sigma = 0.006;

  const std::vector<LabelledPoint> points =
      LabelPoints(params, frame.points_C, frame.planes, X_WC, {});

  int floor_points = 0;
  for (size_t i = 0, j = 0; i < frame.points_C.points.size(); ++i) {
    if (!PointImage::Valid(frame.points_C.points[i])) continue;
    const LabelledPoint& lp = points[j++];
    const int k = frame.planes.labels.data[i];
    if (lp.h == -std::numeric_limits<float>::infinity()) {
      EXPECT_EQ(lp.h_sigma, 0.0f);
      continue;
    }
    ASSERT_GE(k, 0);
    EXPECT_FLOAT_EQ(lp.h_sigma, float(std::max(0.004 * (k + 1), 0.006)));
    ++floor_points;
  }
  EXPECT_GT(floor_points, 2000);
}

TEST(LabelPoints, TiltedAndDownwardFacingPlanesAreNotFloor) {
  // a ramp tilted 20 deg, a plate tilted 5 deg, and a slab seen from below
  OrientedBox ramp = AlignedBox(0.8, 1.4, -0.8, -0.2, 0.0, 0.02);
  ramp.X_FB.linear() = Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).matrix();
  OrientedBox plate = AlignedBox(0.8, 1.4, 0.2, 0.8, 0.05, 0.07);
  plate.X_FB.linear() = Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).matrix();
  const OrientedBox slab = AlignedBox(0.8, 1.4, -0.2, 0.2, 0.40, 0.44);
  const std::vector<OrientedBox> world = {ramp, plate, slab};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.25}, {1.1, 0, 0.2});
  const internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  const std::vector<LabelledPoint> points =
      LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_WC, {});
  int ramp_n = 0, plate_n = 0, plate_floor = 0, slab_n = 0;
  for (const LabelledPoint& lp : points) {
    if (lp.p_G.y() < -0.25) {
      ++ramp_n;
      EXPECT_EQ(lp.h, -std::numeric_limits<float>::infinity());
    } else if (lp.p_G.y() > 0.25 && lp.p_G.z() > 0.05) {
      ++plate_n;
      plate_floor += std::isfinite(lp.h);
    } else if (std::abs(lp.p_G.z() - 0.40) < 1e-4) {
      ++slab_n;
      EXPECT_EQ(lp.h, -std::numeric_limits<float>::infinity());
    }
  }
  EXPECT_GT(ramp_n, 100);
  EXPECT_GT(plate_floor, 100);  // its top, within the 10 deg tolerance
  EXPECT_LT(plate_floor, plate_n);
  EXPECT_GT(slab_n, 100);
}

TEST(LabelPoints, PlanesSmallerThanASoleAreNotFloor) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.8, 0.84, -0.2, -0.16, 0.0, 0.10),
                                          AlignedBox(0.8, 1.0, 0.1, 0.3, 0.0, 0.10)};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.5}, {0.9, 0, 0});
  const internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  const std::vector<LabelledPoint> points =
      LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_WC, {});
  int post = 0, box = 0;
  for (const LabelledPoint& lp : points) {
    if (std::abs(lp.p_G.z() - 0.10) > 1e-4) continue;
    if (lp.p_G.y() < 0) {
      ++post;
      EXPECT_EQ(lp.h, -std::numeric_limits<float>::infinity());
    } else {
      ++box;
      EXPECT_NEAR(lp.h, 0.10, 1e-5);
    }
  }
  EXPECT_GT(post, 5);
  EXPECT_GT(box, 100);
}

TEST(LabelPoints, SelfFilterDropsPointsOnTheBody) {
  const std::vector<OrientedBox> world = {Floor()};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.5}, {0.5, 0, 0});
  const internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  // a foot on the floor in view, as the robot's kinematic pose gives it
  OrientedBox foot = AlignedBox(0.40, 0.52, -0.04, 0.04, 0.0, 0.04);
  foot.X_FB.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).matrix();
  LabelParams params;
  const std::vector<LabelledPoint> all =
      LabelPoints(params, frame.points_C, frame.planes, X_WC, {});
  const std::vector<LabelledPoint> kept =
      LabelPoints(params, frame.points_C, frame.planes, X_WC, {foot});
  const Eigen::Isometry3d X_BG = foot.X_FB.inverse();
  auto inside = [&](const LabelledPoint& lp, double margin) {
    const Eigen::Vector3d p_B = X_BG * lp.p_G.cast<double>();
    return (p_B.cwiseAbs().array() <= foot.half_size.array() + margin).all();
  };
  int on_foot = 0;
  for (const LabelledPoint& lp : all) on_foot += inside(lp, params.self_filter_margin - 1e-6);
  EXPECT_GT(on_foot, 50);
  for (const LabelledPoint& lp : kept) EXPECT_FALSE(inside(lp, params.self_filter_margin - 1e-6));
  EXPECT_LE(kept.size(), all.size() - size_t(on_foot));
  EXPECT_GT(kept.size(), all.size() / 2);
}

TEST(LabelPoints, InvalidAndFarPointsAreDroppedAndMissingLabelsMeanNoPlane) {
  PointImage image(4, 1);
  image.at(0, 0) = {0.0f, 0.0f, 1.0f};
  image.at(1, 0) = {0.0f, 0.0f, 5.0f};
  image.at(2, 0) = {std::numeric_limits<float>::quiet_NaN(), 0.0f, 1.0f};
  LabelParams params;
  params.max_range = 3.0;
  const std::vector<LabelledPoint> points =
      LabelPoints(params, image, PlaneSet{}, Eigen::Isometry3d::Identity(), {});
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].h, -std::numeric_limits<float>::infinity());
  EXPECT_NEAR(points[0].p_G.z(), 1.0f, 1e-6);
}

// Points on the rims of nearer surfaces (stereo fattening) keep their place only on floor
// candidates: the box's side is dropped where marked, the floor and the box top are kept.
TEST(LabelPoints, RimPointsAreKeptOnlyOnFloorCandidates) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.8, 1.2, -0.2, 0.2, 0.0, 0.2)};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.5}, {1.0, 0, 0});
  const internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  const std::vector<LabelledPoint> all =
      LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_WC, {});
  Image<uint8_t> everywhere(kK.width_px, kK.height_px, 1);
  const std::vector<LabelledPoint> kept =
      LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_WC, {}, &everywhere);
  int floor_candidates = 0;
  for (const LabelledPoint& lp : all) floor_candidates += std::isfinite(lp.h);
  EXPECT_GT(floor_candidates, 1000);
  EXPECT_GT(all.size(), size_t(floor_candidates) + 100);  // the box's side
  ASSERT_EQ(kept.size(), size_t(floor_candidates));
  for (const LabelledPoint& lp : kept) EXPECT_TRUE(std::isfinite(lp.h));
  // no rims: every point is kept
  const Image<uint8_t> nowhere(kK.width_px, kK.height_px, 0);
  EXPECT_EQ(LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_WC, {}, &nowhere).size(),
            all.size());
}

// Column rims only (a farther surface above or below) keep their points above
// keep_column_rims_above: a 0.3 m box's side is all rim; marked as column rim its upper part
// stays, marked as row rim none of it.
TEST(LabelPoints, ColumnRimPointsAboveTheKeepHeightAreKept) {
  const std::vector<OrientedBox> world = {Floor(), AlignedBox(0.8, 1.2, -0.2, 0.2, 0.0, 0.3)};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.5}, {1.0, 0, 0});
  const internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  LabelParams params;
  params.keep_column_rims_above = 0.2;
  const std::vector<LabelledPoint> all =
      LabelPoints(params, frame.points_C, frame.planes, X_WC, {});
  int floor_candidates = 0, high_side = 0;
  for (const LabelledPoint& lp : all) {
    floor_candidates += std::isfinite(lp.h);
    high_side += !std::isfinite(lp.h) && lp.p_G.z() > 0.2;
  }
  EXPECT_GT(high_side, 100);
  const Image<uint8_t> column(kK.width_px, kK.height_px, kColumnRim);
  const std::vector<LabelledPoint> kept =
      LabelPoints(params, frame.points_C, frame.planes, X_WC, {}, &column);
  EXPECT_EQ(kept.size(), size_t(floor_candidates + high_side));
  for (const LabelledPoint& lp : kept) EXPECT_TRUE(std::isfinite(lp.h) || lp.p_G.z() > 0.2);
  const Image<uint8_t> row(kK.width_px, kK.height_px, kRowRim);
  EXPECT_EQ(LabelPoints(params, frame.points_C, frame.planes, X_WC, {}, &row).size(),
            size_t(floor_candidates));
}

// Stereo smears points along the rays: here every other point moves 2 cm farther, the rest
// 2 cm nearer. The floor at a wall's foot then reaches into the wall, and the wall's top over
// the floor before it; with face_clip those points lose their height, and only those: the
// floor beside the wall's end, behind the line of its face, keeps it.
TEST(LabelPoints, PointsSmearedPastAFaceLoseTheirHeight) {
  const double face_x = 1.0;
  const std::vector<OrientedBox> world = {Floor(),
                                          AlignedBox(face_x, 1.1, -0.2, 0.2, 0.0, 0.3)};
  const Eigen::Isometry3d X_WC = LookAt({0, 0, 0.5}, {1.0, 0, 0});
  internal::SyntheticFrame frame = RenderBoxes(world, X_WC, kK);
  for (int v = 0; v < kK.height_px; ++v) {
    for (int u = 0; u < kK.width_px; ++u) {
      Eigen::Vector3f& p = frame.points_C.points[size_t(v * kK.width_px + u)];
      if (PointImage::Valid(p)) p *= 1.0f + ((u + v) % 2 == 0 ? 0.02f : -0.02f) / p.norm();
    }
  }
  LabelParams params;
  params.face_clip = 0;
  const std::vector<LabelledPoint> off =
      LabelPoints(params, frame.points_C, frame.planes, X_WC, {});
  params.face_clip = 0.03;
  const std::vector<LabelledPoint> on = LabelPoints(params, frame.points_C, frame.planes, X_WC, {});
  ASSERT_EQ(on.size(), off.size());  // heights change, points stay
  int floor_behind = 0, top_before = 0, floor_beside = 0, clipped = 0;
  for (size_t i = 0; i < on.size(); ++i) {
    const Eigen::Vector3f& p = off[i].p_G;
    const bool floor = std::abs(off[i].h) < 1e-3, top = std::abs(off[i].h - 0.3) < 0.01;
    const bool behind = p.x() > face_x + 1e-3 && p.x() < face_x + 0.03;
    const bool before = p.x() < face_x - 1e-3 && p.x() > face_x - 0.03;
    const bool within = std::abs(p.y()) < 0.18;
    floor_behind += floor && behind && within;
    top_before += top && before && within;
    floor_beside += floor && behind && std::abs(p.y()) > 0.25;
    if (on[i].h == off[i].h) {
      // what stays: no floor behind the face and no top before it; the rest as it was
      EXPECT_FALSE(floor && behind && within) << p.transpose();
      EXPECT_FALSE(top && before && within) << p.transpose();
      continue;
    }
    // what goes: only heights, of floor points within 3 cm behind the face and of top points
    // within 3 cm before it, within its width
    ++clipped;
    EXPECT_EQ(on[i].h, -std::numeric_limits<float>::infinity());
    const bool floor_clip = floor && p.x() > face_x - 0.005 && p.x() < face_x + 0.035;
    const bool top_clip = top && p.x() > face_x - 0.035 && p.x() < face_x + 0.005;
    EXPECT_TRUE((floor_clip || top_clip) && std::abs(p.y()) < 0.21)
        << p.transpose() << " h " << off[i].h;
  }
  // the smear does cross the face both ways, and the floor beside the wall's end lies behind
  // its line
  EXPECT_GT(floor_behind, 10);
  EXPECT_GT(top_before, 10);
  EXPECT_GT(floor_beside, 10);
  EXPECT_GE(clipped, floor_behind + top_before);
}

}  // namespace
}  // namespace fognav::perception

// Segmentation scores: Table 2 accuracy, coverage and Hoover et al.'s counts on label images
// drawn in code.
#include <functional>

#include <gtest/gtest.h>

#include "perception/segmentation.h"

namespace fognav::perception {
namespace {

// Fills columns [u0, u1) of image with value.
void Fill(LabelImage* image, int u0, int u1, int value) {
  for (int v = 0; v < image->height; ++v)
    for (int u = u0; u < u1; ++u) image->at(u, v) = value;
}

// Ground truth: three surfaces side by side, 20 columns x 10 rows each, at 1 m.
struct Truth {
  LabelImage ids{60, 10, -1};
  DepthImage depth{60, 10, 1.0f};
  Truth() {
    Fill(&ids, 0, 20, 7);
    Fill(&ids, 20, 40, 3);
    Fill(&ids, 40, 60, 11);
  }
};

TEST(ScoreSegmentation, PerfectSegmentationIsCorrectEverywhere) {
  const Truth t;
  LabelImage labels(60, 10, -1);
  Fill(&labels, 0, 20, 0);
  Fill(&labels, 20, 40, 1);
  Fill(&labels, 40, 60, 2);

  const SegmentationScore s = ScoreSegmentation(labels, t.ids, t.depth);

  EXPECT_DOUBLE_EQ(s.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(s.coverage, 1.0);
  EXPECT_EQ(s.correct, 3);
  EXPECT_EQ(s.over + s.under + s.missed + s.noise, 0);
  EXPECT_EQ(s.planes, 3);
  EXPECT_EQ(s.truth_surfaces, 3);
}

TEST(ScoreSegmentation, CountsOverAndUnderSegmentation) {
  const Truth t;
  LabelImage labels(60, 10, -1);
  Fill(&labels, 0, 10, 0);   // surface 7 in two halves: over-segmented
  Fill(&labels, 10, 20, 1);
  Fill(&labels, 20, 60, 2);  // surfaces 3 and 11 in one segment: under-segmented

  const SegmentationScore s = ScoreSegmentation(labels, t.ids, t.depth);

  EXPECT_EQ(s.correct, 0);
  EXPECT_EQ(s.over, 1);
  EXPECT_EQ(s.under, 1);
  EXPECT_EQ(s.missed, 0);
  EXPECT_EQ(s.noise, 0);
  // one to one: 7 -> segment 0 (100/100); segment 2 belongs to 3 (a tie, the lower id), 200/400;
  // 11 has no segment of its own and counts for coverage only
  EXPECT_NEAR(s.accuracy, (100.0 + 200) / (100 + 400), 1e-12);
  EXPECT_NEAR(s.coverage, (100.0 + 200) / 600, 1e-12);
}

TEST(ScoreSegmentation, CountsMissedSurfacesAndNoiseSegments) {
  const Truth t;
  LabelImage labels(60, 10, -1);
  Fill(&labels, 0, 20, 0);   // correct
  Fill(&labels, 20, 25, 1);  // a quarter of surface 3: too small for any instance -> noise
  // surface 11 left unsegmented: missed

  const SegmentationScore s = ScoreSegmentation(labels, t.ids, t.depth);

  EXPECT_EQ(s.correct, 1);
  EXPECT_EQ(s.missed, 2);
  EXPECT_EQ(s.noise, 1);
  EXPECT_NEAR(s.coverage, (200.0 + 50) / 600, 1e-12);
}

TEST(ScoreSegmentation, SurfaceSeenEdgeOnIsMissedNotCountedTwice) {
  // a floor with a wall seen edge-on: 6 columns of wall, all inside the floor's segment
  LabelImage ids(60, 10, 7);
  const DepthImage depth(60, 10, 1.0f);
  Fill(&ids, 27, 33, 3);
  const LabelImage labels(60, 10, 0);

  const SegmentationScore s = ScoreSegmentation(labels, ids, depth);

  // the segment counts once, for the floor; the wall lowers coverage only
  EXPECT_EQ(s.truth_surfaces, 2);
  EXPECT_NEAR(s.accuracy, 540.0 / 600, 1e-12);
  EXPECT_NEAR(s.coverage, 540.0 / 600, 1e-12);
  EXPECT_EQ(s.segment_px, 600);
}

TEST(ScoreSegmentation, CoplanarSurfacesApartNeedASegmentEach) {
  const Truth t;
  LabelImage merged(60, 10, -1), apart(60, 10, -1);
  Fill(&merged, 0, 60, 0);  // 7 and 11 (two table tops at one height) in one segment
  Fill(&merged, 20, 40, 1);
  Fill(&apart, 0, 20, 0);
  Fill(&apart, 20, 40, 1);
  Fill(&apart, 40, 60, 2);

  const SegmentationScore m = ScoreSegmentation(merged, t.ids, t.depth);
  const SegmentationScore a = ScoreSegmentation(apart, t.ids, t.depth);

  // merged: segment 0 belongs to 7 (the lower id of a tie) and holds 11's pixels too; 11 missed
  EXPECT_NEAR(m.accuracy, (200.0 + 200) / (400 + 200), 1e-12);
  EXPECT_NEAR(m.coverage, (200.0 + 200) / 600, 1e-12);
  EXPECT_DOUBLE_EQ(a.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(a.coverage, 1.0);
}

// Exact points of a 60 x 10 view, column by column: `depth(u)` gives the point's z, and x
// follows the column (1 cm per column), y the row.
PointImage ExactPoints(const std::function<double(int)>& depth) {
  PointImage points(60, 10);
  for (int v = 0; v < 10; ++v) {
    for (int u = 0; u < 60; ++u) points.at(u, v) = Eigen::Vector3f(0.01f * u, 0.01f * v, float(depth(u)));
  }
  return points;
}

TEST(JoinCoplanarSurfaces, TouchingFacesInOnePlaneBecomeOneSurface) {
  // a table leg flush with the top's edge: ids 7 and 3 side by side in the plane z = 1, id 11
  // beyond them, 1 cm behind that plane
  const Truth t;
  const LabelImage joined =
      JoinCoplanarSurfaces(t.ids, ExactPoints([](int u) { return u < 40 ? 1.0 : 1.01; }));
  EXPECT_EQ(joined.at(5, 5), 3);  // the lower id
  EXPECT_EQ(joined.at(25, 5), 3);
  EXPECT_EQ(joined.at(45, 5), 11);  // parallel, 1 cm apart: two surfaces

  // a segment over both faces is now one correct detection, not an under-segmentation
  LabelImage labels(60, 10, -1);
  Fill(&labels, 0, 40, 0);
  Fill(&labels, 40, 60, 1);
  const SegmentationScore before = ScoreSegmentation(labels, t.ids, t.depth);
  const SegmentationScore after = ScoreSegmentation(labels, joined, t.depth);
  EXPECT_LT(before.accuracy, 0.7);
  EXPECT_DOUBLE_EQ(after.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(after.coverage, 1.0);
  EXPECT_EQ(after.correct, 2);
  EXPECT_EQ(after.under, 0);
}

TEST(JoinCoplanarSurfaces, FacesAtAnAngleOrApartStayApart) {
  const Truth t;
  // an edge: ids 7 and 3 meet at u = 20 at 45 degrees (z grows with x beyond it)
  const LabelImage corner = JoinCoplanarSurfaces(
      t.ids, ExactPoints([](int u) { return u < 20 ? 1.0 : 1.0 + 0.01 * (u - 20); }));
  EXPECT_EQ(corner.at(5, 5), 7);
  EXPECT_EQ(corner.at(25, 5), 3);
  // a surface of one pixel on the edge fits both planes, and joins neither
  Truth bridged;
  bridged.ids.at(20, 5) = 5;
  const LabelImage bridge = JoinCoplanarSurfaces(
      bridged.ids, ExactPoints([](int u) { return u < 20 ? 1.0 : 1.0 + 0.01 * (u - 20); }));
  EXPECT_EQ(bridge.at(5, 5), 7);
  EXPECT_EQ(bridge.at(25, 5), 3);
  EXPECT_EQ(bridge.at(20, 5), 5);
  // two faces in one plane with a nearer surface between them in the image: not touching
  const LabelImage apart =
      JoinCoplanarSurfaces(t.ids, ExactPoints([](int u) { return u >= 20 && u < 40 ? 0.8 : 1.0; }));
  EXPECT_EQ(apart.at(5, 5), 7);
  EXPECT_EQ(apart.at(45, 5), 11);
}

TEST(ScoreSegmentation, CountsOnlyPixelsWithinTheScoredRange) {
  Truth t;
  for (int v = 6; v < 10; ++v)
    for (int u = 0; u < 20; ++u) t.depth.at(u, v) = 4.0f;  // 7's far rows (its median is 1 m)
  for (int v = 0; v < 10; ++v)
    for (int u = 20; u < 40; ++u) t.depth.at(u, v) = 3.0f;  // 3 beyond 2.5 m: not scored
  LabelImage labels(60, 10, -1);
  Fill(&labels, 0, 40, 0);  // 7 and the far surface 3 in one segment
  Fill(&labels, 40, 60, 1);

  const SegmentationScore s = ScoreSegmentation(labels, t.ids, t.depth);

  // neither the far surface nor 7's far rows count, on either side
  EXPECT_EQ(s.truth_surfaces, 2);
  EXPECT_DOUBLE_EQ(s.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(s.coverage, 1.0);
  EXPECT_EQ(s.segment_px, 120 + 200);
  EXPECT_EQ(s.surface_px, 120 + 200);
}

TEST(ScoreSegmentation, ToleranceDecidesCorrectDetections) {
  const Truth t;
  LabelImage labels(60, 10, -1);
  Fill(&labels, 0, 17, 0);  // 85 % of surface 7
  ScoreParams strict;
  strict.tolerance = 0.9;

  EXPECT_EQ(ScoreSegmentation(labels, t.ids, t.depth).correct, 1);
  EXPECT_EQ(ScoreSegmentation(labels, t.ids, t.depth, strict).correct, 0);
}

TEST(ScoreSegmentation, IgnoresSmallAndDistantSurfaces) {
  Truth t;
  for (int v = 0; v < 10; ++v)
    for (int u = 20; u < 40; ++u) t.depth.at(u, v) = 3.0f;  // surface 3 beyond 2.5 m
  for (int v = 0; v < 4; ++v)
    for (int u = 40; u < 50; ++u) t.ids.at(u, v) = 99;  // 40 px: below 50
  LabelImage labels(60, 10, -1);
  Fill(&labels, 0, 20, 0);

  const SegmentationScore s = ScoreSegmentation(labels, t.ids, t.depth);

  EXPECT_EQ(s.truth_surfaces, 2);  // 7 and the rest of 11
  EXPECT_EQ(s.correct, 1);
  EXPECT_EQ(s.missed, 1);
}

TEST(ScoreSegmentation, CombinesViewsByPixelSums) {
  const Truth t;
  LabelImage mixed(60, 10, -1), half(60, 10, -1);
  Fill(&mixed, 0, 60, 0);
  Fill(&mixed, 0, 20, 1);
  Fill(&mixed, 40, 60, 2);
  Fill(&half, 0, 10, 0);
  const SegmentationScore a = ScoreSegmentation(mixed, t.ids, t.depth);
  const SegmentationScore b = ScoreSegmentation(half, t.ids, t.depth);

  const SegmentationScore c = CombineScores({a, b});

  EXPECT_EQ(c.correct, a.correct + b.correct);
  EXPECT_EQ(c.truth_surfaces, 6);
  EXPECT_NEAR(c.coverage, double(a.overlap_px + b.overlap_px) / (a.surface_px + b.surface_px),
              1e-12);
}

TEST(ScoreSegmentation, EmptyTruthScoresZero) {
  const LabelImage none(10, 10, -1);
  const DepthImage depth(10, 10, 1.0f);
  const SegmentationScore s = ScoreSegmentation(none, none, depth);
  EXPECT_EQ(s.truth_surfaces, 0);
  EXPECT_EQ(s.accuracy, 0.0);
}

}  // namespace
}  // namespace fognav::perception

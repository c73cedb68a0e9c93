// Floor height map: verification (eq. 19, 20) and update (eq. 21).
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "perception/mapping.h"

namespace fognav::perception {
namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();

// Cell x in [0.40, 0.44), y in [0, 0.04): a 3 x 3 patch of points at height z labelled h.
std::vector<LabelledPoint> Patch(float z, float h) {
  std::vector<LabelledPoint> points;
  for (float x : {0.412f, 0.42f, 0.428f}) {
    for (float y : {0.012f, 0.02f, 0.028f}) points.push_back({{x, y, z}, h});
  }
  return points;
}

MapInput Frame(const Eigen::Vector3d& camera, std::vector<LabelledPoint> points) {
  MapInput in;
  in.p_GC = camera;
  in.points = std::move(points);
  return in;
}

const Eigen::Vector3d kAbove(0.42, 0.02, 0.6);  // camera right above the cell

TEST(FloorMap, Eq19FloorIsInsertedOnlyOnceTheGridHoldsIt) {
  MapParams params;
  params.grid.p_occ = 0.8;  // one hit (0.7) is not enough, two (0.845) are
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.0f)), &state);
  EXPECT_EQ(state.FloorAt(0.42, 0.02), kNegInf);
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.0f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);
}

TEST(FloorMap, Eq19OutlierPlaneHeightNotBackedByTheGridIsIgnored) {
  MapParams params;
  MapState state;
  // the points lie at z = 0 but claim a plane at 0.30: the grid holds nothing there
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.30f)), &state);
  EXPECT_EQ(state.FloorAt(0.42, 0.02), kNegInf);
}

TEST(FloorMap, Eq21HigherReplacesLowerIsIgnoredCloseIsSmoothed) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.10f, 0.10f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.10, 1e-6);
  // a higher surface by more than the gate replaces the height
  UpdateMaps(params, Frame(kAbove, Patch(0.20f, 0.20f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.20, 1e-6);
  // a lower one is ignored (seen from the side, so no ray crosses the floor at 0.20)
  UpdateMaps(params, Frame({0.02, 0.02, 0.08}, Patch(0.05f, 0.05f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.20, 1e-6);
  // within the gate: nu * F + (1 - nu) * h, once per point
  std::vector<LabelledPoint> one = {{{0.42f, 0.02f, 0.205f}, 0.205f}};
  UpdateMaps(params, Frame(kAbove, one), &state);
  const double nu = params.floor.smoothing;
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), nu * 0.20 + (1 - nu) * 0.205, 1e-6);
}

TEST(FloorMap, Eq20FloorIsDroppedWhenRaysPassThroughIt) {
  MapParams params;
  MapState state;
  // a box top at 0.20, then the box is gone and the camera sees the floor through it
  UpdateMaps(params, Frame(kAbove, Patch(0.20f, 0.20f)), &state);
  ASSERT_NEAR(state.FloorAt(0.42, 0.02), 0.20, 1e-6);
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.0f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.20, 1e-6);  // P = 0.61 still above P_occ
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.0f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);  // dropped (eq. 20), then the floor below
  EXPECT_LT(state.ProbabilityAt({0.42, 0.02, 0.20}), params.grid.p_occ);
}

TEST(FloorMap, GrazingRaysDoNotEraseAKnownFloor) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.0f)), &state);
  ASSERT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);
  // rays just above the floor across the cell to a floor point further on
  std::vector<LabelledPoint> far = {{{1.0f, 0.02f, 0.0f}, 0.0f}};
  for (int k = 0; k < 5; ++k) UpdateMaps(params, Frame({0.0, 0.02, 0.012}, far), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);
  EXPECT_GT(state.ProbabilityAt({0.42, 0.02, 0.0}), params.grid.p_occ);
}

TEST(FloorMap, RepeatedNoisyObservationsConverge) {
  MapParams params;
  MapState state;
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.003f);
  std::vector<double> late;
  for (int k = 0; k < 60; ++k) {
    const float h = 0.03f + noise(rng);
    UpdateMaps(params, Frame(kAbove, {{{0.42f, 0.02f, h}, h}}), &state);
    if (k >= 40) late.push_back(state.FloorAt(0.42, 0.02));
  }
  double mean = 0;
  for (double f : late) mean += f / late.size();
  double var = 0;
  for (double f : late) var += (f - mean) * (f - mean) / late.size();
  EXPECT_NEAR(mean, 0.03, 0.003);
  EXPECT_LT(std::sqrt(var), 0.003);  // smoothed below the noise of single readings
}

// Patch(z, h) whose height carries a sigma, as LabelPoints gives it.
std::vector<LabelledPoint> Patch(float z, float h, float h_sigma) {
  std::vector<LabelledPoint> points = Patch(z, h);
  for (LabelledPoint& lp : points) lp.h_sigma = h_sigma;
  return points;
}

const Eigen::Vector3d kSide(0.02, 0.02, 0.08);  // camera low to the side: no ray crosses the cell

TEST(FloorMap, HeightsWithSigmaAreAveragedByInverseVarianceOncePerPlaneAndFrame) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.10f, 0.10f, 0.002f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.10, 1e-6);
  // nine points of one plane count as one measurement of variance 0.004^2
  UpdateMaps(params, Frame(kAbove, Patch(0.104f, 0.104f, 0.004f)), &state);
  const double w = 0.002 * 0.002 / (0.002 * 0.002 + 0.004 * 0.004);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.10 + w * 0.004, 1e-6);
}

TEST(FloorMap, NoisyHigherHeightDoesNotReplaceAPreciseOne) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.0f, 0.002f)), &state);
  // 2.5 cm higher but with a 1.5 cm sigma (a far plane): eq. (21) alone would take it as a
  // higher floor; within 2 sigma it is averaged in with its small weight instead
  UpdateMaps(params, Frame(kSide, Patch(0.025f, 0.025f, 0.015f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 0.001);
  // a precise higher floor still replaces it (a box top put on the floor)
  UpdateMaps(params, Frame(kAbove, Patch(0.10f, 0.10f, 0.002f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.10, 1e-6);
}

TEST(FloorMap, PreciseLowerHeightCorrectsANoisyOne) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.05f, 0.05f, 0.01f)), &state);
  ASSERT_NEAR(state.FloorAt(0.42, 0.02), 0.05, 1e-6);
  // lower by more than the gate and at least four times less variance: it replaces the height
  UpdateMaps(params, Frame(kSide, Patch(0.0f, 0.0f, 0.002f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);
  // a lower floor no more precise than the cell's is ignored as in eq. (21)
  UpdateMaps(params, Frame(kAbove, Patch(0.10f, 0.10f, 0.002f)), &state);
  UpdateMaps(params, Frame(kSide, Patch(0.0f, 0.0f, 0.002f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.10, 1e-6);
}

// A wrong height that no later view confirms (a plane merged across a small step, seen once
// from afar) yields to a lower floor seen in the middle of the cell in later frames.
TEST(FloorMap, ALowerFloorSeenAgainAndAgainReplacesAHeightNothingConfirms) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.018f, 0.018f, 0.002f)), &state);
  int frames = 0;
  while (state.FloorAt(0.42, 0.02) > 0.01f && frames < 10) {
    UpdateMaps(params, Frame(kSide, Patch(0.0f, 0.0f, 0.002f)), &state);
    ++frames;
  }
  // equally precise: doubted twice (variance x4), then replaced as eq. (21) allows (the
  // variances are powers of two times the same value, so the comparison is exact)
  EXPECT_EQ(frames, 3);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);
}

// Lower floor points only at a cell's side (the foot of a step edge) do not doubt its height.
TEST(FloorMap, ALowerFloorAtTheSideOfACellDoesNotDoubtIt) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.018f, 0.018f, 0.002f)), &state);
  std::vector<LabelledPoint> side;
  for (float y : {0.012f, 0.02f, 0.028f}) side.push_back({{0.402f, y, 0.0f}, 0.0f, 0.002f});
  for (int i = 0; i < 5; ++i) UpdateMaps(params, Frame(kSide, side), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.018, 1e-6);
}

// The higher floor of a step edge cell stays while the same views confirm it along the edge.
TEST(FloorMap, TheHigherFloorOfAStepEdgeStaysWhileItsNeighboursConfirmIt) {
  MapParams params;
  MapState state;
  auto edge_frame = [](float edge_cell_h) {
    std::vector<LabelledPoint> points = Patch(edge_cell_h, edge_cell_h, 0.002f);
    // the tread goes on in the next cell along the edge, y in [0.04, 0.08)
    for (LabelledPoint lp : Patch(0.03f, 0.03f, 0.002f)) {
      lp.p_G.y() += 0.04f;
      points.push_back(lp);
    }
    return Frame(kAbove, points);
  };
  UpdateMaps(params, edge_frame(0.03f), &state);
  ASSERT_NEAR(state.FloorAt(0.42, 0.02), 0.03, 1e-6);
  // five views that see only the lower floor in the edge cell but the tread beside it
  for (int i = 0; i < 5; ++i) UpdateMaps(params, edge_frame(0.0f), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.03, 1e-6);
  EXPECT_NEAR(state.FloorAt(0.42, 0.06), 0.03, 1e-6);
}

// A step's riser joined to the floor plane by segmentation: two of the floor plane's points lie
// in a tread cell. They are too few against the tread's nine to set the cell's height, although
// the floor plane is the more precise (which alone would let it replace the tread's height).
TEST(FloorMap, AFewPointsOfANeighbouringPlaneDoNotSetACellsHeight) {
  MapParams params;
  MapState state;
  std::vector<LabelledPoint> points = Patch(0.03f, 0.03f, 0.005f);
  for (float y : {0.012f, 0.028f}) points.push_back({{0.401f, y, 0.005f}, 0.0f, 0.002f});
  UpdateMaps(params, Frame(kAbove, points), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.03, 1e-6);
  // with as many points as the tread's in the cell the floor plane is no minor height
  for (int i = 0; i < 7; ++i) points.push_back({{0.402f, 0.02f, 0.004f}, 0.0f, 0.002f});
  MapState both;
  UpdateMaps(params, Frame(kAbove, points), &both);
  EXPECT_NEAR(both.FloorAt(0.42, 0.02), 0.0, 1e-6);
}

// Points more than 2 sigma and 1 cm above their plane's height (a face joined to the plane)
// give their cell no floor, although the grid layer they hit holds the plane's height; points
// within that do, and so do points below their plane (they can only raise the cell's height).
TEST(FloorMap, PointsFarAboveTheirPlaneGiveNoHeight) {
  MapParams params;
  MapState state;
  UpdateMaps(params, Frame(kAbove, Patch(0.015f, 0.0f, 0.002f)), &state);
  ASSERT_EQ(state.LayerOf(0.015), state.LayerOf(0.0));
  EXPECT_GT(state.ProbabilityAt({0.42, 0.02, 0.015}), 0.5);
  EXPECT_EQ(state.FloorAt(0.42, 0.02), kNegInf);
  UpdateMaps(params, Frame(kAbove, Patch(0.008f, 0.0f, 0.002f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);
  MapState below;
  UpdateMaps(params, Frame(kAbove, Patch(0.0f, 0.015f, 0.002f)), &below);
  EXPECT_NEAR(below.FloorAt(0.42, 0.02), 0.015, 1e-6);
}

// A minor height above the cell's other one is kept, however few its points: the cell keeps
// the highest floor in it, as in eq. (21). A tread 3 cm up, and a table top 0.28 m up seen from
// the side with the floor below its edge.
TEST(FloorMap, AFewPointsOfAHigherPlaneStillSetACellsHeight) {
  MapParams params;
  for (const auto& [top, camera] : {std::pair{0.03f, kAbove}, std::pair{0.28f, kSide}}) {
    SCOPED_TRACE(top);
    MapState state;
    std::vector<LabelledPoint> points = Patch(0.0f, 0.0f, 0.002f);
    for (float y : {0.012f, 0.028f}) points.push_back({{0.438f, y, top}, top, 0.002f});
    UpdateMaps(params, Frame(camera, points), &state);
    EXPECT_NEAR(state.FloorAt(0.42, 0.02), top, 1e-6);
  }
}

// A fresh look fades the grid (FadeGrid) but spares the layers that hold floor heights: a top
// seen once (one hit, log-odds 0.85) would fall below P_occ's 0.41 at a quarter, and eq. (20)
// would drop it; other layers fade, in floor cells and elsewhere.
TEST(FloorMap, FadingTheGridKeepsTheLayersThatHoldFloorHeights) {
  MapParams params;
  MapState state;
  std::vector<LabelledPoint> points = Patch(0.30f, 0.30f);
  const LabelledPoint obstacle{{0.42f, 0.22f, 0.30f}, kNegInf};  // a point of no floor plane
  points.push_back(obstacle);
  UpdateMaps(params, Frame(kAbove, points), &state);
  ASSERT_NEAR(state.FloorAt(0.42, 0.02), 0.30, 1e-6);
  const double top = state.ProbabilityAt({0.42, 0.02, 0.30});
  const double other = state.ProbabilityAt({0.42, 0.22, 0.30});
  ASSERT_GT(top, 0.6);
  ASSERT_GT(other, 0.6);
  const auto faded = [](double p, double keep) {
    return 1.0 / (1.0 + std::exp(-keep * std::log(p / (1.0 - p))));
  };

  MapState plain = state;
  for (float& l : plain.log_odds) l *= 0.25f;
  UpdateMaps(params, Frame(kAbove, {}), &plain);
  EXPECT_EQ(plain.FloorAt(0.42, 0.02), kNegInf);  // what fading everything does

  FadeGrid(params, 0.25, &state);
  EXPECT_NEAR(state.ProbabilityAt({0.42, 0.02, 0.30}), top, 1e-6);
  EXPECT_NEAR(state.ProbabilityAt({0.42, 0.22, 0.30}), faded(other, 0.25), 1e-5);
  UpdateMaps(params, Frame(kAbove, {}), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.30, 1e-6);
  // the free layers the rays crossed above the top fade too
  const double above = state.ProbabilityAt({0.42, 0.02, 0.45});
  EXPECT_LT(above, 0.5);
  EXPECT_NEAR(above, plain.ProbabilityAt({0.42, 0.02, 0.45}), 1e-6);
}

// A state never updated has no cells to fade (map_update_fuzz: FadeGrid read the floor heights
// of the default window's 10000 cells from an empty vector)
TEST(FloorMap, FadingAStateNeverUpdatedLeavesItEmpty) {
  MapState state;
  FadeGrid(MapParams(), 0.25, &state);
  EXPECT_TRUE(state.log_odds.empty());
  EXPECT_TRUE(state.floor.empty());
  UpdateMaps(MapParams(), Frame(kAbove, Patch(0.0f, 0.0f)), &state);
  EXPECT_NEAR(state.FloorAt(0.42, 0.02), 0.0, 1e-6);
}

}  // namespace
}  // namespace fognav::perception

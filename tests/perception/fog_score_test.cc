// FOG scores against ground truth on small FOGs written cell by cell: traversability with its
// one-cell tolerance, unsafe cells, floor heights and the six-type match.
#include <gtest/gtest.h>

#include "perception/mapping.h"

namespace fognav::perception {
namespace {

const FogParams kParams;  // h_floor 1.5 cm

// A 12 x 12 window of 4 cm cells whose global cells start at (origin, origin).
GridWindow Window(int origin = 0) {
  GridWindow w;
  w.size_x = w.size_y = 12;
  w.origin_ix = w.origin_iy = origin;
  return w;
}

void Set(Fog* fog, int ix, int iy, CellType type, float height) {
  const size_t i = size_t(fog->window.Index(ix, iy));
  fog->type[i] = type;
  fog->height[i] = height;
}

// The truth: floor at 0 everywhere, a block 0.2 m high over cells x, y in [4, 7) and a table
// (tunnel) over x in [9, 12), y in [0, 3).
Fog Truth() {
  Fog truth(Window());
  for (int iy = 0; iy < 12; ++iy)
    for (int ix = 0; ix < 12; ++ix) Set(&truth, ix, iy, CellType::kFloor, 0.0f);
  for (int iy = 4; iy < 7; ++iy)
    for (int ix = 4; ix < 7; ++ix) Set(&truth, ix, iy, CellType::kObstacle, 0.2f);
  for (int iy = 0; iy < 3; ++iy)
    for (int ix = 9; ix < 12; ++ix) Set(&truth, ix, iy, CellType::kTunnel, 0.0f);
  return truth;
}

FogCellComparison At(const std::vector<FogCellComparison>& c, const Fog& fog, int ix, int iy) {
  return c[size_t(fog.window.Index(ix, iy))];
}

TEST(FogScore, TraversabilityClassesFollowThePlanner) {
  EXPECT_EQ(TraversabilityOf(CellType::kFloor), Traversability::kStandable);
  EXPECT_EQ(TraversabilityOf(CellType::kStairs), Traversability::kStandable);
  EXPECT_EQ(TraversabilityOf(CellType::kTunnel), Traversability::kCrawlOnly);
  EXPECT_EQ(TraversabilityOf(CellType::kBorder), Traversability::kBlocked);
  EXPECT_EQ(TraversabilityOf(CellType::kObstacle), Traversability::kBlocked);
  EXPECT_EQ(TraversabilityOf(CellType::kUnknown), Traversability::kUnknown);
}

TEST(FogScore, TheTruthScoresPerfectly) {
  const Fog truth = Truth();

  const FogScore s = ScoreFog(truth, truth, kParams);

  EXPECT_EQ(s.observed, 144);
  EXPECT_DOUBLE_EQ(s.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(s.traversability, 1.0);
  EXPECT_EQ(s.unsafe_cells, 0);
  EXPECT_EQ(s.unsafe_cells_strict, 0);
  EXPECT_EQ(s.comparisons[int(FogCellComparison::kRight)], 144);
  EXPECT_EQ(s.height_cells, 144 - 9 - 9);
  EXPECT_DOUBLE_EQ(s.height_error_max, 0.0);
}

TEST(FogScore, AnEdgeSmearedByACellIsRightByTraversabilityOnly) {
  const Fog truth = Truth();
  Fog fog = truth;
  // the block grown by one cell toward -x: floor cells x = 3 typed obstacle
  for (int iy = 4; iy < 7; ++iy) Set(&fog, 3, iy, CellType::kObstacle, 0.2f);
  // and the tunnel typed obstacle at the cell nearest the open floor
  Set(&fog, 9, 2, CellType::kObstacle, 0.7f);

  const FogScore s = ScoreFog(fog, truth, kParams);
  const std::vector<FogCellComparison> c = CompareFog(fog, truth, kParams);

  EXPECT_EQ(At(c, fog, 3, 5), FogCellComparison::kRightNearby);
  EXPECT_EQ(At(c, fog, 9, 2), FogCellComparison::kWrongClass);  // no blocked cell near it
  EXPECT_EQ(s.correct, 144 - 4);
  EXPECT_NEAR(s.accuracy, 140.0 / 144, 1e-12);
  EXPECT_NEAR(s.traversability, 143.0 / 144, 1e-12);
  EXPECT_EQ(s.unsafe_cells, 0);
}

TEST(FogScore, StandableInsideABlockIsUnsafeAndAtItsEdgeOnlyStrictly) {
  const Fog truth = Truth();
  Fog fog = truth;
  Set(&fog, 5, 5, CellType::kFloor, 0.0f);  // the block's middle: blocked all around
  Set(&fog, 4, 4, CellType::kFloor, 0.0f);  // the block's corner: floor beside it
  Set(&fog, 10, 1, CellType::kFloor, 0.0f);  // under the table, crawl-only all around

  const FogScore s = ScoreFog(fog, truth, kParams);
  const std::vector<FogCellComparison> c = CompareFog(fog, truth, kParams);

  EXPECT_EQ(At(c, fog, 5, 5), FogCellComparison::kUnsafe);
  EXPECT_EQ(At(c, fog, 4, 4), FogCellComparison::kStandableEdge);
  EXPECT_EQ(At(c, fog, 10, 1), FogCellComparison::kUnsafe);
  EXPECT_EQ(s.unsafe_cells, 2);
  EXPECT_EQ(s.unsafe_cells_strict, 3);
  EXPECT_NEAR(s.traversability, 142.0 / 144, 1e-12);  // the edge cell is right nearby
}

TEST(FogScore, StandableCellsMustHoldTheirHeightWithinHFloor) {
  const Fog truth = Truth();
  Fog fog = truth;
  Set(&fog, 1, 10, CellType::kFloor, 0.01f);  // 1 cm off: right
  Set(&fog, 2, 10, CellType::kFloor, 0.03f);  // 3 cm off, and so is every neighbour
  Set(&fog, 3, 10, CellType::kStairs, -0.02f);

  const FogScore s = ScoreFog(fog, truth, kParams);
  const std::vector<FogCellComparison> c = CompareFog(fog, truth, kParams);

  EXPECT_EQ(At(c, fog, 1, 10), FogCellComparison::kRight);
  EXPECT_EQ(At(c, fog, 2, 10), FogCellComparison::kWrongHeight);
  EXPECT_EQ(At(c, fog, 3, 10), FogCellComparison::kWrongHeight);
  EXPECT_NEAR(s.traversability, 142.0 / 144, 1e-12);
  EXPECT_EQ(s.unsafe_cells, 0);
  // heights over the 126 cells both hold standable: 123 exact, 0.01, 0.02, 0.03
  EXPECT_EQ(s.height_cells, 126);
  EXPECT_NEAR(s.height_error_max, 0.03, 1e-6);
  EXPECT_DOUBLE_EQ(s.height_error_median, 0.0);
  EXPECT_DOUBLE_EQ(s.height_error_p95, 0.0);  // 3 of 126 cells lie above the 95th percentile
}

TEST(FogScore, FloorHeldUnderATopTheTruthStandsOnIsAHeightError) {
  // a table top 0.49 m high, just below the eyes: the truth holds its 3 x 3 cells as floor up
  // there (a border around them); the map holds the floor seen under it at 0. By class the
  // cells are standable on both sides, so they are wrong in height, and the height error's
  // tail shows them.
  Fog truth = Truth();
  for (int iy = 7; iy < 12; ++iy)
    for (int ix = 0; ix < 5; ++ix) Set(&truth, ix, iy, CellType::kBorder, 0.49f);
  for (int iy = 8; iy < 11; ++iy)
    for (int ix = 1; ix < 4; ++ix) Set(&truth, ix, iy, CellType::kFloor, 0.49f);
  Fog fog = truth;
  for (int iy = 8; iy < 11; ++iy)
    for (int ix = 1; ix < 4; ++ix) Set(&fog, ix, iy, CellType::kFloor, 0.0f);

  const FogScore s = ScoreFog(fog, truth, kParams);
  const std::vector<FogCellComparison> c = CompareFog(fog, truth, kParams);

  EXPECT_EQ(At(c, fog, 2, 9), FogCellComparison::kWrongHeight);
  EXPECT_EQ(s.comparisons[int(FogCellComparison::kWrongHeight)], 9);
  EXPECT_EQ(s.unsafe_cells, 0);
  EXPECT_NEAR(s.height_error_max, 0.49, 1e-6);
  EXPECT_GT(s.height_cells, 0);
}

TEST(FogScore, UnknownCellsAreNotScoredAndLostFloorIsWrong) {
  const Fog truth = Truth();
  Fog fog(Window());
  Set(&fog, 0, 0, CellType::kFloor, 0.0f);
  Set(&fog, 1, 11, CellType::kBorder, 0.0f);  // open floor typed border: a floor lost
  Set(&fog, 5, 5, CellType::kTunnel, 0.0f);   // a block typed tunnel

  const FogScore s = ScoreFog(fog, truth, kParams);

  EXPECT_EQ(s.observed, 3);
  EXPECT_EQ(s.comparisons[int(FogCellComparison::kUnobserved)], 141);
  EXPECT_EQ(s.comparisons[int(FogCellComparison::kWrongClass)], 2);
  EXPECT_NEAR(s.traversability, 1.0 / 3, 1e-12);
  EXPECT_EQ(s.unsafe_cells, 0);
}

TEST(FogScore, WindowsAreMatchedByGlobalCells) {
  // the estimate's window starts 3 cells further along x and y: its local (1, 1) is the
  // truth's (4, 4), the block's corner
  const Fog truth = Truth();
  Fog fog(Window(3));
  Set(&fog, 2, 2, CellType::kFloor, 0.0f);  // truth's (5, 5): inside the block
  Set(&fog, 0, 0, CellType::kFloor, 0.0f);  // truth's (3, 3): open floor

  const FogScore s = ScoreFog(fog, truth, kParams);
  const std::vector<FogCellComparison> c = CompareFog(fog, truth, kParams);

  EXPECT_EQ(At(c, fog, 2, 2), FogCellComparison::kUnsafe);
  EXPECT_EQ(At(c, fog, 0, 0), FogCellComparison::kRight);
  EXPECT_EQ(s.unsafe_cells, 1);
  // cells beyond the truth's window (local 9 to 11) are not compared at all
  int compared = 0;
  for (int k = 0; k < kNumFogCellComparisons; ++k) compared += s.comparisons[size_t(k)];
  EXPECT_EQ(compared, 9 * 9);
}

}  // namespace
}  // namespace fognav::perception

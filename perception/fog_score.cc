// Scores of an estimated FOG against the ground-truth FOG: the six-type match, traversability
// with a one-cell tolerance, unsafe cells and floor heights (docs/scores.md).
#include <algorithm>
#include <cmath>
#include <vector>

#include "perception/mapping.h"

namespace fognav::perception {
namespace {

// The value at quantile q in [0, 1] of `values` (nearest rank); 0 if empty.
double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  const size_t k = std::min(values.size() - 1, size_t(std::ceil(q * double(values.size()))) - 1);
  std::nth_element(values.begin(), values.begin() + long(k), values.end());
  return values[k];
}

// A truth cell of the estimate's local cell (ix, iy).
struct TruthCell {
  int x, y;
  bool inside;
};

TruthCell TruthCellOf(const GridWindow& we, const GridWindow& wt, int ix, int iy) {
  const int x = we.origin_ix + ix - wt.origin_ix, y = we.origin_iy + iy - wt.origin_iy;
  return {x, y, wt.Contains(x, y)};
}

}  // namespace

Traversability TraversabilityOf(CellType type) {
  switch (type) {
    case CellType::kFloor:
    case CellType::kStairs:
      return Traversability::kStandable;
    case CellType::kTunnel:
      return Traversability::kCrawlOnly;
    case CellType::kBorder:
    case CellType::kObstacle:
      return Traversability::kBlocked;
    case CellType::kUnknown:
      break;
  }
  return Traversability::kUnknown;
}

const char* FogCellComparisonName(FogCellComparison c) {
  switch (c) {
    case FogCellComparison::kUnobserved: return "unobserved";
    case FogCellComparison::kRight: return "right";
    case FogCellComparison::kRightNearby: return "right_nearby";
    case FogCellComparison::kStandableEdge: return "standable_edge";
    case FogCellComparison::kWrongHeight: return "wrong_height";
    case FogCellComparison::kWrongClass: return "wrong_class";
    case FogCellComparison::kUnsafe: return "unsafe";
  }
  return "?";
}

std::vector<FogCellComparison> CompareFog(const Fog& estimate, const Fog& truth,
                                          const FogParams& params) {
  using T = Traversability;
  const GridWindow& we = estimate.window;
  const GridWindow& wt = truth.window;
  std::vector<FogCellComparison> out(size_t(we.NumCells()), FogCellComparison::kUnobserved);
  for (int iy = 0; iy < we.size_y; ++iy) {
    for (int ix = 0; ix < we.size_x; ++ix) {
      const TruthCell c = TruthCellOf(we, wt, ix, iy);
      const T est = TraversabilityOf(estimate.TypeAt(ix, iy));
      if (!c.inside || est == T::kUnknown) continue;
      const T at = TraversabilityOf(truth.TypeAt(c.x, c.y));
      if (at == T::kUnknown) continue;
      const float h = estimate.HeightAt(ix, iy);
      // right at truth cell (x, y): the same class, and for standable a height within h_floor
      auto right_at = [&](int x, int y) {
        if (TraversabilityOf(truth.TypeAt(x, y)) != est) return false;
        return est != T::kStandable || std::abs(double(h) - truth.HeightAt(x, y)) <= params.h_floor;
      };
      bool right_near = false, standable_near = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = c.x + dx, y = c.y + dy;
          if ((dx == 0 && dy == 0) || !wt.Contains(x, y)) continue;
          right_near = right_near || right_at(x, y);
          standable_near = standable_near || TraversabilityOf(truth.TypeAt(x, y)) == T::kStandable;
        }
      }
      const bool standable_over_blocked = est == T::kStandable && at != T::kStandable;
      FogCellComparison& r = out[size_t(we.Index(ix, iy))];
      if (right_at(c.x, c.y)) {
        r = FogCellComparison::kRight;
      } else if (standable_over_blocked && !standable_near) {
        r = FogCellComparison::kUnsafe;
      } else if (right_near) {
        r = standable_over_blocked ? FogCellComparison::kStandableEdge
                                   : FogCellComparison::kRightNearby;
      } else {
        r = est == T::kStandable ? FogCellComparison::kWrongHeight : FogCellComparison::kWrongClass;
      }
    }
  }
  return out;
}

FogScore ScoreFog(const Fog& estimate, const Fog& truth, const FogParams& params) {
  FogScore score;
  std::vector<double> errors;
  const GridWindow& we = estimate.window;
  const std::vector<FogCellComparison> compared = CompareFog(estimate, truth, params);
  for (int iy = 0; iy < we.size_y; ++iy) {
    for (int ix = 0; ix < we.size_x; ++ix) {
      const TruthCell c = TruthCellOf(we, truth.window, ix, iy);
      if (!c.inside) continue;
      const CellType e = estimate.TypeAt(ix, iy);
      const CellType t = truth.TypeAt(c.x, c.y);
      ++score.confusion[int(t)][int(e)];
      const FogCellComparison k = compared[size_t(we.Index(ix, iy))];
      ++score.comparisons[int(k)];
      if (e == CellType::kUnknown) continue;
      ++score.observed;
      if (e == t) ++score.correct;
      const Traversability te = TraversabilityOf(e), tt = TraversabilityOf(t);
      const float he = estimate.HeightAt(ix, iy), ht = truth.HeightAt(c.x, c.y);
      if (te == Traversability::kStandable && tt != Traversability::kUnknown &&
          tt != Traversability::kStandable) {
        ++score.unsafe_cells_strict;
      }
      if (te == Traversability::kStandable && tt == Traversability::kStandable &&
          std::isfinite(he) && std::isfinite(ht)) {
        errors.push_back(std::abs(double(he) - double(ht)));
      }
    }
  }
  using C = FogCellComparison;
  const auto& n = score.comparisons;
  const int right = n[int(C::kRight)] + n[int(C::kRightNearby)] + n[int(C::kStandableEdge)];
  const int wrong = n[int(C::kWrongHeight)] + n[int(C::kWrongClass)] + n[int(C::kUnsafe)];
  score.traversability_cells = right + wrong;
  score.traversability =
      score.traversability_cells > 0 ? double(right) / score.traversability_cells : 0.0;
  score.unsafe_cells = n[int(C::kUnsafe)];
  score.accuracy = score.observed > 0 ? double(score.correct) / score.observed : 0.0;
  score.height_cells = int(errors.size());
  if (!errors.empty()) {
    score.height_error_max = *std::max_element(errors.begin(), errors.end());
    score.height_error_p95 = Quantile(errors, 0.95);
    score.height_error_median = Quantile(std::move(errors), 0.5);
  }
  return score;
}

}  // namespace fognav::perception

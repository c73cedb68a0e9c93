// The paper's classify algorithm (Section 5.4), shared by the estimated and the true FOG.
#ifndef FOGNAV_PERCEPTION_INTERNAL_MAP_CLASSIFY_H_
#define FOGNAV_PERCEPTION_INTERNAL_MAP_CLASSIFY_H_

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "perception/mapping.h"

namespace fognav::perception::internal {

// Quantities of one cell: floor height f, Obstacle o (eq. 22) and Ceiling c (eq. 23) above it,
// floor change dh (eq. 24); -infinity where the paper says so (dh: 0 without neighbours).
struct CellQuantities {
  float f = -std::numeric_limits<float>::infinity();
  float o = -std::numeric_limits<float>::infinity();
  float c = -std::numeric_limits<float>::infinity();
  float dh = 0;
};

// Algorithm classify.
inline CellType Classify(const FogParams& p, const CellQuantities& q) {
  constexpr float kNegInf = -std::numeric_limits<float>::infinity();
  if (q.o > q.f) {
    if (q.f == kNegInf) return CellType::kObstacle;
    if (q.c > q.f + p.h_robot) return CellType::kFloor;
    if (q.c > q.f + p.h_tunnel) return CellType::kTunnel;
    return CellType::kObstacle;
  }
  if (q.f == kNegInf) return CellType::kUnknown;
  if (q.dh < p.h_floor) return CellType::kFloor;
  if (q.dh < p.h_stairs) return CellType::kStairs;
  return CellType::kBorder;
}

// Eq. (25).
inline float FogHeight(CellType t, const CellQuantities& q) {
  if (t == CellType::kUnknown) return -std::numeric_limits<float>::infinity();
  if (t == CellType::kObstacle) return q.o;
  return q.f;
}

// For every cell of a floor map on `window`: eq. (24) floor change dh and the highest floor in
// U(x, y) (-infinity without floor).
inline void FloorChange(const GridWindow& window, const std::vector<float>& floor, int radius,
                        std::vector<float>* dh, std::vector<float>* highest) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const int nx = window.size_x, ny = window.size_y;
  // separable max and min over U of the known floor heights (unknown is -inf for the max, +inf
  // for the min)
  std::vector<float> row_max(floor.size()), row_min(floor.size());
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      float hi = -kInf, lo = kInf;
      for (int jx = std::max(0, ix - radius); jx <= std::min(nx - 1, ix + radius); ++jx) {
        const float g = floor[size_t(iy * nx + jx)];
        hi = std::max(hi, g);
        lo = std::min(lo, g == -kInf ? kInf : g);
      }
      row_max[size_t(iy * nx + ix)] = hi;
      row_min[size_t(iy * nx + ix)] = lo;
    }
  }
  dh->assign(floor.size(), 0.0f);
  highest->assign(floor.size(), -kInf);
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      float hi = -kInf, lo = kInf;
      for (int jy = std::max(0, iy - radius); jy <= std::min(ny - 1, iy + radius); ++jy) {
        hi = std::max(hi, row_max[size_t(jy * nx + ix)]);
        lo = std::min(lo, row_min[size_t(jy * nx + ix)]);
      }
      const size_t i = size_t(iy * nx + ix);
      const float f = floor[i];
      (*highest)[i] = hi;
      // eq. (24): max |f - f'| over known f' in U is max(hi - f, f - lo)
      if (f != -kInf) (*dh)[i] = std::max(hi - f, f - lo);
    }
  }
}

// Lowest height a solid must exceed to count as above the floor of a cell (eq. 22, 23 "z > h_f"
// with FogParams::obstacle_margin and ignore_risers); -infinity without floor.
inline float ObstacleThreshold(const FogParams& p, float f, float highest_near) {
  if (f == -std::numeric_limits<float>::infinity()) return f;
  const float base = p.ignore_risers ? std::max(f, highest_near) : f;
  return base + float(p.obstacle_margin);
}

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_MAP_CLASSIFY_H_

// Steps of UpdateMaps shared between the mapping source files.
#ifndef FOGNAV_PERCEPTION_INTERNAL_MAP_UPDATE_H_
#define FOGNAV_PERCEPTION_INTERNAL_MAP_UPDATE_H_

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Eigenvalues>

#include "perception/mapping.h"

namespace fognav::perception::internal {

// floor() without a libm call (x86-64 without SSE4.1 has no rounding instruction).
inline int FastFloor(float x) {
  const int i = int(x);
  return i - int(x < float(i));
}

inline float LogOdds(double p) { return float(std::log(p / (1.0 - p))); }

// The extents of n points in the x-y plane with these sums (of x, y, x^2, y^2, xy; metres):
// along their principal direction and across it, each sqrt(12 variance) (exact for a uniformly
// covered rectangle).
inline Eigen::Vector2d Extents(double n, double sx, double sy, double sxx, double syy,
                               double sxy) {
  const double mx = sx / n, my = sy / n;
  Eigen::Matrix2d cov;
  cov << sxx / n - mx * mx, sxy / n - mx * my, sxy / n - mx * my, syy / n - my * my;
  const Eigen::Vector2d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvalues();
  return {std::sqrt(12.0 * std::max(0.0, ev(1))), std::sqrt(12.0 * std::max(0.0, ev(0)))};
}

// Whether such points extend at least min_length by min_width: "at least a sole large", for
// the floor candidates among planes (LabelPoints) and among inferred tops (ComputeFog).
inline bool SpansAtLeast(double n, double sx, double sy, double sxx, double syy, double sxy,
                         double min_length, double min_width) {
  const Eigen::Vector2d e = Extents(n, sx, sy, sxx, syy, sxy);
  return e(0) >= min_length && e(1) >= min_width;
}

// Ray traces every point of the input into the 3D grid (eq. 18). A crossed cell in a layer
// touching [g - tol, g + tol] is left alone when the ray stays above g - tol in it, for g the
// known floor height of its column and for g the height h of the floor plane the ray ends on.
void UpdateOccupancy(const OccupancyParams& params, double floor_tolerance, const MapInput& input,
                     MapState* state);

// The grid's layers touching [z - tol, z + tol]: [*lo, *hi], empty (lo > hi) if none.
void LayersNear(const MapState& state, double z, double tol, int* lo, int* hi);

// Highest occupancy log-odds in column (ix, iy) over the layers touching [z - tol, z + tol];
// -infinity if none of them lies in the grid.
float ColumnLogOddsNear(const MapState& state, int ix, int iy, double z, double tol);

// Bit of MapState::floor_frame_marks: floor points of the current frame fell in the cell.
inline constexpr uint8_t kFloorVoted = 4;

// Verifies the floor map against the grid (eq. 20), then inserts the floor points (eq. 19, 21).
void UpdateFloorMap(const MapParams& params, const MapInput& input, MapState* state);

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_MAP_UPDATE_H_

// Steps of UpdateMaps shared between the mapping source files.
#ifndef FOGNAV_PERCEPTION_INTERNAL_MAP_UPDATE_H_
#define FOGNAV_PERCEPTION_INTERNAL_MAP_UPDATE_H_

#include <cmath>

#include "perception/mapping.h"

namespace fognav::perception::internal {

// floor() without a libm call (x86-64 without SSE4.1 has no rounding instruction).
inline int FastFloor(float x) {
  const int i = int(x);
  return i - int(x < float(i));
}

inline float LogOdds(double p) { return float(std::log(p / (1.0 - p))); }

// Ray traces every point of the input into the 3D grid (eq. 18). A crossed cell in a layer
// touching [g - tol, g + tol] is left alone when the ray stays above g - tol in it, for g the
// known floor height of its column and for g the height h of the floor plane the ray ends on.
void UpdateOccupancy(const OccupancyParams& params, double floor_tolerance, const MapInput& input,
                     MapState* state);

// Highest occupancy log-odds in column (ix, iy) over the layers touching [z - tol, z + tol];
// -infinity if none of them lies in the grid.
float ColumnLogOddsNear(const MapState& state, int ix, int iy, double z, double tol);

// Verifies the floor map against the grid (eq. 20), then inserts the floor points (eq. 19, 21).
void UpdateFloorMap(const MapParams& params, const MapInput& input, MapState* state);

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_MAP_UPDATE_H_

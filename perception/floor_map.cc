// 2.5D floor height map (paper Section 5.3, eq. 19-21).
#include <algorithm>
#include <cmath>
#include <limits>

#include "perception/internal/map_update.h"
#include "perception/mapping.h"

namespace fognav::perception::internal {

float ColumnLogOddsNear(const MapState& state, int ix, int iy, double z, double tol) {
  const float inv_res = float(1.0 / state.window.resolution);
  const float zl = (float(z) - float(state.z_min)) * inv_res, tl = float(tol) * inv_res;
  const int lo = std::max(0, FastFloor(zl - tl));
  const int hi = std::min(state.size_z - 1, FastFloor(zl + tl));
  float best = -std::numeric_limits<float>::infinity();
  const float* column = state.log_odds.data() + size_t(state.window.Index(ix, iy)) * state.size_z;
  for (int iz = lo; iz <= hi; ++iz) best = std::max(best, column[iz]);
  return best;
}

void UpdateFloorMap(const MapParams& params, const MapInput& input, MapState* state) {
  MapState& s = *state;
  const float l_occ = LogOdds(params.grid.p_occ);
  const double tol = params.floor.verify_tolerance;
  const float gate = float(params.floor.gate);
  const float nu = float(params.floor.smoothing);
  constexpr float kNegInf = -std::numeric_limits<float>::infinity();

  // eq. (20): keep a floor height only while the grid still holds it (P_Floor > P_occ)
  for (int iy = 0; iy < s.window.size_y; ++iy) {
    for (int ix = 0; ix < s.window.size_x; ++ix) {
      float& f = s.floor[size_t(s.window.Index(ix, iy))];
      if (f != kNegInf && !(ColumnLogOddsNear(s, ix, iy, f, tol) > l_occ)) f = kNegInf;
    }
  }

  // eq. (19, 21): insert floor points that the grid confirms
  const float inv_res = float(1.0 / s.window.resolution);
  int last_ix = -1, last_iy = -1;
  float last_h = 0;
  bool last_ok = false;
  for (const LabelledPoint& lp : input.points) {
    if (!std::isfinite(lp.h) || !lp.p_G.allFinite()) continue;
    const int ix = FastFloor(lp.p_G.x() * inv_res) - s.window.origin_ix;
    const int iy = FastFloor(lp.p_G.y() * inv_res) - s.window.origin_iy;
    if (!s.window.Contains(ix, iy)) continue;
    // neighbouring pixels mostly share the cell and the plane: reuse the last check
    if (ix != last_ix || iy != last_iy || lp.h != last_h) {
      last_ix = ix;
      last_iy = iy;
      last_h = lp.h;
      last_ok = ColumnLogOddsNear(s, ix, iy, lp.h, tol) > l_occ;
    }
    if (!last_ok) continue;
    float& f = s.floor[size_t(s.window.Index(ix, iy))];
    if (lp.h < f - gate) continue;  // a lower surface under the floor already known
    if (lp.h > f + gate) {
      f = lp.h;  // a new or higher floor: only the highest is kept
    } else {
      f = nu * f + (1.0f - nu) * lp.h;
    }
  }
}

}  // namespace fognav::perception::internal

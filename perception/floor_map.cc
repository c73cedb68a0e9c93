// 2.5D floor height map (paper Section 5.3, eq. 19-21).
#include <algorithm>
#include <cmath>
#include <limits>

#include "perception/internal/map_update.h"
#include "perception/mapping.h"

namespace fognav::perception::internal {

void LayersNear(const MapState& state, double z, double tol, int* lo, int* hi) {
  const float inv_res = float(1.0 / state.window.resolution);
  const float tl = float(tol) * inv_res;
  // a height far outside the grid (any float) comes to just beyond its layers: the same empty
  // range, and a layer index that an int holds
  const float zl = std::clamp((float(z) - float(state.z_min)) * inv_res, -2.0f - tl,
                              float(state.size_z) + 1.0f + tl);
  *lo = std::max(0, FastFloor(zl - tl));
  *hi = std::min(state.size_z - 1, FastFloor(zl + tl));
}

float ColumnLogOddsNear(const MapState& state, int ix, int iy, double z, double tol) {
  int lo, hi;
  LayersNear(state, z, tol, &lo, &hi);
  float best = -std::numeric_limits<float>::infinity();
  const float* column = state.log_odds.data() + size_t(state.window.Index(ix, iy)) * state.size_z;
  for (int iz = lo; iz <= hi; ++iz) best = std::max(best, column[iz]);
  return best;
}

namespace {

// bits of MapState::floor_frame_marks besides kFloorVoted
constexpr uint8_t kConfirmed = 1, kLowerSeen = 2;
constexpr int kNoSlotYet = -2;  // VoteSlot not asked yet (it answers -1 for no slot left)

// The slot of the cell's votes of this frame that counts height h (its plane's), opened if
// new; -1 if the cell has no slot left (a fourth plane in one cell and frame, a few cells in
// a look-around).
int VoteSlot(float h, float h_sigma, int cell, MapState* state) {
  MapState::FloorVote& v = state->floor_votes[size_t(cell)];
  for (int k = 0; k < MapState::kFloorVotes; ++k) {
    if (v.count[k] == 0) {
      if (k == 0) state->floor_voted_cells.push_back(cell);
      v.h[k] = h;
      v.sigma[k] = h_sigma;
      return k;
    }
    if (v.h[k] == h) return k;
  }
  return -1;
}

// eq. (21) for a height h with sigma: within the gate the two are averaged by inverse variance;
// beyond it the more precise one wins, with the paper's preference for the higher floor
void FuseHeight(const FloorParams& p, float h, float h_sigma, size_t cell, MapState* state) {
  MapState& s = *state;
  float& f = s.floor[cell];
  float& var = s.floor_var[cell];
  const float min_var = float(p.min_sigma * p.min_sigma);
  const float var_h = std::max(h_sigma * h_sigma, min_var);
  if (f == -std::numeric_limits<float>::infinity()) {
    f = h;
    var = var_h;
    return;
  }
  const float var_f = var > 0 ? var : min_var;  // a height without sigma counts as precise
  const float gate = float(p.gate), ratio = float(p.replace_ratio);
  if (std::abs(h - f) <= gate) {
    const float w = var_f / (var_f + var_h);  // weight of the measurement
    f += w * (h - f);
    var = std::max(var_f * var_h / (var_f + var_h), min_var);
  } else if (h > f ? var_h <= ratio * var_f : var_h * ratio <= var_f) {
    f = h;  // a higher floor not much less precise, or a lower one much more precise
    var = var_h;
  }
}

}  // namespace

void UpdateFloorMap(const MapParams& params, const MapInput& input, MapState* state) {
  MapState& s = *state;
  const float l_occ = LogOdds(params.grid.p_occ);
  const double tol = params.floor.verify_tolerance;
  const float gate = float(params.floor.gate);
  const float nu = float(params.floor.smoothing);
  const float lower_doubt = float(params.floor.lower_doubt);
  constexpr float kNegInf = -std::numeric_limits<float>::infinity();

  // eq. (20): keep a floor height only while the grid still holds it (P_Floor > P_occ)
  for (int iy = 0; iy < s.window.size_y; ++iy) {
    for (int ix = 0; ix < s.window.size_x; ++ix) {
      float& f = s.floor[size_t(s.window.Index(ix, iy))];
      if (f != kNegInf && !(ColumnLogOddsNear(s, ix, iy, f, tol) > l_occ)) {
        f = kNegInf;
        s.floor_var[size_t(s.window.Index(ix, iy))] = 0;
      }
    }
  }

  // eq. (19, 21): insert floor points that the grid confirms. Points whose heights have a
  // sigma vote first; each cell then fuses once per frame each height it got, in the order
  // they came, minus the minor lower ones (FloorParams::minor_share).
  s.floor_votes.resize(s.floor.size());  // all empty: each update empties the cells it used
  s.floor_frame_marks.assign(s.floor.size(), 0);
  const float inv_res = float(1.0 / s.window.resolution);
  const float on_plane_sigmas = float(params.floor.on_plane_sigmas);
  const float on_plane_min = float(params.floor.on_plane_min);
  int last_ix = -1, last_iy = -1;
  float last_h = 0;
  bool last_ok = false;
  int last_slot = kNoSlotYet;  // the vote slot of (last_ix, last_iy, last_h)
  for (const LabelledPoint& lp : input.points) {
    // a height or spread no plane of a world within +-1000 m has would overflow the fusion
    if (!(std::abs(lp.h) < 1e3f) || !(lp.h_sigma >= 0 && lp.h_sigma < 1e3f) ||
        !lp.p_G.allFinite()) {
      continue;
    }
    // a point too far for an int cell index lies outside any window
    const float gx = lp.p_G.x() * inv_res, gy = lp.p_G.y() * inv_res;
    if (!(std::abs(gx) < 1e9f && std::abs(gy) < 1e9f)) continue;
    const int ix = FastFloor(gx) - s.window.origin_ix;
    const int iy = FastFloor(gy) - s.window.origin_iy;
    if (!s.window.Contains(ix, iy)) continue;
    // neighbouring pixels mostly share the cell and the plane: reuse the last check
    if (ix != last_ix || iy != last_iy || lp.h != last_h) {
      last_ix = ix;
      last_iy = iy;
      last_h = lp.h;
      last_ok = ColumnLogOddsNear(s, ix, iy, lp.h, tol) > l_occ;
      last_slot = kNoSlotYet;
    }
    if (!last_ok) continue;
    const int cell = s.window.Index(ix, iy);
    if (lp.h_sigma > 0) {
      if (on_plane_sigmas > 0 &&
          lp.p_G.z() - lp.h > std::max(on_plane_sigmas * lp.h_sigma, on_plane_min)) {
        continue;
      }
      if (last_slot == kNoSlotYet) last_slot = VoteSlot(lp.h, lp.h_sigma, cell, state);
      if (last_slot < 0) continue;
      MapState::FloorVote& v = s.floor_votes[size_t(cell)];
      if (v.count[last_slot] == UINT16_MAX) continue;
      ++v.count[last_slot];
      // in the middle half of the cell (for the doubt below)
      const float u = lp.p_G.x() * inv_res - float(ix + s.window.origin_ix);
      const float w = lp.p_G.y() * inv_res - float(iy + s.window.origin_iy);
      if (std::abs(u - 0.5f) < 0.25f && std::abs(w - 0.5f) < 0.25f) ++v.middle[last_slot];
      continue;
    }
    s.floor_frame_marks[size_t(cell)] |= kFloorVoted;
    float& f = s.floor[size_t(cell)];
    s.floor_var[size_t(cell)] = 0;
    if (lp.h < f - gate) continue;  // a lower surface under the floor already known
    if (lp.h > f + gate) {
      f = lp.h;  // a new or higher floor: only the highest is kept
    } else {
      f = nu * f + (1.0f - nu) * lp.h;
    }
  }
  const float minor_share = float(params.floor.minor_share);
  const float minor_range = float(params.floor.minor_range);
  for (int cell : s.floor_voted_cells) {
    MapState::FloorVote& v = s.floor_votes[size_t(cell)];
    for (int k = 0; k < MapState::kFloorVotes && v.count[k] > 0; ++k) {
      bool minor = false;
      for (int j = 0; j < MapState::kFloorVotes && v.count[j] > 0; ++j) {
        minor |= v.h[k] < v.h[j] && v.h[j] - v.h[k] <= minor_range &&
                 float(v.count[k]) < minor_share * float(v.count[j] + v.count[k]);
      }
      if (!minor) FuseHeight(params.floor, v.h[k], v.sigma[k], size_t(cell), state);
    }
    // what this frame says about the cell's height, for the doubt below: a lower floor counts
    // only in the middle half of the cell, so the lower side of a step edge does not doubt the
    // edge cell's higher floor
    const float f = s.floor[size_t(cell)];
    uint8_t& marks = s.floor_frame_marks[size_t(cell)];
    marks |= kFloorVoted;
    for (int k = 0; k < MapState::kFloorVotes && v.count[k] > 0; ++k) {
      if (std::abs(v.h[k] - f) <= gate) {
        marks |= kConfirmed;
      } else if (v.h[k] < f && f - v.h[k] <= lower_doubt && v.middle[k] > 0) {
        marks |= kLowerSeen;
      }
    }
    v = {};
  }
  s.floor_voted_cells.clear();

  // a height that this frame confirmed nowhere near the cell while it saw a lower floor in
  // it: doubt it (the higher floor of a step edge is confirmed in the cells along the edge)
  const GridWindow& w = s.window;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const size_t cell = size_t(w.Index(ix, iy));
      if ((s.floor_frame_marks[cell] & (kConfirmed | kLowerSeen)) != kLowerSeen) continue;
      bool confirmed_near = false;
      for (int jy = std::max(0, iy - 1); jy <= std::min(w.size_y - 1, iy + 1); ++jy) {
        for (int jx = std::max(0, ix - 1); jx <= std::min(w.size_x - 1, ix + 1); ++jx) {
          const size_t other = size_t(w.Index(jx, jy));
          confirmed_near |= (s.floor_frame_marks[other] & kConfirmed) != 0 &&
                            std::abs(s.floor[other] - s.floor[cell]) <= gate;
        }
      }
      // (heights without a sigma keep variance 0 and so are never doubted)
      if (!confirmed_near) s.floor_var[cell] *= 2;
    }
  }
}

}  // namespace fognav::perception::internal

namespace fognav::perception {

void FadeGrid(const MapParams& params, double keep, MapState* state) {
  MapState& s = *state;
  if (s.log_odds.empty()) return;  // never updated: its window has no cells yet
  for (int iy = 0; iy < s.window.size_y; ++iy) {
    for (int ix = 0; ix < s.window.size_x; ++ix) {
      const size_t cell = size_t(s.window.Index(ix, iy));
      const float f = s.floor[cell];
      int lo = s.size_z, hi = -1;  // the layers that hold the floor height (eq. 20): spared
      if (f != -std::numeric_limits<float>::infinity()) {
        internal::LayersNear(s, f, params.floor.verify_tolerance, &lo, &hi);
      }
      float* column = s.log_odds.data() + cell * size_t(s.size_z);
      for (int iz = 0; iz < s.size_z; ++iz) {
        if (iz < lo || iz > hi) column[iz] *= float(keep);
      }
    }
  }
}

}  // namespace fognav::perception

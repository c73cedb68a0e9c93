// Floor and Obstacle Grid from the 3D grid and the floor map (paper Section 5.4), and scores.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <vector>

#include "perception/internal/map_classify.h"
#include "perception/internal/map_update.h"
#include "perception/mapping.h"

namespace fognav::perception {

Fog ComputeFog(const MapParams& params, const MapState& state) {
  Fog fog(state.window);
  if (state.Empty()) return fog;
  const GridWindow& w = state.window;
  const float l_occ = internal::LogOdds(params.grid.p_occ);
  const float res = float(w.resolution), inv_res = 1.0f / res;
  const float z_min = float(state.z_min);
  const int nz = state.size_z;
  if (nz > 64) {
    std::fprintf(stderr, "fognav mapping: ComputeFog supports at most 64 layers, got %d\n", nz);
    std::abort();
  }
  // only reliable heights enter eq. (24): a height whose sigma exceeds max_height_sigma
  // (a cell seen only by far, noisy planes) is left out, so it marks no step in its neighbours
  const bool check_sigma =
      std::isfinite(params.fog.max_height_sigma) && state.floor_var.size() == state.floor.size();
  const float max_var = float(params.fog.max_height_sigma * params.fog.max_height_sigma);
  auto unreliable = [&](size_t i) { return check_sigma && state.floor_var[i] > max_var; };
  std::vector<float> reliable;
  const std::vector<float>* floor = &state.floor;
  if (check_sigma) {
    reliable = state.floor;
    for (size_t i = 0; i < reliable.size(); ++i)
      if (unreliable(i)) reliable[i] = -std::numeric_limits<float>::infinity();
    floor = &reliable;
  }
  std::vector<float> dh, highest;
  internal::FloorChange(w, *floor, params.fog.neighbourhood_radius, &dh, &highest);
  fog.headroom_seen.assign(fog.type.size(), 0);
  const float h_tunnel = float(params.fog.h_tunnel), h_robot = float(params.fog.h_robot);

  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      internal::CellQuantities q;
      q.f = state.floor[i];
      q.dh = dh[i];
      // eq. (22, 23): highest and lowest occupied layers above the floor, from a bit mask of
      // the occupied layers of the column
      float z_lo = internal::ObstacleThreshold(params.fog, q.f, highest[i]);
      // a cell without floor beside a known floor (the strip behind a step down that the eyes
      // cannot see): what lies no higher than the neighbouring floor + margin is no obstacle
      if (params.fog.ignore_low_unknown && q.f == -std::numeric_limits<float>::infinity() &&
          highest[i] != -std::numeric_limits<float>::infinity()) {
        z_lo = highest[i] + float(params.fog.obstacle_margin);
      }
      const float* column = state.log_odds.data() + i * nz;
      uint64_t occupied = 0;
      for (int iz = 0; iz < nz; ++iz) occupied |= uint64_t(column[iz] > l_occ) << iz;
      // layers whose bottom is at or above z_lo
      const int first = z_lo == -std::numeric_limits<float>::infinity()
                            ? 0
                            : std::clamp(-internal::FastFloor(-(z_lo - z_min) * inv_res + 1e-4f),
                                         0, 64);
      if (first < 64) occupied &= ~uint64_t(0) << first; else occupied = 0;
      if (occupied != 0) {
        const int lowest = __builtin_ctzll(occupied), top = 63 - __builtin_clzll(occupied);
        q.c = z_min + float(lowest) * res;
        q.o = z_min + float(top + 1) * res;
      }
      CellType t = internal::Classify(params.fog, q);
      // an unreliable height is no floor information yet: obstacles above it still count
      if (unreliable(i) && t != CellType::kObstacle && t != CellType::kTunnel) {
        t = CellType::kUnknown;
      }
      fog.type[i] = t;
      fog.height[i] = internal::FogHeight(t, q);
      // headroom: every layer overlapping [f + h_tunnel, f + h_robot) observed and free
      if (std::isfinite(q.f) && t != CellType::kObstacle && t != CellType::kTunnel) {
        const int lo = std::max(0, internal::FastFloor((q.f + h_tunnel - z_min) * inv_res));
        const int hi = std::min(nz, -internal::FastFloor(-(q.f + h_robot - z_min) * inv_res));
        bool seen = lo < hi;
        for (int iz = lo; iz < hi && seen; ++iz) seen = column[iz] < 0.0f;
        fog.headroom_seen[i] = seen;
      }
    }
  }
  if (params.fog.require_known_neighbourhood) {
    // unknown cells (and places beyond the window) in U and in U grown by one cell
    const std::vector<CellType> first = fog.type;
    const int r = params.fog.neighbourhood_radius, outer = r + 1;
    auto unknown = [&](int jx, int jy) {
      return !w.Contains(jx, jy) || first[size_t(w.Index(jx, jy))] == CellType::kUnknown;
    };
    for (int iy = 0; iy < w.size_y; ++iy) {
      for (int ix = 0; ix < w.size_x; ++ix) {
        const size_t i = size_t(w.Index(ix, iy));
        if (first[i] != CellType::kFloor && first[i] != CellType::kStairs) continue;
        int in_u = 0, around = 0;
        for (int jy = iy - outer; jy <= iy + outer; ++jy) {
          for (int jx = ix - outer; jx <= ix + outer; ++jx) {
            if (!unknown(jx, jy)) continue;
            ++around;
            in_u += std::abs(jx - ix) <= r && std::abs(jy - iy) <= r;
          }
        }
        if (in_u == 0 || around < params.fog.min_unknown_around) continue;
        fog.type[i] = CellType::kUnknown;
        fog.height[i] = -std::numeric_limits<float>::infinity();
      }
    }
  }
  return fog;
}

FogScore ScoreFog(const Fog& estimate, const Fog& truth) {
  FogScore score;
  std::vector<double> errors;
  const GridWindow& we = estimate.window;
  const GridWindow& wt = truth.window;
  auto is_floor = [](CellType t) { return t == CellType::kFloor || t == CellType::kStairs; };
  for (int iy = 0; iy < we.size_y; ++iy) {
    for (int ix = 0; ix < we.size_x; ++ix) {
      const int tx = we.origin_ix + ix - wt.origin_ix;
      const int ty = we.origin_iy + iy - wt.origin_iy;
      if (!wt.Contains(tx, ty)) continue;
      const CellType e = estimate.TypeAt(ix, iy);
      const CellType t = truth.TypeAt(tx, ty);
      ++score.confusion[int(t)][int(e)];
      if (e == CellType::kUnknown) continue;
      ++score.observed;
      if (e == t) ++score.correct;
      const float he = estimate.HeightAt(ix, iy), ht = truth.HeightAt(tx, ty);
      if (is_floor(e) && is_floor(t) && std::isfinite(he) && std::isfinite(ht)) {
        errors.push_back(std::abs(double(he) - double(ht)));
      }
    }
  }
  score.accuracy = score.observed > 0 ? double(score.correct) / score.observed : 0.0;
  score.height_cells = int(errors.size());
  if (!errors.empty()) {
    score.height_error_max = *std::max_element(errors.begin(), errors.end());
    auto mid = errors.begin() + errors.size() / 2;
    std::nth_element(errors.begin(), mid, errors.end());
    score.height_error_median = *mid;
  }
  return score;
}

}  // namespace fognav::perception

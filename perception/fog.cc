// Floor and Obstacle Grid from the 3D grid and the floor map (paper Section 5.4), and scores.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "perception/internal/map_classify.h"
#include "perception/internal/map_update.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();

// The bit mask of a column's layers whose log-odds exceed l (nz <= 64); four at a time where
// SSE2 is there (every x86-64).
uint64_t LayersAbove(const float* column, int nz, float l) {
  uint64_t mask = 0;
  int iz = 0;
#if defined(__SSE2__)
  const __m128 threshold = _mm_set1_ps(l);
  for (; iz + 4 <= nz; iz += 4) {
    const int four = _mm_movemask_ps(_mm_cmpgt_ps(_mm_loadu_ps(column + iz), threshold));
    mask |= uint64_t(four) << iz;
  }
#endif
  for (; iz < nz; ++iz) mask |= uint64_t(column[iz] > l) << iz;
  return mask;
}

// FogParams::infer_tops: per cell the floor height inferred from the grid for a top that no
// plane covered, -infinity elsewhere. `highest` is the highest known floor in U(x, y),
// `occupied` the bit mask of each column's occupied layers.
std::vector<float> InferTops(const MapParams& params, const MapState& state,
                             const std::vector<float>& highest,
                             const std::vector<uint64_t>& occupied) {
  const GridWindow& w = state.window;
  const FogParams& p = params.fog;
  const int nz = state.size_z;
  const float res = float(w.resolution), z_min = float(state.z_min);
  const float l_free = -internal::LogOdds(params.grid.p_occ);
  std::vector<int> top(size_t(w.NumCells()), -1);  // highest occupied layer of a candidate
  for (size_t i = 0; i < top.size(); ++i) {
    // the floor the solid stands on: the cell's own or its neighbours'
    const float base = std::max(state.floor[i], highest[i]);
    if (base == kNegInf || occupied[i] == 0) continue;
    // the highest occupied layer; above the grid's top layer nothing is known
    const int k = 63 - __builtin_clzll(occupied[i]);
    if (k == nz - 1) continue;
    const float z_top = z_min + float(k + 1) * res;
    if (z_top > float(p.camera_height) || z_top - res - base <= float(p.h_stairs)) continue;
    // a solid from the floor up: no layer between them seen free (a table's top is no top:
    // free space lies under it)
    const int first =
        std::max(0, internal::FastFloor((base + float(p.obstacle_margin) - z_min) / res));
    const float* column = state.log_odds.data() + i * size_t(nz);
    bool solid = true;
    for (int iz = first; iz < k && solid; ++iz) solid = !(column[iz] < l_free);
    if (solid) top[i] = k;
  }
  std::vector<float> out(top.size(), kNegInf);
  std::vector<int> patch_of(top.size(), -1);  // the seed of the patch holding the cell
  std::vector<int> patch, open;
  for (int seed = 0; seed < int(top.size()); ++seed) {
    if (top[size_t(seed)] < 0 || patch_of[size_t(seed)] >= 0) continue;
    patch.clear();
    open.assign(1, seed);
    patch_of[size_t(seed)] = seed;
    while (!open.empty()) {
      const int c = open.back();
      open.pop_back();
      patch.push_back(c);
      const int cx = c % w.size_x, cy = c / w.size_x;
      for (int jy = cy - 1; jy <= cy + 1; ++jy) {
        for (int jx = cx - 1; jx <= cx + 1; ++jx) {
          if (!w.Contains(jx, jy)) continue;
          const int j = w.Index(jx, jy);
          if (top[size_t(j)] < 0 || patch_of[size_t(j)] >= 0 ||
              std::abs(top[size_t(j)] - top[size_t(c)]) > 1) {
            continue;
          }
          patch_of[size_t(j)] = seed;
          open.push_back(j);
        }
      }
    }
    // its extents from the spread of the cell centres, as LabelPoints measures planes
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (int c : patch) {
      const double x = (c % w.size_x) * w.resolution, y = (c / w.size_x) * w.resolution;
      sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
    }
    const Eigen::Vector2d extents = internal::Extents(double(patch.size()), sx, sy, sxx, syy, sxy);
    // flat: its tops span at most two layers, the band; a rough top (posts of several heights)
    // is an obstacle, as in the ground truth. A thin top may have a lower rim
    // (FogParams::top_band_share); a patch's layers have no gaps (neighbours differ by one).
    int count[64] = {0};
    int k_hi = 0;
    for (int c : patch) {
      ++count[top[size_t(c)]];
      k_hi = std::max(k_hi, top[size_t(c)]);
    }
    const int k_lo = k_hi > 0 && count[k_hi - 1] > 0 ? k_hi - 1 : k_hi;
    const int in_band = count[k_hi] + (k_lo < k_hi ? count[k_lo] : 0);
    if (in_band < int(patch.size())) {
      if (in_band < p.top_band_share * double(patch.size()) ||
          extents(1) > p.top_band_max_width) {
        continue;
      }
      // every cell below the band has a neighbour outside the patch
      const bool rim_only = std::all_of(patch.begin(), patch.end(), [&](int c) {
        if (top[size_t(c)] >= k_lo) return true;
        const int cx = c % w.size_x, cy = c / w.size_x;
        for (int jy = cy - 1; jy <= cy + 1; ++jy) {
          for (int jx = cx - 1; jx <= cx + 1; ++jx) {
            if (!w.Contains(jx, jy) || patch_of[size_t(w.Index(jx, jy))] != seed) return true;
          }
        }
        return false;
      });
      if (!rim_only) continue;  // the top: the band and its lower rim, whose faces reach it unseen
    }
    // a sole large
    if (extents(0) < p.min_floor_length || extents(1) < p.min_floor_width) continue;
    // one height for the flat top: the middle of its layer, or the boundary of its two
    const float h = z_min + (float(k_lo) + (k_hi > k_lo ? 1.0f : 0.5f)) * res;
    for (int c : patch) out[size_t(c)] = h;
  }
  return out;
}

// FogParams::ceiling_gap: floor cells of unseen headroom between tunnel cells whose ceilings lie
// within one layer of each other become tunnel under the lower of the two ceilings.
void FillCeilingGaps(int gap, Fog* fog) {
  const GridWindow& w = fog->window;
  const float layer = float(w.resolution) * 1.001f;
  // the nearest tunnel cell from (ix, iy) along (dx, dy) across floor cells only: its ceiling
  // and its distance in steps; no ceiling (-infinity) if there is none within `gap` steps
  struct Hit {
    float ceiling = kNegInf;
    int steps = 0;
  };
  auto nearest = [&](int ix, int iy, int dx, int dy) {
    for (int k = 1; k <= gap; ++k) {
      const int jx = ix + k * dx, jy = iy + k * dy;
      if (!w.Contains(jx, jy)) break;
      const size_t j = size_t(w.Index(jx, jy));
      if (fog->type[j] == CellType::kTunnel) return Hit{fog->ceiling[j], k};
      if (fog->type[j] != CellType::kFloor) break;
    }
    return Hit{};
  };
  // a cell between two tunnel cells lies inside their bounding box
  int x0 = w.size_x, y0 = w.size_y, x1 = -1, y1 = -1;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      if (fog->type[size_t(w.Index(ix, iy))] != CellType::kTunnel) continue;
      x0 = std::min(x0, ix), x1 = std::max(x1, ix), y0 = std::min(y0, iy), y1 = std::max(y1, iy);
    }
  }
  constexpr int kAxes[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  std::vector<std::pair<size_t, float>> filled;
  for (int iy = y0; iy <= y1; ++iy) {
    for (int ix = x0; ix <= x1; ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      if (fog->type[i] != CellType::kFloor || fog->headroom_seen[i]) continue;
      for (const auto& a : kAxes) {
        const Hit h0 = nearest(ix, iy, a[0], a[1]), h1 = nearest(ix, iy, -a[0], -a[1]);
        // the floor cells between the two tunnel cells: h0.steps + h1.steps - 1
        if (h0.ceiling != kNegInf && h1.ceiling != kNegInf &&
            std::abs(h0.ceiling - h1.ceiling) <= layer && h0.steps + h1.steps - 1 <= gap) {
          filled.emplace_back(i, std::min(h0.ceiling, h1.ceiling));
          break;
        }
      }
    }
  }
  // the heights stay the floor's (eq. 25)
  for (const auto& [i, c] : filled) {
    fog->type[i] = CellType::kTunnel;
    fog->ceiling[i] = c;
  }
}

}  // namespace

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
  if (params.fog.neighbourhood_radius < 0) {
    std::fprintf(stderr, "fognav mapping: FogParams::neighbourhood_radius must not be negative\n");
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
  // bit mask of the occupied layers of each column
  std::vector<uint64_t> occupied(fog.type.size(), 0);
  for (size_t i = 0; i < occupied.size(); ++i) {
    occupied[i] = LayersAbove(state.log_odds.data() + i * nz, nz, l_occ);
  }
  // inferred tops enter eq. (24) for every cell; the obstacle threshold keeps `highest`
  std::vector<float> tops;
  if (params.fog.infer_tops) {
    tops = InferTops(params, state, highest, occupied);
    if (std::any_of(tops.begin(), tops.end(), [](float t) { return t != kNegInf; })) {
      std::vector<float> with_tops = *floor, unused;
      for (size_t i = 0; i < tops.size(); ++i) {
        if (tops[i] != kNegInf) with_tops[i] = tops[i];
      }
      internal::FloorChange(w, with_tops, params.fog.neighbourhood_radius, &dh, &unused);
    } else {
      tops.clear();
    }
  }
  fog.headroom_seen.assign(fog.type.size(), 0);
  fog.ceiling.assign(fog.type.size(), kNegInf);
  const float h_tunnel = float(params.fog.h_tunnel), h_robot = float(params.fog.h_robot);
  const int no_floor_frames =
      state.no_floor_frames.size() == fog.type.size() ? params.no_floor.min_frames : 0;

  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      const float* column = state.log_odds.data() + i * nz;
      // eq. (22, 23): highest and lowest occupied layers above the floor f, from the column's
      // bit mask
      auto quantities = [&](float f) {
        internal::CellQuantities q;
        q.f = f;
        q.dh = dh[i];
        float z_lo = internal::ObstacleThreshold(params.fog, q.f, highest[i]);
        // a cell without floor beside a known floor (the strip behind a step down that the eyes
        // cannot see): what lies no higher than the neighbouring floor + margin is no obstacle
        if (params.fog.ignore_low_unknown && q.f == kNegInf && highest[i] != kNegInf) {
          z_lo = highest[i] + float(params.fog.obstacle_margin);
        }
        // layers whose bottom is at or above z_lo
        const int first =
            z_lo == kNegInf
                ? 0
                : std::clamp(-internal::FastFloor(-(z_lo - z_min) * inv_res + 1e-4f), 0, 64);
        const uint64_t above = first < 64 ? occupied[i] & (~uint64_t(0) << first) : 0;
        if (above != 0) {
          const int lowest = __builtin_ctzll(above), top = 63 - __builtin_clzll(above);
          q.c = z_min + float(lowest) * res;
          q.o = z_min + float(top + 1) * res;
        }
        return q;
      };
      internal::CellQuantities q = quantities(state.floor[i]);
      CellType t = internal::Classify(params.fog, q);
      if (!tops.empty() && tops[i] != kNegInf) {
        // an inferred top makes its cell border, or floor amid tops of its own layer; its
        // height is too rough to tell stairs
        const internal::CellQuantities q_top = quantities(tops[i]);
        const CellType t_top = internal::Classify(params.fog, q_top);
        if (t_top == CellType::kBorder || t_top == CellType::kFloor) {
          q = q_top;
          t = t_top;
        }
      }
      // an unreliable height is no floor information yet: obstacles above it still count
      if (unreliable(i) && t != CellType::kObstacle && t != CellType::kTunnel) {
        t = CellType::kUnknown;
      }
      // no floor where the eyes would have seen one (VoidParams): border without a height
      if (t == CellType::kUnknown && no_floor_frames > 0 && q.f == kNegInf && occupied[i] == 0 &&
          state.no_floor_frames[i] >= no_floor_frames) {
        t = CellType::kBorder;
      }
      fog.type[i] = t;
      fog.height[i] = internal::FogHeight(t, q);
      if (t == CellType::kTunnel) fog.ceiling[i] = q.c;
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
  if (params.fog.ceiling_gap > 0) FillCeilingGaps(params.fog.ceiling_gap, &fog);
  if (params.fog.require_known_neighbourhood) {
    // unknown cells (and places beyond the window) in U and in U grown by one cell, counted
    // from a summed-area table of the window padded by `outer` unknown cells on every side
    const int r = params.fog.neighbourhood_radius, outer = r + 1;
    cv::Mat1b unknown(w.size_y, w.size_x);
    for (int iy = 0; iy < w.size_y; ++iy) {
      for (int ix = 0; ix < w.size_x; ++ix) {
        unknown(iy, ix) = fog.type[size_t(w.Index(ix, iy))] == CellType::kUnknown;
      }
    }
    cv::Mat1b padded;
    cv::copyMakeBorder(unknown, padded, outer, outer, outer, outer, cv::BORDER_CONSTANT, 1);
    cv::Mat1i sum;  // sum(y, x): the unknown padded cells in rows before y, columns before x
    cv::integral(padded, sum, CV_32S);
    // unknown cells in the square of half-width h around window cell (ix, iy)
    auto count = [&](int ix, int iy, int h) {
      const int x0 = ix + outer - h, x1 = ix + outer + h + 1;
      const int y0 = iy + outer - h, y1 = iy + outer + h + 1;
      return sum(y1, x1) - sum(y0, x1) - sum(y1, x0) + sum(y0, x0);
    };
    for (int iy = 0; iy < w.size_y; ++iy) {
      for (int ix = 0; ix < w.size_x; ++ix) {
        const size_t i = size_t(w.Index(ix, iy));
        if (fog.type[i] != CellType::kFloor && fog.type[i] != CellType::kStairs) continue;
        const int in_u = count(ix, iy, r), around = count(ix, iy, outer);
        if (in_u == 0 || around < params.fog.min_unknown_around) continue;
        fog.type[i] = CellType::kUnknown;
        fog.height[i] = -std::numeric_limits<float>::infinity();
      }
    }
  }
  return fog;
}

}  // namespace fognav::perception

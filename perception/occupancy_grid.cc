// 3D occupancy grid update by ray tracing (paper Section 5.2, eq. 18).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "perception/internal/map_update.h"
#include "perception/mapping.h"

namespace fognav::perception::internal {
namespace {

constexpr uint8_t kMarkHit = 2;
constexpr uint8_t kMarkTraced = 4;  // a ray to this end cell was traced this frame
constexpr uint8_t kHitCountStep = 8;  // bits 3-7 count the points ending in the cell (up to 31)
constexpr float kInf = std::numeric_limits<float>::infinity();

// Clips the segment a + t (b - a), t in [0, 1], to the box [0, n) per axis; false if it misses.
bool ClipToBox(const Eigen::Vector3f& a, const Eigen::Vector3f& d, const Eigen::Vector3f& n,
               float* t0, float* t1) {
  float lo = 0.0f, hi = 1.0f;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12f) {
      if (a[k] < 0.0f || a[k] >= n[k]) return false;
      continue;
    }
    float ta = (0.0f - a[k]) / d[k];
    float tb = (n[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    lo = std::max(lo, ta);
    hi = std::min(hi, tb);
    if (lo > hi) return false;
  }
  *t0 = lo;
  *t1 = hi;
  return true;
}

// The bit mask of layers lo..hi, 0 <= lo <= hi < 64.
inline uint64_t LayerSpan(int lo, int hi) {
  return (~uint64_t(0) >> (63 - hi)) & (~uint64_t(0) << lo);
}

// A height g (layer units) that rays leave unmarked within tol: layer iz is spared where
// iz <= g + tol and the ray's lowest height in the layer exceeds g - tol. Above a ray's lowest
// layer that height is iz itself, so those layers are a fixed mask, iz in (g - tol, g + tol].
uint64_t SparedLayers(float g, float tol, int nz) {
  if (!std::isfinite(g)) return 0;
  const int lo = std::max(FastFloor(std::clamp(g - tol, -2.0f, 66.0f)) + 1, 0);
  const int hi = std::min(FastFloor(std::clamp(g + tol, -2.0f, 66.0f)), nz - 1);
  return lo <= hi ? LayerSpan(lo, hi) : 0;
}

// Whether height g spares a ray's lowest layer lo, which the ray enters at height z_lo.
inline bool SparesLowest(float g, float tol, int lo, float z_lo) {
  return float(lo) <= g + tol && z_lo > g - tol;
}

// Whether any of the n marks is set.
inline bool AnyMark(const uint8_t* m, int n) {
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    uint64_t block;
    std::memcpy(&block, m + i, 8);
    if (block != 0) return true;
  }
  for (; i < n; ++i) {
    if (m[i] != 0) return true;
  }
  return false;
}

}  // namespace

void UpdateOccupancy(const OccupancyParams& params, double floor_tolerance, const MapInput& input,
                     MapState* state) {
  MapState& s = *state;
  const int nx = s.window.size_x, ny = s.window.size_y, nz = s.size_z;
  const float inv_res = float(1.0 / s.window.resolution);
  // local continuous coordinates: cell (ix, iy, iz) is the unit cube at (ix, iy, iz)
  const Eigen::Vector3d origin(s.window.origin_ix * s.window.resolution,
                               s.window.origin_iy * s.window.resolution, s.z_min);
  const Eigen::Vector3f a = ((input.p_GC - origin) * double(inv_res)).cast<float>();
  const Eigen::Vector3f n_box(static_cast<float>(nx), static_cast<float>(ny), static_cast<float>(nz));
  const Eigen::Vector3f o_f = origin.cast<float>();
  uint8_t* marks = s.marks.data();
  uint64_t* crossed = s.crossed.data();
  if (!a.allFinite()) return;
  // known floor heights in layer units, and the layers each spares
  const float tol_local = float(floor_tolerance) * inv_res;
  std::vector<float>& floor_local = s.floor_local;
  floor_local.resize(s.floor.size());
  s.floor_layers.resize(s.floor.size());
  for (size_t i = 0; i < s.floor.size(); ++i) {
    floor_local[i] = (s.floor[i] - float(s.z_min)) * inv_res;
    s.floor_layers[i] = SparedLayers(floor_local[i], tol_local, nz);
  }
  const uint64_t* floor_layers = s.floor_layers.data();

  const bool overrule = params.overrule_ratio > 0;
  // whether height z (layer units) in column c lies off its floor: more than the tolerance
  // from a known floor, else above the two layers a floor up to h_stairs high may fill
  auto off_floor = [&](size_t c, float z) {
    const float f = floor_local[c];
    return std::isfinite(f) ? std::abs(z - f) > tol_local + 0.5f : z >= 2.0f;
  };
  const size_t columns = size_t(nx) * size_t(ny);
  if (overrule) s.free_range.assign(columns, kInf);
  const float res = float(s.window.resolution);
  const Eigen::Vector3f p_GC = input.p_GC.cast<float>();

  for (const LabelledPoint& lp : input.points) {
    if (!lp.p_G.allFinite()) continue;
    const Eigen::Vector3f b = (lp.p_G - o_f) * inv_res;
    const bool end_inside = b.x() >= 0.0f && b.y() >= 0.0f && b.z() >= 0.0f &&
                            b.x() < n_box.x() && b.y() < n_box.y() && b.z() < n_box.z();
    if (end_inside) {
      // (non-negative: truncation floors)
      const size_t c = size_t(int(b.y()) * nx + int(b.x()));
      // obstacle evidence: a point off the column's floor (a raised top's face lies below it)
      if (off_floor(c, b.z())) {
        s.obstacle_range[c] = std::min(s.obstacle_range[c], (lp.p_G - p_GC).norm());
      }
      // one traced ray per end cell (the first point's): rays to one 4 cm cell cross the same
      // cells
      uint8_t& end_mark = marks[c * size_t(nz) + size_t(b.z())];
      end_mark |= kMarkHit;
      if (end_mark / kHitCountStep < 31) end_mark += kHitCountStep;
      if (params.one_ray_per_end_cell) {
        if (end_mark & kMarkTraced) continue;
        end_mark |= kMarkTraced;
      }
    }
    const Eigen::Vector3f d = b - a;
    float t0, t1;
    if (!ClipToBox(a, d, n_box, &t0, &t1)) continue;
    const Eigen::Vector3f s0 = a + t0 * d;
    const Eigen::Vector3f e0 = end_inside ? b : Eigen::Vector3f(a + t1 * d);
    // a ray too short or too long for floats to clip (a point at the camera) traces nothing
    if (!s0.allFinite() || !e0.allFinite()) continue;
    const int ez = std::clamp(FastFloor(e0.z()), 0, nz - 1);
    if (!end_inside && params.one_ray_per_end_cell) {
      // rays leaving the grid: one per exit cell
      const int ex = std::clamp(FastFloor(e0.x()), 0, nx - 1);
      const int ey = std::clamp(FastFloor(e0.y()), 0, ny - 1);
      uint8_t& exit_mark = marks[size_t(ey * nx + ex) * nz + ez];
      if (exit_mark & kMarkTraced) continue;
      exit_mark |= kMarkTraced;
    }
    const int ex = std::clamp(FastFloor(e0.x()), 0, nx - 1);
    const int ey = std::clamp(FastFloor(e0.y()), 0, ny - 1);

    // Amanatides-Woo over the x-y columns; within a column the ray spans the layers between its
    // entry and exit heights, which is the same cell set as the 3D traversal
    int cx = std::clamp(FastFloor(s0.x()), 0, nx - 1);
    int cy = std::clamp(FastFloor(s0.y()), 0, ny - 1);
    const int step_x = d.x() > 0.0f ? 1 : -1, step_y = d.y() > 0.0f ? 1 : -1;
    int rem_x = std::max(0, (ex - cx) * step_x), rem_y = std::max(0, (ey - cy) * step_y);
    float tx = rem_x > 0 ? (float(cx + (step_x > 0)) - a.x()) / d.x() : kInf;
    float ty = rem_y > 0 ? (float(cy + (step_y > 0)) - a.y()) / d.y() : kInf;
    const float dtx = rem_x > 0 ? 1.0f / std::abs(d.x()) : 0.0f;
    const float dty = rem_y > 0 ? 1.0f / std::abs(d.y()) : 0.0f;
    const int dcol_x = step_x, dcol_y = step_y * nx;
    int col = cy * nx + cx;
    const float az = a.z(), dz = d.z();

    // marks the layers the ray spans in column `col` between ray parameters ta and tb; a layer
    // touching a floor height g +- tol stays untouched where the ray runs above g - tol in it (the
    // layer is only partly free then, and a floor in it stays). g is the column's known floor
    // and the height of the floor plane the ray ends on: grazing rays to a floor run inside the
    // layer of that floor for a while before they reach it.
    const float h_end = (lp.h - float(s.z_min)) * inv_res;
    const uint64_t end_layers = SparedLayers(h_end, tol_local, nz);
    const float metres_per_t = d.norm() * res;
    auto mark_column = [&](float ta, float tb, int hit_layer) {
      if (overrule && hit_layer < 0) {
        float& range = s.free_range[size_t(col)];
        range = std::min(range, ta * metres_per_t);
      }
      const float za = az + ta * dz, zb = az + tb * dz;
      const float z_low = std::min(za, zb);
      const int lo = std::clamp(int(z_low), 0, nz - 1);
      const int hi = std::clamp(int(std::max(za, zb)), 0, nz - 1);
      const float f = floor_local[col];
      const uint64_t lo_bit = uint64_t(1) << lo;
      const float z_lo = std::max(z_low, float(lo));
      uint64_t spared = (floor_layers[col] | end_layers) & ~lo_bit;
      if (SparesLowest(f, tol_local, lo, z_lo) || SparesLowest(h_end, tol_local, lo, z_lo)) {
        spared |= lo_bit;
      }
      // the end cell is a hit (marked with its point above), never crossed
      if (hit_layer >= 0) spared |= uint64_t(1) << hit_layer;
      crossed[col] |= LayerSpan(lo, hi) & ~spared;
    };
    float t_enter = t0;
    for (int n = rem_x + rem_y; n > 0; --n) {
      const bool along_x = tx < ty;
      const float t_exit = along_x ? tx : ty;
      mark_column(t_enter, t_exit, -1);
      t_enter = t_exit;
      // branch-free step: the axis is unpredictable
      col += along_x ? dcol_x : dcol_y;
      rem_x -= int(along_x);
      rem_y -= int(!along_x);
      const float tx_next = rem_x == 0 ? kInf : tx + dtx;
      const float ty_next = rem_y == 0 ? kInf : ty + dty;
      tx = along_x ? tx_next : tx;
      ty = along_x ? ty : ty_next;
    }
    mark_column(t_enter, t1, end_inside ? ez : -1);
  }

  // eq. (18) in log-odds: l += log(P(p|c) / P(p|!c)), once per cell and frame
  const float l_hit = LogOdds(params.p_hit), l_miss = LogOdds(params.p_miss);
  const float l_min = LogOdds(params.p_min), l_max = LogOdds(params.p_max);
  const int min_hits = std::max(1, params.min_hits_per_frame);
  if (overrule) {
    // a near miss overrules obstacle evidence seen only from afar: the cell starts afresh
    const float ratio = float(params.overrule_ratio);
    const int below =
        std::clamp(int(std::ceil((params.overrule_below - s.z_min) / s.window.resolution)), 0, nz);
    for (size_t c = 0; c < columns; ++c) {
      if (!(s.free_range[c] * ratio <= s.obstacle_range[c])) continue;
      for (int iz = 0; iz < below; ++iz) {
        const size_t i = c * size_t(nz) + size_t(iz);
        const uint8_t m = marks[i];
        const bool hit = (m & kMarkHit) && (m / kHitCountStep) >= min_hits;
        if (((crossed[c] >> iz) & 1) && !hit && s.log_odds[i] > 0 &&
            off_floor(c, float(iz) + 0.5f)) {
          s.log_odds[i] = 0;
        }
      }
    }
  }
  // per cell: a hit if at least min_hits points ended in it, else a miss if a ray crossed it;
  // the frame's marks are cleared
  for (size_t c = 0; c < columns; ++c) {
    const uint64_t free = crossed[c];
    uint8_t* mark = marks + c * size_t(nz);
    if (free == 0 && !AnyMark(mark, nz)) continue;
    crossed[c] = 0;
    float* l = s.log_odds.data() + c * size_t(nz);
    for (int iz = 0; iz < nz; ++iz) {
      const uint8_t m = mark[iz];
      const bool was_crossed = (free >> iz) & 1;
      if (m == 0 && !was_crossed) continue;
      mark[iz] = 0;
      const bool hit = (m & kMarkHit) && (m / kHitCountStep) >= min_hits;
      if (!hit && !was_crossed) continue;
      l[iz] = std::clamp(l[iz] + (hit ? l_hit : l_miss), l_min, l_max);
    }
  }
}

}  // namespace fognav::perception::internal

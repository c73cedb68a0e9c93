// Ground-truth FOG: the paper's classification applied to exact box geometry (DESIGN.md,
// "Ground truth"; the sampling rule is documented at GroundTruthFog in mapping.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "perception/internal/map_classify.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();
constexpr double kMaxFloorTiltDeg = 10.0;
constexpr double kExposedEps = 1e-4;  // metres above a top that must be free for it to be floor

// A solid prepared for vertical-line queries.
struct Solid {
  Eigen::Matrix3d R_BG;
  Eigen::Vector3d p_BG;
  Eigen::Vector3d half;
  Eigen::Vector2d lo_xy, hi_xy;  // footprint bounding box in the grid frame
  bool floor_candidate = false;

  // The z interval where the vertical line at (x, y) is inside the box; false if none.
  bool Vertical(double x, double y, double* lo, double* hi) const {
    const Eigen::Vector3d q0 = R_BG * Eigen::Vector3d(x, y, 0.0) + p_BG;
    const Eigen::Vector3d u = R_BG.col(2);
    double a = -std::numeric_limits<double>::infinity();
    double b = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (std::abs(u[k]) < 1e-12) {
        if (std::abs(q0[k]) > half[k]) return false;
        continue;
      }
      double t1 = (-half[k] - q0[k]) / u[k];
      double t2 = (half[k] - q0[k]) / u[k];
      if (t1 > t2) std::swap(t1, t2);
      a = std::max(a, t1);
      b = std::min(b, t2);
    }
    if (a > b) return false;
    *lo = a;
    *hi = b;
    return true;
  }
};

Solid Prepare(const OrientedBox& box, const FogParams& p) {
  Solid s;
  const Eigen::Isometry3d X_BG = box.X_FB.inverse();
  s.R_BG = X_BG.linear();
  s.p_BG = X_BG.translation();
  s.half = box.half_size;
  const Eigen::Matrix3d R_GB = box.X_FB.linear();
  const Eigen::Vector3d c = box.X_FB.translation();
  const Eigen::Vector3d reach = R_GB.cwiseAbs() * box.half_size;
  s.lo_xy = c.head<2>() - reach.head<2>();
  s.hi_xy = c.head<2>() + reach.head<2>();
  // floor candidate: one box axis near vertical, its top face a sole large and below the eyes
  for (int k = 0; k < 3; ++k) {
    if (std::abs(R_GB(2, k)) < std::cos(kMaxFloorTiltDeg * M_PI / 180.0)) continue;
    const double a = 2.0 * box.half_size[(k + 1) % 3], b = 2.0 * box.half_size[(k + 2) % 3];
    const double top = c.z() + reach.z();
    s.floor_candidate = std::max(a, b) >= p.min_floor_length &&
                        std::min(a, b) >= p.min_floor_width && top <= p.camera_height;
  }
  return s;
}

struct Interval {
  double lo, hi;
  bool candidate;
};

}  // namespace

Fog GroundTruthFog(const std::vector<OrientedBox>& solids_G, const GridWindow& window,
                   const FogParams& params) {
  Fog fog(window);
  std::vector<Solid> solids;
  solids.reserve(solids_G.size());
  for (const OrientedBox& box : solids_G) solids.push_back(Prepare(box, params));
  const int ns = std::max(1, params.truth_samples);
  const double res = window.resolution;

  // per cell, the vertical intervals at each sample; the floor map from exposed candidate tops
  std::vector<std::vector<Interval>> samples(size_t(window.NumCells()) * ns * ns);
  std::vector<float> floor(size_t(window.NumCells()), kNegInf);
  std::vector<const Solid*> near;
  for (int iy = 0; iy < window.size_y; ++iy) {
    for (int ix = 0; ix < window.size_x; ++ix) {
      const double x0 = (window.origin_ix + ix) * res, y0 = (window.origin_iy + iy) * res;
      near.clear();
      for (const Solid& s : solids) {
        if (s.hi_xy.x() < x0 || s.lo_xy.x() > x0 + res || s.hi_xy.y() < y0 ||
            s.lo_xy.y() > y0 + res) {
          continue;
        }
        near.push_back(&s);
      }
      const size_t cell = size_t(window.Index(ix, iy));
      float& f = floor[cell];
      for (int sy = 0; sy < ns; ++sy) {
        for (int sx = 0; sx < ns; ++sx) {
          const double x = x0 + (sx + 0.5) * res / ns, y = y0 + (sy + 0.5) * res / ns;
          std::vector<Interval>& iv = samples[(cell * ns + sy) * ns + sx];
          for (const Solid* s : near) {
            double lo, hi;
            if (s->Vertical(x, y, &lo, &hi)) iv.push_back({lo, hi, s->floor_candidate});
          }
          for (const Interval& a : iv) {
            if (!a.candidate) continue;
            const double above = a.hi + kExposedEps;
            const bool covered = std::any_of(iv.begin(), iv.end(), [&](const Interval& b) {
              return b.lo <= above && above < b.hi;
            });
            if (!covered) f = std::max(f, float(a.hi));
          }
        }
      }
    }
  }

  // eq. (22-25) on the exact solids
  std::vector<float> dh, highest;
  internal::FloorChange(window, floor, params.neighbourhood_radius, &dh, &highest);
  for (int iy = 0; iy < window.size_y; ++iy) {
    for (int ix = 0; ix < window.size_x; ++ix) {
      const size_t cell = size_t(window.Index(ix, iy));
      internal::CellQuantities q;
      q.f = floor[cell];
      q.dh = dh[cell];
      const float z_lo = internal::ObstacleThreshold(params, q.f, highest[cell]);
      bool any = false;
      for (int k = 0; k < ns * ns; ++k) {
        for (const Interval& a : samples[cell * ns * ns + k]) {
          if (!(a.hi > z_lo)) continue;
          const float bottom = std::max(float(a.lo), q.f);
          q.o = std::max(q.o, float(a.hi));
          q.c = any ? std::min(q.c, bottom) : bottom;
          any = true;
        }
      }
      CellType t = internal::Classify(params, q);
      // no solid under any sample: no floor to stand on (the world's floor ends)
      bool none = true;
      for (int k = 0; k < ns * ns && none; ++k) none = samples[cell * ns * ns + k].empty();
      if (none) t = CellType::kBorder;
      fog.type[cell] = t;
      fog.height[cell] = internal::FogHeight(t, q);
    }
  }
  return fog;
}

}  // namespace fognav::perception

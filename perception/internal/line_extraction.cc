// Line extraction along scan lines (paper Section 3.2).
#include "perception/internal/line_extraction.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fognav::perception::internal {
namespace {

// Sums x y z xx xy xz yy yz zz over points [i0, i1] from the running sums.
Moments RangeMoments(const ScanlineScratch& s, int i0, int i1) {
  const auto& hi = s.prefix[size_t(i1) + 1];
  const auto& lo = s.prefix[size_t(i0)];
  double d[9];
  for (int k = 0; k < 9; ++k) d[k] = hi[k] - lo[k];
  Moments m;
  m.n = i1 - i0 + 1;
  m.b = Eigen::Vector3d(d[0], d[1], d[2]);
  m.A << d[3], d[4], d[5], d[4], d[6], d[7], d[5], d[7], d[8];
  return m;
}

// A least-squares line in the 2D coordinates (a, c) of a scan line's plane.
struct Line2 {
  double ma = 0, mc = 0;  // centroid
  double na = 0, nc = 1;  // unit normal
  double sigma = 0;       // RMS orthogonal residual
};

// The scan line's plane contains the x axis and the unit direction (0, ty, 1) / k; a point's 2D
// coordinates are a = x and c = (ty y + z) / k. The line fit uses the centred 2D moments, which
// follow linearly from the 3D moments.
struct ScanPlane {
  double ty = 0, k = 1;
};

Line2 FitLine(const Moments& m, const ScanPlane& sp) {
  const double n = m.n;
  const double sa = m.b.x(), sc = (sp.ty * m.b.y() + m.b.z()) / sp.k;
  const double saa = m.A(0, 0);
  const double sac = (sp.ty * m.A(0, 1) + m.A(0, 2)) / sp.k;
  const double scc =
      (sp.ty * sp.ty * m.A(1, 1) + 2 * sp.ty * m.A(1, 2) + m.A(2, 2)) / (sp.k * sp.k);
  Line2 l;
  l.ma = sa / n;
  l.mc = sc / n;
  const double caa = saa / n - l.ma * l.ma;
  const double cac = sac / n - l.ma * l.mc;
  const double ccc = scc / n - l.mc * l.mc;
  // smallest eigenvalue and its eigenvector of the 2x2 covariance
  const double half_diff = 0.5 * (caa - ccc);
  const double root = std::sqrt(half_diff * half_diff + cac * cac);
  const double lmin = 0.5 * (caa + ccc) - root;
  l.sigma = std::sqrt(std::max(lmin, 0.0));
  const double theta = 0.5 * std::atan2(2 * cac, caa - ccc);  // direction of the line
  l.na = -std::sin(theta);
  l.nc = std::cos(theta);
  return l;
}

// Index in (i0, i1) of the point farthest from the chord between points i0 and i1.
int FarthestFromChord(const ScanlineScratch& s, int i0, int i1, double* dist) {
  const double da = double(s.q[size_t(i1)].x()) - s.q[size_t(i0)].x(),
               dc = s.c[size_t(i1)] - s.c[size_t(i0)];
  const double len = std::sqrt(da * da + dc * dc);
  int best = i0 + 1;
  double best_d = -1;
  for (int i = i0 + 1; i < i1; ++i) {
    const double ra = double(s.q[size_t(i)].x()) - s.q[size_t(i0)].x(),
                 rc = s.c[size_t(i)] - s.c[size_t(i0)];
    const double d = len > 0 ? std::abs(ra * dc - rc * da) / len : std::sqrt(ra * ra + rc * rc);
    if (d > best_d) {
      best_d = d;
      best = i;
    }
  }
  *dist = best_d;
  return best;
}

class RowSplitter {
 public:
  RowSplitter(const SegmentParams& p, int row, const Eigen::Vector3f* row_points,
              const ScanPlane& sp, ScanlineScratch* s, std::vector<LineSegment>* out)
      : p_(p), row_(row), row_points_(row_points), sp_(sp), s_(*s), out_(*out) {}

  // rd-split: fit, count same-side runs, accept or split at the farthest point
  void RdSplit(int i0, int i1) {
    const int n = i1 - i0 + 1;
    if (n < p_.n_min) return;
    const Moments m = RangeMoments(s_, i0, i1);
    const Line2 line = FitLine(m, sp_);
    // max-count-consecutive-same-side, stopping as soon as a run reaches C_max
    const double off = line.na * line.ma + line.nc * line.mc;
    const Eigen::Vector3f* q = &s_.q[size_t(i0)];
    const double* c = &s_.c[size_t(i0)];
    const int longest = LongestSameSideRun(
        n, [&](int i) { return line.na * q[i].x() + line.nc * c[i] - off; }, p_.side_tolerance,
        p_.c_max);
    const bool split = longest >= p_.c_max;
    if (!split || n < 3) {
      Emit(i0, i1, m, line);
      return;
    }
    double dist;
    const int k = FarthestFromChord(s_, i0, i1, &dist);
    RdSplit(i0, k);
    RdSplit(k + 1, i1);
  }

  // classic split of Duda and Hart with the chord threshold d_cord
  void Split(int i0, int i1) {
    const int n = i1 - i0 + 1;
    if (n < p_.n_min) return;
    double dist = 0;
    const int k = n >= 3 ? FarthestFromChord(s_, i0, i1, &dist) : i0;
    if (n < 3 || dist < p_.d_cord) {
      const Moments m = RangeMoments(s_, i0, i1);
      Emit(i0, i1, m, FitLine(m, sp_));
      return;
    }
    Split(i0, k);
    Split(k + 1, i1);
  }

 private:
  void Emit(int i0, int i1, const Moments& m, const Line2& line) {
    LineSegment l;
    l.s = row_;
    l.b = s_.u[size_t(i0)];
    l.e = s_.u[size_t(i1)];
    l.m = m;
    l.sigma = line.sigma;
    // the 2D normal (na, nc) in 3D: a along x, c along (0, ty, 1) / k
    l.normal = Eigen::Vector3d(line.na, line.nc * sp_.ty / sp_.k, line.nc / sp_.k);
    l.p_first = row_points_[l.b].cast<double>();
    l.p_last = row_points_[l.e].cast<double>();
    out_.push_back(l);
  }

  const SegmentParams& p_;
  int row_;
  const Eigen::Vector3f* row_points_;
  ScanPlane sp_;
  ScanlineScratch& s_;
  std::vector<LineSegment>& out_;
};

}  // namespace

int MaxConsecutiveSameSide(const double* residuals, int count, double tolerance) {
  return LongestSameSideRun(
      count, [&](int i) { return residuals[i]; }, tolerance, std::numeric_limits<int>::max());
}

void ExtractLines(const PointImage& points, const SegmentParams& p, LineSet* out,
                  ScanlineScratch* scratch) {
  const int w = points.width, h = points.height;
  out->width = w;
  out->height = h;
  out->lines.clear();
  out->row_begin.assign(size_t(h) + 1, 0);
  out->valid.assign(size_t(w) * h, 0);
  ScanlineScratch& s = *scratch;
  s.u.resize(size_t(w));
  s.c.resize(size_t(w));
  s.q.resize(size_t(w));
  s.prefix.resize(size_t(w) + 1);
  s.cut.resize(size_t(w) + 1);

  const int max_step = p.max_gap_px + 1;
  const bool cut_jumps = p.jump_ratio > 0;
  for (int v = 0; v < h; ++v) {
    out->row_begin[size_t(v)] = int(out->lines.size());
    // read the row's points once: valid mask, compact list and the cuts into runs at gaps and
    // depth jumps (s.cut[j] is the first index of run j)
    const Eigen::Vector3f* row = &points.points[size_t(v) * w];
    uint8_t* valid = &out->valid[size_t(v) * w];
    int n = 0, cuts = 0;
    ScanPlane sp;  // 2D coordinates: a = x, c = (ty y + z) / k
    double inv_k = 1;
    int prev_u = 0;
    double prev_c = 0;  // |c| of the previous point
    // raw pointers in locals: the byte stores to `valid` could alias the vectors' own pointers
    int* su = s.u.data();
    int* scut = s.cut.data();
    Eigen::Vector3f* sq = s.q.data();
    double* sc = s.c.data();
    const double jump_ratio = p.jump_ratio;
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3f& q = row[u];
      const double x = q.x(), y = q.y(), z = q.z();
      // finite iff all three are (double sums of floats cannot overflow)
      if (!std::isfinite(x + y + z)) continue;
      valid[u] = 1;
      if (n == 0) {
        // the scan line's plane through the camera centre, from its first point
        sp.ty = z != 0 ? y / z : 0;
        sp.k = std::sqrt(1 + sp.ty * sp.ty);
        inv_k = 1 / sp.k;
      }
      const double c = (sp.ty * y + z) * inv_k, abs_c = std::abs(c);
      if (n == 0 || u - prev_u > max_step ||
          (cut_jumps && std::abs(abs_c - prev_c) > jump_ratio * std::min(abs_c, prev_c)))
        scut[cuts++] = n;
      prev_u = u;
      prev_c = abs_c;
      su[n] = u;
      sq[n] = q;
      sc[n] = c;
      ++n;
    }
    // the running sums, in a second loop without branches, so that the nine sums stay in registers
    {
      double sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;
      std::array<double, 9>* prefix = s.prefix.data();
      prefix[0] = {};
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3f& q = sq[i];
        const double x = q.x(), y = q.y(), z = q.z();
        sx += x;
        sy += y;
        sz += z;
        sxx += x * x;
        sxy += x * y;
        sxz += x * z;
        syy += y * y;
        syz += y * z;
        szz += z * z;
        prefix[i + 1] = {sx, sy, sz, sxx, sxy, sxz, syy, syz, szz};
      }
    }
    if (n < p.n_min) continue;
    s.cut[size_t(cuts)] = n;

    // split each run into line segments
    RowSplitter splitter(p, v, row, sp, &s, &out->lines);
    for (int j = 0; j < cuts; ++j) {
      const int i0 = s.cut[size_t(j)], i1 = s.cut[size_t(j) + 1] - 1;
      if (p.method == LineMethod::kRdSplit) {
        splitter.RdSplit(i0, i1);
      } else {
        splitter.Split(i0, i1);
      }
    }
  }
  out->row_begin[size_t(h)] = int(out->lines.size());
}

}  // namespace fognav::perception::internal

// Plane segmentation by extended scan-line grouping (paper Sections 3.3-3.5) and the segment
// picture.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "perception/internal/line_extraction.h"
#include "perception/internal/plane_moments.h"
#include "perception/segmentation.h"

namespace fognav::perception {
namespace {

using internal::FitPlane;
using internal::LineSegment;
using internal::LineSet;
using internal::MeanSquaredResidual;
using internal::Moments;
using internal::PlaneFit;
using internal::Rms;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Label images are mostly uniform inside regions, so the full-image passes below skip runs of
// kChunk pixels whose labels all equal those of their neighbours in the given offsets (a loop
// the compiler vectorises); the caller keeps every offset inside the image.
constexpr int kChunk = 16;

template <int kOffsets>
bool UniformChunk(const int32_t* lab, int i, const int (&offsets)[kOffsets]) {
  int32_t acc = 0;
  for (int k = i; k < i + kChunk; ++k)
    for (int o : offsets) acc |= lab[k] ^ lab[k + o];
  return acc == 0;
}

// A planar region under construction: its moments and current fit.
struct Region {
  Moments m;
  PlaneFit fit;
  double sigma = 0;  // RMS residual of its own points, floored (used when trading and merging)
  int lines = 0;
};

// Buffers reused across calls on one thread, so that a call allocates only its output.
struct Workspace {
  LineSet line_set;
  internal::ScanlineScratch scratch;
  std::vector<int> order;
  std::vector<int> open;
  std::vector<Region> regions;
  std::vector<int> queue;
  std::vector<uint8_t> visits;
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> parent;
  std::vector<int> final_index;
};

class Grouper {
 public:
  Grouper(const PointImage& points, const SegmentParams& p, Workspace* ws)
      : points_(points), p_(p), ws_(*ws), ls_(ws->line_set), lines_(ws->line_set.lines) {}

  PlaneSet Run() {
    internal::ExtractLines(points_, p_, &ls_, &ws_.scratch);
    ws_.regions.clear();
    GroupLines();
    if (p_.trade_lines) TradeLines();
    PlaneSet out;
    out.labels = LabelImage(points_.width, points_.height, -1);
    LabelLines(&out.labels);
    RefitAll();
    if (p_.trade_points) TradePoints(&out.labels);
    RefitAll();
    ws_.parent.resize(ws_.regions.size());
    std::iota(ws_.parent.begin(), ws_.parent.end(), 0);
    if (p_.merge_planes) MergePlanes(out.labels);
    Finish(&out);
    return out;
  }

 private:
  // the r_sigma test of eq. (13)/(14), or the UB method's end point test with d_line
  bool Fits(const LineSegment& l, const PlaneFit& f, double r_max) const {
    if (!f.ok) return false;
    if (p_.method == LineMethod::kSplit) {
      return std::abs(l.p_first.dot(f.n) - f.dist) < p_.d_line &&
             std::abs(l.p_last.dot(f.n) - f.dist) < p_.d_line;
    }
    const double sigma = std::max(LineNoise(l, f.n), p_.sigma_min);
    if (!(Rms(l.m, f.n, f.dist) < r_max * sigma)) return false;  // eq. (10)
    if (p_.offset_sigmas <= 0) return true;
    return OffsetFits(l.m, sigma, f);
  }

  // the offset bound: a distance `offset` from a plane, averaged over n points that spread by
  // sigma across it, is small if below offset_min or offset_sigmas standard errors of the mean
  bool SmallOffset(double offset, double n, double sigma) const {
    if (offset <= p_.offset_min) return true;
    const double independent = std::max(1.0, n / std::max(p_.correlation_px, 1.0));
    return offset < p_.offset_sigmas * sigma / std::sqrt(independent);
  }

  // the mean offset test: the mean distance of a point set to plane f within the offset bound
  bool OffsetFits(const Moments& m, double sigma, const PlaneFit& f) const {
    if (p_.offset_sigmas <= 0 || m.n <= 0) return true;
    return SmallOffset(std::abs(m.b.dot(f.n) / m.n - f.dist), m.n, sigma);
  }

  // a region fits a joint plane f if its RMS about f is within r_seed of its own sigma (the
  // seed test of eq. 13 with regions in place of lines) and f departs from the region's own
  // plane by little: the RMS of f - own over the region's points (sqrt(rms_f^2 - rms_own^2))
  // within the offset bound. The mean offset alone misses two parallel treads a few
  // centimetres apart, to which a joint plane tilted between them fits with no mean offset.
  bool JointFits(const Region& r, const PlaneFit& f) const {
    const double joint = MeanSquaredResidual(r.m, f.n, f.dist);
    if (std::sqrt(joint) >= p_.r_seed * r.sigma) return false;
    if (p_.offset_sigmas <= 0 || r.m.n <= 0) return true;
    const double own = r.fit.ok ? MeanSquaredResidual(r.m, r.fit.n, r.fit.dist) : 0.0;
    return SmallOffset(std::sqrt(std::max(0.0, joint - own)), r.m.n, r.sigma);
  }

  // the spread across plane normal n that the line's noise along the viewing rays gives: the
  // line's sigma is measured along its normal m in the scan plane, and a depth error dz at ray
  // q = p / z moves a point by dz q, so by dz |m . q| across the line and dz |n . q| across the
  // plane
  double LineNoise(const LineSegment& l, const Eigen::Vector3d& n) const {
    if (!p_.ray_noise || !(l.m.b.z() > 0)) return l.sigma;
    const Eigen::Vector3d q = l.m.b / l.m.b.z();
    const double across_line = std::abs(l.normal.dot(q)), across_plane = std::abs(n.dot(q));
    if (!(across_line > 0) || across_plane >= across_line) return l.sigma;
    return l.sigma * across_plane / across_line;
  }

  // calls fn(index) for each line of row s whose columns overlap [b, e]
  template <typename Fn>
  void ForOverlapping(int s, int b, int e, Fn fn) {
    if (s < 0 || s >= ls_.height) return;
    for (int i = ls_.row_begin[size_t(s)], end = ls_.row_begin[size_t(s) + 1]; i < end; ++i) {
      const LineSegment& l = lines_[size_t(i)];
      if (l.e < b) continue;
      if (l.b > e) break;
      fn(i);
    }
  }

  // seed selection (eq. 12-13) in order of decreasing line length, then region growing (eq. 14)
  void GroupLines() {
    std::vector<int>& order = ws_.order;
    order.resize(lines_.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return lines_[size_t(a)].m.n > lines_[size_t(b)].m.n; });
    for (int mid : order) {
      const LineSegment& l2 = lines_[size_t(mid)];
      if (l2.plane >= 0) continue;
      int seed1 = -1, seed3 = -1;
      PlaneFit seed_fit;
      ForOverlapping(l2.s - 1, l2.b, l2.e, [&](int i1) {
        if (seed1 >= 0 || lines_[size_t(i1)].plane >= 0) return;
        ForOverlapping(l2.s + 1, l2.b, l2.e, [&](int i3) {
          if (seed1 >= 0 || lines_[size_t(i3)].plane >= 0) return;
          const LineSegment& l1 = lines_[size_t(i1)];
          const LineSegment& l3 = lines_[size_t(i3)];
          Moments m = l1.m;  // eq. (12)
          m.Add(l2.m);
          m.Add(l3.m);
          const PlaneFit f = FitPlane(m);
          if (Fits(l1, f, p_.r_seed) && Fits(l2, f, p_.r_seed) && Fits(l3, f, p_.r_seed)) {
            seed1 = i1;
            seed3 = i3;
            seed_fit = f;
          }
        });
      });
      if (seed1 < 0) continue;
      Grow(seed1, mid, seed3, seed_fit);
    }
  }

  void Grow(int i1, int i2, int i3, const PlaneFit& fit) {
    const int id = int(ws_.regions.size());
    ws_.regions.emplace_back();
    Region& r = ws_.regions.back();
    r.fit = fit;
    std::vector<int>& open = ws_.open;
    open.clear();
    for (int i : {i1, i2, i3}) {
      lines_[size_t(i)].plane = id;
      r.m.Add(lines_[size_t(i)].m);
      ++r.lines;
      open.push_back(i);
    }
    while (!open.empty()) {
      const int c = open.back();
      open.pop_back();
      const LineSegment lc = lines_[size_t(c)];
      for (int s : {lc.s - 1, lc.s + 1}) {
        ForOverlapping(s, lc.b, lc.e, [&](int i) {
          LineSegment& l = lines_[size_t(i)];
          if (l.plane >= 0 || !Fits(l, r.fit, p_.r_grow)) return;
          l.plane = id;
          r.m.Add(l.m);  // eq. (7)
          ++r.lines;
          const PlaneFit f = FitPlane(r.m);
          if (f.ok) r.fit = f;
          open.push_back(i);
        });
      }
    }
  }

  // trading line segments: a line at a region border moves to the neighbouring region it fits
  // better (RMS of eq. 9); lines in no region join the best-fitting neighbour that accepts them
  void TradeLines() {
    // a move refits two planes, which may make other moves worthwhile: a few passes
    constexpr int kMaxPasses = 4;
    for (int pass = 0; pass < kMaxPasses && TradeLinesPass(); ++pass) {
    }
  }

  bool TradeLinesPass() {
    bool moved = false;
    for (size_t i = 0; i < lines_.size(); ++i) {
      LineSegment& l = lines_[i];
      const int own = l.plane;
      double best_cost = kInf;
      int best = -1;
      if (own >= 0) {
        if (ws_.regions[size_t(own)].lines <= 3) continue;
        best_cost = Rms(l.m, ws_.regions[size_t(own)].fit.n, ws_.regions[size_t(own)].fit.dist);
        best = own;
      }
      for (int s : {l.s - 1, l.s + 1}) {
        ForOverlapping(s, l.b, l.e, [&](int j) {
          const int q = lines_[size_t(j)].plane;
          if (q < 0 || q == own || q == best) return;
          const Region& rq = ws_.regions[size_t(q)];
          if (!Fits(l, rq.fit, p_.r_grow)) return;
          const double cost = Rms(l.m, rq.fit.n, rq.fit.dist);
          if (cost < best_cost) {
            best_cost = cost;
            best = q;
          }
        });
      }
      if (best == own || best < 0) continue;
      if (own >= 0) {
        Region& ro = ws_.regions[size_t(own)];
        ro.m.Subtract(l.m);  // eq. (7), subtracting
        --ro.lines;
        const PlaneFit f = FitPlane(ro.m);
        if (f.ok) ro.fit = f;
      }
      Region& rb = ws_.regions[size_t(best)];
      rb.m.Add(l.m);
      ++rb.lines;
      const PlaneFit f = FitPlane(rb.m);
      if (f.ok) rb.fit = f;
      l.plane = best;
      moved = true;
    }
    return moved;
  }

  void LabelLines(LabelImage* labels) const {
    const int w = ls_.width;
    for (const LineSegment& l : lines_) {
      if (l.plane < 0) continue;
      int32_t* row = &labels->data[size_t(l.s) * w];
      const uint8_t* valid = &ls_.valid[size_t(l.s) * w];
      // lines do not overlap and invalid points keep -1: a select the compiler vectorises
      for (int u = l.b; u <= l.e; ++u) row[u] = valid[u] ? l.plane : -1;
    }
  }

  void RefitAll() {
    for (Region& r : ws_.regions) {
      const PlaneFit f = FitPlane(r.m);
      if (f.ok) r.fit = f;
      r.sigma = std::max(r.fit.ok ? Rms(r.m, r.fit.n, r.fit.dist) : 0.0, p_.sigma_min);
    }
  }

  // trading points: border points (and unsegmented points next to a region) move to the
  // neighbouring region whose plane has the smallest RMS over the window statistics around the
  // point; a point joins a region only if it lies within r_grow of that region's sigma
  void TradePoints(LabelImage* labels) {
    const int w = ls_.width, h = ls_.height;
    const int half = std::max(p_.trade_window, 1) / 2;
    const std::vector<uint8_t>& valid = ls_.valid;
    int32_t* lab = labels->data.data();
    std::vector<int>& queue = ws_.queue;
    std::vector<uint8_t>& visits = ws_.visits;
    queue.clear();
    visits.assign(size_t(w) * h, 0);
    constexpr uint8_t kQueued = 0x80;
    constexpr int kMaxVisits = 3;

    // border points in raster order (invalid points are never labelled, so a uniform chunk holds
    // no border point)
    auto differs = [&](int i, int j) { return valid[size_t(j)] && lab[j] != lab[i]; };
    auto visit = [&](int u, int v) {
      const int i = v * w + u;
      if (!valid[size_t(i)]) return;
      const bool border = (u > 0 && differs(i, i - 1)) || (u + 1 < w && differs(i, i + 1)) ||
                          (v > 0 && differs(i, i - w)) || (v + 1 < h && differs(i, i + w));
      if (!border) return;
      queue.push_back(i);
      visits[size_t(i)] |= kQueued;
    };
    const int around[4] = {-1, 1, -w, w};
    for (int v = 0; v < h; ++v) {
      int u = 0;
      if (v > 0 && v + 1 < h) {
        visit(u++, v);
        for (; u + kChunk < w; u += kChunk) {
          if (UniformChunk(lab, v * w + u, around)) continue;
          for (int k = u; k < u + kChunk; ++k) visit(k, v);
        }
      }
      for (; u < w; ++u) visit(u, v);
    }

    int cands[5];
    for (size_t head = 0; head < queue.size(); ++head) {
      const int i = queue[head];
      visits[size_t(i)] = uint8_t((visits[size_t(i)] & ~kQueued) + 1);
      const int u = i % w, v = i / w;
      const int own = lab[i];
      // candidate regions: the labels of the 4 neighbours
      int nc = 0;
      auto add = [&](int j) {
        if (!valid[size_t(j)] || lab[j] < 0 || lab[j] == own) return;
        for (int k = 0; k < nc; ++k)
          if (cands[k] == lab[j]) return;
        cands[nc++] = lab[j];
      };
      if (u > 0) add(i - 1);
      if (u + 1 < w) add(i + 1);
      if (v > 0) add(i - w);
      if (v + 1 < h) add(i + w);
      if (nc == 0) continue;

      // a candidate must hold the point itself within r_grow of its sigma and, against a region
      // the point already has, closer in units of sigma; the window RMS then decides (the
      // window alone favours the plane with the denser points at an edge)
      const Eigen::Vector3d x = points_.points[size_t(i)].cast<double>();
      double own_ratio = p_.r_grow;
      if (own >= 0) {
        const Region& r = ws_.regions[size_t(own)];
        own_ratio = std::min(own_ratio, std::abs(x.dot(r.fit.n) - r.fit.dist) / r.sigma);
      }
      int kept = 0;
      for (int k = 0; k < nc; ++k) {
        const Region& r = ws_.regions[size_t(cands[k])];
        if (r.fit.ok && std::abs(x.dot(r.fit.n) - r.fit.dist) <= own_ratio * r.sigma)
          cands[kept++] = cands[k];
      }
      nc = kept;
      if (nc == 0) continue;

      // window statistics N, b, A around the point
      Moments win;
      const int v0 = std::max(v - half, 0), v1 = std::min(v + half, h - 1);
      const int u0 = std::max(u - half, 0), u1 = std::min(u + half, w - 1);
      double sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;
      int n = 0;
      for (int vv = v0; vv <= v1; ++vv) {
        const Eigen::Vector3f* prow = &points_.points[size_t(vv) * w];
        const uint8_t* vrow = &valid[size_t(vv) * w];
        for (int uu = u0; uu <= u1; ++uu) {
          if (!vrow[uu]) continue;
          const double x = prow[uu].x(), y = prow[uu].y(), z = prow[uu].z();
          ++n;
          sx += x, sy += y, sz += z;
          sxx += x * x, sxy += x * y, sxz += x * z, syy += y * y, syz += y * z, szz += z * z;
        }
      }
      win.n = n;
      win.b = Eigen::Vector3d(sx, sy, sz);
      win.A << sxx, sxy, sxz, sxy, syy, syz, sxz, syz, szz;

      int best = own;
      double best_cost = kInf;
      if (own >= 0) {
        const Region& r = ws_.regions[size_t(own)];
        best_cost = Rms(win, r.fit.n, r.fit.dist);
      }
      for (int k = 0; k < nc; ++k) {
        const Region& r = ws_.regions[size_t(cands[k])];
        const double cost = Rms(win, r.fit.n, r.fit.dist);
        if (cost < best_cost) {
          best_cost = cost;
          best = cands[k];
        }
      }
      if (best == own) continue;

      // move the point (eq. 7 with a single point) and revisit its neighbours
      if (own >= 0) ws_.regions[size_t(own)].m.Subtract(x);
      ws_.regions[size_t(best)].m.Add(x);
      lab[i] = best;
      auto push = [&](int j) {
        uint8_t& vis = visits[size_t(j)];
        if (!valid[size_t(j)] || (vis & kQueued) || (vis & ~kQueued) >= kMaxVisits) return;
        vis |= kQueued;
        queue.push_back(j);
      };
      if (u > 0) push(i - 1);
      if (u + 1 < w) push(i + 1);
      if (v > 0) push(i - w);
      if (v + 1 < h) push(i + w);
    }
  }

  int Root(int a) {
    while (ws_.parent[size_t(a)] != a) {
      ws_.parent[size_t(a)] = ws_.parent[size_t(ws_.parent[size_t(a)])];
      a = ws_.parent[size_t(a)];
    }
    return a;
  }

  // merging planes: neighbouring regions whose joint plane fits each of them within r_seed of
  // its own RMS (the seed test of eq. 13 with regions in place of lines)
  void MergePlanes(const LabelImage& labels) {
    const int w = labels.width, h = labels.height;
    std::vector<std::pair<int, int>>& pairs = ws_.pairs;
    pairs.clear();
    const int32_t* lab = labels.data.data();
    auto visit = [&](int u, int v) {
      const int a = lab[v * w + u];
      if (a < 0) return;
      auto add = [&](int b) {
        if (b < 0 || b == a) return;
        const std::pair<int, int> pr(std::min(a, b), std::max(a, b));
        if (pairs.empty() || pairs.back() != pr) pairs.push_back(pr);
      };
      if (u + 1 < w) add(lab[v * w + u + 1]);
      if (v + 1 < h) add(lab[(v + 1) * w + u]);
    };
    const int right_and_below[2] = {1, w};
    for (int v = 0; v < h; ++v) {
      int u = 0;
      if (v + 1 < h) {
        for (; u + kChunk < w; u += kChunk) {
          if (UniformChunk(lab, v * w + u, right_and_below)) continue;
          for (int k = u; k < u + kChunk; ++k) visit(k, v);
        }
      }
      for (; u < w; ++u) visit(u, v);
    }
    if (p_.merge_across_missing) AddPairsAcrossMissing(labels);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    MergePairs(pairs);
    if (!p_.merge_coplanar) return;
    // coplanar regions apart in the image: every remaining pair
    pairs.clear();
    const int nr = int(ws_.regions.size());
    for (int a = 0; a < nr; ++a)
      for (int b = a + 1; b < nr; ++b)
        if (Root(a) == a && Root(b) == b) pairs.emplace_back(a, b);
    MergePairs(pairs);
  }

  // regions that only pixels without a point separate along a row or a column: one eye's view
  // of a surface hidden from the other (by the robot's own arm, say) leaves a band without
  // matches that splits the surface. A pixel whose point found no region breaks the bridge.
  // Visits the runs of missing points only (a byte search finds them), each pixel of them once
  // along its row and once down its column.
  void AddPairsAcrossMissing(const LabelImage& labels) {
    const int w = labels.width, h = labels.height;
    const int32_t* lab = labels.data.data();
    const uint8_t* valid = ls_.valid.data();
    std::vector<std::pair<int, int>>& pairs = ws_.pairs;
    auto bridge = [&](int a, int b) {
      if (a >= 0 && b >= 0 && a != b) pairs.emplace_back(std::min(a, b), std::max(a, b));
    };
    for (int v = 0; v < h; ++v) {
      const uint8_t* row = valid + size_t(v) * w;
      for (int u = 0; u < w;) {
        const void* hole = std::memchr(row + u, 0, size_t(w - u));
        if (hole == nullptr) break;
        const int u0 = int(static_cast<const uint8_t*>(hole) - row);
        int u1 = u0;
        while (u1 < w && !row[u1]) ++u1;
        if (u0 > 0 && u1 < w) bridge(lab[v * w + u0 - 1], lab[v * w + u1]);
        // down each column from the top of its run of missing points
        for (int c = u0; v > 0 && c < u1; ++c) {
          if (!valid[(v - 1) * w + c]) continue;
          int vv = v + 1;
          while (vv < h && !valid[vv * w + c]) ++vv;
          if (vv < h) bridge(lab[(v - 1) * w + c], lab[vv * w + c]);
        }
        u = u1;
      }
    }
  }

  void MergePairs(const std::vector<std::pair<int, int>>& pairs) {
    for (bool changed = true; changed;) {
      changed = false;
      for (const auto& [pa, pb] : pairs) {
        const int a = Root(pa), b = Root(pb);
        if (a == b) continue;
        Region& ra = ws_.regions[size_t(a)];
        Region& rb = ws_.regions[size_t(b)];
        Moments m = ra.m;
        m.Add(rb.m);
        const PlaneFit f = FitPlane(m);
        if (!f.ok || !JointFits(ra, f) || !JointFits(rb, f)) continue;
        ra.m = m;
        ra.fit = f;
        ra.sigma = std::max(Rms(m, f.n, f.dist), p_.sigma_min);
        ra.lines += rb.lines;
        rb.m = Moments();
        ws_.parent[size_t(b)] = a;
        changed = true;
      }
    }
  }

  // final planes: merged labels, small or degenerate regions dropped, sorted by size, borders
  void Finish(PlaneSet* out) {
    const int nr = int(ws_.regions.size());
    std::vector<int>& idx = ws_.final_index;
    idx.assign(size_t(nr), -1);
    std::vector<int> keep;
    for (int r = 0; r < nr; ++r) {
      if (Root(r) != r) continue;
      const Region& reg = ws_.regions[size_t(r)];
      if (reg.m.n < std::max(p_.min_plane_points, 3)) continue;
      if (!FitPlane(reg.m).ok) continue;
      keep.push_back(r);
    }
    std::stable_sort(keep.begin(), keep.end(), [&](int a, int b) {
      return ws_.regions[size_t(a)].m.n > ws_.regions[size_t(b)].m.n;
    });
    out->planes.resize(keep.size());
    for (size_t k = 0; k < keep.size(); ++k) {
      const Region& reg = ws_.regions[size_t(keep[k])];
      idx[size_t(keep[k])] = int(k);
      Plane& pl = out->planes[k];
      const PlaneFit f = FitPlane(reg.m);
      pl.n = f.n;
      pl.d = f.dist;
      pl.num_points = reg.m.n;
      pl.b = reg.m.b;
      pl.A = reg.m.A;
      pl.rms = Rms(reg.m, f.n, f.dist);
    }
    for (int r = 0; r < nr; ++r) idx[size_t(r)] = idx[size_t(Root(r))];

    // relabel and collect the border per scan line
    const int w = out->labels.width, h = out->labels.height;
    std::vector<int> first(keep.size(), -1), last(keep.size(), -1);
    std::vector<int> touched;
    for (int v = 0; v < h; ++v) {
      int32_t* row = &out->labels.data[size_t(v) * w];
      touched.clear();
      // one run of equal labels at a time
      for (int u0 = 0, u1; u0 < w; u0 = u1) {
        const int32_t label = row[u0];
        for (u1 = u0 + 1; u1 < w && row[u1] == label; ++u1) {
        }
        if (label < 0) continue;
        const int k = idx[size_t(label)];
        std::fill(row + u0, row + u1, k);
        if (k < 0) continue;
        if (first[size_t(k)] < 0) {
          first[size_t(k)] = u0;
          touched.push_back(k);
        }
        last[size_t(k)] = u1 - 1;
      }
      for (int k : touched) {
        out->planes[size_t(k)].border.push_back({v, first[size_t(k)], last[size_t(k)]});
        first[size_t(k)] = -1;
      }
    }
  }

  const PointImage& points_;
  const SegmentParams& p_;
  Workspace& ws_;
  LineSet& ls_;
  std::vector<LineSegment>& lines_;
};

}  // namespace

PlaneSet SegmentPlanes(const PointImage& points, const SegmentParams& p) {
  thread_local Workspace ws;
  if (points.width <= 0 || points.height <= 0) {
    PlaneSet empty;
    empty.labels = LabelImage(std::max(points.width, 0), std::max(points.height, 0), -1);
    return empty;
  }
  return Grouper(points, p, &ws).Run();
}

}  // namespace fognav::perception

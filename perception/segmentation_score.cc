// Segmentation scores against ground-truth surfaces: Table 2 accuracy, coverage and the counts
// of Hoover et al. (1996).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "perception/internal/plane_moments.h"
#include "perception/segmentation.h"

namespace fognav::perception {
namespace {

// Maps arbitrary non-negative ids to 0..n-1 in order of first appearance.
class IdMap {
 public:
  int Index(int32_t id) {
    auto [it, inserted] = map_.try_emplace(id, int(ids_.size()));
    if (inserted) ids_.push_back(id);
    return it->second;
  }
  int size() const { return int(ids_.size()); }
  int32_t Id(int index) const { return ids_[size_t(index)]; }

 private:
  std::unordered_map<int32_t, int> map_;
  std::vector<int32_t> ids_;
};

void Ratios(SegmentationScore* s) {
  s->accuracy = s->segment_px > 0 ? double(s->overlap_px) / double(s->segment_px) : 0.0;
  s->coverage = s->surface_px > 0 ? double(s->overlap_px) / double(s->surface_px) : 0.0;
}

// Eigenvalues (ascending) and vectors of the points' scatter about their mean.
Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> Scatter(const internal::Moments& m) {
  const Eigen::Vector3d mean = m.b / m.n;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m.A / m.n - mean * mean.transpose());
}

}  // namespace

LabelImage JoinCoplanarSurfaces(const LabelImage& truth, const PointImage& exact_points,
                                double tolerance, double max_angle, int min_points,
                                double min_spread) {
  std::map<int32_t, internal::Moments> moments;
  for (int v = 0; v < truth.height; ++v) {
    for (int u = 0; u < truth.width; ++u) {
      const int32_t id = truth.at(u, v);
      const Eigen::Vector3f& p = exact_points.at(u, v);
      if (id >= 0 && p.allFinite()) moments[id].Add(p.cast<double>());
    }
  }
  // the pairs of ids that touch
  std::set<std::pair<int32_t, int32_t>> pairs;
  auto touch = [&](int32_t a, int32_t b) {
    if (a >= 0 && b >= 0 && a != b && moments.count(a) && moments.count(b)) {
      pairs.emplace(std::min(a, b), std::max(a, b));
    }
  };
  for (int v = 0; v < truth.height; ++v) {
    for (int u = 0; u < truth.width; ++u) {
      if (u + 1 < truth.width) touch(truth.at(u, v), truth.at(u + 1, v));
      if (v + 1 < truth.height) touch(truth.at(u, v), truth.at(u, v + 1));
    }
  }
  // each surface's normal, if it has one of its own: min_points spread in two directions (a
  // pixel or a strip fits any plane through it and would join surfaces at an angle)
  std::map<int32_t, Eigen::Vector3d> normal;
  for (const auto& [id, m] : moments) {
    if (m.n < min_points) continue;
    const auto scatter = Scatter(m);
    if (scatter.eigenvalues()(1) >= min_spread * min_spread) {
      normal[id] = scatter.eigenvectors().col(0);
    }
  }
  // union-find over the coplanar pairs; a root is its component's lowest id
  std::map<int32_t, int32_t> parent;
  for (const auto& [id, m] : moments) parent[id] = id;
  auto find = [&](int32_t id) {
    while (parent[id] != id) id = parent[id] = parent[parent[id]];
    return id;
  };
  for (const auto& [a, b] : pairs) {
    if (!normal.count(a) || !normal.count(b)) continue;
    internal::Moments joint = moments[a];
    joint.Add(moments[b]);
    if (Scatter(joint).eigenvalues()(0) > tolerance * tolerance) continue;
    if (std::acos(std::min(1.0, std::abs(normal[a].dot(normal[b])))) > max_angle) continue;
    const int32_t ra = find(a), rb = find(b);
    parent[std::max(ra, rb)] = std::min(ra, rb);
  }
  LabelImage joined = truth;
  for (int32_t& id : joined.data) {
    if (id >= 0 && parent.count(id)) id = find(id);
  }
  return joined;
}

SegmentationScore ScoreSegmentation(const LabelImage& labels, const LabelImage& truth_surface_ids,
                                    const DepthImage& truth_depth_m, const ScoreParams& p) {
  SegmentationScore score;
  const size_t npx = labels.data.size();
  if (truth_surface_ids.data.size() != npx || truth_depth_m.data.size() != npx) return score;

  // compact ids, pixel counts and the overlap tables: all pixels (Hoover counts) and those
  // whose true depth lies within max_depth_m (Table 2 accuracy and coverage)
  IdMap seg_ids, truth_ids;
  std::vector<int> seg_of(npx, -1), truth_of(npx, -1);
  for (size_t i = 0; i < npx; ++i) {
    if (labels.data[i] >= 0) seg_of[i] = seg_ids.Index(labels.data[i]);
    if (truth_surface_ids.data[i] >= 0) truth_of[i] = truth_ids.Index(truth_surface_ids.data[i]);
  }
  const int ns = seg_ids.size(), ng = truth_ids.size();
  std::vector<int64_t> seg_px(size_t(ns), 0), truth_px(size_t(ng), 0);
  std::vector<int64_t> seg_in_range(size_t(ns), 0), truth_in_range(size_t(ng), 0);
  std::vector<int64_t> overlap(size_t(ns) * ng, 0);  // [s * ng + g]
  std::vector<int64_t> overlap_in_range(size_t(ns) * ng, 0);
  std::vector<std::vector<float>> depths(static_cast<size_t>(ng));
  for (size_t i = 0; i < npx; ++i) {
    const int s = seg_of[i], g = truth_of[i];
    const float z = truth_depth_m.data[i];
    const bool in_range = std::isfinite(z) && z <= p.max_depth_m;
    if (s >= 0) {
      ++seg_px[size_t(s)];
      seg_in_range[size_t(s)] += in_range;
    }
    if (g >= 0) {
      ++truth_px[size_t(g)];
      truth_in_range[size_t(g)] += in_range;
      if (std::isfinite(z)) depths[size_t(g)].push_back(z);
    }
    if (s >= 0 && g >= 0) {
      ++overlap[size_t(s) * ng + g];
      overlap_in_range[size_t(s) * ng + g] += in_range;
    }
  }
  score.planes = ns;

  // scored surfaces: at least min_surface_px pixels, median depth within max_depth_m
  std::vector<uint8_t> scored(size_t(ng), 0);
  for (int g = 0; g < ng; ++g) {
    std::vector<float>& d = depths[size_t(g)];
    if (truth_px[size_t(g)] < p.min_surface_px || d.empty()) continue;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    if (d[d.size() / 2] > p.max_depth_m) continue;
    scored[size_t(g)] = 1;
    ++score.truth_surfaces;
  }

  // Table 2 accuracy and coverage, one to one: each segment belongs to the surface it overlaps
  // most (ties: the lower surface id); each scored surface takes the segment of its own that
  // overlaps it most. A scored surface without a segment of its own is missed: it adds to
  // sum |G| only.
  std::vector<int> owner(size_t(ns), -1);
  for (int s = 0; s < ns; ++s) {
    int64_t best_ov = 0;
    for (int g = 0; g < ng; ++g) {
      const int64_t o = overlap_in_range[size_t(s) * ng + g];
      const int b = owner[size_t(s)];
      if (o > best_ov || (o == best_ov && o > 0 && truth_ids.Id(g) < truth_ids.Id(b))) {
        best_ov = o;
        owner[size_t(s)] = g;
      }
    }
  }
  for (int g = 0; g < ng; ++g) {
    if (!scored[size_t(g)]) continue;
    score.surface_px += truth_in_range[size_t(g)];
    int best = -1;
    for (int s = 0; s < ns; ++s) {
      if (owner[size_t(s)] != g) continue;
      if (best < 0 || overlap_in_range[size_t(s) * ng + g] > overlap_in_range[size_t(best) * ng + g])
        best = s;
    }
    if (best < 0) continue;
    score.overlap_px += overlap_in_range[size_t(best) * ng + g];
    score.segment_px += seg_in_range[size_t(best)];
  }
  Ratios(&score);

  // Hoover et al.: segments that lie at least half on scored surfaces take part
  std::vector<uint8_t> seg_in(size_t(ns), 0);
  for (int s = 0; s < ns; ++s) {
    int64_t on = 0;
    for (int g = 0; g < ng; ++g)
      if (scored[size_t(g)]) on += overlap[size_t(s) * ng + g];
    seg_in[size_t(s)] = 2 * on >= seg_px[size_t(s)];
  }
  const double t = p.tolerance;
  auto ov = [&](int s, int g) { return double(overlap[size_t(s) * ng + g]); };
  std::vector<uint8_t> seg_used(size_t(ns), 0), truth_used(size_t(ng), 0);
  // correct detection: O >= T |S| and O >= T |G|
  for (int g = 0; g < ng; ++g) {
    if (!scored[size_t(g)]) continue;
    for (int s = 0; s < ns; ++s) {
      if (!seg_in[size_t(s)] || seg_used[size_t(s)]) continue;
      if (ov(s, g) >= t * seg_px[size_t(s)] && ov(s, g) >= t * truth_px[size_t(g)]) {
        ++score.correct;
        seg_used[size_t(s)] = truth_used[size_t(g)] = 1;
        break;
      }
    }
  }
  // over-segmentation: >= 2 segments each O >= T |S_i| whose overlaps sum to >= T |G|
  for (int g = 0; g < ng; ++g) {
    if (!scored[size_t(g)] || truth_used[size_t(g)]) continue;
    int count = 0;
    double sum = 0;
    for (int s = 0; s < ns; ++s) {
      if (!seg_in[size_t(s)] || seg_used[size_t(s)] || ov(s, g) < t * seg_px[size_t(s)]) continue;
      ++count;
      sum += ov(s, g);
    }
    if (count < 2 || sum < t * truth_px[size_t(g)]) continue;
    ++score.over;
    truth_used[size_t(g)] = 1;
    for (int s = 0; s < ns; ++s)
      if (seg_in[size_t(s)] && !seg_used[size_t(s)] && ov(s, g) >= t * seg_px[size_t(s)])
        seg_used[size_t(s)] = 1;
  }
  // under-segmentation: a segment over >= 2 surfaces each O >= T |G_i|, summing to >= T |S|
  for (int s = 0; s < ns; ++s) {
    if (!seg_in[size_t(s)] || seg_used[size_t(s)]) continue;
    int count = 0;
    double sum = 0;
    for (int g = 0; g < ng; ++g) {
      if (!scored[size_t(g)] || truth_used[size_t(g)] || ov(s, g) < t * truth_px[size_t(g)])
        continue;
      ++count;
      sum += ov(s, g);
    }
    if (count < 2 || sum < t * seg_px[size_t(s)]) continue;
    ++score.under;
    seg_used[size_t(s)] = 1;
    for (int g = 0; g < ng; ++g)
      if (scored[size_t(g)] && !truth_used[size_t(g)] && ov(s, g) >= t * truth_px[size_t(g)])
        truth_used[size_t(g)] = 1;
  }
  // the rest: missed surfaces and noise segments
  for (int g = 0; g < ng; ++g) score.missed += scored[size_t(g)] && !truth_used[size_t(g)];
  for (int s = 0; s < ns; ++s) score.noise += seg_in[size_t(s)] && !seg_used[size_t(s)];
  return score;
}

SegmentationScore CombineScores(const std::vector<SegmentationScore>& scores) {
  SegmentationScore total;
  for (const SegmentationScore& s : scores) {
    total.correct += s.correct;
    total.over += s.over;
    total.under += s.under;
    total.missed += s.missed;
    total.noise += s.noise;
    total.planes += s.planes;
    total.truth_surfaces += s.truth_surfaces;
    total.overlap_px += s.overlap_px;
    total.segment_px += s.segment_px;
    total.surface_px += s.surface_px;
  }
  Ratios(&total);
  return total;
}

StereoScore ScoreStereo(const PointImage& points, const DepthImage& truth_depth_m,
                        const CameraIntrinsics& K, double max_depth_m) {
  if (points.width != truth_depth_m.width || points.height != truth_depth_m.height) {
    std::fprintf(stderr, "fognav ScoreStereo: point image %dx%d, depth %dx%d\n", points.width,
                 points.height, truth_depth_m.width, truth_depth_m.height);
    std::abort();
  }
  StereoScore score;
  std::vector<double> disparity_errors, depth_errors;
  const double fb = K.fx * K.baseline;
  int64_t bad = 0;
  for (size_t i = 0; i < truth_depth_m.data.size(); ++i) {
    const double z_true = truth_depth_m.data[i];
    if (!std::isfinite(z_true) || z_true <= 0 || z_true > max_depth_m) continue;
    ++score.pixels;
    const double z = points.points[i].z();
    if (!std::isfinite(z) || z <= 0) continue;
    const double e = std::abs(fb / z - fb / z_true);
    disparity_errors.push_back(e);
    depth_errors.push_back(std::abs(z - z_true));
    if (e > 1.0) ++bad;
  }
  if (!disparity_errors.empty()) {
    score.valid = double(disparity_errors.size()) / double(score.pixels);
    score.bad_1px = double(bad) / double(disparity_errors.size());
    score.median_error_px = Median(std::move(disparity_errors));
    score.median_depth_error = Median(std::move(depth_errors));
  }
  return score;
}

StereoScore CombineStereoScores(const std::vector<StereoScore>& scores) {
  StereoScore total;
  std::vector<double> error_px, error_m;
  double valid_px = 0, bad_px = 0;
  for (const StereoScore& s : scores) {
    total.pixels += s.pixels;
    valid_px += s.valid * double(s.pixels);
    bad_px += s.bad_1px * s.valid * double(s.pixels);
    if (s.valid > 0) {
      error_px.push_back(s.median_error_px);
      error_m.push_back(s.median_depth_error);
    }
  }
  total.valid = total.pixels > 0 ? valid_px / double(total.pixels) : 0;
  total.bad_1px = valid_px > 0 ? bad_px / valid_px : 0;
  total.median_error_px = Median(std::move(error_px));
  total.median_depth_error = Median(std::move(error_m));
  return total;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  if (values.size() % 2) return *mid;
  return 0.5 * (*mid + *std::max_element(values.begin(), mid));
}

}  // namespace fognav::perception

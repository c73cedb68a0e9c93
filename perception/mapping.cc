#include "perception/mapping.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include "perception/internal/box_slab.h"
#include "perception/internal/map_update.h"

namespace fognav::perception {
namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Always-on invariant check.
void Check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fognav mapping: broken invariant: %s\n", what);
    std::abort();
  }
}

// A body box as a point test in its own frame.
struct BodyTest {
  Eigen::Matrix3f R_BG;
  Eigen::Vector3f p_BG;
  Eigen::Vector3f half;
  bool Contains(const Eigen::Vector3f& p_G) const {
    const Eigen::Vector3f p_B = R_BG * p_G + p_BG;
    return (p_B.cwiseAbs().array() <= half.array()).all();
  }
};

// Sums over one plane's points in the grid frame.
struct PlaneMoments {
  double n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, syy = 0, szz = 0;
  void Add(const Eigen::Vector3f& p) {
    n += 1;
    sx += p.x();
    sy += p.y();
    sz += p.z();
    szz += double(p.z()) * p.z();
    sxx += double(p.x()) * p.x();
    sxy += double(p.x()) * p.y();
    syy += double(p.y()) * p.y();
  }
};

// LabelParams::face_clip: where a floor candidate meets a vertical face in the image, its
// points smeared past the face lose their height (a floor's behind the face at its foot, a
// top's before the face at its top). A clip holds the face in the grid frame: a point p is
// clipped if lo < n.p + d < hi (n horizontal, towards the camera) and along_lo < u.p < along_hi
// (u horizontal, along the face).
struct FaceClip {
  int floor_plane = -1;
  Eigen::Vector3f n, u;
  float d = 0, lo = 0, hi = 0, along_lo = 0, along_hi = 0;
};

std::vector<FaceClip> FaceClips(const LabelParams& params, const PlaneSet& planes,
                                const Eigen::Isometry3d& X_GC, const std::vector<float>& plane_h,
                                const std::vector<PlaneMoments>& moments) {
  const int num_planes = int(planes.planes.size());
  const double cos_tilt = std::cos(params.max_tilt_deg * M_PI / 180.0);
  // vertical planes (within max_tilt_deg) of at least ten points: horizontal normal and
  // direction along them in the grid frame; from their points' moments, the mean and spread of
  // the height and of the position along them, and the mean offset n.p
  struct Face {
    bool vertical = false;
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), u = Eigen::Vector3d::Zero();
    double offset = 0, mz = 0, rz = 0, mt = 0, rt = 0;
  };
  std::vector<Face> faces(static_cast<size_t>(num_planes));
  bool any = false;
  for (int k = 0; k < num_planes; ++k) {
    Face& f = faces[size_t(k)];
    const PlaneMoments& m = moments[size_t(k)];
    f.n = X_GC.linear() * planes.planes[size_t(k)].n;
    f.n.z() = 0;
    if (f.n.norm() < cos_tilt || m.n < 10) continue;  // |horizontal part| = cos(tilt)
    f.n.normalize();
    f.u = Eigen::Vector3d(-f.n.y(), f.n.x(), 0);
    f.vertical = any = true;
    // the extents of a uniformly covered face: mean +- sqrt(3) standard deviations
    const double ux = f.u.x(), uy = f.u.y();
    f.offset = (f.n.x() * m.sx + f.n.y() * m.sy) / m.n;
    f.mz = m.sz / m.n;
    f.rz = std::sqrt(3.0 * std::max(0.0, m.szz / m.n - f.mz * f.mz));
    f.mt = (ux * m.sx + uy * m.sy) / m.n;
    const double stt = ux * ux * m.sxx + 2 * ux * uy * m.sxy + uy * uy * m.syy;
    f.rt = std::sqrt(3.0 * std::max(0.0, stt / m.n - f.mt * f.mt));
  }
  if (!any) return {};
  // floor candidates and faces that touch in the image: within two pixels along a row or a
  // column (trading points may leave a pixel between them)
  const LabelImage& lab = planes.labels;
  constexpr uint8_t kFloor = 1, kFace = 2;
  std::vector<uint8_t> role(size_t(num_planes), 0);
  for (int k = 0; k < num_planes; ++k) {
    role[size_t(k)] = uint8_t((plane_h[size_t(k)] != kNegInf ? kFloor : 0) |
                              (faces[size_t(k)].vertical ? kFace : 0));
  }
  std::vector<std::pair<int, int>> touch;  // (floor candidate, face), repeated
  std::pair<int, int> last(-1, -1);
  auto pair = [&](int a, uint8_t ra, int b) {
    if (b == a || b < 0 || b >= num_planes) return;
    const uint8_t rb = role[size_t(b)];
    if ((ra & kFloor) && (rb & kFace) && last != std::pair(a, b)) touch.push_back(last = {a, b});
    if ((rb & kFloor) && (ra & kFace) && last != std::pair(b, a)) touch.push_back(last = {b, a});
  };
  const int width = lab.width, height = lab.height;
  std::vector<uint8_t> edge(size_t(width) + 8, 0);  // of a row: a label differs within reach
  for (int v = 0; v < height; ++v) {
    const int32_t* row = lab.data.data() + size_t(v) * size_t(width);
    // where the label is the same two pixels on and down, nothing touches (a fast first pass)
    const int32_t* down1 = v + 1 < height ? row + width : row;
    const int32_t* down2 = v + 2 < height ? row + 2 * width : row;
    const int inner = std::max(0, width - 2);
    for (int u = 0; u < inner; ++u) {
      edge[size_t(u)] = uint8_t((row[u] != row[u + 1]) | (row[u] != row[u + 2]) |
                                (row[u] != down1[u]) | (row[u] != down2[u]));
    }
    for (int u = inner; u < width; ++u) edge[size_t(u)] = 1;
    for (int u = 0; u < width; ++u) {
      if (!edge[size_t(u)]) {
        uint64_t block;  // skip eight inner pixels at once
        std::memcpy(&block, &edge[size_t(u)], 8);
        if (block == 0) u += 7;
        continue;
      }
      const int a = row[u];
      if (a < 0 || a >= num_planes || role[size_t(a)] == 0) continue;
      const uint8_t ra = role[size_t(a)];
      if (u + 1 < width) pair(a, ra, row[u + 1]);
      if (u + 2 < width) pair(a, ra, row[u + 2]);
      if (v + 1 < height) pair(a, ra, row[u + width]);
      if (v + 2 < height) pair(a, ra, row[u + 2 * width]);
    }
  }
  std::sort(touch.begin(), touch.end());
  touch.erase(std::unique(touch.begin(), touch.end()), touch.end());
  const double reach = params.face_clip;
  std::vector<FaceClip> clips;
  for (const auto& [a, b] : touch) {
    const Face& f = faces[size_t(b)];
    const double h = plane_h[size_t(a)], mz = f.mz, rz = f.rz;
    FaceClip c;
    c.floor_plane = a;
    c.n = f.n.cast<float>();
    c.u = f.u.cast<float>();
    c.d = float(-f.offset);
    c.along_lo = float(f.mt - f.rt);
    c.along_hi = float(f.mt + f.rt);
    // the floor at the face's foot (nearer its foot than its top: a riser's lower tread)
    // loses its points behind the face, the top it holds (its upper tread) those before it
    const double to_foot = std::abs(h - (mz - rz)), to_top = std::abs(h - (mz + rz));
    if (to_foot < to_top) {
      if (to_foot > reach) continue;
      c.lo = float(-reach);
      c.hi = 0;
    } else {
      if (to_top > reach) continue;
      c.lo = 0;
      c.hi = float(reach);
    }
    clips.push_back(c);
  }
  return clips;
}

// The clips in the buckets of a coarse x-y grid that their regions overlap, so that a point
// tests only the clips near it.
class ClipBuckets {
 public:
  explicit ClipBuckets(const std::vector<FaceClip>& clips) {
    if (clips.empty()) return;
    std::vector<Eigen::Vector4f> boxes;  // x0, y0, x1, y1 of each clip's region
    Eigen::Vector4f all(kInf, kInf, -kInf, -kInf);
    for (const FaceClip& c : clips) {
      Eigen::Vector4f box(kInf, kInf, -kInf, -kInf);
      for (float side : {c.lo, c.hi}) {
        for (float along : {c.along_lo, c.along_hi}) {
          const Eigen::Vector2f p = c.n.head<2>() * (side - c.d) + c.u.head<2>() * along;
          box.head<2>() = box.head<2>().cwiseMin(p);
          box.tail<2>() = box.tail<2>().cwiseMax(p);
        }
      }
      boxes.push_back(box);
      all.head<2>() = all.head<2>().cwiseMin(box.head<2>());
      all.tail<2>() = all.tail<2>().cwiseMax(box.tail<2>());
    }
    if (!all.allFinite()) return;
    x0_ = all(0);
    y0_ = all(1);
    nx_ = std::min(kMaxSide, int((all(2) - x0_) / kCell) + 1);
    ny_ = std::min(kMaxSide, int((all(3) - y0_) / kCell) + 1);
    inv_cell_x_ = float(nx_) / std::max(all(2) - x0_, 1e-6f) * 0.999f;
    inv_cell_y_ = float(ny_) / std::max(all(3) - y0_, 1e-6f) * 0.999f;
    // per bucket its clips, each list ended by -1
    std::vector<std::vector<int>> lists(size_t(nx_) * size_t(ny_));
    for (size_t j = 0; j < clips.size(); ++j) {
      const Eigen::Vector4f& b = boxes[j];
      const int bx0 = Bx(b(0)), bx1 = Bx(b(2)), by0 = By(b(1)), by1 = By(b(3));
      for (int by = by0; by <= by1; ++by) {
        for (int bx = bx0; bx <= bx1; ++bx) lists[size_t(by * nx_ + bx)].push_back(int(j));
      }
    }
    first_.resize(lists.size());
    for (size_t b = 0; b < lists.size(); ++b) {
      first_[b] = int(clip_.size());
      clip_.insert(clip_.end(), lists[b].begin(), lists[b].end());
      clip_.push_back(-1);
    }
  }
  // the clips of p's bucket, ended by -1; nullptr if p lies outside every clip's region
  const int* Of(const Eigen::Vector3f& p) const {
    if (first_.empty()) return nullptr;
    const float fx = (p.x() - x0_) * inv_cell_x_, fy = (p.y() - y0_) * inv_cell_y_;
    if (!(fx >= 0 && fy >= 0 && fx < float(nx_) && fy < float(ny_))) return nullptr;
    return clip_.data() + first_[size_t(int(fy) * nx_ + int(fx))];
  }

 private:
  static constexpr float kCell = 0.1f;  // metres
  static constexpr int kMaxSide = 128;
  int Bx(float x) const { return std::clamp(int((x - x0_) * inv_cell_x_), 0, nx_ - 1); }
  int By(float y) const { return std::clamp(int((y - y0_) * inv_cell_y_), 0, ny_ - 1); }
  float x0_ = 0, y0_ = 0, inv_cell_x_ = 0, inv_cell_y_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> first_, clip_;
};

}  // namespace

const char* CellTypeName(CellType type) {
  switch (type) {
    case CellType::kUnknown: return "unknown";
    case CellType::kFloor: return "floor";
    case CellType::kStairs: return "stairs";
    case CellType::kBorder: return "border";
    case CellType::kTunnel: return "tunnel";
    case CellType::kObstacle: return "obstacle";
  }
  return "invalid";
}

double MapState::Probability(int ix, int iy, int iz) const {
  const float l = log_odds[size_t(window.Index(ix, iy)) * size_z + iz];
  return 1.0 - 1.0 / (1.0 + std::exp(double(l)));
}

double MapState::ProbabilityAt(const Eigen::Vector3d& p_G) const {
  int ix, iy;
  window.CellOf(p_G.x(), p_G.y(), &ix, &iy);
  const int iz = LayerOf(p_G.z());
  if (Empty() || !window.Contains(ix, iy) || iz < 0 || iz >= size_z) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return Probability(ix, iy, iz);
}

float MapState::FloorAt(double x, double y) const {
  int ix, iy;
  window.CellOf(x, y, &ix, &iy);
  if (Empty() || !window.Contains(ix, iy)) return kNegInf;
  return floor[size_t(window.Index(ix, iy))];
}

int MapState::LayerOf(double z) const {
  return int(std::floor((z - z_min) / window.resolution));
}

double MapState::LayerBottom(int iz) const { return z_min + iz * window.resolution; }

size_t MapState::MemoryBytes() const {
  return log_odds.capacity() * sizeof(float) + floor.capacity() * sizeof(float) +
         (floor_var.capacity() + obstacle_range.capacity() + free_range.capacity()) *
             sizeof(float) +
         marks.capacity() + (crossed.capacity() + floor_layers.capacity()) * sizeof(uint64_t) +
         scratch.capacity() * sizeof(float) +
         floor_local.capacity() * sizeof(float) + floor_votes.capacity() * sizeof(FloorVote) +
         floor_voted_cells.capacity() * sizeof(int) + floor_frame_marks.capacity() +
         no_floor_frames.capacity() + no_floor_pixels.capacity() * sizeof(uint16_t);
}

std::vector<LabelledPoint> LabelPoints(const LabelParams& params, const PointImage& points_C,
                                       const PlaneSet& planes, const Eigen::Isometry3d& X_GC,
                                       const std::vector<OrientedBox>& body_G,
                                       const Image<uint8_t>* rims) {
  const bool have_labels = !planes.labels.empty();
  if (have_labels) {
    Check(planes.labels.width == points_C.width && planes.labels.height == points_C.height,
          "LabelPoints: label image and point image differ in size");
  }
  if (rims != nullptr) {
    Check(rims->width == points_C.width && rims->height == points_C.height,
          "LabelPoints: rim image and point image differ in size");
  }
  const int num_planes = int(planes.planes.size());
  const Eigen::Matrix3f R_GC = X_GC.linear().cast<float>();
  const Eigen::Vector3f p_GC = X_GC.translation().cast<float>();
  const float max_range2 = std::isfinite(params.max_range)
                               ? float(params.max_range * params.max_range)
                               : std::numeric_limits<float>::infinity();

  std::vector<BodyTest> bodies;
  bodies.reserve(body_G.size());
  for (const OrientedBox& box : body_G) {
    const Eigen::Isometry3d X_BG = box.X_FB.inverse();
    bodies.push_back({X_BG.linear().cast<float>(), X_BG.translation().cast<float>(),
                      (box.half_size.array() + params.self_filter_margin).matrix().cast<float>()});
  }

  // transform, range gate and self-filter; plane moments in the grid frame
  const size_t n = points_C.points.size();
  std::vector<LabelledPoint> out;
  out.reserve(n);
  std::vector<int> plane_of;  // plane index of each kept point, -1 none
  plane_of.reserve(n);
  std::vector<uint8_t> on_rim;  // of each kept point
  on_rim.reserve(n);
  std::vector<PlaneMoments> moments(static_cast<size_t>(num_planes));
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p_C = points_C.points[i];
    if (!PointImage::Valid(p_C) || p_C.squaredNorm() > max_range2) continue;
    const Eigen::Vector3f p_G = R_GC * p_C + p_GC;
    bool on_body = false;
    for (const BodyTest& body : bodies) {
      if (body.Contains(p_G)) {
        on_body = true;
        break;
      }
    }
    if (on_body) continue;
    int label = have_labels ? planes.labels.data[i] : -1;
    if (label >= num_planes) label = -1;
    if (label >= 0) moments[size_t(label)].Add(p_G);
    out.push_back({p_G, kNegInf});
    plane_of.push_back(label);
    const uint8_t rim = rims != nullptr ? rims->data[i] : 0;
    on_rim.push_back(rim != 0 && !(rim == kColumnRim && p_G.z() > params.keep_column_rims_above));
  }

  // floor candidates: horizontal, seen from above (so facing up), at least a sole large
  const double cos_tilt = std::cos(params.max_tilt_deg * M_PI / 180.0);
  std::vector<float> plane_h(size_t(num_planes), kNegInf);
  std::vector<float> plane_sigma(size_t(num_planes), 0.0f);
  for (int k = 0; k < num_planes; ++k) {
    const PlaneMoments& m = moments[size_t(k)];
    if (m.n < 3) continue;
    const Eigen::Vector3d n_G = X_GC.linear() * planes.planes[size_t(k)].n;
    if (n_G.norm() < 1e-9 || std::abs(n_G.z()) < cos_tilt * n_G.norm()) continue;
    const double h = m.sz / m.n;
    if (h >= X_GC.translation().z()) continue;
    if (!internal::SpansAtLeast(m.n, m.sx, m.sy, m.sxx, m.syy, m.sxy, params.min_floor_length,
                                params.min_floor_width)) {
      continue;
    }
    plane_h[size_t(k)] = float(h);
    plane_sigma[size_t(k)] = float(std::max(planes.planes[size_t(k)].rms, params.min_height_sigma));
  }
  const std::vector<FaceClip> clips =
      params.face_clip > 0 ? FaceClips(params, planes, X_GC, plane_h, moments)
                           : std::vector<FaceClip>();
  const ClipBuckets buckets(clips);
  std::vector<uint8_t> has_clip(size_t(num_planes), 0);
  for (const FaceClip& c : clips) has_clip[size_t(c.floor_plane)] = 1;
  size_t kept = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    if (plane_of[i] >= 0) {
      const size_t k = size_t(plane_of[i]);
      out[i].h = plane_h[k];
      if (out[i].h != kNegInf) out[i].h_sigma = plane_sigma[k];
      const int* bucket = has_clip[k] ? buckets.Of(out[i].p_G) : nullptr;
      for (; bucket != nullptr && *bucket >= 0 && out[i].h != kNegInf; ++bucket) {
        const FaceClip& c = clips[size_t(*bucket)];
        if (c.floor_plane != int(k)) continue;
        const Eigen::Vector3f& p = out[i].p_G;
        const float side = c.n.dot(p) + c.d, along = c.u.dot(p);
        if (side > c.lo && side < c.hi && along > c.along_lo && along < c.along_hi) {
          out[i].h = kNegInf;
          out[i].h_sigma = 0;
        }
      }
    }
    if (on_rim[i] && out[i].h == kNegInf) continue;
    out[kept++] = out[i];
  }
  out.resize(kept);
  return out;
}

GridWindow CenteredWindow(const OccupancyParams& params, const Pose2& robot_G) {
  GridWindow w;
  w.size_x = params.size_x;
  w.size_y = params.size_y;
  w.resolution = params.resolution;
  w.origin_ix = int(std::floor(robot_G.x / params.resolution)) - params.size_x / 2;
  w.origin_iy = int(std::floor(robot_G.y / params.resolution)) - params.size_y / 2;
  return w;
}

void ResetMaps(const MapParams& params, const Pose2& robot_G, MapState* state) {
  const OccupancyParams& g = params.grid;
  Check(g.size_x > 0 && g.size_y > 0 && g.size_z > 0 && g.resolution > 0,
        "ResetMaps: grid sizes and resolution must be positive");
  Check(g.size_z <= 64, "ResetMaps: at most 64 layers (a column's layers are one 64-bit mask)");
  state->window = CenteredWindow(g, robot_G);
  state->size_z = g.size_z;
  state->z_min = g.z_min;
  const size_t cells3 = size_t(state->window.NumCells()) * g.size_z;
  state->log_odds.assign(cells3, 0.0f);
  state->floor.assign(size_t(state->window.NumCells()), kNegInf);
  state->floor_var.assign(size_t(state->window.NumCells()), 0.0f);
  state->obstacle_range.assign(size_t(state->window.NumCells()), kInf);
  state->no_floor_frames.assign(size_t(state->window.NumCells()), 0);
  state->marks.assign(cells3, 0);
  state->crossed.assign(size_t(state->window.NumCells()), 0);
  state->scratch.assign(cells3, 0.0f);
}

void ScrollMaps(const MapParams& params, const Pose2& robot_G, MapState* state) {
  const OccupancyParams& g = params.grid;
  MapState& s = *state;
  if (s.Empty() || s.window.size_x != g.size_x || s.window.size_y != g.size_y ||
      s.size_z != g.size_z || s.window.resolution != g.resolution || s.z_min != g.z_min) {
    ResetMaps(params, robot_G, state);
    return;
  }
  const GridWindow next = CenteredWindow(g, robot_G);
  const int dx = next.origin_ix - s.window.origin_ix;
  const int dy = next.origin_iy - s.window.origin_iy;
  if (dx == 0 && dy == 0) return;
  const int nx = g.size_x, ny = g.size_y, nz = g.size_z;

  // new local cell (ix, iy) holds old local cell (ix + dx, iy + dy); the rest is unknown
  std::fill(s.scratch.begin(), s.scratch.end(), 0.0f);
  std::vector<float> floor_next(s.floor.size(), kNegInf);
  std::vector<float> var_next(s.floor.size(), 0.0f);
  std::vector<float> range_next(s.floor.size(), kInf);
  std::vector<uint8_t> no_floor_next(s.floor.size(), 0);
  const int x_begin = std::max(0, -dx), x_end = std::min(nx, nx - dx);
  for (int iy = std::max(0, -dy); iy < std::min(ny, ny - dy); ++iy) {
    if (x_begin >= x_end) break;
    const size_t to = size_t(iy * nx + x_begin);
    const size_t from = size_t((iy + dy) * nx + x_begin + dx);
    const size_t len = size_t(x_end - x_begin);
    std::copy_n(s.log_odds.begin() + from * nz, len * nz, s.scratch.begin() + to * nz);
    std::copy_n(s.floor.begin() + from, len, floor_next.begin() + to);
    std::copy_n(s.floor_var.begin() + from, len, var_next.begin() + to);
    std::copy_n(s.obstacle_range.begin() + from, len, range_next.begin() + to);
    std::copy_n(s.no_floor_frames.begin() + from, len, no_floor_next.begin() + to);
  }
  s.log_odds.swap(s.scratch);
  s.floor.swap(floor_next);
  s.floor_var.swap(var_next);
  s.obstacle_range.swap(range_next);
  s.no_floor_frames.swap(no_floor_next);
  s.window = next;
}

Image<uint8_t> TexturelessPixels(const VoidParams& params, const RgbImage& image) {
  Image<uint8_t> out(image.width, image.height, 0);
  if (image.empty()) return out;
  cv::Mat1b grey(image.height, image.width);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const Rgb& c = image.at(u, v);
      grey(v, u) = uint8_t((299 * c.r + 587 * c.g + 114 * c.b + 500) / 1000);
    }
  }
  const int k = std::max(1, params.texture_window);
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k));
  cv::Mat1b hi, lo;
  cv::dilate(grey, hi, kernel, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
  cv::erode(grey, lo, kernel, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      if (hi(v, u) - lo(v, u) <= params.max_contrast) out.at(u, v) = 255;
    }
  }
  return out;
}

namespace {

// A box of the robot's body with the camera's position in its frame, for EmptyRays' segment
// test (what the rays share is computed once).
struct BodyBox {
  Eigen::Matrix3d R_BG;  // grid frame to box frame
  Eigen::Vector3d o;     // the camera in the box frame
  Eigen::Vector3d half;  // half sizes grown by the margin

  // Whether the segment from the camera to the camera + d (grid frame) meets the box.
  bool Meets(const Eigen::Vector3d& d_G) const {
    double t_in = 0, t_out = 0;
    int face = -1;
    return internal::SlabInterval(o, R_BG * d_G, half, &t_in, &t_out, &face) &&
           std::max(t_in, 0.0) <= std::min(t_out, 1.0);
  }
};

// The boxes of `body_G` grown by `margin` that may hide something from a camera at p_GC: all but
// the one the eyes look out of (the head's).
std::vector<BodyBox> HidingBoxes(const std::vector<OrientedBox>& body_G, double margin,
                                 const Eigen::Vector3d& p_GC) {
  std::vector<BodyBox> boxes;
  for (const OrientedBox& b : body_G) {
    BodyBox box;
    box.R_BG = b.X_FB.linear().transpose();
    box.o = box.R_BG * (p_GC - b.X_FB.translation());
    box.half = b.half_size.array() + margin;
    if ((box.o.cwiseAbs() - box.half).maxCoeff() > 0) boxes.push_back(box);
  }
  return boxes;
}

}  // namespace

std::vector<Eigen::Vector3f> EmptyRays(const VoidParams& params, const PointImage& points_C,
                                       const Image<uint8_t>& textureless,
                                       const CameraIntrinsics& K, const Eigen::Isometry3d& X_GC,
                                       double floor_z, const std::vector<OrientedBox>& body_G,
                                       double body_margin) {
  std::vector<Eigen::Vector3f> rays;
  if (params.min_frames <= 0 || points_C.width == 0 || points_C.height == 0) return rays;
  Check(textureless.width == points_C.width && textureless.height == points_C.height,
        "EmptyRays: texture mask and point image differ in size");
  cv::Mat1b empty(points_C.height, points_C.width);
  for (int v = 0; v < points_C.height; ++v) {
    for (int u = 0; u < points_C.width; ++u) {
      empty(v, u) = !PointImage::Valid(points_C.at(u, v)) && textureless.at(u, v) ? 255 : 0;
    }
  }
  // only regions a min_width_px square fits in (an opening)
  const int k = std::max(1, params.min_width_px);
  cv::morphologyEx(empty, empty, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));
  const Eigen::Matrix3f R = X_GC.linear().cast<float>();
  const Eigen::Vector3f t = X_GC.translation().cast<float>();
  const float tolerance = float(params.floor_tolerance);
  const std::vector<BodyBox> hiding = HidingBoxes(body_G, body_margin, X_GC.translation());
  for (int u = 0; u < points_C.width; ++u) {
    // up the column from the bottom row: an empty pixel counts where the nearest point below it
    // lies on the floor (the floor runs up to the emptiness, as at a drop); in a column that is
    // empty from top to bottom every pixel counts (the eyes look beyond the drop)
    bool floor_below = true;
    for (int v = 0; v < points_C.height && floor_below; ++v) floor_below = empty(v, u) != 0;
    for (int v = points_C.height - 1; v >= 0; --v) {
      const Eigen::Vector3f& p_C = points_C.at(u, v);
      if (PointImage::Valid(p_C)) {
        floor_below = std::abs((R * p_C + t).z() - float(floor_z)) <= tolerance;
        continue;
      }
      if (empty(v, u) == 0 || !floor_below) continue;
      const Eigen::Vector3f d_C(float((u - K.cx) / K.fx), float((v - K.cy) / K.fy), 1.0f);
      const Eigen::Vector3f d_G = R * d_C;
      if (d_G.z() >= 0.0f) continue;
      // the robot's own body, untextured and without range, hides the floor along this ray
      const Eigen::Vector3d to_floor =
          d_G.cast<double>() * ((floor_z - X_GC.translation().z()) / double(d_G.z()));
      if (std::any_of(hiding.begin(), hiding.end(),
                      [&](const BodyBox& b) { return b.Meets(to_floor); })) {
        continue;
      }
      rays.push_back(d_G);
    }
  }
  return rays;
}

namespace {

// VoidParams: this frame's empty rays to the floor plane, one frame of evidence per cell they
// meet often enough; floor heights they contradict are dropped (VoidParams::drop_floor)
void UpdateNoFloor(const MapParams& map_params, const MapInput& input, MapState* state) {
  const VoidParams& params = map_params.no_floor;
  MapState& s = *state;
  if (params.min_frames <= 0 || input.empty_rays_G.empty()) return;
  const GridWindow& w = s.window;
  s.no_floor_pixels.assign(size_t(w.NumCells()), 0);
  const Eigen::Vector3d& c = input.p_GC;
  const double drop = input.floor_z - c.z();  // negative: the camera is above the floor
  if (!(drop < 0)) return;
  for (const Eigen::Vector3f& d : input.empty_rays_G) {
    if (!d.allFinite() || !(d.z() < 0)) continue;  // meets no floor below the camera
    const double t = drop / double(d.z());
    if (t * double(d.norm()) < params.min_distance) continue;
    const double x = c.x() + t * double(d.x()), y = c.y() + t * double(d.y());
    if (std::hypot(x - c.x(), y - c.y()) > params.range) continue;
    int ix, iy;
    w.CellOf(x, y, &ix, &iy);
    if (!w.Contains(ix, iy)) continue;
    uint16_t& n = s.no_floor_pixels[size_t(w.Index(ix, iy))];
    if (n < 0xffff) ++n;
  }
  constexpr float kNegInf = -std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < s.no_floor_pixels.size(); ++i) {
    if (s.no_floor_pixels[i] < params.min_pixels) continue;
    const bool has_floor = s.floor[i] != kNegInf;
    // a frame whose floor points fell in the cell does not contradict its floor
    if (params.drop_floor && has_floor &&
        (s.floor_frame_marks[i] & internal::kFloorVoted) != 0) {
      continue;
    }
    if (s.no_floor_frames[i] < 255) ++s.no_floor_frames[i];
    if (params.drop_floor && has_floor && s.no_floor_frames[i] >= params.min_frames &&
        std::abs(s.floor[i] - input.floor_z) <= params.floor_tolerance) {
      // eq. (20) would drop the height once the grid no longer holds it: the layers that
      // hold it lose their evidence (P 0.5 at most)
      int lo, hi;
      internal::LayersNear(s, s.floor[i], map_params.floor.verify_tolerance, &lo, &hi);
      float* column = s.log_odds.data() + i * size_t(s.size_z);
      for (int iz = std::max(lo, 0); iz <= std::min(hi, s.size_z - 1); ++iz) {
        column[iz] = std::min(column[iz], 0.0f);
      }
      s.floor[i] = kNegInf;
      s.floor_var[i] = 0;
    }
  }
}

}  // namespace

void UpdateMaps(const MapParams& params, const MapInput& input, MapState* state) {
  ScrollMaps(params, input.robot_G, state);
  internal::UpdateOccupancy(params.grid, params.floor.verify_tolerance, input, state);
  internal::UpdateFloorMap(params, input, state);
  UpdateNoFloor(params, input, state);
}

}  // namespace fognav::perception

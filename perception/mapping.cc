#include "perception/mapping.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <Eigen/Eigenvalues>

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
  double n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, syy = 0;
  void Add(const Eigen::Vector3f& p) {
    n += 1;
    sx += p.x();
    sy += p.y();
    sz += p.z();
    sxx += double(p.x()) * p.x();
    sxy += double(p.x()) * p.y();
    syy += double(p.y()) * p.y();
  }
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
         marks.capacity() + scratch.capacity() * sizeof(float) +
         floor_local.capacity() * sizeof(float) + floor_votes.capacity() * sizeof(FloorVote) +
         floor_voted_cells.capacity() * sizeof(int) + floor_frame_marks.capacity();
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
  size_t kept = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    if (plane_of[i] >= 0) {
      out[i].h = plane_h[size_t(plane_of[i])];
      if (out[i].h != kNegInf) out[i].h_sigma = plane_sigma[size_t(plane_of[i])];
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
  state->window = CenteredWindow(g, robot_G);
  state->size_z = g.size_z;
  state->z_min = g.z_min;
  const size_t cells3 = size_t(state->window.NumCells()) * g.size_z;
  state->log_odds.assign(cells3, 0.0f);
  state->floor.assign(size_t(state->window.NumCells()), kNegInf);
  state->floor_var.assign(size_t(state->window.NumCells()), 0.0f);
  state->obstacle_range.assign(size_t(state->window.NumCells()), kInf);
  state->marks.assign(cells3, 0);
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
  }
  s.log_odds.swap(s.scratch);
  s.floor.swap(floor_next);
  s.floor_var.swap(var_next);
  s.obstacle_range.swap(range_next);
  s.window = next;
}

void UpdateMaps(const MapParams& params, const MapInput& input, MapState* state) {
  ScrollMaps(params, input.robot_G, state);
  internal::UpdateOccupancy(params.grid, params.floor.verify_tolerance, input, state);
  internal::UpdateFloorMap(params, input, state);
}

}  // namespace fognav::perception

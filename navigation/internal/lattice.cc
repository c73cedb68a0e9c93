#include "navigation/internal/lattice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "navigation/internal/open_list.h"

namespace fognav::navigation::internal {
namespace {

using perception::CellType;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 1e-9;

// The range of the known floor heights under the soles: they stand level when it spans at most
// h_floor. Each cell within h_floor of the origin's alone lets a cell across a riser, whose
// height the map averages between the two treads, join both treads (a 2 cm rise, the cell at
// 3 cm, both treads within 1.5 cm of it) and a sole stand across the riser.
class Spread {
 public:
  explicit Spread(float h) { Add(h, kInf); }
  // Takes height h in (unknown and -infinity are not heights); whether the range stays within
  // `limit`.
  bool Add(float h, double limit) {
    if (!std::isfinite(h)) return true;
    lo_ = std::min(lo_, double(h));
    hi_ = std::max(hi_, double(h));
    return hi_ - lo_ <= limit;
  }

 private:
  double lo_ = kInf, hi_ = -kInf;
};

[[noreturn]] void Die(const char* what) {
  std::fprintf(stderr, "fognav::navigation: %s\n", what);
  std::abort();
}

// felzenszwalb & huttenlocher's lower envelope of parabolas, one line of the transform
void Transform1d(const double* f, int n, int stride, double* d, std::vector<int>* v_buf,
                 std::vector<double>* z_buf) {
  std::vector<int>& v = *v_buf;
  std::vector<double>& z = *z_buf;
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  auto fq = [&](int q) { return f[size_t(q) * size_t(stride)]; };
  for (int q = 1; q < n; ++q) {
    // intersection of the parabola from q with the rightmost one of the envelope
    auto meet = [&](int r) {
      return ((fq(q) + double(q) * q) - (fq(r) + double(r) * r)) / (2.0 * q - 2.0 * r);
    };
    double s = meet(v[size_t(k)]);
    while (s <= z[size_t(k)]) {
      --k;
      s = meet(v[size_t(k)]);
    }
    ++k;
    v[size_t(k)] = q;
    z[size_t(k)] = s;
    z[size_t(k) + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[size_t(k) + 1] < q) ++k;
    const int r = v[size_t(k)];
    d[size_t(q) * size_t(stride)] = double(q - r) * (q - r) + fq(r);
  }
}

}  // namespace

double WrapAngle(double a) {
  while (a > M_PI) a -= 2 * M_PI;
  while (a <= -M_PI) a += 2 * M_PI;
  return a;
}

CellStep HeadingStep(int heading) { return kSteps[heading]; }

double HeadingYaw(int heading) {
  return std::atan2(double(kSteps[heading].dy), double(kSteps[heading].dx));
}

int NearestHeading(double yaw) {
  int best = 0;
  double best_diff = kInf;
  for (int k = 0; k < kNumHeadings; ++k) {
    const double diff = std::abs(WrapAngle(yaw - HeadingYaw(k)));
    if (diff < best_diff) {
      best_diff = diff;
      best = k;
    }
  }
  return best;
}

void SquaredDistanceTransform(const std::vector<uint8_t>& feature, int size_x, int size_y,
                              std::vector<double>* out) {
  const size_t n = size_t(size_x) * size_t(size_y);
  if (feature.size() != n) Die("SquaredDistanceTransform: feature size does not match grid");
  std::vector<double> f(n);
  for (size_t i = 0; i < n; ++i) f[i] = feature[i] ? 0.0 : kFarSquared;
  out->assign(n, kFarSquared);
  const int longest = std::max(size_x, size_y);
  std::vector<int> v(size_t(longest) + 1);
  std::vector<double> z(size_t(longest) + 2);
  std::vector<double> tmp(n);
  // columns (along y), then rows (along x)
  for (int x = 0; x < size_x; ++x) Transform1d(&f[size_t(x)], size_y, size_x, &tmp[size_t(x)], &v, &z);
  for (int y = 0; y < size_y; ++y) {
    Transform1d(&tmp[size_t(y) * size_t(size_x)], size_x, 1, &(*out)[size_t(y) * size_t(size_x)],
                &v, &z);
  }
  for (double& d : *out) {
    if (d >= 0.5 * kFarSquared) d = kFarSquared;
  }
}

uint32_t SearchMemory::Begin(int num_states) {
  // generations live in the upper 28 bits of the stamps; start over before they wrap
  if (generation >= (1u << 27)) {
    generation = 0;
    std::fill(valid_stamp.begin(), valid_stamp.end(), 0u);
    std::fill(search_stamp.begin(), search_stamp.end(), 0u);
  }
  ++generation;
  const size_t n = size_t(num_states);
  if (valid_stamp.size() < n) {
    valid_stamp.resize(n, 0u);
    search_stamp.resize(n, 0u);
    g.resize(n);
    parent.resize(n);
    move.resize(n);
    heap_position.resize(n);
  }
  return generation;
}

Lattice::Lattice(const perception::Fog& fog, const Eigen::Vector2d& goal_G, const PlannerParams& p,
                 SearchMemory* memory, End end, bool heuristic)
    : fog_(fog), p_(p), goal_G_(goal_G), end_(end), memory_(memory ? memory : &own_memory_) {
  const perception::GridWindow& w = fog.window;
  if (w.size_x <= 0 || w.size_y <= 0 || !(w.resolution > 0)) Die("Plan: empty FOG window");
  num_cells_ = w.NumCells();
  if (fog.type.size() != size_t(num_cells_) || fog.height.size() != size_t(num_cells_)) {
    Die("Plan: FOG type/height arrays do not match its window");
  }
  const double min_factor = std::min({p.walk_factor, p.backward_factor, p.sidestep_factor,
                                      p.stairs_factor, p.crawl_factor,
                                      p.crawl_factor * p.backward_factor});
  if (!(min_factor > 0)) Die("Plan: move cost factors must be positive");
  if (!(p.turn_cost_per_rad >= 0 && p.posture_change_cost >= 0 && p.unknown_penalty >= 0 &&
        p.clearance_weight >= 0 && p.exit_factor >= 0)) {
    Die("Plan: turn, posture change, unknown, clearance and exit costs must not be negative");
  }
  if (!(p.clearance_height_ref > 0)) Die("Plan: clearance_height_ref must be positive");
  if (!(p.exit_band >= 0)) Die("Plan: exit_band must not be negative");
  if (!(p.max_step_length > 0)) Die("Plan: max_step_length must be positive");
  if (!(p.max_step_sideways >= 0)) Die("Plan: max_step_sideways must not be negative");
  if (!(p.level_margin >= 0 && p.level_margin <= p.margin)) {
    Die("Plan: level_margin must be in [0, margin]");
  }
  if (!(p.stance_width > 0)) Die("Plan: stance_width must be positive");
  if (!(p.hand_low >= 0)) Die("Plan: hand_low must not be negative");
  if (!(p.hidden_reach >= 0 && p.hidden_reach <= 1.0)) {
    Die("Plan: hidden_reach must lie in [0, 1] m");
  }
  if (!(p.head_reach >= 0)) Die("Plan: head_reach must not be negative");
  if (!(p.kneel_offset >= 0)) Die("Plan: kneel_offset must not be negative");
  if (!(p.kneel_clear_reach >= 0)) Die("Plan: kneel_clear_reach must not be negative");
  static_cast<LatticeShapes&>(*this) = CachedShapes(p, w.resolution);
  for (int k = 0; k < kNumHeadings; ++k) {
    footprint_index_[k].clear();
    for (const CellStep& o : footprint_[0][k]) {
      footprint_index_[k].push_back(o.dy * w.size_x + o.dx);
    }
  }

  ComputeFloorHeights();
  head_meets_.assign(size_t(num_cells_), 0);
  ComputeLevelRanges();
  ComputePermissions();
  ComputeCellCosts();
  valid_generation_ = memory_->Begin(NumStates());
  heuristic_on_ = heuristic;
  SetEnd(end);
}

void Lattice::SetEnd(End end) {
  const perception::GridWindow& w = fog_.window;
  int gx = 0, gy = 0;
  w.CellOf(goal_G_.x(), goal_G_.y(), &gx, &gy);
  end_ = end;
  goal_in_window_ = end == End::kGoal && w.Contains(gx, gy);
  if (!w.Contains(gx, gy) && end_ == End::kGoal) end_ = End::kExit;
  has_end_ = false;
  ComputeTerminalCosts();
  if (heuristic_on_) {
    ComputeHeuristic();
  } else {
    heuristic_.assign(2 * size_t(num_cells_), 0.0);
  }
}

void Lattice::ComputePermissions() {
  const perception::GridWindow& w = fog_.window;
  const size_t n = size_t(num_cells_);
  // crawl zone: tunnel cells, floor cells whose headroom the map has not seen (a ceiling seen
  // only in part may go on there) and floor cells near either
  std::vector<uint8_t> tunnel(n), ceiling(n);
  const bool use_headroom = p_.get_up_under_seen_headroom && !fog_.headroom_seen.empty();
  for (size_t i = 0; i < n; ++i) {
    tunnel[i] = fog_.type[i] == CellType::kTunnel;
    ceiling[i] = tunnel[i] || (use_headroom && fog_.type[i] == CellType::kFloor &&
                               !fog_.headroom_seen[i]);
  }
  SquaredDistanceTransform(tunnel, w.size_x, w.size_y, &tunnel_d2_);
  std::vector<uint8_t> unknown(n);
  for (size_t i = 0; i < n; ++i) unknown[i] = UnseenUnwalked(i);
  SquaredDistanceTransform(unknown, w.size_x, w.size_y, &unknown_d2_);
  SquaredDistanceTransform(ceiling, w.size_x, w.size_y, &zone_d2_);
  const double zone_cells = p_.crawl_zone_radius / w.resolution;
  zone_d2_max_ = zone_cells * zone_cells + kEps;
  ok_[0].assign(n, 0);
  ok_[1].assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const CellType t = fog_.type[i];
    ok_[0][i] = t == CellType::kFloor || t == CellType::kStairs || t == CellType::kUnknown;
    ok_[1][i] = t == CellType::kTunnel ||
                ((t == CellType::kFloor || t == CellType::kUnknown) &&
                 zone_d2_[i] <= zone_d2_max_);
  }
  // border cells may lie under a standing robot, and in the crawl zone under a crawling one, on
  // their own level (see FootprintFits), so they count as blocked for the "certainly fits" test
  // but not for the "certainly blocked" one
  for (int q = 0; q < 2; ++q) {
    std::vector<uint8_t> blocked(n);
    for (size_t i = 0; i < n; ++i) blocked[i] = !ok_[q][i];
    SquaredDistanceTransform(blocked, w.size_x, w.size_y, &maybe_blocked_d2_[q]);
    for (size_t i = 0; i < n; ++i) blocked[i] = blocked[i] && !MayBeLevelBorder(i, q);
    SquaredDistanceTransform(blocked, w.size_x, w.size_y, &blocked_d2_[q]);
  }
}

void Lattice::ComputeCellCosts() {
  const perception::GridWindow& w = fog_.window;
  cell_cost_.assign(size_t(num_cells_), 0.0);
  // falloff disc, in cells, row by row: row dy spans dx in [-half[dy + r], half[dy + r]] (half
  // -1 for an empty row), its falloffs at falloff[(dy + r) * (2 r + 1) + dx + r]
  const double radius_cells = p_.clearance_radius / w.resolution;
  const int r = int(std::ceil(radius_cells));
  const bool disc = p_.clearance_weight > 0 && radius_cells > 0;
  const int span = 2 * r + 1;
  std::vector<int> half(size_t(span), -1);
  std::vector<double> falloff(size_t(span) * size_t(span), 0.0);
  for (int dy = -r; dy <= r && disc; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const double d = std::hypot(double(dx), double(dy));
      if (!(d < radius_cells)) continue;
      half[size_t(dy + r)] = std::max(half[size_t(dy + r)], std::abs(dx));
      falloff[size_t(dy + r) * size_t(span) + size_t(dx + r)] = 1.0 - d / radius_cells;
    }
  }
  auto blocking = [](CellType t) { return t == CellType::kObstacle || t == CellType::kBorder; };
  auto has_floor = [](CellType t) {
    return t == CellType::kFloor || t == CellType::kStairs || t == CellType::kTunnel ||
           t == CellType::kBorder;
  };
  for (int iy = 0; iy < w.size_y && disc; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      const CellType t = fog_.type[i];
      if (!blocking(t)) continue;
      // only cells on the rim of a blocked blob: the inner ones are farther from any free cell
      bool rim = false;
      double ref_floor = -kInf, low_floor = kInf;
      for (int ny = iy - 1; ny <= iy + 1; ++ny) {
        for (int nx = ix - 1; nx <= ix + 1; ++nx) {
          if (!w.Contains(nx, ny) || (nx == ix && ny == iy)) continue;
          const size_t j = size_t(w.Index(nx, ny));
          if (!blocking(fog_.type[j])) rim = true;
          if (has_floor(fog_.type[j]) && std::isfinite(fog_.height[j])) {
            ref_floor = std::max(ref_floor, double(fog_.height[j]));
            low_floor = std::min(low_floor, double(fog_.height[j]));
          }
        }
      }
      if (!rim) continue;
      double rel = p_.clearance_height_cap;
      if (t == CellType::kBorder) {
        // the upper edge of a drop stands as high above the floor below as the drop is deep
        rel = std::isfinite(low_floor) && std::isfinite(fog_.height[i])
                  ? double(fog_.height[i]) - low_floor
                  : p_.h_stairs;
      } else if (std::isfinite(fog_.height[i]) && std::isfinite(ref_floor)) {
        rel = double(fog_.height[i]) - ref_floor;
      }
      rel = std::clamp(rel, 0.0, p_.clearance_height_cap);
      const double weight = p_.clearance_weight * rel / p_.clearance_height_ref;
      if (!(weight > 0)) continue;
      for (int ny = std::max(0, iy - r); ny <= std::min(w.size_y - 1, iy + r); ++ny) {
        const int m = half[size_t(ny - iy + r)];
        const int x0 = std::max(0, ix - m), x1 = std::min(w.size_x - 1, ix + m);
        double* cost = &cell_cost_[size_t(w.Index(0, ny))];
        const double* row = &falloff[size_t(ny - iy + r) * size_t(span) + size_t(r)];  // dx = 0
        for (int nx = x0; nx <= x1; ++nx) cost[nx] = std::max(cost[nx], weight * row[nx - ix]);
      }
    }
  }
  for (size_t i = 0; i < size_t(num_cells_); ++i) {
    if (fog_.type[i] == CellType::kUnknown) cell_cost_[i] += p_.unknown_penalty;
  }
}

void Lattice::ComputeFloorHeights() {
  // known floor heights; unknown cells take the height of the nearest known floor (breadth
  // first over unknown cells), so a step hidden by an unknown cell is still seen as a step.
  // Walkable cells (floor, stairs, tunnel) fill first; border cells fill only the unknown cells
  // that no walkable cell reaches: a border cell is the rim of a height change, so the unknown
  // cells beyond it (behind a wall whose top was seen) lie on another level than the rim
  const perception::GridWindow& w = fog_.window;
  const size_t n = size_t(num_cells_);
  floor_h_.assign(n, -std::numeric_limits<float>::infinity());
  std::vector<int> walkable, border;
  for (size_t i = 0; i < n; ++i) {
    const CellType t = fog_.type[i];
    if (t == CellType::kObstacle || t == CellType::kUnknown || !std::isfinite(fog_.height[i])) {
      continue;
    }
    floor_h_[i] = fog_.height[i];
    (t == CellType::kBorder ? border : walkable).push_back(int(i));
  }
  auto fill_from = [&](std::vector<int> frontier) {
    for (size_t next = 0; next < frontier.size(); ++next) {
      const int i = frontier[next];
      const int ix = i % w.size_x, iy = i / w.size_x;
      const int nx[4] = {ix + 1, ix - 1, ix, ix}, ny[4] = {iy, iy, iy + 1, iy - 1};
      for (int k = 0; k < 4; ++k) {
        if (!w.Contains(nx[k], ny[k])) continue;
        const size_t j = size_t(w.Index(nx[k], ny[k]));
        if (fog_.type[j] != CellType::kUnknown || std::isfinite(floor_h_[j])) continue;
        floor_h_[j] = floor_h_[size_t(i)];
        frontier.push_back(int(j));
      }
    }
  };
  fill_from(std::move(walkable));
  fill_from(std::move(border));
}

void Lattice::ComputeLevelRanges() {
  // lowest and highest known floor height in the square around each cell that holds every
  // standing footprint, separably: along x, then along y
  const perception::GridWindow& w = fog_.window;
  const size_t n = size_t(num_cells_);
  const int r = std::max(outer_reach_cells_[0], body_reach_cells_);
  constexpr float kFloatInf = std::numeric_limits<float>::infinity();
  std::vector<float> row_lo(n, kFloatInf), row_hi(n, -kFloatInf);
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      float lo = kFloatInf, hi = -kFloatInf;
      for (int x = std::max(0, ix - r); x <= std::min(w.size_x - 1, ix + r); ++x) {
        const size_t j = size_t(w.Index(x, iy));
        const CellType t = fog_.type[j];
        if (t == CellType::kUnknown || t == CellType::kObstacle || !std::isfinite(fog_.height[j])) {
          continue;
        }
        lo = std::min(lo, fog_.height[j]);
        hi = std::max(hi, fog_.height[j]);
      }
      row_lo[size_t(w.Index(ix, iy))] = lo;
      row_hi[size_t(w.Index(ix, iy))] = hi;
    }
  }
  level_lo_.assign(n, kFloatInf);
  level_hi_.assign(n, -kFloatInf);
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      float lo = kFloatInf, hi = -kFloatInf;
      for (int y = std::max(0, iy - r); y <= std::min(w.size_y - 1, iy + r); ++y) {
        lo = std::min(lo, row_lo[size_t(w.Index(ix, y))]);
        hi = std::max(hi, row_hi[size_t(w.Index(ix, y))]);
      }
      level_lo_[size_t(w.Index(ix, iy))] = lo;
      level_hi_[size_t(w.Index(ix, iy))] = hi;
    }
  }
  // per unknown or border cell: the highest floor, stairs or border cell within hidden_reach
  // (the edge of a solid's top seen from one side, or placed a cell short; not obstacle cells,
  // which stray stereo matches make too)
  hidden_top_.assign(n, -kFloatInf);
  const int hr = int(std::lround(p_.hidden_reach / w.resolution));
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      if (fog_.type[i] != CellType::kUnknown && fog_.type[i] != CellType::kBorder) continue;
      float top = -kFloatInf;
      for (int y = std::max(0, iy - hr); y <= std::min(w.size_y - 1, iy + hr); ++y) {
        for (int x = std::max(0, ix - hr); x <= std::min(w.size_x - 1, ix + hr); ++x) {
          const size_t j = size_t(w.Index(x, y));
          const CellType t = fog_.type[j];
          if ((t == CellType::kBorder || t == CellType::kFloor || t == CellType::kStairs) &&
              std::isfinite(fog_.height[j])) {
            top = std::max(top, fog_.height[j]);
          }
        }
      }
      hidden_top_[i] = top;
    }
  }
  // the highest of them in the square around each cell that holds the standing body (row_hi
  // holds the rows' maxima)
  std::vector<float>& row_hidden = row_hi;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      float hi = -kFloatInf;
      for (int x = std::max(0, ix - r); x <= std::min(w.size_x - 1, ix + r); ++x) {
        hi = std::max(hi, hidden_top_[size_t(w.Index(x, iy))]);
      }
      row_hidden[size_t(w.Index(ix, iy))] = hi;
    }
  }
  hidden_hi_.assign(n, -kFloatInf);
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      float hi = -kFloatInf;
      for (int y = std::max(0, iy - r); y <= std::min(w.size_y - 1, iy + r); ++y) {
        hi = std::max(hi, row_hidden[size_t(w.Index(ix, y))]);
      }
      hidden_hi_[size_t(w.Index(ix, iy))] = hi;
    }
  }
}

double Lattice::HeightStep(int from_cell, int to_cell) const {
  const float a = floor_h_[size_t(from_cell)], b = floor_h_[size_t(to_cell)];
  if (!std::isfinite(a) || !std::isfinite(b)) return 0.0;
  return double(b) - double(a);
}

Eigen::Vector2d Lattice::FloorGradient(int cell) const {
  const perception::GridWindow& w = fog_.window;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  auto floor_at = [&](int x, int y, double* h) {
    if (!w.Contains(x, y)) return false;
    const size_t i = size_t(w.Index(x, y));
    const CellType t = fog_.type[i];
    if (t == CellType::kObstacle || t == CellType::kUnknown || !std::isfinite(fog_.height[i])) {
      return false;
    }
    *h = fog_.height[i];
    return true;
  };
  auto diff = [&](int dx, int dy) {
    double lo = 0, hi = 0, mid = 0;
    const bool has_lo = floor_at(ix - dx, iy - dy, &lo), has_hi = floor_at(ix + dx, iy + dy, &hi);
    const bool has_mid = floor_at(ix, iy, &mid);
    if (has_lo && has_hi) return 0.5 * (hi - lo);
    if (has_hi && has_mid) return hi - mid;
    if (has_lo && has_mid) return mid - lo;
    return 0.0;
  };
  return {diff(1, 0), diff(0, 1)};
}

bool Lattice::InGoalRegion(int cell) const {
  const perception::GridWindow& w = fog_.window;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  int gx = 0, gy = 0;
  w.CellOf(goal_G_.x(), goal_G_.y(), &gx, &gy);
  if (ix == gx && iy == gy) return true;
  return (w.CellCenter(ix, iy) - goal_G_).norm() <= p_.goal_tolerance;
}

void Lattice::ComputeTerminalCosts() {
  const perception::GridWindow& w = fog_.window;
  terminal_.assign(size_t(num_cells_), kInf);
  int gx = 0, gy = 0;
  w.CellOf(goal_G_.x(), goal_G_.y(), &gx, &gy);
  if (end_ == End::kBeyond && !w.Contains(gx, gy)) return;  // has_end_ stays false
  const int band_cells = int(std::floor(p_.exit_band / w.resolution + 1e-9));
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const int i = w.Index(ix, iy);
      const auto toward = [&] { return (w.CellCenter(ix, iy) - goal_G_).norm() * p_.exit_factor; };
      if (end_ == End::kToward) {
        terminal_[size_t(i)] = toward();
      } else if (end_ == End::kExit) {
        const int b = band_cells;  // on a side beyond which the goal lies
        const bool exit = (ix <= b && gx < 0) || (iy <= b && gy < 0) ||
                          (ix >= w.size_x - 1 - b && gx >= w.size_x) ||
                          (iy >= w.size_y - 1 - b && gy >= w.size_y);
        if (exit) terminal_[size_t(i)] = toward();
      } else if (InGoalRegion(i)) {
        terminal_[size_t(i)] = 0.0;
      }
    }
  }
  if (end_ == End::kBeyond) ComputeBeyondTerminalCosts();
  has_end_ = std::any_of(terminal_.begin(), terminal_.end(), [](double t) { return t < kInf; });
}

void Lattice::ComputeBeyondTerminalCosts() {
  const perception::GridWindow& w = fog_.window;
  // the goal's region: the cells a walk or crawl over floor, stairs, tunnel and unknown cells
  // reaches from the goal region, never across a border cell or a rise of more than h_stairs
  // (so it does not climb a wall's top, as the heuristic's relaxed graph may through the
  // heights of border cells); each cell's cost is its distance from the goal at walk_factor
  const size_t n = size_t(num_cells_);
  auto passable = [&](size_t i) {
    const CellType t = fog_.type[i];
    return t == CellType::kFloor || t == CellType::kStairs || t == CellType::kTunnel ||
           t == CellType::kUnknown;
  };
  std::vector<double> cost(n, kInf);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (size_t i = 0; i < n; ++i) {
    if (terminal_[i] == 0.0 && passable(i)) {
      cost[i] = 0.0;
      queue.push({0.0, int(i)});
    }
  }
  while (!queue.empty()) {
    const auto [c, i] = queue.top();
    queue.pop();
    if (c > cost[size_t(i)]) continue;
    const int ix = i % w.size_x, iy = i / w.size_x;
    for (int k = 0; k < kNumHeadings; k += 2) {  // the 8 neighbours
      const int jx = ix + kSteps[k].dx, jy = iy + kSteps[k].dy;
      if (!w.Contains(jx, jy)) continue;
      const size_t j = size_t(w.Index(jx, jy));
      if (!passable(j)) continue;
      const float hi = floor_h_[size_t(i)], hj = floor_h_[j];
      if (std::isfinite(hi) && std::isfinite(hj) &&
          std::abs(double(hj) - double(hi)) > p_.h_stairs) {
        continue;
      }
      const double cj = c + step_length_[k] * p_.walk_factor;
      if (cj < cost[j]) {
        cost[j] = cj;
        queue.push({cj, int(j)});
      }
    }
  }
  // the window's edge: where the region meets it, and every edge cell priced by those
  std::vector<int> edge;
  for (int ix = 0; ix < w.size_x; ++ix) {
    edge.push_back(w.Index(ix, 0));
    if (w.size_y > 1) edge.push_back(w.Index(ix, w.size_y - 1));
  }
  for (int iy = 1; iy + 1 < w.size_y; ++iy) {
    edge.push_back(w.Index(0, iy));
    if (w.size_x > 1) edge.push_back(w.Index(w.size_x - 1, iy));
  }
  std::vector<std::pair<Eigen::Vector2d, double>> reached;  // edge cell centre, its cost
  for (const int i : edge) {
    if (cost[size_t(i)] < kInf) {
      reached.push_back({w.CellCenter(i % w.size_x, i / w.size_x), cost[size_t(i)]});
    }
  }
  terminal_.assign(n, kInf);
  for (const int i : edge) {
    const Eigen::Vector2d c = w.CellCenter(i % w.size_x, i / w.size_x);
    for (const auto& [b, h] : reached) {
      terminal_[size_t(i)] = std::min(terminal_[size_t(i)], h + (c - b).norm() * p_.exit_factor);
    }
  }
}

void Lattice::ComputeHeuristic() {
  // exact cost-to-go on a relaxed graph of cells x posture: the same cell steps, per-metre
  // costs at the lowest factor any move of that posture can have there (standing on stairs
  // costs at least stairs_factor), posture changes at their cost, turns free, no footprint
  // orientation, a cell open for a posture unless it is certainly blocked for it, and standing
  // steps between cells whose floor heights differ by at most h_stairs + 2 h_floor. Every 3D
  // edge maps to a relaxed path that costs no more (a step up or down of m lattice steps to the
  // m relaxed steps along its line, whose cells its sweep keeps open and within h_floor of its
  // two levels; one a little across its heading to a relaxed edge of its own at the stairs
  // factor without cell costs), so this is admissible and consistent. The Dijkstra that
  // computes it settles nodes only as far as Heuristic asks (SettleNext).
  const size_t n = size_t(num_cells_);
  h_open_.assign(2 * n, 0);
  for (size_t i = 0; i < n; ++i) {
    for (int q = 0; q < 2; ++q) {
      const double in = inner_radius_cells_[q] - kEps;
      const bool centre_ok = ok_[q][i] || MayBeLevelBorder(i, q);
      h_open_[2 * i + size_t(q)] = centre_ok && !(in > 0 && blocked_d2_[q][i] <= in * in);
    }
  }
  // the climbs across their heading, which no line of lattice steps follows, in both directions
  h_aside_.clear();
  for (int k = 0; k < kNumHeadings; ++k) {
    for (const Climb& c : climbs_[k]) {
      if (std::abs(c.across) <= kEps) continue;
      const bool known = std::any_of(h_aside_.begin(), h_aside_.end(), [&](const auto& e) {
        return e.first.dx == c.to.dx && e.first.dy == c.to.dy;
      });
      if (!known) h_aside_.push_back({c.to, c.length});
    }
  }
  // Dijkstra from every end node at once; a node is queued while its stamp is 1, done at 2
  heuristic_.assign(2 * n, kInf);
  h_stamp_.assign(2 * n, 0);
  h_position_.resize(2 * n);
  h_heap_.clear();
  h_heap_.reserve(2 * n);
  for (size_t node = 0; node < 2 * n; ++node) {
    if (h_open_[node]) Relax(int(node), terminal_[node / 2]);
  }
}

void Lattice::Relax(int node, double h) {
  if (h_stamp_[size_t(node)] == 2 || h >= heuristic_[size_t(node)]) return;
  heuristic_[size_t(node)] = h;
  OpenList(&h_heap_, &h_position_, /*clear=*/false)
      .Push({h, 0.0f, node}, h_stamp_[size_t(node)] == 1);
  h_stamp_[size_t(node)] = 1;
}

void Lattice::SettleNext() {
  const perception::GridWindow& w = fog_.window;
  const double upright_factor = std::min({p_.walk_factor, p_.backward_factor, p_.sidestep_factor});
  const double stairs_factor = std::max(upright_factor, p_.stairs_factor);
  const double crawl_factor = std::min(p_.crawl_factor, p_.crawl_factor * p_.backward_factor);
  const float* height = floor_h_.data();
  const OpenEntry top = OpenList(&h_heap_, &h_position_, false).Pop();
  const int node = top.state;
  const double h = top.f;
  h_stamp_[size_t(node)] = 2;
  const int i = node / 2, q = node % 2;
  const int ix = i % w.size_x, iy = i / w.size_x;
  // posture changes move the origin by the kneel offset along the heading; the set of
  // offsets is symmetric, so the reversed edges are the same
  for (int k = 0; k < kNumHeadings; ++k) {
    const int px = ix + kneel_steps_[k] * kSteps[k].dx, py = iy + kneel_steps_[k] * kSteps[k].dy;
    if (!w.Contains(px, py)) continue;
    const int other = 2 * w.Index(px, py) + (q ^ 1);
    if (h_open_[size_t(other)]) Relax(other, h + p_.posture_change_cost);
  }
  // a step up or down crosses cells between its ends up to h_floor beyond its two levels
  const double max_dh = q == 0 ? p_.h_stairs + 2 * p_.h_floor : p_.h_floor;
  const bool interior = ix >= 2 && iy >= 2 && ix < w.size_x - 2 && iy < w.size_y - 2;
  for (int k = 0; k < kNumHeadings; ++k) {
    if (!interior && !w.Contains(ix + kSteps[k].dx, iy + kSteps[k].dy)) continue;
    const int j = i + kSteps[k].dy * w.size_x + kSteps[k].dx;
    const int other = 2 * j + q;
    if (!h_open_[size_t(other)] || h_stamp_[size_t(other)] == 2) continue;
    double dh = 0.0;
    if (std::isfinite(height[i]) && std::isfinite(height[j])) {
      dh = std::abs(double(height[j]) - double(height[i]));
    }
    if (dh > max_dh) continue;
    double factor = crawl_factor;
    if (q == 0) {
      const bool stairs = fog_.type[size_t(i)] == CellType::kStairs ||
                          fog_.type[size_t(j)] == CellType::kStairs || dh > p_.h_floor;
      factor = stairs ? stairs_factor : upright_factor;
    }
    Relax(other, h + step_length_[k] * (factor + 0.5 * (cell_cost_[size_t(i)] +
                                                        cell_cost_[size_t(j)])));
  }
  if (q == 1) return;
  for (const auto& [e, length] : h_aside_) {
    const int jx = ix + e.dx, jy = iy + e.dy;
    if (!w.Contains(jx, jy)) continue;
    const int j = w.Index(jx, jy);
    const int other = 2 * j;
    if (!h_open_[size_t(other)] || h_stamp_[size_t(other)] == 2) continue;
    if (std::isfinite(height[i]) && std::isfinite(height[j]) &&
        std::abs(double(height[j]) - double(height[i])) > max_dh) {
      continue;
    }
    Relax(other, h + length * stairs_factor);
  }
}

perception::Pose2 Lattice::PoseOf(int s) const {
  const int cell = CellOfState(s);
  const Eigen::Vector2d c =
      fog_.window.CellCenter(cell % fog_.window.size_x, cell / fog_.window.size_x);
  return {c.x(), c.y(), HeadingYaw(HeadingOfState(s))};
}

bool Lattice::HeadroomSeen(int cell, int heading) const {
  if (!p_.get_up_under_seen_headroom) {
    const double clear = p_.unseen_headroom_clearance / fog_.window.resolution;
    return tunnel_d2_[size_t(cell)] > clear * clear + kEps;
  }
  if (fog_.headroom_seen.empty()) return true;
  const perception::GridWindow& w = fog_.window;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  auto seen = [&](int nx, int ny) {
    return w.Contains(nx, ny) && fog_.headroom_seen[size_t(w.Index(nx, ny))] != 0;
  };
  for (const CellStep& o : footprint_[0][heading]) {
    if (!seen(ix + o.dx, iy + o.dy)) return false;
  }
  // where the head reaches, looking down
  const double r = (p_.head_reach + p_.margin) / w.resolution + kEps;
  const int reach = int(r);
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      if (dx * dx + dy * dy <= r * r && !seen(ix + dx, iy + dy)) return false;
    }
  }
  return true;
}

bool Lattice::MayBeLevelBorder(size_t cell, int q) const {
  if (fog_.type[cell] != CellType::kBorder) return false;
  if (q == 0) return true;
  return zone_d2_[cell] <= zone_d2_max_;
}

bool Lattice::MayGetDown(int cell) const {
  return tunnel_d2_[size_t(cell)] <= zone_d2_max_;
}

bool Lattice::CrawlFootprintInOpen(int cell, int heading) const {
  const perception::GridWindow& w = fog_.window;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  // along the heading, from the standing origin (kneel_steps_ behind the crawling one); beyond
  // kneel_clear_reach the body stays below any tunnel's ceiling while it gets down or up
  const double c = std::cos(HeadingYaw(heading)), s = std::sin(HeadingYaw(heading));
  const double kneel = kneel_steps_[heading] * step_length_[heading];
  for (const CellStep& o : footprint_[1][heading]) {
    const int nx = ix + o.dx, ny = iy + o.dy;
    if (!w.Contains(nx, ny) || fog_.type[size_t(w.Index(nx, ny))] != CellType::kTunnel) continue;
    const double ahead = kneel + (o.dx * c + o.dy * s) * w.resolution;
    if (ahead <= p_.kneel_clear_reach + kEps) return false;
  }
  return true;
}

bool Lattice::FootprintFits(int cell, int heading, int q) const {
  const perception::GridWindow& w = fog_.window;
  if (q == 0) {
    const double head = (p_.head_reach + p_.margin) / w.resolution + kEps;
    if (tunnel_d2_[size_t(cell)] <= head * head) return false;
  }
  const double d2 = blocked_d2_[q][size_t(cell)];
  const double in = inner_radius_cells_[q] - kEps;
  if (in > 0 && d2 <= in * in) return false;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  const float centre_h = floor_h_[size_t(cell)];
  if (q == 0) {
    uint8_t& head = head_meets_[size_t(cell)];  // the same at every heading
    if (head == 0) head = HeadMeetsSolid(cell, ix, iy, centre_h) ? 2 : 1;
    if (head == 2) return false;
  }
  const int reach = outer_reach_cells_[q];
  const bool inside =
      ix - reach >= 0 && iy - reach >= 0 && ix + reach < w.size_x && iy + reach < w.size_y;
  const double out = outer_radius_cells_[q] + kEps;
  const double maybe_d2 = maybe_blocked_d2_[q][size_t(cell)];
  if (maybe_d2 > out * out) {
    if (q == 1 && inside) return true;
    // standing: fits for certain when every known floor height around is on the centre's level
    if (q == 0 && LevelAround(cell)) return true;
  }
  const std::vector<CellStep>& cells = footprint_[q][heading];
  Spread stance(centre_h);
  if (q == 0 && inside) {
    // standing with all of the footprint in the window: the checks below, by cell index
    const int* index = footprint_index_[heading].data();
    const uint8_t* level = level_cell_[heading].data();
    for (size_t j = 0; j < cells.size(); ++j) {
      const size_t i = size_t(cell + index[j]);
      if (!OnLevel(i, centre_h, level[j] ? p_.h_floor : p_.h_stairs)) return false;
      if (level[j] && !stance.Add(fog_.height[i], p_.h_floor)) return false;
    }
    return true;
  }
  for (size_t j = 0; j < cells.size(); ++j) {
    const int nx = ix + cells[j].dx, ny = iy + cells[j].dy;
    if (!w.Contains(nx, ny)) {
      // beyond the window is unknown: standing is allowed there, crawling is not
      if (q == 1) return false;
      continue;
    }
    const size_t i = size_t(w.Index(nx, ny));
    if (q == 1 && ok_[1][i]) continue;
    if (q == 1 && !MayBeLevelBorder(i, 1)) return false;
    // on the origin's level (crawling, only border cells of the crawl zone get here); standing,
    // in the ring beyond the soles' stance grown by level_margin a tread's height (up to
    // h_stairs off) is allowed too
    const bool ring = q == 0 && !level_cell_[heading][j];
    if (!OnLevel(i, centre_h, ring ? p_.h_stairs : p_.h_floor)) return false;
    if (q == 0 && !ring && !stance.Add(fog_.height[i], p_.h_floor)) return false;
  }
  return true;
}

uint32_t Lattice::StateFlags(int s) {
  uint32_t& v = memory_->valid_stamp[size_t(s)];
  if ((v >> 4) != valid_generation_) {
    const int cell = CellOfState(s), heading = HeadingOfState(s), q = int(PostureOfState(s));
    const bool fits = FootprintFits(cell, heading, q);
    const int touch = fits && q == 0 ? BodyTouches(cell, heading) : kNoTouch;
    v = (valid_generation_ << 4) | (fits ? 1u : 2u) | (uint32_t(touch) << 2);
  }
  return v & 15u;
}

bool Lattice::SweepClear(int cell, const Climb& c, double lo, double hi) const {
  const perception::GridWindow& w = fog_.window;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  for (const CellStep& o : c.swept) {
    const int nx = ix + o.dx, ny = iy + o.dy;
    if (!w.Contains(nx, ny)) continue;  // unknown
    const size_t i = size_t(w.Index(nx, ny));
    const CellType t = fog_.type[i];
    if (t == CellType::kObstacle || t == CellType::kTunnel) return false;
    // unknown cells by the nearest known floor's height, like the origins of moves
    const float h = floor_h_[i];
    if (std::isfinite(h) && (double(h) < lo || double(h) > hi)) return false;
  }
  return true;
}

bool Lattice::FacesStep(int cell, int heading, const Climb& c) const {
  // the floor's height gradient summed along the origin's line crosses the riser wherever the
  // ends themselves stand on level floor
  const perception::GridWindow& w = fog_.window;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  Eigen::Vector2d grad = FloorGradient(cell);
  for (const CellStep& o : c.line) {
    if (w.Contains(ix + o.dx, iy + o.dy)) grad += FloorGradient(w.Index(ix + o.dx, iy + o.dy));
  }
  const double norm = grad.norm();
  if (norm <= 0.25 * p_.h_floor) return true;
  const double yaw = HeadingYaw(heading);
  const double along = std::abs(grad.x() * std::cos(yaw) + grad.y() * std::sin(yaw)) / norm;
  return along >= cos_stairs_error_ - kEps;
}

void Lattice::AddStairsMove(int s, Successor* out, int* n) {
  const perception::GridWindow& w = fog_.window;
  const int cell = CellOfState(s);
  const int k = HeadingOfState(s);
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  const float h0 = floor_h_[size_t(cell)];
  if (!std::isfinite(h0)) return;
  for (const Climb& c : climbs_[k]) {
    // the end: a floor on another level within reach, where the robot stands level
    const int nx = ix + c.to.dx, ny = iy + c.to.dy;
    if (!w.Contains(nx, ny)) continue;
    const int to = w.Index(nx, ny);
    const float h1 = floor_h_[size_t(to)];
    if (!std::isfinite(h1)) continue;
    const double rise = double(h1) - double(h0);
    if (std::abs(rise) <= p_.h_floor || std::abs(rise) > p_.h_stairs) continue;
    const int t = StateIndex(nx, ny, k, Posture::kUpright);
    if (!Valid(t)) continue;
    // the way there: nothing in the way of the feet, no drop below or rise above the two levels
    const double lo = std::min(double(h0), double(h1)) - p_.h_floor;
    const double hi = std::max(double(h0), double(h1)) + p_.h_floor;
    if (!SweepClear(cell, c, lo, hi) || !FacesStep(cell, k, c)) continue;
    // cost: its length at the stairs factor, with the mean clearance and unknown cost of the
    // origin cells along it (as the heuristic's relaxed steps)
    const double factor = std::max(p_.walk_factor, p_.stairs_factor);
    double cell_cost = cell_cost_[size_t(cell)];
    for (const CellStep& o : c.line) cell_cost += cell_cost_[size_t(w.Index(ix + o.dx, iy + o.dy))];
    cell_cost /= double(c.line.size() + 1);
    out[(*n)++] = {t, c.length * (factor + cell_cost), c.length,
                   rise > 0 ? Move::kStairsUp : Move::kStairsDown};
    return;
  }
}

int Lattice::Successors(int s, Successor* out) {
  const perception::GridWindow& w = fog_.window;
  const int cell = CellOfState(s);
  const int k = HeadingOfState(s);
  const Posture posture = PostureOfState(s);
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  int n = 0;

  // a translation by heading step `dir` keeping heading k and the posture, on one level;
  // `blind` (0..3, see blind_lead_) for the moves the eyes do not look along, else -1
  auto translate = [&](int dir, int sign, double factor, Move move, int blind) {
    const int nx = ix + sign * kSteps[dir].dx, ny = iy + sign * kSteps[dir].dy;
    if (!w.Contains(nx, ny)) return;
    const int to = w.Index(nx, ny);
    if (std::abs(HeightStep(cell, to)) > p_.h_floor) return;
    const int t = StateIndex(nx, ny, k, posture);
    const uint32_t flags = StateFlags(t);
    if (!(flags & 1u)) return;
    const bool stay_known = blind == 3 ? p_.crawl_stays_known : p_.blind_moves_stay_known;
    if (blind >= 0 && stay_known && BlindIntoUnknown(nx, ny, int(posture), k, blind)) {
      return;
    }
    const bool on_stairs =
        fog_.type[size_t(cell)] == CellType::kStairs || fog_.type[size_t(to)] == CellType::kStairs;
    if (on_stairs) factor = std::max(factor, p_.stairs_factor);
    const double length = step_length_[dir];
    double cost = length * (factor + 0.5 * (cell_cost_[size_t(cell)] + cell_cost_[size_t(to)]));
    cost += TouchCost(int(flags >> 2));
    out[n++] = {t, cost, length, move};
  };
  // a turn in place to heading k2 at angle `angle`; standing, the soles sweep level floor only,
  // and a body sweeping into an obstacle costs as one ending there; crawling, the head, hands and
  // knees sweep only cells they may lie on
  auto turn = [&](int k2, double angle, double factor) {
    const int t = StateIndex(ix, iy, k2, posture);
    const uint32_t flags = StateFlags(t);
    if (!(flags & 1u)) return;
    int touch = int(flags >> 2);
    const int from = k2 == (k + 1) % kNumHeadings ? k : k2;
    if (posture == Posture::kUpright ? !TurnSweepClear(cell, from, &touch)
                                     : !CrawlTurnClear(cell, from)) {
      return;
    }
    double cost = angle * p_.turn_cost_per_rad * factor + TouchCost(touch);
    out[n++] = {t, cost, 0.0, Move::kTurn};
  };
  const int left = (k + 1) % kNumHeadings, right = (k + kNumHeadings - 1) % kNumHeadings;
  const int across = (k + 4) % kNumHeadings;

  if (posture == Posture::kUpright) {
    translate(k, +1, p_.walk_factor, Move::kWalk, -1);
    AddStairsMove(s, out, &n);  // steps up and down only forward, facing them
    translate(k, -1, p_.backward_factor, Move::kWalk, 0);
    translate(across, +1, p_.sidestep_factor, Move::kSidestep, 1);
    translate(across, -1, p_.sidestep_factor, Move::kSidestep, 2);
    turn(left, turn_angle_[k], 1.0);
    turn(right, turn_angle_[right], 1.0);
    // getting down: the origin moves forward to the knees
    const int m = kneel_steps_[k];
    const int dx = ix + m * kSteps[k].dx, dy = iy + m * kSteps[k].dy;
    const int knees = w.Contains(dx, dy) ? w.Index(dx, dy) : -1;
    if (knees >= 0 && MayGetDown(knees) && std::abs(HeightStep(cell, knees)) <= p_.h_floor) {
      const int down = StateIndex(dx, dy, k, Posture::kCrawling);
      if (Valid(down) && CrawlFootprintInOpen(knees, k)) {
        out[n++] = {down, p_.posture_change_cost, m * step_length_[k], Move::kCrawl};
      }
    }
  } else {
    translate(k, +1, p_.crawl_factor, Move::kCrawl, 3);
    translate(k, -1, p_.crawl_factor * p_.backward_factor, Move::kCrawl, 0);
    turn(left, turn_angle_[k], p_.crawl_factor);
    turn(right, turn_angle_[right], p_.crawl_factor);
    // getting up: the origin moves back from the knees to the feet
    const int m = kneel_steps_[k];
    const int ux = ix - m * kSteps[k].dx, uy = iy - m * kSteps[k].dy;
    if (w.Contains(ux, uy) && std::abs(HeightStep(cell, w.Index(ux, uy))) <= p_.h_floor &&
        CrawlFootprintInOpen(cell, k) && HeadroomSeen(w.Index(ux, uy), k)) {
      const int up = StateIndex(ux, uy, k, Posture::kUpright);
      if (Valid(up)) out[n++] = {up, p_.posture_change_cost, m * step_length_[k], Move::kCrawl};
    }
  }
  return n;
}

bool Lattice::HeadMeetsSolid(int cell, int ix, int iy, float centre_h) const {
  if (!std::isfinite(centre_h)) return false;
  const double top = double(centre_h) + p_.head_low;
  const double head = (p_.head_reach + p_.margin) / fog_.window.resolution + kEps;
  const bool obstacle_near = blocked_d2_[0][size_t(cell)] <= head * head;
  if (!obstacle_near && !(double(level_hi_[size_t(cell)]) > top)) return false;
  const perception::GridWindow& w = fog_.window;
  for (const CellStep& o : head_disc_) {
    const int nx = ix + o.dx, ny = iy + o.dy;
    if (!w.Contains(nx, ny)) continue;
    const size_t i = size_t(w.Index(nx, ny));
    const CellType t = fog_.type[i];
    if (t == CellType::kUnknown || t == CellType::kTunnel) continue;  // tunnels: see above
    if (std::isfinite(fog_.height[i]) && double(fog_.height[i]) > top) return true;
  }
  return false;
}

bool Lattice::LevelAround(int cell) const {
  const float centre_h = floor_h_[size_t(cell)];
  const double lo = std::min(double(level_lo_[size_t(cell)]), double(centre_h));
  const double hi = std::max(double(level_hi_[size_t(cell)]), double(centre_h));
  return std::isfinite(centre_h) && hi - lo <= p_.h_floor;
}

int Lattice::BodyTouches(int cell, int heading) const {
  return BodyMeets(cell, body_extra_[heading], body_extra_legs_[heading]);
}

double Lattice::TouchCost(int touch) const {
  return touch == kTouch ? p_.body_touch_cost : touch == kEdgeTouch ? p_.edge_touch_cost : 0.0;
}

int Lattice::BodyMeets(int cell, const std::vector<CellStep>& offsets,
                       const std::vector<uint8_t>& legs) const {
  const perception::GridWindow& w = fog_.window;
  const float centre_h = floor_h_[size_t(cell)];
  const double body = body_outer_radius_cells_ + kEps;
  const bool obstacle_near = blocked_d2_[0][size_t(cell)] <= body * body;
  const bool high_near = std::isfinite(centre_h) &&
                         double(level_hi_[size_t(cell)]) - double(centre_h) > p_.h_stairs;
  const bool hidden_near =
      std::isfinite(centre_h) &&
      double(hidden_hi_[size_t(cell)]) - double(centre_h) > std::min(p_.h_stairs, p_.hand_low);
  if (!obstacle_near && !high_near && !hidden_near) return kNoTouch;
  int touch = kNoTouch;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  for (size_t j = 0; j < offsets.size(); ++j) {
    const int nx = ix + offsets[j].dx, ny = iy + offsets[j].dy;
    if (!w.Contains(nx, ny)) continue;
    const size_t i = size_t(w.Index(nx, ny));
    const CellType t = fog_.type[i];
    if (t == CellType::kObstacle || t == CellType::kTunnel) return kTouch;
    if (t == CellType::kUnknown) {
      // beside the edge of a top the eyes saw from one side only (a wall's far face, a block's
      // hidden corner) the solid may go on: higher than a step, it meets the knees and shins;
      // beside the legs, only the hands reach out there
      const double low = legs[j] ? p_.h_stairs : p_.hand_low;
      if (std::isfinite(centre_h) && double(hidden_top_[i]) - double(centre_h) > low) {
        return kTouch;
      }
      continue;
    }
    // on the low side of a border the top's edge may lie a cell further out (stereo ends a
    // table top's far edge short): beside the legs, a top the hands reach may be there
    if (t == CellType::kBorder && !legs[j] && std::isfinite(centre_h) &&
        double(hidden_top_[i]) - double(centre_h) > p_.hand_low) {
      touch = kEdgeTouch;
    }
    if (high_near && std::isfinite(fog_.height[i]) &&
        double(fog_.height[i]) - double(centre_h) > p_.h_stairs) {
      return kTouch;
    }
  }
  return touch;
}

bool Lattice::OnLevel(size_t i, float centre_h, double tolerance) const {
  // never on an obstacle or under a table; anywhere on unknown cells; floor, stairs and border
  // cells only on the level of the floor under the origin, so the feet never reach onto
  // another tread or over a drop (the paper's border marks both sides of a drop: the robot may
  // stand at the foot of a wall or block or on the rim of a platform, but its footprint never
  // spans the drop); without heights to compare, floor and stairs cells are allowed and border
  // cells are not
  const CellType t = fog_.type[i];
  if (t == CellType::kUnknown) return true;
  if (t == CellType::kObstacle || t == CellType::kTunnel) return false;
  const float h = fog_.height[i];
  if (!std::isfinite(h) || !std::isfinite(centre_h)) return t != CellType::kBorder;
  return std::abs(double(h) - double(centre_h)) <= tolerance;
}

bool Lattice::TurnSweepClear(int cell, int k, int* touch) const {
  const perception::GridWindow& w = fog_.window;
  const float centre_h = floor_h_[size_t(cell)];
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  // the soles: nothing to check where no cell that may block lies within their sweep and every
  // known floor around is on the origin's level
  const double soles = turn_soles_radius_cells_ + kEps;
  if (maybe_blocked_d2_[0][size_t(cell)] <= soles * soles ||
      !(LevelAround(cell) || !std::isfinite(centre_h))) {
    // the soles at an angle between cover cells of both ends' stances and of the sweep
    Spread soles_h(centre_h);
    for (const int e : {k, (k + 1) % kNumHeadings}) {
      const std::vector<CellStep>& cells = footprint_[0][e];
      for (size_t j = 0; j < cells.size(); ++j) {
        const int nx = ix + cells[j].dx, ny = iy + cells[j].dy;
        if (level_cell_[e][j] && w.Contains(nx, ny) &&
            !soles_h.Add(fog_.height[size_t(w.Index(nx, ny))], p_.h_floor)) {
          return false;
        }
      }
    }
    for (const CellStep& o : turn_soles_[k]) {
      const int nx = ix + o.dx, ny = iy + o.dy;
      if (!w.Contains(nx, ny)) continue;
      const size_t i = size_t(w.Index(nx, ny));
      if (!OnLevel(i, centre_h, p_.h_floor) || !soles_h.Add(fog_.height[i], p_.h_floor)) {
        return false;
      }
    }
  }
  // the body, as BodyTouches
  if (*touch != kTouch) {
    *touch = std::max(*touch, BodyMeets(cell, turn_body_[k], turn_body_legs_[k]));
  }
  return true;
}

bool Lattice::CrawlTurnClear(int cell, int k) const {
  const perception::GridWindow& w = fog_.window;
  const int ix = cell % w.size_x, iy = cell / w.size_x;
  const float centre_h = floor_h_[size_t(cell)];
  for (const CellStep& o : turn_crawl_[k]) {
    const int nx = ix + o.dx, ny = iy + o.dy;
    if (!w.Contains(nx, ny)) return false;  // beyond the window is unknown, never crawled on
    const size_t i = size_t(w.Index(nx, ny));
    if (ok_[1][i]) continue;
    if (!MayBeLevelBorder(i, 1) || !OnLevel(i, centre_h, p_.h_floor)) return false;
  }
  return true;
}

bool Lattice::BlindIntoUnknown(int ix, int iy, int q, int k, int b) const {
  const perception::GridWindow& w = fog_.window;
  // no unknown cell within the footprint's reach, and all of it inside the window
  const int reach = outer_reach_cells_[q];
  const double out = outer_radius_cells_[q] + kEps;
  if (unknown_d2_[size_t(w.Index(ix, iy))] > out * out && ix - reach >= 0 && iy - reach >= 0 &&
      ix + reach < w.size_x && iy + reach < w.size_y) {
    return false;
  }
  for (const CellStep& o : blind_lead_[q][k][b]) {
    const int nx = ix + o.dx, ny = iy + o.dy;
    if (!w.Contains(nx, ny) || UnseenUnwalked(size_t(w.Index(nx, ny)))) return true;
  }
  return false;
}

double Lattice::TerminalCost(int s) const {
  const int cell = CellOfState(s);
  return terminal_[size_t(cell)];
}

bool Lattice::GoalRegionHasValidState() {
  if (!goal_in_window_) return false;
  const perception::GridWindow& w = fog_.window;
  int gx = 0, gy = 0;
  w.CellOf(goal_G_.x(), goal_G_.y(), &gx, &gy);
  const int r = int(std::ceil(p_.goal_tolerance / w.resolution)) + 1;
  for (int iy = gy - r; iy <= gy + r; ++iy) {
    for (int ix = gx - r; ix <= gx + r; ++ix) {
      if (!w.Contains(ix, iy) || !InGoalRegion(w.Index(ix, iy))) continue;
      for (int q = 0; q < 2; ++q) {
        for (int k = 0; k < kNumHeadings; ++k) {
          if (Valid(StateIndex(ix, iy, k, Posture(q)))) return true;
        }
      }
    }
  }
  return false;
}

std::vector<Seed> Lattice::StartSeeds(const perception::Pose2& start_G, Posture posture) {
  const perception::GridWindow& w = fog_.window;
  std::vector<Seed> seeds;
  int sx = 0, sy = 0;
  w.CellOf(start_G.x, start_G.y, &sx, &sy);
  if (!w.Contains(sx, sy)) return seeds;
  const int exact = StateIndex(sx, sy, NearestHeading(start_G.yaw), posture);
  if (Valid(exact)) {
    seeds.push_back({exact, 0.0, 0.0, Move::kNone});
    return seeds;
  }
  // shuffle free: any allowed state close by, at the cost of side-stepping, turning and
  // changing posture there. Changing posture moves the origin kneel_offset along the heading
  // (forward getting down, back getting up), so such states lie close to where that puts it:
  // a crawling robot at a table's edge that got up at once, as if standing where it knelt,
  // came up with its head under the top.
  const Eigen::Vector2d kneel =
      p_.kneel_offset * Eigen::Vector2d(std::cos(start_G.yaw), std::sin(start_G.yaw));
  Eigen::Vector2d from[2];  // per posture, where the robot's origin is in it
  int from_cell[2][2];
  for (int q = 0; q < 2; ++q) {
    const double side = Posture(q) == posture ? 0.0 : Posture(q) == Posture::kCrawling ? 1.0 : -1.0;
    from[q] = Eigen::Vector2d(start_G.x, start_G.y) + side * kneel;
    w.CellOf(from[q].x(), from[q].y(), &from_cell[q][0], &from_cell[q][1]);
  }
  const int r = int(std::ceil((p_.start_escape_radius + p_.kneel_offset) / w.resolution)) + 1;
  for (int iy = sy - r; iy <= sy + r; ++iy) {
    for (int ix = sx - r; ix <= sx + r; ++ix) {
      if (!w.Contains(ix, iy)) continue;
      for (int q = 0; q < 2; ++q) {
        const bool changes = Posture(q) != posture;
        const double d = (w.CellCenter(ix, iy) - from[q]).norm();
        if (d > p_.start_escape_radius && !(ix == from_cell[q][0] && iy == from_cell[q][1])) {
          continue;
        }
        if (changes && Posture(q) == Posture::kCrawling && !MayGetDown(w.Index(ix, iy))) continue;
        for (int k = 0; k < kNumHeadings; ++k) {
          const int s = StateIndex(ix, iy, k, Posture(q));
          if (!Valid(s)) continue;
          const double angle = std::abs(WrapAngle(HeadingYaw(k) - start_G.yaw));
          const double cost = d * p_.sidestep_factor +
                              angle * p_.turn_cost_per_rad *
                                  (Posture(q) == Posture::kCrawling ? p_.crawl_factor : 1.0) +
                              (changes ? p_.posture_change_cost : 0.0);
          // a crawling robot shuffles by crawling, a standing one by side-stepping
          const Move move = changes || (d > kEps && Posture(q) == Posture::kCrawling)
                                ? Move::kCrawl
                                : d > kEps ? Move::kSidestep : Move::kTurn;
          seeds.push_back({s, cost, d + (changes ? p_.kneel_offset : 0.0), move});
        }
      }
    }
  }
  return seeds;
}

}  // namespace fognav::navigation::internal

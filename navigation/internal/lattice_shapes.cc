// The lattice's shapes (LatticeShapes): footprints, the body's and the sweeps' cell offsets and
// the climbs of each heading, from the robot's sizes and the cell size; built once per thread.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <utility>

#include "navigation/internal/lattice.h"

namespace fognav::navigation::internal {
namespace {

constexpr double kEps = 1e-9;

[[noreturn]] void Die(const char* what) {
  std::fprintf(stderr, "fognav::navigation: %s\n", what);
  std::abort();
}

// Whether offset (dx, dy) is one of `cells`.
bool Covers(const std::vector<CellStep>& cells, int dx, int dy) {
  return std::any_of(cells.begin(), cells.end(),
                     [&](const CellStep& c) { return c.dx == dx && c.dy == dy; });
}

int MaxComponent(const std::vector<CellStep>& cells) {
  int m = 0;
  for (const CellStep& o : cells) m = std::max({m, std::abs(o.dx), std::abs(o.dy)});
  return m;
}

}  // namespace

// The robot's extents as the shapes use them (each grown by margin, or by level_margin for the
// soles' stance) and the frames of the headings.
struct ShapeFrame {
  ShapeFrame(const PlannerParams& params, double cell)
      : p(params),
        resolution(cell),
        half_along{0.5 * p.depth + p.margin, 0.5 * p.crawl_length + p.margin},
        half_across{0.5 * p.shoulder_width + p.margin, 0.5 * p.crawl_width + p.margin},
        level_along(0.5 * p.depth + p.level_margin),
        level_across(0.5 * std::min(p.stance_width, p.shoulder_width) + p.level_margin),
        body_back(p.body_back + p.margin),
        body_front(p.body_front + p.margin),
        body_half(std::max(half_across[0], p.arm_reach + p.margin)),
        legs_half(0.5 * std::min(p.stance_width, p.shoulder_width) + p.margin) {
    for (int k = 0; k < kNumHeadings; ++k) {
      cos_k[k] = std::cos(HeadingYaw(k));
      sin_k[k] = std::sin(HeadingYaw(k));
    }
  }
  // a cell offset in the frame of heading k: along and across it, metres
  Eigen::Vector2d InFrame(int k, int dx, int dy) const {
    const double c = cos_k[k], s = sin_k[k];
    return Eigen::Vector2d((dx * c + dy * s) * resolution, (-dx * s + dy * c) * resolution);
  }
  // the offsets up to `reach` cells away whose centres lie in [u_lo, u_hi] x [v_lo, v_hi] of
  // the frame of heading k
  std::vector<CellStep> CellsIn(int k, int reach, double u_lo, double u_hi, double v_lo,
                                double v_hi) const {
    std::vector<CellStep> cells;
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const Eigen::Vector2d uv = InFrame(k, dx, dy);
        if (uv.x() >= u_lo - kEps && uv.x() <= u_hi + kEps && uv.y() >= v_lo - kEps &&
            uv.y() <= v_hi + kEps) {
          cells.push_back({dx, dy});
        }
      }
    }
    return cells;
  }
  // whether an offset's centre in the frame of a heading lies in the soles' stance grown by
  // level_margin
  bool InStance(const Eigen::Vector2d& uv) const {
    return std::abs(uv.x()) <= level_along + kEps && std::abs(uv.y()) <= level_across + kEps;
  }

  const PlannerParams& p;
  double resolution;
  double cos_k[kNumHeadings], sin_k[kNumHeadings];
  double half_along[2], half_across[2];  // each footprint's half extents
  double level_along, level_across;      // the soles' stance's
  // the standing body rectangle: behind and ahead of the origin, half its width; and the
  // legs' half width
  double body_back, body_front, body_half, legs_half;
};

void LatticeShapes::Build(const PlannerParams& p, double resolution) {
  cos_stairs_error_ = std::cos(std::clamp(p.max_stairs_heading_error, 0.0, M_PI));
  for (int k = 0; k < kNumHeadings; ++k) {
    step_length_[k] = std::hypot(double(kSteps[k].dx), double(kSteps[k].dy)) * resolution;
    turn_angle_[k] = std::abs(WrapAngle(HeadingYaw((k + 1) % kNumHeadings) - HeadingYaw(k)));
    kneel_steps_[k] = int(std::lround(p.kneel_offset / step_length_[k]));
  }
  const ShapeFrame f(p, resolution);
  BuildFootprints(f);
  BuildBody(f);
  BuildTurnSweeps(f);
  BuildCrawlTurnSweeps(f);
  BuildHead(f);
  BuildBlindLeads();
  BuildClimbs(f);
}

void LatticeShapes::BuildFootprints(const ShapeFrame& f) {
  // footprints: cells whose centres lie in the grown rectangle
  for (int q = 0; q < 2; ++q) {
    const double a = f.half_along[q], b = f.half_across[q];
    const double offset = q == 0 ? 0.0 : f.p.crawl_offset;  // rectangle centre ahead of the origin
    if (!(a > 0 && b > 0)) Die("Plan: footprint sizes must be positive");
    if (std::abs(offset) >= a) Die("Plan: crawl_offset must be inside the crawling footprint");
    // circles about the robot's origin inside and around the rectangle
    inner_radius_cells_[q] = std::min(a - std::abs(offset), b) / f.resolution;
    outer_radius_cells_[q] = std::hypot(a + std::abs(offset), b) / f.resolution;
    const int reach = int(std::ceil(outer_radius_cells_[q])) + 1;
    outer_reach_cells_[q] = 0;
    for (int k = 0; k < kNumHeadings; ++k) {
      std::vector<CellStep>& cells = footprint_[q][k];
      cells = f.CellsIn(k, reach, offset - a, offset + a, -b, b);
      outer_reach_cells_[q] = std::max(outer_reach_cells_[q], MaxComponent(cells));
      // outermost cells first: they meet obstacles first
      std::sort(cells.begin(), cells.end(), [](const CellStep& l, const CellStep& r) {
        return l.dx * l.dx + l.dy * l.dy > r.dx * r.dx + r.dy * r.dy;
      });
      if (q == 1) continue;
      level_cell_[k].clear();
      for (const CellStep& o : cells)
        level_cell_[k].push_back(f.InStance(f.InFrame(k, o.dx, o.dy)));
    }
  }
}

void LatticeShapes::BuildBody(const ShapeFrame& f) {
  // the standing body beyond the soles' footprint
  {
    if (!(f.body_back >= 0 && f.body_front >= 0)) Die("Plan: body extents must not be negative");
    body_outer_radius_cells_ =
        std::hypot(std::max(f.body_back, f.body_front), f.body_half) / f.resolution;
    const int reach = int(std::ceil(body_outer_radius_cells_)) + 1;
    for (int k = 0; k < kNumHeadings; ++k) {
      std::vector<CellStep>& extra = body_extra_[k];
      extra = f.CellsIn(k, reach, -f.body_back, f.body_front, -f.body_half, f.body_half);
      extra.erase(
          std::remove_if(extra.begin(), extra.end(),
                         [&](const CellStep& o) { return Covers(footprint_[0][k], o.dx, o.dy); }),
          extra.end());
      body_reach_cells_ = std::max(body_reach_cells_, MaxComponent(extra));
      body_extra_legs_[k].clear();
      for (const CellStep& o : extra) {
        body_extra_legs_[k].push_back(std::abs(f.InFrame(k, o.dx, o.dy).y()) <= f.legs_half + kEps);
      }
    }
  }
}

void LatticeShapes::BuildTurnSweeps(const ShapeFrame& f) {
  // turns in place between heading k and k + 1: the cells the soles' stance (grown by
  // level_margin) and the body sweep at the angles in between, beyond what the two ends cover
  // (the robot turns about its origin; the shapes every degree or less). The body sweeps as the
  // shape it has, not as its bounding rectangle, whose corners (the knees' reach ahead, the
  // hands' to the side) hold no part of it and would sweep 2 cm further out: the legs as far
  // ahead and behind as the body rectangle and as wide as the footprint, the arms beside the
  // footprint as far out as the hands.
  {
    const double a = f.half_along[0], b = f.half_across[0];
    const int reach = int(std::ceil(body_outer_radius_cells_)) + 1;
    auto in_body_shape = [&](const Eigen::Vector2d& uv) {
      return (uv.x() >= -f.body_back - kEps && uv.x() <= f.body_front + kEps &&
              std::abs(uv.y()) <= b + kEps) ||
             (std::abs(uv.x()) <= a + kEps && std::abs(uv.y()) <= f.body_half + kEps);
    };
    // what the ends' own checks cover: the footprint and the body rectangle beyond it
    auto at_ends = [&](int k, int k2, int dx, int dy) {
      return Covers(footprint_[0][k], dx, dy) || Covers(body_extra_[k], dx, dy) ||
             Covers(footprint_[0][k2], dx, dy) || Covers(body_extra_[k2], dx, dy);
    };
    for (int k = 0; k < kNumHeadings; ++k) {
      const int k2 = (k + 1) % kNumHeadings;
      const double yaw = HeadingYaw(k), turn = WrapAngle(HeadingYaw(k2) - yaw);
      const int n = std::max(2, int(std::ceil(std::abs(turn) / (M_PI / 180))));
      std::vector<double> cos_j(static_cast<size_t>(n)), sin_j(static_cast<size_t>(n));
      for (int j = 1; j < n; ++j) {
        cos_j[size_t(j)] = std::cos(yaw + turn * j / n) * f.resolution;
        sin_j[size_t(j)] = std::sin(yaw + turn * j / n) * f.resolution;
      }
      turn_soles_[k].clear();
      turn_body_[k].clear();
      turn_body_legs_[k].clear();
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          bool soles = false, body = false, legs = false;
          for (int j = 1; j < n && !(soles && legs); ++j) {
            const double c = cos_j[size_t(j)], s = sin_j[size_t(j)];
            const Eigen::Vector2d uv(dx * c + dy * s, -dx * s + dy * c);
            soles = soles || f.InStance(uv);
            body = body || in_body_shape(uv);
            legs = legs || (uv.x() >= -f.body_back - kEps && uv.x() <= f.body_front + kEps &&
                            std::abs(uv.y()) <= f.legs_half + kEps);
          }
          if (soles && !f.InStance(f.InFrame(k, dx, dy)) && !f.InStance(f.InFrame(k2, dx, dy))) {
            turn_soles_[k].push_back({dx, dy});
          }
          if (body && !at_ends(k, k2, dx, dy)) {
            turn_body_[k].push_back({dx, dy});
            turn_body_legs_[k].push_back(legs);
          }
        }
      }
      body_reach_cells_ =
          std::max({body_reach_cells_, MaxComponent(turn_soles_[k]), MaxComponent(turn_body_[k])});
      for (const CellStep& o : turn_soles_[k]) {
        turn_soles_radius_cells_ =
            std::max(turn_soles_radius_cells_, std::hypot(double(o.dx), double(o.dy)));
      }
    }
  }
}

void LatticeShapes::BuildCrawlTurnSweeps(const ShapeFrame& f) {
  // crawling turns in place between heading k and k + 1: the cells the crawling footprint (head,
  // hands and knees) sweeps at the angles in between (every degree or less) beyond both ends'
  const double a = f.half_along[1], b = f.half_across[1];
  const int reach = int(std::ceil(outer_radius_cells_[1])) + 1;
  for (int k = 0; k < kNumHeadings; ++k) {
    const int k2 = (k + 1) % kNumHeadings;
    const double yaw = HeadingYaw(k), turn = WrapAngle(HeadingYaw(k2) - yaw);
    const int n = std::max(2, int(std::ceil(std::abs(turn) / (M_PI / 180))));
    turn_crawl_[k].clear();
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        if (Covers(footprint_[1][k], dx, dy) || Covers(footprint_[1][k2], dx, dy)) continue;
        for (int j = 1; j < n; ++j) {
          const double c = std::cos(yaw + turn * j / n), s = std::sin(yaw + turn * j / n);
          const double u = (dx * c + dy * s) * f.resolution - f.p.crawl_offset;
          const double v = (-dx * s + dy * c) * f.resolution;
          if (std::abs(u) <= a + kEps && std::abs(v) <= b + kEps) {
            turn_crawl_[k].push_back({dx, dy});
            break;
          }
        }
      }
    }
  }
}

void LatticeShapes::BuildHead(const ShapeFrame& f) {
  // the head's reach
  {
    const double head = (f.p.head_reach + f.p.margin) / f.resolution + kEps;
    const int reach = int(std::ceil(head));
    head_disc_.clear();
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        if (std::hypot(double(dx), double(dy)) <= head) head_disc_.push_back({dx, dy});
      }
    }
    body_reach_cells_ = std::max(body_reach_cells_, reach);
  }
}

void LatticeShapes::BuildBlindLeads() {
  // the cells a blind move brings under the footprint: offsets o of the new footprint with
  // o + step (relative to the old origin) outside the old one
  for (int q = 0; q < 2; ++q) {
    for (int k = 0; k < kNumHeadings; ++k) {
      const CellStep ahead = kSteps[k], across = kSteps[(k + 4) % kNumHeadings];
      const CellStep delta[4] = {{-ahead.dx, -ahead.dy},
                                 {across.dx, across.dy},
                                 {-across.dx, -across.dy},
                                 {ahead.dx, ahead.dy}};
      for (int b = 0; b < 4; ++b) {
        std::vector<CellStep>& lead = blind_lead_[q][k][b];
        lead.clear();
        for (const CellStep& o : footprint_[q][k]) {
          if (!Covers(footprint_[q][k], o.dx + delta[b].dx, o.dy + delta[b].dy)) lead.push_back(o);
        }
      }
    }
  }
}

void LatticeShapes::BuildClimbs(const ShapeFrame& f) {
  // climbs: every cell offset ahead within max_step_length whose part across the heading is at
  // most max_step_sideways (so at 26.6 and 45 degrees, whose lattice steps of 0.089 and 0.057 m
  // do not add up to a step over a riser within the limit, the robot still climbs on its
  // heading), with the cells the standing footprint sweeps: centres in the rectangle from the
  // start footprint's back edge to the end footprint's front edge, as wide as the two side by side
  const int reach_end = int(std::ceil(f.p.max_step_length / f.resolution + kEps));
  for (int k = 0; k < kNumHeadings; ++k) {
    const double a = f.half_along[0], b = f.half_across[0];
    climbs_[k].clear();
    for (int ey = -reach_end; ey <= reach_end; ++ey) {
      for (int ex = -reach_end; ex <= reach_end; ++ex) {
        const Eigen::Vector2d end = f.InFrame(k, ex, ey);
        const double along = end.x(), across = end.y(), length = std::hypot(along, across);
        if (along <= kEps || length > f.p.max_step_length + kEps ||
            std::abs(across) > f.p.max_step_sideways + kEps) {
          continue;
        }
        Climb climb;
        climb.to = {ex, ey};
        climb.length = length;
        climb.across = across;
        const int reach = int(std::ceil((length + std::hypot(a, b)) / f.resolution)) + 1;
        climb.swept = f.CellsIn(k, reach, -a, along + a, std::min(0.0, across) - b,
                                std::max(0.0, across) + b);
        const int n = std::max(std::abs(ex), std::abs(ey));
        for (int j = 1; j <= n; ++j) {
          climb.line.push_back(
              {int(std::lround(double(j * ex) / n)), int(std::lround(double(j * ey) / n))});
        }
        climbs_[k].push_back(std::move(climb));
      }
    }
    std::stable_sort(climbs_[k].begin(), climbs_[k].end(), [](const Climb& x, const Climb& y) {
      return x.length < y.length - kEps ||
             (x.length <= y.length + kEps && std::abs(x.across) < std::abs(y.across) - kEps);
    });
  }
}

// CachedShapes: a few robots' worth per thread, the oldest go when more come
const LatticeShapes& CachedShapes(const PlannerParams& p, double resolution) {
  // every PlannerParams field that LatticeShapes::Build reads
  using Key = std::array<double, 17>;
  const Key key = {resolution,
                   p.shoulder_width,
                   p.depth,
                   p.crawl_length,
                   p.crawl_width,
                   p.crawl_offset,
                   p.margin,
                   p.level_margin,
                   p.stance_width,
                   p.body_back,
                   p.body_front,
                   p.arm_reach,
                   p.head_reach,
                   p.max_step_length,
                   p.max_step_sideways,
                   p.max_stairs_heading_error,
                   p.kneel_offset};
  thread_local std::vector<std::pair<Key, std::unique_ptr<LatticeShapes>>> cache;
  for (const auto& [k, shapes] : cache) {
    if (k == key) return *shapes;
  }
  constexpr size_t kKept = 8;
  if (cache.size() == kKept) cache.erase(cache.begin());
  auto shapes = std::make_unique<LatticeShapes>();
  shapes->Build(p, resolution);
  cache.emplace_back(key, std::move(shapes));
  return *cache.back().second;
}

}  // namespace fognav::navigation::internal

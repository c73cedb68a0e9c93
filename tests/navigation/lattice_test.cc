#include "navigation/internal/lattice.h"

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "navigation/internal/test_worlds.h"
#include "navigation/planner.h"

namespace fognav::navigation::internal {
namespace {

using perception::CellType;
using perception::Fog;
using perception::Pose2;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Plain Dijkstra over every state of the lattice from the start seeds: the cheapest
// path cost plus end cost, +infinity if none.
double BruteForceCost(const Fog& fog, const Pose2& start, const Eigen::Vector2d& goal,
                      const PlannerParams& p, Posture posture, End end = End::kGoal) {
  Lattice lattice(fog, goal, p, nullptr, end);
  std::vector<double> dist(size_t(lattice.NumStates()), kInf);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (const Seed& s : lattice.StartSeeds(start, posture)) {
    if (s.cost < dist[size_t(s.state)]) {
      dist[size_t(s.state)] = s.cost;
      queue.push({s.cost, s.state});
    }
  }
  double best = kInf;
  Successor succ[kMaxSuccessors];
  while (!queue.empty()) {
    const auto [d, s] = queue.top();
    queue.pop();
    if (d > dist[size_t(s)]) continue;
    best = std::min(best, d + lattice.TerminalCost(s));
    const int n = lattice.Successors(s, succ);
    for (int i = 0; i < n; ++i) {
      const double nd = d + succ[i].cost;
      if (nd < dist[size_t(succ[i].state)]) {
        dist[size_t(succ[i].state)] = nd;
        queue.push({nd, succ[i].state});
      }
    }
  }
  return best;
}

// A small map with a bit of everything: random obstacles of random heights, a tread, a table,
// unknown patches.
Fog ClutteredFog(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Fog fog = FlatFog(36, 30, 0.04);  // 1.44 m x 1.2 m
  FillBox(&fog, 0.60, 0.0, 0.76, 1.2, CellType::kFloor, 0.03f);
  FillBox(&fog, 0.90, 0.70, 1.10, 0.90, CellType::kFloor, 0.10f);  // a platform: border rim
  ClassifyFloorChanges(&fog, 0.015, 0.05);
  FillBox(&fog, 1.00, 0.10, 1.30, 0.50, CellType::kTunnel, 0.0f);
  for (int i = 0; i < 6; ++i) {
    const double x = 0.2 + 1.1 * u(rng), y = 1.1 * u(rng);
    const double sx = 0.04 + 0.12 * u(rng), sy = 0.04 + 0.12 * u(rng);
    const float h = float(0.05 + 0.3 * u(rng));
    FillBox(&fog, x, y, x + sx, y + sy, CellType::kObstacle, h);
  }
  for (int i = 0; i < 3; ++i) {
    const double x = 1.3 * u(rng), y = 1.1 * u(rng);
    FillBox(&fog, x, y, x + 0.12, y + 0.12, CellType::kUnknown, -INFINITY);
  }
  return fog;
}

TEST(Lattice, AStarCostEqualsBruteForceDijkstra) {
  PlannerParams p;
  p.clearance_radius = 0.3;
  int found = 0, none = 0;
  // the planner's per-thread scratch memory holds states of other windows in between
  const Course course = PaperCourse();
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    if (seed % 3 == 1) {
      ASSERT_EQ(Plan(course.fog, course.start_G, course.goal_G, p).status, PlanStatus::kOk);
    }
    const Fog fog = ClutteredFog(seed);
    const Pose2 start{0.14, 0.58, 0.3};
    for (const Eigen::Vector2d& goal : {Eigen::Vector2d(1.30, 0.62), Eigen::Vector2d(1.16, 0.30),
                                       Eigen::Vector2d(3.0, 0.9)}) {
      const PlanResult r = Plan(fog, start, goal, p);
      double expected = BruteForceCost(fog, start, goal, p, Posture::kUpright);
      if (expected == kInf && goal.x() > 1.44) {  // outside the window: as near it as may be
        expected = BruteForceCost(fog, start, goal, p, Posture::kUpright, End::kToward);
      }
      if (expected == kInf) {
        EXPECT_EQ(r.status, PlanStatus::kNoPath) << "seed " << seed;
        ++none;
      } else {
        ASSERT_EQ(r.status, PlanStatus::kOk) << "seed " << seed;
        EXPECT_NEAR(r.cost, expected, 1e-9 * expected) << "seed " << seed << " goal "
                                                        << goal.transpose();
        ++found;
      }
    }
  }
  // the worlds are mostly passable, so the comparison means something (goals under the small
  // tunnels are often out of reach: the robot gets down only where its crawling footprint is
  // clear of tunnel cells)
  EXPECT_GT(found, 15) << found << " found, " << none << " without a path";
}

TEST(Lattice, AStarCostEqualsBruteForceDijkstraFromUnderATable) {
  PlannerParams p;
  Fog fog = FlatFog(36, 30, 0.04);
  FillBox(&fog, 0.80, 0.20, 1.20, 0.80, CellType::kTunnel, 0.0f);
  FillBox(&fog, 0.80, 0.20, 0.84, 0.24, CellType::kObstacle, 0.56f);
  FillBox(&fog, 0.30, 0.70, 0.50, 1.00, CellType::kObstacle, 0.20f);
  FillBox(&fog, 0.10, 0.10, 0.40, 0.30, CellType::kUnknown, -INFINITY);
  const Pose2 start{1.00, 0.50, 2.8};
  const Eigen::Vector2d goal(0.20, 0.20);
  const PlanResult r = Plan(fog, start, goal, p, Posture::kCrawling);
  const double expected = BruteForceCost(fog, start, goal, p, Posture::kCrawling);
  ASSERT_LT(expected, kInf);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_NEAR(r.cost, expected, 1e-9 * expected);
  EXPECT_EQ(r.path.back().posture, Posture::kUpright);  // it crawled out and got up
}

// A path as runs of (move, heading) pairs: each pose after the first as its move's letter (w
// walk, s sidestep, t turn, u/d stairs up/down, c crawl) and its lattice heading in hex, a run
// of the same pair followed by its length ("w07" is seven walks along heading 0).
std::string MovesOf(const PlanResult& r) {
  static const char kLetter[kNumMoves + 1] = "nwstudc";
  std::vector<std::string> poses;
  for (size_t i = 1; i < r.path.size(); ++i) {
    const PathPose& q = r.path[i];
    const char heading = "0123456789abcdef"[NearestHeading(q.pose_G.yaw)];
    poses.push_back(std::string(1, kLetter[int(q.move)]) + heading);
  }
  std::string out;
  for (size_t i = 0; i < poses.size();) {
    size_t j = i;
    while (j < poses.size() && poses[j] == poses[i]) ++j;
    out += (out.empty() ? "" : " ") + poses[i] + (j - i > 1 ? std::to_string(j - i) : "");
    i = j;
  }
  return out;
}

// The plans the search found before it was made faster (commit be9dea0): the same moves at the
// same cost, which is the brute-force Dijkstra's. A faster search that breaks ties differently
// or prunes a state it should not fails here.
TEST(Lattice, FasterSearchKeepsThePlans) {
  struct Case {
    const char* name;
    Fog fog;
    Pose2 start;
    Eigen::Vector2d goal;
    double clearance_radius;
    double cost;
    const char* moves;
  };
  const Course course = PaperCourse();
  const Fog table = CorridorWithTable();
  const std::vector<Case> cases = {
      {"course", course.fog, course.start_G, course.goal_G, 0.6, 10.148540144593401,
       "w07 t1 w1 t2 t3 s33 t2 s2 w2 t1 w1 t0 w02 u0 w04 u0 w05 d0 w04 d0 w02 t1 t2 t3 t4 s417 "
       "w43 c4 t3 t2 t1 t0 c021"},
      {"table", table, {0.3, 0.9, 0.0}, {2.9, 1.2}, 0.6, 7.4029926386806872,
       "t1 w17 t0 w02 c032 w017"},
      {"table straight", table, {0.3, 1.2, 0.0}, {2.9, 1.2}, 0.6, 6.9786646604855251,
       "w016 c032 w017"},
      {"cluttered 2", ClutteredFog(2), {0.14, 0.58, 0.3}, {1.30, 0.62}, 0.3, 5.8225430496183748,
       "t0 tf te td wd4 te we3 tf wf t0 w0 u0 w0 s022 d0 s02 w0 t1 w1 t0 w04 tf wf2 te we2 td wd "
       "tc wc5"},
      {"cluttered 4", ClutteredFog(4), {0.14, 0.58, 0.3}, {1.30, 0.62}, 0.3, 3.8739182915732773,
       "t0 w0 s08 t1 w15 t0 w0 u0 w0 d0 w09 tf wf te we2 td wd tc wc6"},
  };
  for (const Case& c : cases) {
    PlannerParams p;
    p.clearance_radius = c.clearance_radius;
    const PlanResult r = Plan(c.fog, c.start, c.goal, p);
    ASSERT_EQ(r.status, PlanStatus::kOk) << c.name;
    EXPECT_NEAR(r.cost, c.cost, 1e-9 * c.cost) << c.name;
    EXPECT_NEAR(r.cost, BruteForceCost(c.fog, c.start, c.goal, p, Posture::kUpright),
                1e-9 * c.cost)
        << c.name;
    EXPECT_EQ(MovesOf(r), c.moves) << c.name;
  }
}

// Plan's fallback for a goal beyond the window that no way out leads toward searches the
// lattice of its first search again with the other end (Lattice::SetEnd): the plan is the one a
// fresh lattice gives (PlanToward), state for state. The way out is a wall's L-shaped slot too
// narrow to turn the corner in, which only the full first search shows to be closed.
TEST(Lattice, FallbackOnTheSameLatticeGivesTheFreshPlan) {
  const PlannerParams p;
  Fog fog = FlatFog(100, 100, 0.04);
  FillBox(&fog, 2.0, 0.0, 2.4, 4.0, CellType::kObstacle, 0.3f);
  FillBox(&fog, 1.96, 1.0, 2.26, 1.16, CellType::kFloor, 0.0f);
  FillBox(&fog, 2.1, 1.0, 2.26, 1.8, CellType::kFloor, 0.0f);
  FillBox(&fog, 2.1, 1.64, 2.44, 1.8, CellType::kFloor, 0.0f);
  const Pose2 start{0.5, 2.02, 0.0};
  const Eigen::Vector2d goal(5.0, 2.02);  // beyond the wall and the window
  const PlanResult fallback = Plan(fog, start, goal, p);
  const PlanResult fresh = PlanToward(fog, start, goal, p);
  ASSERT_EQ(fresh.status, PlanStatus::kOk);
  ASSERT_EQ(fallback.status, PlanStatus::kOk);
  EXPECT_FALSE(fallback.reaches_goal);
  EXPECT_LT(fallback.path.back().pose_G.x, 2.0);  // short of the wall
  EXPECT_EQ(fallback.cost, fresh.cost);
  EXPECT_EQ(fallback.expanded, fresh.expanded);
  EXPECT_EQ(MovesOf(fallback), MovesOf(fresh));
  EXPECT_GT(fallback.path.size(), 5u);
}

// The heuristic's Dijkstra settles only as far as the search asks: its values do not depend on
// the order in which the states are asked for (the goal in the window, beyond it, toward it).
TEST(Lattice, HeuristicIsTheSameInWhateverOrderItIsAsked) {
  const PlannerParams p;
  std::mt19937 rng(7);
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const Fog fog = ClutteredFog(seed);
    for (const auto& [goal, end] : {std::pair(Eigen::Vector2d(1.30, 0.62), End::kGoal),
                                    std::pair(Eigen::Vector2d(3.0, 0.9), End::kGoal),
                                    std::pair(Eigen::Vector2d(3.0, 0.9), End::kToward)}) {
      Lattice ascending(fog, goal, p, nullptr, end), descending(fog, goal, p, nullptr, end);
      Lattice sampled(fog, goal, p, nullptr, end);
      const int n = ascending.NumStates();
      std::vector<double> down(size_t(n), 0.0);
      for (int s = n - 1; s >= 0; --s) down[size_t(s)] = descending.Heuristic(s);
      std::uniform_int_distribution<int> any(0, n - 1);
      for (int i = 0; i < 50; ++i) sampled.Heuristic(any(rng));
      int finite = 0;
      for (int s = 0; s < n; ++s) {
        const double h = ascending.Heuristic(s);
        ASSERT_EQ(h, down[size_t(s)]) << "state " << s;
        ASSERT_EQ(h, sampled.Heuristic(s)) << "state " << s;
        finite += h < kInf;
      }
      EXPECT_GT(finite, n / 4) << "seed " << seed;
    }
  }
}

TEST(Lattice, HeuristicIsConsistent) {
  const PlannerParams p;
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    const Fog fog = ClutteredFog(seed);
    for (const Eigen::Vector2d& goal : {Eigen::Vector2d(1.30, 0.62), Eigen::Vector2d(3.0, 0.9)}) {
      Lattice lattice(fog, goal, p);
      Successor succ[kMaxSuccessors];
      int checked = 0;
      for (int s = 0; s < lattice.NumStates(); ++s) {
        if (!lattice.Valid(s)) continue;
        const double h = lattice.Heuristic(s);
        EXPECT_LE(h, lattice.TerminalCost(s) + 1e-12);
        const int n = lattice.Successors(s, succ);
        for (int i = 0; i < n; ++i) {
          ASSERT_LE(h, succ[i].cost + lattice.Heuristic(succ[i].state) + 1e-12)
              << "state " << s << " -> " << succ[i].state;
          ++checked;
        }
      }
      EXPECT_GT(checked, 1000);
    }
  }
}

// Open floor with a ramp rising 0.5 cm per cell along x (every neighbour within h_floor, but a
// footprint across it spans 3 cm), treads of 3 and 6 cm, a 10 cm platform with its border rim,
// an obstacle, a table, and unknown patches, one of them over a riser.
Fog LevelsFog() {
  Fog fog = FlatFog(40, 36, 0.04);  // 1.6 m x 1.44 m
  for (int iy = 0; iy < 12; ++iy) {
    for (int ix = 0; ix < 40; ++ix) fog.height[size_t(fog.window.Index(ix, iy))] = 0.005f * ix;
  }
  FillBox(&fog, 0.40, 0.48, 0.60, 1.44, CellType::kFloor, 0.03f);
  FillBox(&fog, 0.60, 0.48, 0.84, 1.44, CellType::kFloor, 0.06f);
  FillBox(&fog, 1.10, 0.90, 1.40, 1.20, CellType::kFloor, 0.10f);
  ClassifyFloorChanges(&fog, 0.015, 0.05);
  FillBox(&fog, 1.20, 0.56, 1.32, 0.64, CellType::kObstacle, 0.2f);
  FillBox(&fog, 0.96, 0.48, 1.16, 0.72, CellType::kTunnel, 0.0f);
  FillBox(&fog, 0.56, 1.00, 0.64, 1.20, CellType::kUnknown, -INFINITY);
  FillBox(&fog, 1.40, 0.10, 1.52, 0.30, CellType::kUnknown, -INFINITY);
  return fog;
}

// Standing is allowed exactly where no footprint cell is an obstacle or tunnel, the known floor
// heights (not unknown, finite) under the soles' stance grown by level_margin span at most
// h_floor with the floor under the origin, and those outside it are within h_stairs of the
// origin's, checked cell by cell here, so the planner's shortcuts (distance transforms, height
// ranges) can never let a footprint span a step, even on a ramp where no neighbours differ by
// more than h_floor.
TEST(Lattice, StandingIsAllowedExactlyWhereTheFootprintIsLevel) {
  const PlannerParams p;
  const Fog fog = LevelsFog();
  const perception::GridWindow& w = fog.window;
  Lattice lattice(fog, {1.5, 0.7}, p);
  const double a = 0.5 * p.depth + p.margin, b = 0.5 * p.shoulder_width + p.margin;
  const double la = 0.5 * p.depth + p.level_margin, lb = 0.5 * p.stance_width + p.level_margin;
  int allowed = 0, refused_for_level = 0;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const double level = lattice.FloorHeight(w.Index(ix, iy));
      for (int k = 0; k < kNumHeadings; ++k) {
        const double c = std::cos(HeadingYaw(k)), s = std::sin(HeadingYaw(k));
        bool fits = true, off_level = false;
        double lo = std::isfinite(level) ? level : INFINITY, hi = -lo;
        for (int dy = -6; dy <= 6; ++dy) {
          for (int dx = -6; dx <= 6; ++dx) {
            const double u = (dx * c + dy * s) * w.resolution;
            const double v = (-dx * s + dy * c) * w.resolution;
            const CellType t =
                w.Contains(ix + dx, iy + dy) ? fog.TypeAt(ix + dx, iy + dy) : CellType::kUnknown;
            const float h = w.Contains(ix + dx, iy + dy) ? fog.HeightAt(ix + dx, iy + dy) : 0.0f;
            // within the head's reach nothing rises more than head_low above the origin's floor
            if (std::hypot(dx, dy) * w.resolution <= p.head_reach + p.margin + 1e-9 &&
                t != CellType::kUnknown && t != CellType::kTunnel && std::isfinite(h) &&
                std::isfinite(level) && double(h) - level > p.head_low) {
              fits = false;
            }
            if (std::abs(u) > a + 1e-9 || std::abs(v) > b + 1e-9) continue;
            if (!w.Contains(ix + dx, iy + dy)) continue;
            if (t == CellType::kUnknown) continue;
            const bool ring = std::abs(u) > la + 1e-9 || std::abs(v) > lb + 1e-9;
            if (t == CellType::kObstacle || t == CellType::kTunnel) {
              fits = false;
            } else if (!std::isfinite(h) || !std::isfinite(level)) {
              fits = fits && t != CellType::kBorder;
            } else if (ring && std::abs(double(h) - level) > p.h_stairs) {
              fits = false;
              off_level = true;
            } else if (!ring) {
              lo = std::min(lo, double(h));
              hi = std::max(hi, double(h));
            }
          }
        }
        if (hi - lo > p.h_floor) {
          fits = false;
          off_level = true;
        }
        // and no tunnel cell within the head's reach
        const double head = p.head_reach + p.margin;
        for (int ty = 0; ty < w.size_y; ++ty) {
          for (int tx = 0; tx < w.size_x; ++tx) {
            if (fog.TypeAt(tx, ty) == CellType::kTunnel &&
                std::hypot(tx - ix, ty - iy) * w.resolution <= head + 1e-9) {
              fits = false;
            }
          }
        }
        const int s_up = lattice.StateIndex(ix, iy, k, Posture::kUpright);
        ASSERT_EQ(lattice.Valid(s_up), fits) << "cell " << ix << "," << iy << " heading " << k;
        allowed += fits;
        refused_for_level += off_level;
      }
    }
  }
  // the world has both, so the comparison means something
  EXPECT_GT(allowed, 3000);
  EXPECT_GT(refused_for_level, 3000);
  // on the ramp: level facing up it (the stance's 3 cells along span 1 cm), not across it (its
  // 5 cells span 2 cm, though each is within 1 cm of the origin's: a flat sole on the
  // origin's floor would meet the ramp 1 cm up)
  EXPECT_TRUE(lattice.Valid(lattice.StateIndex(20, 5, 0, Posture::kUpright)));
  EXPECT_FALSE(lattice.Valid(lattice.StateIndex(20, 5, 4, Posture::kUpright)));
}

// A riser inside a cell, as the map holds it: the column of cells it crosses at the mean of
// the two treads (2 and 4 cm, the column at 3 cm). Standing on the column, facing along it or
// across it, the soles cover both treads (each within h_floor of the origin's 3 cm, but 2 cm
// apart): not allowed. On either tread beside the column, or on the 2 cm tread alone, allowed.
TEST(Lattice, NoStandingAcrossARiserTheMapAveraged) {
  Fog fog = FlatFog(40, 30, 0.04);
  FillBox(&fog, 0.40, 0.0, 0.80, 1.2, CellType::kFloor, 0.02f);
  FillBox(&fog, 0.80, 0.0, 0.84, 1.2, CellType::kFloor, 0.03f);  // x cell 20
  FillBox(&fog, 0.84, 0.0, 1.20, 1.2, CellType::kFloor, 0.04f);
  ClassifyFloorChanges(&fog, 0.015, 0.05);
  Lattice lattice(fog, {1.4, 0.6}, PlannerParams());
  for (const int k : {0, 2, 4}) {
    EXPECT_FALSE(lattice.Valid(lattice.StateIndex(20, 15, k, Posture::kUpright))) << k;
    EXPECT_TRUE(lattice.Valid(lattice.StateIndex(15, 15, k, Posture::kUpright))) << k;
  }
  // facing +x, the soles' stance is 3 cells deep: two cells before or after the column it
  // ends a cell short of it; one cell before or after, it holds the column and one tread, 1 cm
  // apart
  EXPECT_TRUE(lattice.Valid(lattice.StateIndex(18, 15, 0, Posture::kUpright)));
  EXPECT_TRUE(lattice.Valid(lattice.StateIndex(22, 15, 0, Posture::kUpright)));
  EXPECT_TRUE(lattice.Valid(lattice.StateIndex(19, 15, 0, Posture::kUpright)));
  EXPECT_TRUE(lattice.Valid(lattice.StateIndex(21, 15, 0, Posture::kUpright)));
}

// Steps up and down go forward (at most max_step_sideways across the heading), by at most
// max_step_length, from a level standing state to one on a floor more than h_floor and at most
// h_stairs higher or lower, and cost at least their length at the stairs factor; walks,
// side-steps and crawls stay within h_floor; the heuristic stays consistent across them.
TEST(Lattice, StepsJumpBetweenLevelStatesWithinReach) {
  PlannerParams p;
  for (const double max_step : {0.16, 0.30}) {
    p.max_step_length = max_step;
    for (const Fog& fog : {LevelsFog(), ClutteredFog(3)}) {
      Lattice lattice(fog, {1.3, 0.62}, p);
      Successor succ[kMaxSuccessors];
      int steps = 0;
      for (int s = 0; s < lattice.NumStates(); ++s) {
        if (!lattice.Valid(s)) continue;
        const int n = lattice.Successors(s, succ);
        const double h0 = lattice.FloorHeight(lattice.CellOfState(s));
        for (int i = 0; i < n; ++i) {
          const int t = succ[i].state;
          ASSERT_LE(lattice.Heuristic(s), succ[i].cost + lattice.Heuristic(t) + 1e-12);
          const double dh = lattice.FloorHeight(lattice.CellOfState(t)) - h0;
          const Pose2 a = lattice.PoseOf(s), b = lattice.PoseOf(t);
          const double along = (b.x - a.x) * std::cos(a.yaw) + (b.y - a.y) * std::sin(a.yaw);
          if (succ[i].move != Move::kStairsUp && succ[i].move != Move::kStairsDown) {
            if (std::isfinite(dh)) {
              EXPECT_LE(std::abs(dh), p.h_floor + 1e-7) << MoveName(succ[i].move);
            }
            continue;
          }
          ++steps;
          EXPECT_EQ(lattice.HeadingOfState(t), lattice.HeadingOfState(s));
          EXPECT_EQ(lattice.PostureOfState(t), Posture::kUpright);
          EXPECT_TRUE(lattice.Valid(t));
          const double across = -(b.x - a.x) * std::sin(a.yaw) + (b.y - a.y) * std::cos(a.yaw);
          EXPECT_NEAR(std::hypot(along, across), succ[i].length, 1e-9);
          EXPECT_GT(along, 0.0);
          EXPECT_LE(std::abs(across), p.max_step_sideways + 1e-9);
          EXPECT_GT(succ[i].length, 0.0);
          EXPECT_LE(succ[i].length, p.max_step_length + 1e-9);
          EXPECT_GT(std::abs(dh), p.h_floor);
          EXPECT_LE(std::abs(dh), p.h_stairs + 1e-7);
          EXPECT_EQ(dh > 0, succ[i].move == Move::kStairsUp);
          EXPECT_GE(succ[i].cost, succ[i].length * p.stairs_factor - 1e-12);
        }
      }
      EXPECT_GT(steps, 20) << "max_step_length " << max_step;
    }
  }
}

TEST(Lattice, SuccessorsStayValidAndCostAtLeastTheirLength) {
  const PlannerParams p;
  const Fog fog = ClutteredFog(5);
  Lattice lattice(fog, {1.3, 0.6}, p);
  Successor succ[kMaxSuccessors];
  for (int s = 0; s < lattice.NumStates(); ++s) {
    if (!lattice.Valid(s)) continue;
    const int n = lattice.Successors(s, succ);
    ASSERT_LE(n, kMaxSuccessors);
    for (int i = 0; i < n; ++i) {
      EXPECT_TRUE(lattice.Valid(succ[i].state));
      EXPECT_GE(succ[i].cost, succ[i].length * p.walk_factor - 1e-12);
      EXPECT_GT(succ[i].cost, 0.0);
    }
  }
}

TEST(Lattice, DistanceTransformMatchesBruteForce) {
  std::mt19937 rng(7);
  const int nx = 23, ny = 17;
  std::vector<uint8_t> feature(size_t(nx * ny));
  for (auto& f : feature) f = (rng() % 13) == 0;
  std::vector<double> d2;
  SquaredDistanceTransform(feature, nx, ny, &d2);
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      double best = kFarSquared;
      for (int fy = 0; fy < ny; ++fy) {
        for (int fx = 0; fx < nx; ++fx) {
          if (feature[size_t(fy * nx + fx)]) {
            best = std::min(best, double((fx - x) * (fx - x) + (fy - y) * (fy - y)));
          }
        }
      }
      EXPECT_EQ(d2[size_t(y * nx + x)], best) << x << "," << y;
    }
  }
  std::vector<uint8_t> none(size_t(nx * ny), 0);
  SquaredDistanceTransform(none, nx, ny, &d2);
  for (double d : d2) EXPECT_EQ(d, kFarSquared);
}

TEST(Lattice, HeadingsAreTheSixteenCellStepsInOrder) {
  for (int k = 0; k < kNumHeadings; ++k) {
    const double yaw = HeadingYaw(k);
    const double next = HeadingYaw((k + 1) % kNumHeadings);
    double gap = next - yaw;
    if (gap <= 0) gap += 2 * M_PI;
    EXPECT_GT(gap, 0.3);
    EXPECT_LT(gap, 0.47);
    EXPECT_EQ(NearestHeading(yaw + 0.05), k);
    // a quarter turn of a step is the step four headings on
    const CellStep s = HeadingStep(k), q = HeadingStep((k + 4) % kNumHeadings);
    EXPECT_EQ(q.dx, -s.dy);
    EXPECT_EQ(q.dy, s.dx);
  }
}

TEST(Lattice, CrawlZoneSurroundsTheTunnel) {
  Fog fog = FlatFog(60, 30, 0.04);
  FillBox(&fog, 1.0, 0.0, 1.4, 1.2, CellType::kTunnel, 0.0f);
  Lattice lattice(fog, {2.2, 0.6}, PlannerParams());
  EXPECT_TRUE(lattice.CrawlAllowedAt(30, 15));  // under the table
  EXPECT_TRUE(lattice.CrawlAllowedAt(20, 15));  // 0.2 m before it
  EXPECT_TRUE(lattice.CrawlAllowedAt(6, 15));   // 0.76 m before it
  EXPECT_FALSE(lattice.CrawlAllowedAt(3, 15));  // 0.88 m before it
}

TEST(Lattice, ClearanceCostGrowsWithObstacleHeight) {
  Fog fog = FlatFog(60, 40, 0.04);
  FillBox(&fog, 0.40, 0.40, 0.48, 0.48, CellType::kObstacle, 0.08f);
  FillBox(&fog, 1.60, 0.40, 1.68, 0.48, CellType::kObstacle, 0.20f);
  Lattice lattice(fog, {2.2, 0.6}, PlannerParams());
  // 0.2 m from each obstacle
  EXPECT_GT(lattice.CellCost(46, 10), 2.0 * lattice.CellCost(16, 10));
  EXPECT_GT(lattice.CellCost(16, 10), 0.0);
  EXPECT_EQ(lattice.CellCost(30, 35), 0.0);  // far from both
}

// The successor of state s that reaches state t, or null.
const Successor* SuccessorTo(Lattice* lattice, int s, int t, Successor* succ) {
  const int n = lattice->Successors(s, succ);
  for (int i = 0; i < n; ++i) {
    if (succ[i].state == t) return &succ[i];
  }
  return nullptr;
}

// A crawling turn in place sweeps its head and hands through cells neither end covers: one such
// cell, found here from the footprint's sizes, refuses the turn when it is an obstacle, though
// both ends fit.
TEST(Lattice, CrawlingTurnIsRefusedWhenACellOnlyItsSweepCoversIsAnObstacle) {
  const PlannerParams p;
  const double a = 0.5 * p.crawl_length + p.margin, b = 0.5 * p.crawl_width + p.margin;
  const int cx = 30, cy = 30;
  auto under = [&](double yaw, int dx, int dy) {
    const double u = (dx * std::cos(yaw) + dy * std::sin(yaw)) * 0.04 - p.crawl_offset;
    const double v = (-dx * std::sin(yaw) + dy * std::cos(yaw)) * 0.04;
    return std::abs(u) <= a + 1e-9 && std::abs(v) <= b + 1e-9;
  };
  // the first cell under the footprint part way through a turn from heading k to k + 1 but
  // under neither end's
  int sx = 0, sy = 0, k = 0;
  bool found = false;
  for (k = 0; k < kNumHeadings / 4 && !found; ++k) {
    const double y0 = HeadingYaw(k), y1 = HeadingYaw(k + 1);
    for (int j = 1; j < 16 && !found; ++j) {
      const double yaw = y0 + (y1 - y0) * j / 16;
      for (int dy = -12; dy <= 12 && !found; ++dy) {
        for (int dx = -12; dx <= 12 && !found; ++dx) {
          if (under(yaw, dx, dy) && !under(y0, dx, dy) && !under(y1, dx, dy)) {
            sx = dx, sy = dy, found = true;
          }
        }
      }
    }
  }
  --k;
  ASSERT_TRUE(found);
  for (const bool blocked : {false, true}) {
    Fog fog = FlatFog(60, 60, 0.04, CellType::kTunnel);
    if (blocked) {
      fog.type[size_t(fog.window.Index(cx + sx, cy + sy))] = CellType::kObstacle;
      fog.height[size_t(fog.window.Index(cx + sx, cy + sy))] = 0.3f;
    }
    Lattice lattice(fog, {2.2, 1.2}, p);
    const int from = lattice.StateIndex(cx, cy, k, Posture::kCrawling);
    const int to = lattice.StateIndex(cx, cy, k + 1, Posture::kCrawling);
    ASSERT_TRUE(lattice.Valid(from) && lattice.Valid(to)) << blocked;
    Successor succ[kMaxSuccessors];
    EXPECT_EQ(SuccessorTo(&lattice, from, to, succ) == nullptr, blocked) << blocked;
    EXPECT_EQ(SuccessorTo(&lattice, to, from, succ) == nullptr, blocked) << blocked;
  }
}

// The cost of the standing move from cell (x0, y0) to (x1, y1) at heading k on `fog` with goal
// `goal`, or -1 if the lattice offers no such move.
double StandingMoveCost(const Fog& fog, const Eigen::Vector2d& goal, const PlannerParams& p, int k,
                        int x0, int y0, int x1, int y1) {
  Lattice lattice(fog, goal, p);
  Successor succ[kMaxSuccessors];
  const Successor* move = SuccessorTo(&lattice, lattice.StateIndex(x0, y0, k, Posture::kUpright),
                                      lattice.StateIndex(x1, y1, k, Posture::kUpright), succ);
  return move != nullptr ? move->cost : -1.0;
}

// A standing robot's tilted head reaches head_reach + margin (3 cells): nothing higher than
// head_low may lie there, a low block may.
TEST(Lattice, HeadKeepsClearOfTallSolids) {
  Fog fog = FlatFog(40, 30, 0.04);
  FillBox(&fog, 0.80, 0.20, 0.84, 0.24, CellType::kObstacle, 0.50f);   // cell (20, 5)
  FillBox(&fog, 0.80, 0.60, 0.84, 0.64, CellType::kObstacle, 0.20f);   // cell (20, 15)
  FillBox(&fog, 0.80, 1.00, 0.84, 1.04, CellType::kFloor, 0.46f);      // cell (20, 25): a top
  Lattice lattice(fog, {1.4, 0.6}, PlannerParams());
  for (int k : {0, 4, 8}) {  // facing it, beside it, facing away
    // three cells away: only the head reaches it
    EXPECT_FALSE(lattice.Valid(lattice.StateIndex(17, 5, k, Posture::kUpright))) << k;
    // (beside it, the shoulders' footprint itself covers the low block)
    if (k != 4) {
      EXPECT_TRUE(lattice.Valid(lattice.StateIndex(17, 15, k, Posture::kUpright))) << k;
    }
    EXPECT_FALSE(lattice.Valid(lattice.StateIndex(17, 25, k, Posture::kUpright))) << k;
    // four cells away: clear
    EXPECT_TRUE(lattice.Valid(lattice.StateIndex(16, 5, k, Posture::kUpright))) << k;
    EXPECT_TRUE(lattice.Valid(lattice.StateIndex(16, 25, k, Posture::kUpright))) << k;
  }
}

// A robot whose start pose is not allowed shuffles free; where that changes its posture, the
// states lie near where the change puts its origin (kneel_offset back getting up, forward
// getting down), not near where it starts: a robot crawling out from under a table that got up
// at once, as if it would stand where its knees were, came up with its head under the top.
TEST(Lattice, StartSeedsThatChangePostureLieWhereTheKneesPutTheRobot) {
  Fog fog = FlatFog(70, 40, 0.04);
  FillBox(&fog, 1.00, 0.40, 1.60, 1.20, CellType::kTunnel, 0.0f);  // a table's top over x < 1.6
  FillBox(&fog, 2.00, 0.76, 2.04, 0.84, CellType::kObstacle, 0.3f);  // a post before the knees
  PlannerParams p;
  p.kneel_offset = 0.178;
  Lattice lattice(fog, {2.6, 0.8}, p);
  for (const double yaw : {0.0, 0.3}) {
    // crawling out of the table facing +x; the post is under the crawling footprint
    const Pose2 start{1.70, 0.80, yaw};
    const std::vector<Seed> seeds = lattice.StartSeeds(start, Posture::kCrawling);
    ASSERT_FALSE(seeds.empty());
    ASSERT_NE(seeds.front().move, Move::kNone) << "the start pose itself should not be allowed";
    const Eigen::Vector2d up_at = Eigen::Vector2d(start.x, start.y) -
                                  p.kneel_offset * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    int crawling = 0;
    for (const Seed& seed : seeds) {
      const Pose2 q = lattice.PoseOf(seed.state);
      if (lattice.PostureOfState(seed.state) == Posture::kCrawling) {
        ++crawling;
        EXPECT_LE(std::hypot(q.x - start.x, q.y - start.y), p.start_escape_radius + 0.03);
        continue;
      }
      // getting up there puts the origin under the top, where no standing state is allowed
      EXPECT_LE(std::hypot(q.x - up_at.x(), q.y - up_at.y()), p.start_escape_radius + 0.03)
          << q.x << " " << q.y;
    }
    EXPECT_GT(crawling, 0);  // it may crawl free (back, away from the post)
  }
}

// Walking backward and side-stepping never bring unknown cells under the footprint; walking
// forward may.
TEST(Lattice, BlindMovesStayOnKnownCells) {
  Fog fog = FlatFog(40, 30, 0.04);
  FillBox(&fog, 0.0, 0.0, 0.56, 1.2, CellType::kUnknown, -INFINITY);  // x < 0.56 unknown
  FillBox(&fog, 0.0, 0.0, 1.6, 0.44, CellType::kUnknown, -INFINITY);  // y < 0.44 unknown
  FillBox(&fog, 1.04, 0.0, 1.6, 1.2, CellType::kUnknown, -INFINITY);  // x >= 1.04 unknown
  Lattice lattice(fog, {0.8, 0.9}, PlannerParams());
  Successor succ[kMaxSuccessors];
  // whether standing state `from` has a move to cell (ix, iy), heading +x
  auto moves_to = [&](int from, int ix, int iy) {
    return SuccessorTo(&lattice, from, lattice.StateIndex(ix, iy, 0, Posture::kUpright), succ) !=
           nullptr;
  };
  // facing +x at (15, 14): the footprint covers x cells 14..16 and y cells 11..17, all known
  const int s = lattice.StateIndex(15, 14, 0, Posture::kUpright);
  ASSERT_TRUE(lattice.Valid(s));
  // back to x cell 13 brings unknown cells 13 under it; right to y cell 13 brings row 10
  EXPECT_FALSE(moves_to(s, 14, 14));
  EXPECT_FALSE(moves_to(s, 15, 13));
  // left and forward are known
  EXPECT_TRUE(moves_to(s, 15, 15));
  EXPECT_TRUE(moves_to(s, 16, 14));
  // facing +x at (24, 20), the cell ahead of x cell 26 is unknown: forward is allowed, as is
  // backward onto known cells
  const int f = lattice.StateIndex(24, 20, 0, Posture::kUpright);
  ASSERT_TRUE(lattice.Valid(f));
  EXPECT_TRUE(moves_to(f, 25, 20));
  EXPECT_TRUE(moves_to(f, 23, 20));
}

// Unknown cells the robot has stood on (Fog::walked) do not bar blind moves: it came over
// them. Unwalked unknown cells beside them still do.
TEST(Lattice, BlindMovesMayGoBackOverWalkedCells) {
  Fog fog = FlatFog(40, 30, 0.04);
  FillBox(&fog, 0.0, 0.0, 0.56, 1.2, CellType::kUnknown, -INFINITY);  // x < 0.56 unknown
  fog.walked.assign(fog.type.size(), 0);
  for (int iy = 11; iy <= 17; ++iy) {  // the way it came: x cells 10..13, y cells 11..17
    for (int ix = 10; ix <= 13; ++ix) fog.walked[size_t(fog.window.Index(ix, iy))] = 1;
  }
  Lattice walked(fog, {0.8, 0.9}, PlannerParams());
  fog.walked.clear();
  Lattice unwalked(fog, {0.8, 0.9}, PlannerParams());
  Successor succ[kMaxSuccessors];
  // whether standing state (fx, fy), heading +x, has a move to cell (ix, iy)
  auto moves_to = [&](Lattice* lattice, int fx, int fy, int ix, int iy) {
    const int from = lattice->StateIndex(fx, fy, 0, Posture::kUpright);
    EXPECT_TRUE(lattice->Valid(from));
    return SuccessorTo(lattice, from, lattice->StateIndex(ix, iy, 0, Posture::kUpright), succ) !=
           nullptr;
  };
  // facing +x at (15, 14) the footprint covers x cells 14..16 and y cells 11..17: back to x
  // cell 14 brings x cell 13, y cells 11..17 under it, all walked
  EXPECT_TRUE(moves_to(&walked, 15, 14, 14, 14));
  EXPECT_FALSE(moves_to(&unwalked, 15, 14, 14, 14));
  // one cell to the left, y cells 12..18: y cell 18 of x cell 13 is unknown and unwalked
  EXPECT_FALSE(moves_to(&walked, 15, 15, 14, 15));
  // forward is allowed either way
  EXPECT_TRUE(moves_to(&walked, 15, 15, 16, 15));
  EXPECT_TRUE(moves_to(&unwalked, 15, 15, 16, 15));
}

// The knees reach past the soles' footprint: a walk that ends with an obstacle under them costs
// body_touch_cost more than the same walk in the open.
TEST(Lattice, KneesOverAnObstacleCostMore) {
  Fog fog = FlatFog(40, 30, 0.04);
  FillBox(&fog, 0.80, 0.20, 0.84, 0.24, CellType::kObstacle, 0.10f);  // cell (20, 5)
  const PlannerParams p;
  Lattice lattice(fog, {1.4, 0.6}, p);
  Successor succ[kMaxSuccessors];
  // facing +x: from x cell 17 to 18 the obstacle comes 2 cells (0.08 m) ahead, under the knees
  // (0.09 m + margin) but not the soles (0.06 m + margin)
  const Successor* near = SuccessorTo(&lattice, lattice.StateIndex(17, 5, 0, Posture::kUpright),
                                      lattice.StateIndex(18, 5, 0, Posture::kUpright), succ);
  ASSERT_NE(near, nullptr);
  const double near_cost = near->cost;
  const Successor* open = SuccessorTo(&lattice, lattice.StateIndex(17, 20, 0, Posture::kUpright),
                                      lattice.StateIndex(18, 20, 0, Posture::kUpright), succ);
  ASSERT_NE(open, nullptr);
  const double open_cost = open->cost;
  // the clearance cost differs a little too: compare against the pure body term
  EXPECT_GT(near_cost - open_cost, 0.9 * p.body_touch_cost);
  EXPECT_LT(near_cost - open_cost, p.body_touch_cost + 0.1);
}

// The eyes see a wall from one side only: the unknown cells beside it may hold the rest of it
// (a wall's far face, a block's hidden corner, where hands hit in 60-degree-view missions). A
// walk that ends with a hand over such a cell costs body_touch_cost more than the same walk
// beside the same wall with known floor beyond it; beside unknown cells away from any solid, or
// beside a top lower than the hands, it costs nothing more.
TEST(Lattice, HandsKeepOffTheUnseenSideOfASolid) {
  const PlannerParams p;
  Fog seen = FlatFog(40, 30, 0.04);
  FillBox(&seen, 0.80, 0.20, 0.84, 0.60, CellType::kBorder, 0.30f);  // x cell 20, y cells 5-14
  Fog hidden = seen;
  FillBox(&hidden, 0.84, 0.20, 0.88, 0.60, CellType::kUnknown, -INFINITY);  // x cell 21
  Fog open = FlatFog(40, 30, 0.04);
  Fog open_unknown = open;
  FillBox(&open_unknown, 0.84, 0.20, 0.88, 0.60, CellType::kUnknown, -INFINITY);
  // facing +y at x cell 25 (centre 1.02 m): cell 21's centre lies 0.16 m across, within the
  // hands' reach (0.167 m with the margin) but beyond the footprint (0.145 m); cell 20's beyond
  const int k = NearestHeading(M_PI / 2);
  ASSERT_NEAR(HeadingYaw(k), M_PI / 2, 1e-9);
  auto walk_cost = [&](const Fog& fog) {
    return StandingMoveCost(fog, {1.0, 1.1}, p, k, 25, 8, 25, 9);
  };
  const double c_seen = walk_cost(seen), c_hidden = walk_cost(hidden);
  const double c_open = walk_cost(open), c_open_unknown = walk_cost(open_unknown);
  ASSERT_GT(c_seen, 0);
  ASSERT_GT(c_open, 0);
  EXPECT_NEAR(c_hidden - c_seen, p.body_touch_cost, 1e-9);
  EXPECT_NEAR(c_open_unknown, c_open, 1e-9);
  // the wall itself stays out of reach: known floor beside it costs only its clearance
  EXPECT_LT(c_seen - c_open, 0.5 * p.body_touch_cost);
  // a top below the hands (a 15 cm ottoman) passes under them, seen or not
  Fog low_seen = FlatFog(40, 30, 0.04);
  FillBox(&low_seen, 0.80, 0.20, 0.84, 0.60, CellType::kBorder, 0.15f);
  Fog low_hidden = low_seen;
  FillBox(&low_hidden, 0.84, 0.20, 0.88, 0.60, CellType::kUnknown, -INFINITY);
  ASSERT_LT(0.15, p.hand_low);
  EXPECT_NEAR(walk_cost(low_hidden), walk_cost(low_seen), 1e-9);
}

// The eyes never see the end of a block the robot turns round beside its feet: unknown cells
// within hidden_reach of a seen top may hold it. A walk that ends with the knees over such a
// cell costs body_touch_cost more when the top is higher than a step (the shins would meet
// it), and nothing more when the top is a step or lower, when no top is near, or when the
// cell is seen floor.
TEST(Lattice, KneesKeepOffUnseenCellsNearASeenTop) {
  const PlannerParams p;
  ASSERT_NEAR(p.hidden_reach, 0.08, 1e-9);
  auto world = [](float top, bool unknown) {
    Fog fog = FlatFog(40, 30, 0.04);
    if (top > 0) FillBox(&fog, 0.40, 0.20, 0.80, 0.60, CellType::kFloor, top);  // x cells 10-19
    if (unknown) FillBox(&fog, 0.80, 0.20, 0.88, 0.60, CellType::kUnknown, -INFINITY);  // 20-21
    return fog;
  };
  // facing -x from x cell 24 to 23 (centre 0.94 m): cell 21's centre lies 0.08 m ahead, under
  // the knees (0.09 m + margin) but not the soles (0.06 m + margin), two cells from the top
  const int k = NearestHeading(M_PI);
  ASSERT_NEAR(std::abs(HeadingYaw(k)), M_PI, 1e-9);
  auto walk_cost = [&](const Fog& fog) {
    return StandingMoveCost(fog, {0.2, 1.0}, p, k, 24, 8, 23, 8);
  };
  const double seen = walk_cost(world(0.175f, false)), hidden = walk_cost(world(0.175f, true));
  ASSERT_GT(seen, 0);
  EXPECT_NEAR(hidden - seen, p.body_touch_cost, 1e-9);
  // a top no higher than a step, or none, makes the unknown cells nothing to keep off
  const double open = walk_cost(world(0, false));
  EXPECT_NEAR(walk_cost(world(0.04f, true)), open, 1e-9);
  EXPECT_NEAR(walk_cost(world(0, true)), open, 1e-9);
  // beyond hidden_reach the top no longer counts
  PlannerParams near = p;
  near.hidden_reach = 0.04;
  EXPECT_NEAR(StandingMoveCost(world(0.175f, true), {0.2, 1.0}, near, k, 24, 8, 23, 8), seen, 1e-9);
}

// The low side of a top's edge (border cells at floor height) counts as the top for the body,
// since the map may end a top a cell short: a hand passing 0.16 m from such a cell beside a
// 0.28 m table top pays edge_touch_cost; beside a 0.15 m top (below the hands) it does not.
TEST(Lattice, HandsKeepOffTheLowSideOfATopsEdge) {
  const PlannerParams p;
  auto world = [](float top, bool border) {
    Fog fog = FlatFog(40, 30, 0.04);
    FillBox(&fog, 0.40, 0.20, 0.80, 0.60, CellType::kFloor, top);                // x cells 10-19
    if (border) FillBox(&fog, 0.80, 0.20, 0.84, 0.60, CellType::kBorder, 0.0f);  // cell 20
    return fog;
  };
  // facing +y from y cell 8 to 9 at x cell 24 (0.98 m): cell 20's centre lies 0.16 m to the
  // right, inside the hands' reach (0.152 m + margin), the top's cell 19 0.20 m, outside it
  const int k = NearestHeading(M_PI / 2);
  ASSERT_NEAR(HeadingYaw(k), M_PI / 2, 1e-9);
  auto walk_cost = [&](const Fog& fog) {
    return StandingMoveCost(fog, {0.2, 1.0}, p, k, 24, 8, 24, 9);
  };
  const double open = walk_cost(world(0.28f, false));
  ASSERT_GT(open, 0);
  EXPECT_NEAR(walk_cost(world(0.28f, true)) - open, p.edge_touch_cost, 1e-9);
  EXPECT_NEAR(walk_cost(world(0.15f, true)), walk_cost(world(0.15f, false)), 1e-9);
}

// A standing turn in place between two valid headings is offered exactly when no cell the
// soles' stance (grown by level_margin) sweeps on the way is an obstacle or tunnel and the
// known floors it sweeps, the ends' included, span at most h_floor with the origin's, and
// costs body_touch_cost more when the body (the legs' band as deep as the body rectangle and
// as wide as the footprint, the arms' as deep as the footprint and as wide as the hands
// reach) sweeps an obstacle, tunnel or a floor more than h_stairs higher beyond
// the body at the start heading (paid for on the way there). Checked cell by cell with the
// shapes turned in 100 steps (a cell centre moves by less than 1 mm per step); a cell whose
// centre lies within 2 mm of a shape's edge may count either way.
struct TurnCounts {
  int offered = 0, refused = 0, touching = 0, edge_touching = 0;
};

void CheckTurnsInPlace(const Fog& fog, TurnCounts* counts) {
  const PlannerParams p;
  const perception::GridWindow& w = fog.window;
  Lattice lattice(fog, {1.5, 0.7}, p);
  const double sa = 0.5 * p.depth + p.level_margin, sb = 0.5 * p.stance_width + p.level_margin;
  const double back = p.body_back + p.margin, front = p.body_front + p.margin;
  const double half = p.arm_reach + p.margin;
  const double a = 0.5 * p.depth + p.margin, b = 0.5 * p.shoulder_width + p.margin;
  const double legs_half = 0.5 * std::min(p.stance_width, p.shoulder_width) + p.margin;
  const int hr = int(std::lround(p.hidden_reach / w.resolution));
  Successor succ[kMaxSuccessors];
  int& offered = counts->offered;
  int& refused = counts->refused;
  int& touching = counts->touching;
  int& edge_touching = counts->edge_touching;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const double level = lattice.FloorHeight(w.Index(ix, iy));
      for (int k = 0; k < kNumHeadings; ++k) {
        const int k2 = (k + 1) % kNumHeadings;
        const int s = lattice.StateIndex(ix, iy, k, Posture::kUpright);
        const int t = lattice.StateIndex(ix, iy, k2, Posture::kUpright);
        if (!lattice.Valid(s) || !lattice.Valid(t)) continue;
        const double yaw = HeadingYaw(k), d = HeadingYaw(k2) - yaw;
        const double turn = std::atan2(std::sin(d), std::cos(d));
        // per cell: inside at some angle by more than 2 mm (surely), by less (maybe)
        bool soles_surely = false, soles_maybe = false, body_surely = false, body_maybe = false;
        bool edge_surely = false, edge_maybe = false;  // a hand over a border's low side only
        // the range of the known floors under the soles at any angle, with the origin's: [0]
        // surely, [1] maybe
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        if (std::isfinite(level)) lo[0] = lo[1] = hi[0] = hi[1] = level;
        for (int dy = -6; dy <= 6; ++dy) {
          for (int dx = -6; dx <= 6; ++dx) {
            if (!w.Contains(ix + dx, iy + dy)) continue;
            const CellType type = fog.TypeAt(ix + dx, iy + dy);
            const float h = fog.HeightAt(ix + dx, iy + dy);
            const bool known = type != CellType::kUnknown && std::isfinite(h);
            const bool solid = type == CellType::kObstacle || type == CellType::kTunnel;
            const bool off_level = solid || (known && std::abs(double(h) - level) > p.h_floor) ||
                                   (type == CellType::kBorder && !std::isfinite(h));
            // an unknown or border cell within hidden_reach of a floor, stairs or border cell
            // higher than the body reaches down there: hand_low anywhere, h_stairs at the legs
            double hidden_top = -std::numeric_limits<double>::infinity();
            if (type == CellType::kUnknown || type == CellType::kBorder) {
              for (int ny = iy + dy - hr; ny <= iy + dy + hr; ++ny) {
                for (int nx = ix + dx - hr; nx <= ix + dx + hr; ++nx) {
                  if (!w.Contains(nx, ny)) continue;
                  const CellType tn = fog.TypeAt(nx, ny);
                  const float hn = fog.HeightAt(nx, ny);
                  if ((tn == CellType::kBorder || tn == CellType::kFloor ||
                       tn == CellType::kStairs) &&
                      std::isfinite(hn)) {
                    hidden_top = std::max(hidden_top, double(hn));
                  }
                }
              }
            }
            // (the soles' footprint at the end is the end state's to check, as level floor)
            const bool hidden_legs = type == CellType::kUnknown && hidden_top - level > p.h_stairs;
            const bool hidden_hands = hidden_top - level > p.hand_low;
            const bool border = type == CellType::kBorder;
            const bool touch = solid || (known && double(h) - level > p.h_stairs);
            const bool near = std::hypot(dx, dy) * w.resolution <= std::hypot(sa, sb) + 0.003;
            if (!off_level && !touch && !hidden_legs && !hidden_hands && !(known && near)) continue;
            const double c1 = std::cos(yaw + turn), s1 = std::sin(yaw + turn);
            const double u1 = (dx * c1 + dy * s1) * w.resolution;
            const double v1 = (-dx * s1 + dy * c1) * w.resolution;
            const double u0 = (dx * std::cos(yaw) + dy * std::sin(yaw)) * w.resolution;
            const double v0 = (-dx * std::sin(yaw) + dy * std::cos(yaw)) * w.resolution;
            const bool at_start =
                (u0 >= -back - 0.002 && u0 <= front + 0.002 && std::abs(v0) <= half + 0.002) ||
                (std::abs(u0) <= a + 0.002 && std::abs(v0) <= b + 0.002);
            for (int j = 0; j <= 100; ++j) {
              const double c = std::cos(yaw + turn * j / 100), sn = std::sin(yaw + turn * j / 100);
              const double u = (dx * c + dy * sn) * w.resolution;
              const double v = (-dx * sn + dy * c) * w.resolution;
              for (const double g : {-0.002, 0.002}) {
                const bool in_soles = std::abs(u) <= sa + g && std::abs(v) <= sb + g;
                // on the way the body's shape, at the end the end state's rectangles
                const bool in_body =
                    j == 100 ? (u >= -back - g && u <= front + g && std::abs(v) <= half + g) ||
                                   (std::abs(u) <= a + g && std::abs(v) <= b + g)
                             : (u >= -back - g && u <= front + g && std::abs(v) <= b + g) ||
                                   (std::abs(u) <= a + g && std::abs(v) <= half + g);
                // the legs' band: at the end pose as wide as the legs, on the way as deep as
                // the body rectangle
                auto legs_band = [&](double gg) {
                  return std::abs(v) <= legs_half + gg &&
                         (j == 100 ? in_body : u >= -back - gg && u <= front + gg);
                };
                const bool in_legs = legs_band(g);
                // cells the end state covers count as it sees them: never under its soles,
                // with its own legs' band
                const bool in_end_soles = std::abs(u1) <= a - g && std::abs(v1) <= b - g;
                const bool in_end_body =
                    (u1 >= -back + g && u1 <= front - g && std::abs(v1) <= half - g) ||
                    in_end_soles;
                // unknown cells: the hands' top anywhere, a step's at the legs; border cells
                // (their low side): the hands' top beside the legs only, at the lesser cost
                const bool hidden_here = (hidden_hands && !border) || (hidden_legs && in_legs);
                const bool edge_here = hidden_hands && border && !legs_band(-g);
                const bool counted =
                    !in_end_soles && (j == 100 || !in_end_body) && in_body && (g > 0 || !at_start);
                (g < 0 ? soles_surely : soles_maybe) |= off_level && in_soles;
                if (known && in_soles) {
                  lo[g > 0] = std::min(lo[g > 0], double(h));
                  hi[g > 0] = std::max(hi[g > 0], double(h));
                }
                (g < 0 ? body_surely : body_maybe) |=
                    (touch && in_body && (g > 0 || !at_start)) || (hidden_here && counted);
                (g < 0 ? edge_surely : edge_maybe) |= edge_here && counted;
              }
            }
          }
        }
        soles_surely = soles_surely || hi[0] - lo[0] > p.h_floor;
        soles_maybe = soles_maybe || hi[1] - lo[1] > p.h_floor;
        const Successor* move = SuccessorTo(&lattice, s, t, succ);
        if (soles_surely) {
          EXPECT_EQ(move, nullptr) << "cell " << ix << "," << iy << " heading " << k;
        }
        if (!soles_maybe) {
          ASSERT_NE(move, nullptr) << "cell " << ix << "," << iy << " heading " << k;
        }
        if (move == nullptr) {
          ++refused;
          continue;
        }
        ++offered;
        const double extra = move->cost - std::abs(turn) * p.turn_cost_per_rad;
        if (body_surely) {
          EXPECT_NEAR(extra, p.body_touch_cost, 1e-9) << "cell " << ix << "," << iy << " " << k;
        }
        if (!body_maybe && edge_surely) {
          EXPECT_NEAR(extra, p.edge_touch_cost, 1e-9) << "cell " << ix << "," << iy << " " << k;
        }
        if (!body_maybe && !edge_maybe) {
          EXPECT_NEAR(extra, 0.0, 1e-9) << "cell " << ix << "," << iy << " " << k;
        }
        edge_touching += !body_maybe && edge_surely;
        touching += extra > 0;
      }
    }
  }
}

TEST(Lattice, TurnsInPlaceSweepOnlyLevelFloor) {
  TurnCounts counts;
  CheckTurnsInPlace(LevelsFog(), &counts);
  // the world has all three, so the comparison means something
  EXPECT_GT(counts.offered, 3000);
  EXPECT_GT(counts.refused, 20);
  EXPECT_GT(counts.touching, 100);
}

TEST(Lattice, TurnsInPlaceBesideATopsLowSidePayTheEdgeCost) {
  // a 0.28 m top whose low side the map typed border at floor height, a 0.15 m one likewise
  Fog fog = FlatFog(40, 30, 0.04);
  FillBox(&fog, 0.36, 0.36, 0.84, 0.84, CellType::kBorder, 0.0f);  // the ring, then the top
  FillBox(&fog, 0.40, 0.40, 0.80, 0.80, CellType::kFloor, 0.28f);
  FillBox(&fog, 0.96, 0.36, 1.24, 0.84, CellType::kBorder, 0.0f);
  FillBox(&fog, 1.00, 0.40, 1.20, 0.80, CellType::kFloor, 0.15f);
  TurnCounts counts;
  CheckTurnsInPlace(fog, &counts);
  EXPECT_GT(counts.offered, 3000);
  EXPECT_GT(counts.edge_touching, 20);
}

}  // namespace
}  // namespace fognav::navigation::internal

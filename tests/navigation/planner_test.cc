#include "navigation/planner.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "navigation/internal/test_worlds.h"

namespace fognav::navigation {
namespace {

using internal::ClassifyFloorChanges;
using internal::CorridorWithTable;
using internal::FillBox;
using internal::FlatFog;
using perception::CellType;
using perception::Fog;
using perception::Pose2;

int Count(const PlanResult& r, Move m) {
  return int(std::count_if(r.path.begin(), r.path.end(),
                           [&](const PathPose& q) { return q.move == m; }));
}

std::string Moves(const PlanResult& r) {
  std::string s;
  for (const PathPose& q : r.path) s += std::string(MoveName(q.move)) + " ";
  return s;
}

// Cells under a pose's footprint, computed here from the parameters independently of the
// planner: cells whose centre lies in the rectangle grown by `margin` (default p.margin).
// (`soles`: standing, only as wide as the soles' stance)
std::vector<std::pair<int, int>> FootprintCells(const Fog& fog, const PathPose& q,
                                                const PlannerParams& p, double margin = -1,
                                                bool soles = false) {
  const bool up = q.posture == Posture::kUpright;
  if (margin < 0) margin = p.margin;
  const double a = 0.5 * (up ? p.depth : p.crawl_length) + margin;
  const double b =
      0.5 * (up ? (soles ? p.stance_width : p.shoulder_width) : p.crawl_width) + margin;
  const double offset = up ? 0.0 : p.crawl_offset;
  std::vector<std::pair<int, int>> cells;
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      const Eigen::Vector2d d = fog.window.CellCenter(ix, iy) - Eigen::Vector2d(q.pose_G.x, q.pose_G.y);
      const double u = d.x() * std::cos(q.pose_G.yaw) + d.y() * std::sin(q.pose_G.yaw) - offset;
      const double v = -d.x() * std::sin(q.pose_G.yaw) + d.y() * std::cos(q.pose_G.yaw);
      if (std::abs(u) <= a + 1e-6 && std::abs(v) <= b + 1e-6) cells.push_back({ix, iy});
    }
  }
  return cells;
}

// Whether a cell has a known floor height: neither unknown nor obstacle, with a finite height.
bool KnownHeight(const Fog& fog, int ix, int iy) {
  const CellType t = fog.TypeAt(ix, iy);
  return t != CellType::kUnknown && t != CellType::kObstacle && std::isfinite(fog.HeightAt(ix, iy));
}

// The floor height under a path pose's origin: the FOG's where it is known (and then the
// pose's floor_z must agree), else the pose's floor_z (the nearest known floor's).
double OriginHeight(const Fog& fog, const PathPose& q) {
  int cx = 0, cy = 0;
  fog.window.CellOf(q.pose_G.x, q.pose_G.y, &cx, &cy);
  if (!KnownHeight(fog, cx, cy)) return q.floor_z;
  EXPECT_NEAR(q.floor_z, fog.HeightAt(cx, cy), 1e-6);
  return fog.HeightAt(cx, cy);
}

// Checks that a standing pose is level: every cell of the soles' stance grown by level_margin
// with a known floor height lies within h_floor of the floor under the origin, and every one of
// the whole footprint within h_stairs.
void ExpectLevel(const Fog& fog, const PathPose& q, const PlannerParams& p,
                 const std::string& what) {
  const double level = OriginHeight(fog, q);
  double lo = level, hi = level;  // under the soles
  for (const bool soles : {true, false}) {
    const double margin = soles ? p.level_margin : p.margin;
    for (const auto& [ix, iy] : FootprintCells(fog, q, p, margin, soles)) {
      if (!KnownHeight(fog, ix, iy)) continue;
      EXPECT_LE(std::abs(fog.HeightAt(ix, iy) - level), (soles ? p.h_floor : p.h_stairs) + 1e-7)
          << what << ": footprint cell " << ix << "," << iy << " ("
          << perception::CellTypeName(fog.TypeAt(ix, iy)) << ", " << fog.HeightAt(ix, iy)
          << " m) off the origin's level " << level << (soles ? " under the soles" : "");
      if (soles) {
        lo = std::min(lo, double(fog.HeightAt(ix, iy)));
        hi = std::max(hi, double(fog.HeightAt(ix, iy)));
      }
    }
  }
  // and the soles' floors span at most h_floor, the origin's with them
  EXPECT_LE(hi - lo, p.h_floor + 1e-7) << what << ": floors from " << lo << " to " << hi
                                       << " m under the soles";
}

// Checks every pose after the start: no obstacle cell under any footprint, a standing one level
// (so no border cell off the robot's own level) and on no tunnel cell, a crawling footprint only
// on tunnel, floor and unknown cells and border cells on its level.
void ExpectFootprintsClear(const Fog& fog, const PlanResult& r, const PlannerParams& p) {
  for (size_t i = 1; i < r.path.size(); ++i) {
    if (r.path[i].posture == Posture::kUpright) {
      ExpectLevel(fog, r.path[i], p,
                  "pose " + std::to_string(i) + " (" + MoveName(r.path[i].move) + ")");
    }
    for (const auto& [ix, iy] : FootprintCells(fog, r.path[i], p)) {
      const CellType t = fog.TypeAt(ix, iy);
      ASSERT_NE(t, CellType::kObstacle) << "pose " << i << " cell " << ix << "," << iy;
      if (r.path[i].posture == Posture::kUpright) {
        ASSERT_NE(t, CellType::kTunnel) << "pose " << i << " cell " << ix << "," << iy;
      } else {
        // border only on the origin's level (the foot of a wall beside a table)
        const bool level_border = t == CellType::kBorder && KnownHeight(fog, ix, iy) &&
                                  std::abs(fog.HeightAt(ix, iy) - r.path[i].floor_z) <=
                                      p.h_floor + 1e-7;
        ASSERT_TRUE(t == CellType::kTunnel || t == CellType::kFloor || t == CellType::kUnknown ||
                    level_border)
            << "pose " << i << " cell " << ix << "," << iy;
      }
    }
  }
}

// Checks that each pose follows from the one before by the move it is labelled with.
void ExpectMovesConsistent(const PlanResult& r) {
  for (size_t i = 2; i < r.path.size(); ++i) {
    const PathPose& a = r.path[i - 1];
    const PathPose& b = r.path[i];
    const Eigen::Vector2d d(b.pose_G.x - a.pose_G.x, b.pose_G.y - a.pose_G.y);
    const Eigen::Vector2d ahead(std::cos(a.pose_G.yaw), std::sin(a.pose_G.yaw));
    const double along = d.dot(ahead), across = ahead.x() * d.y() - ahead.y() * d.x();
    const double turn = std::remainder(b.pose_G.yaw - a.pose_G.yaw, 2 * M_PI);
    const std::string where = "pose " + std::to_string(i) + " (" + MoveName(b.move) + ")";
    switch (b.move) {
      case Move::kWalk:
      case Move::kStairsUp:
      case Move::kStairsDown:
        EXPECT_EQ(b.posture, Posture::kUpright) << where;
        // a step up or down may end a little beside its heading
        EXPECT_LE(std::abs(across),
                  b.move == Move::kWalk ? 1e-9 : PlannerParams().max_step_sideways + 1e-9)
            << where;
        EXPECT_GT(std::abs(along), 0.03) << where;
        if (b.move != Move::kWalk) {
          EXPECT_GT(along, 0.0) << where;  // steps are taken facing them
        }
        EXPECT_NEAR(turn, 0.0, 1e-9) << where;
        break;
      case Move::kSidestep:
        EXPECT_EQ(b.posture, Posture::kUpright) << where;
        EXPECT_NEAR(along, 0.0, 1e-9) << where;
        EXPECT_GT(std::abs(across), 0.03) << where;
        EXPECT_NEAR(turn, 0.0, 1e-9) << where;
        break;
      case Move::kTurn:
        EXPECT_NEAR(d.norm(), 0.0, 1e-9) << where;
        EXPECT_GT(std::abs(turn), 0.3) << where;
        EXPECT_LT(std::abs(turn), 0.47) << where;
        EXPECT_EQ(a.posture, b.posture) << where;
        break;
      case Move::kCrawl:
        if (a.posture != b.posture) {
          // getting down moves the origin forward to the knees, getting up back to the feet:
          // the kneel offset to the nearest lattice step
          const double kneel = PlannerParams().kneel_offset;
          EXPECT_NEAR(across, 0.0, 1e-9) << where;
          EXPECT_NEAR(b.posture == Posture::kCrawling ? along : -along, kneel, 0.045) << where;
        } else {
          EXPECT_EQ(b.posture, Posture::kCrawling) << where;
          EXPECT_NEAR(across, 0.0, 1e-9) << where;
        }
        EXPECT_NEAR(turn, 0.0, 1e-9) << where;
        break;
      case Move::kNone:
        ADD_FAILURE() << where << ": only the start has no move";
        break;
    }
  }
}

// Checks every step up or down: forward (at most max_step_sideways across), longer than 0 and
// at most max_step_length, between two level standing poses whose floors differ by more than
// h_floor and at most h_stairs, the floor_z of each end its own level, and no cell the
// footprint sweeps on the way an obstacle or more than h_floor beyond both levels. Returns how
// many there were.
int ExpectStepsFit(const Fog& fog, const PlanResult& r, const PlannerParams& p) {
  int steps = 0;
  for (size_t i = 1; i < r.path.size(); ++i) {
    const PathPose& b = r.path[i];
    if (b.move != Move::kStairsUp && b.move != Move::kStairsDown) continue;
    ++steps;
    const PathPose& a = r.path[i - 1];
    const std::string where = "pose " + std::to_string(i) + " (" + MoveName(b.move) + ")";
    EXPECT_EQ(a.posture, Posture::kUpright) << where;
    EXPECT_EQ(b.posture, Posture::kUpright) << where;
    const Eigen::Vector2d d(b.pose_G.x - a.pose_G.x, b.pose_G.y - a.pose_G.y);
    const Eigen::Vector2d ahead(std::cos(a.pose_G.yaw), std::sin(a.pose_G.yaw));
    const double along = d.dot(ahead), across = ahead.x() * d.y() - ahead.y() * d.x();
    EXPECT_GT(along, 0.0) << where;
    EXPECT_LE(std::abs(across), p.max_step_sideways + 1e-9) << where;
    EXPECT_LE(d.norm(), p.max_step_length + 1e-9) << where;
    ExpectLevel(fog, a, p, where + " start");
    ExpectLevel(fog, b, p, where + " end");
    const double h0 = OriginHeight(fog, a), h1 = OriginHeight(fog, b);
    EXPECT_GT(std::abs(h1 - h0), p.h_floor) << where;
    EXPECT_LE(std::abs(h1 - h0), p.h_stairs + 1e-7) << where;
    EXPECT_EQ(h1 > h0, b.move == Move::kStairsUp) << where;
    // the swept rectangle: from the start footprint's back edge to the end footprint's front
    const double half_depth = 0.5 * p.depth + p.margin;
    const double half_width = 0.5 * p.shoulder_width + p.margin;
    const double lo = std::min(h0, h1) - p.h_floor - 1e-7, hi = std::max(h0, h1) + p.h_floor + 1e-7;
    for (int iy = 0; iy < fog.window.size_y; ++iy) {
      for (int ix = 0; ix < fog.window.size_x; ++ix) {
        const Eigen::Vector2d c =
            fog.window.CellCenter(ix, iy) - Eigen::Vector2d(a.pose_G.x, a.pose_G.y);
        const double u = c.dot(ahead), v = ahead.x() * c.y() - ahead.y() * c.x();
        if (u < -half_depth - 1e-6 || u > along + half_depth + 1e-6 ||
            v < std::min(0.0, across) - half_width - 1e-6 ||
            v > std::max(0.0, across) + half_width + 1e-6) {
          continue;
        }
        EXPECT_NE(fog.TypeAt(ix, iy), CellType::kObstacle)
            << where << " sweeps " << ix << "," << iy;
        if (!KnownHeight(fog, ix, iy)) continue;
        EXPECT_GE(fog.HeightAt(ix, iy), lo) << where << " sweeps " << ix << "," << iy;
        EXPECT_LE(fog.HeightAt(ix, iy), hi) << where << " sweeps " << ix << "," << iy;
      }
    }
  }
  return steps;
}

// y of the path where it crosses x (linear between poses).
double YAtX(const PlanResult& r, double x) {
  for (size_t i = 1; i < r.path.size(); ++i) {
    const Pose2& a = r.path[i - 1].pose_G;
    const Pose2& b = r.path[i].pose_G;
    if ((a.x - x) * (b.x - x) <= 0 && a.x != b.x) return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
  }
  return NAN;
}

TEST(Planner, OpenFloorGivesStraightWalk) {
  const Fog fog = FlatFog(75, 50, 0.04);  // 3 m x 2 m
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.50, 1.02, 0.0}, {2.50, 1.02}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_TRUE(r.reaches_goal);
  EXPECT_EQ(Count(r, Move::kWalk), int(r.path.size()) - 1) << Moves(r);
  for (const PathPose& q : r.path) {
    EXPECT_NEAR(q.pose_G.y, 1.02, 1e-9);
    EXPECT_NEAR(q.pose_G.yaw, 0.0, 1e-9);
  }
  EXPECT_NEAR(r.path.back().pose_G.x, 2.50, p.goal_tolerance + 1e-9);
  EXPECT_NEAR(r.length, r.path.back().pose_G.x - 0.50, 1e-9);
  EXPECT_NEAR(r.cost, r.length * p.walk_factor, 1e-9);  // no obstacles, no unknown
}

TEST(Planner, TurnsTowardAGoalBehind) {
  const Fog fog = FlatFog(75, 50, 0.04);
  const PlanResult r = Plan(fog, {2.02, 1.02, 0.0}, {0.50, 1.02}, PlannerParams());
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_GT(Count(r, Move::kTurn), 0) << Moves(r);
  EXPECT_EQ(Count(r, Move::kSidestep), 0) << Moves(r);
  EXPECT_NEAR(std::abs(r.path.back().pose_G.yaw), M_PI, 1e-9);
}

// Fig. 12 of the paper: walking between an 8 cm and a 20 cm obstacle, the robot keeps further
// from the taller one.
TEST(Planner, PassesBetweenObstaclesFurtherFromTheTallerOne) {
  for (const bool tall_below : {true, false}) {
    Fog fog = FlatFog(75, 70, 0.04);  // 3 m x 2.8 m
    const float below = tall_below ? 0.20f : 0.08f, above = tall_below ? 0.08f : 0.20f;
    FillBox(&fog, 1.32, 0.80, 1.72, 1.12, CellType::kObstacle, below);  // gap y in [1.12, 1.72)
    FillBox(&fog, 1.32, 1.72, 1.72, 2.04, CellType::kObstacle, above);
    const PlannerParams p;
    const PlanResult r = Plan(fog, {0.30, 1.42, 0.0}, {2.70, 1.42}, p);
    ASSERT_EQ(r.status, PlanStatus::kOk);
    const double y = YAtX(r, 1.52);
    ASSERT_TRUE(std::isfinite(y)) << Moves(r);
    if (tall_below) {
      EXPECT_GE(y, 1.42 + 0.03) << "should keep away from the 20 cm obstacle below";
    } else {
      EXPECT_LE(y, 1.42 - 0.03) << "should keep away from the 20 cm obstacle above";
    }
    ExpectFootprintsClear(fog, r, p);
  }
}

// Two obstacles side by side across the way, with a passage on each side: the robot goes round
// the 8 cm one, away from the 20 cm one.
TEST(Planner, ChoosesThePassageAwayFromTheTallerObstacle) {
  for (const bool tall_below : {true, false}) {
    Fog fog = FlatFog(75, 70, 0.04);
    const float below = tall_below ? 0.20f : 0.08f, above = tall_below ? 0.08f : 0.20f;
    FillBox(&fog, 1.32, 1.12, 1.72, 1.40, CellType::kObstacle, below);
    FillBox(&fog, 1.32, 1.44, 1.72, 1.72, CellType::kObstacle, above);
    FillBox(&fog, 1.32, 1.40, 1.72, 1.44, CellType::kObstacle, 0.14f);
    const PlannerParams p;
    const PlanResult r = Plan(fog, {0.30, 1.42, 0.0}, {2.70, 1.42}, p);
    ASSERT_EQ(r.status, PlanStatus::kOk);
    const double y = YAtX(r, 1.52);
    ASSERT_TRUE(std::isfinite(y));
    if (tall_below) {
      EXPECT_GT(y, 1.72) << Moves(r);
    } else {
      EXPECT_LT(y, 1.12) << Moves(r);
    }
    ExpectFootprintsClear(fog, r, p);
  }
}

// A wall across the map at x in [1.5, 1.6) with one gap in y in [gap_y0, gap_y1).
Fog WallWithGap(double resolution, double gap_y0, double gap_y1) {
  const int nx = int(std::lround(3.0 / resolution)), ny = int(std::lround(2.4 / resolution));
  Fog fog = FlatFog(nx, ny, resolution);
  FillBox(&fog, 1.5, -1.0, 1.6, gap_y0, CellType::kObstacle, 0.20f);
  FillBox(&fog, 1.5, gap_y1, 1.6, 3.0, CellType::kObstacle, 0.20f);
  return fog;
}

// Every pose whose origin is within the wall's x range got there by side-stepping.
void ExpectSidestepsThroughWall(const PlanResult& r) {
  int inside = 0;
  for (size_t i = 1; i < r.path.size(); ++i) {
    const PathPose& q = r.path[i];
    if (q.pose_G.x > 1.46 && q.pose_G.x < 1.64) {
      ++inside;
      EXPECT_TRUE(q.move == Move::kSidestep) << "pose " << i << ": " << Moves(r);
    }
  }
  EXPECT_GT(inside, 0);
}

TEST(Planner, SidestepsThroughA22cmGap) {
  const PlannerParams p;
  // exact geometry on 2 cm cells: the gap is 11 cells
  {
    const Fog fog = WallWithGap(0.02, 1.00, 1.22);
    const PlanResult r = Plan(fog, {0.50, 1.11, 0.0}, {2.50, 1.11}, p);
    ASSERT_EQ(r.status, PlanStatus::kOk);
    ExpectSidestepsThroughWall(r);
    ExpectFootprintsClear(fog, r, p);
  }
  // the same gap on the map's 4 cm cells, where it shows as 5 or 4 free cells
  for (const double y0 : {1.00, 0.99}) {
    const Fog fog = WallWithGap(0.04, y0, y0 + 0.22);
    const PlanResult r = Plan(fog, {0.50, 1.10, 0.0}, {2.50, 1.10}, p);
    ASSERT_EQ(r.status, PlanStatus::kOk) << "gap from " << y0;
    ExpectSidestepsThroughWall(r);
    ExpectFootprintsClear(fog, r, p);
  }
}

TEST(Planner, WalksFacingThroughAWideGap) {
  const Fog fog = WallWithGap(0.04, 0.80, 1.40);
  const PlanResult r = Plan(fog, {0.50, 1.10, 0.0}, {2.50, 1.10}, PlannerParams());
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(Count(r, Move::kSidestep), 0) << Moves(r);
}

TEST(Planner, NoPathThroughAGapNarrowerThanTheDepth) {
  const PlannerParams p;
  {
    const Fog fog = WallWithGap(0.02, 1.00, 1.10);  // 0.10 m < 0.12 m depth
    const PlanResult r = Plan(fog, {0.50, 1.05, 0.0}, {2.50, 1.05}, p);
    EXPECT_EQ(r.status, PlanStatus::kNoPath);
    EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
    EXPECT_TRUE(r.path.empty());
  }
  {
    const Fog fog = WallWithGap(0.04, 1.00, 1.08);  // two free cells
    const PlanResult r = Plan(fog, {0.50, 1.06, 0.0}, {2.50, 1.06}, p);
    EXPECT_EQ(r.status, PlanStatus::kNoPath);
    EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
  }
}

TEST(Planner, CrawlsUnderATableAcrossACorridor) {
  const Fog fog = CorridorWithTable();
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.50, 1.22, 0.0}, {2.70, 1.22}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_TRUE(r.reaches_goal);
  EXPECT_GT(Count(r, Move::kCrawl), 2) << Moves(r);
  // down before the table, up after it, crawling wherever the origin is under it
  int changes = 0;
  for (size_t i = 1; i < r.path.size(); ++i) {
    const PathPose& q = r.path[i];
    if (q.posture != r.path[i - 1].posture) {
      ++changes;
      EXPECT_EQ(q.move, Move::kCrawl);
    }
    int ix = 0, iy = 0;
    fog.window.CellOf(q.pose_G.x, q.pose_G.y, &ix, &iy);
    if (fog.TypeAt(ix, iy) == CellType::kTunnel) {
      EXPECT_EQ(q.posture, Posture::kCrawling);
    }
  }
  EXPECT_GE(changes, 1);
  ExpectFootprintsClear(fog, r, p);
  ExpectMovesConsistent(r);
}

// A table seen only at its front edge: a tunnel band 0.16 m deep, then floor whose headroom the
// map has not seen up to x = 2.0. Getting up needs seen headroom under the standing footprint and
// the head, so the robot crawls on over the unseen floor (allowed for crawling) and stands up
// only beyond x = 2.0; without headroom information it stands up right after the band.
TEST(Planner, GetsUpOnlyWhereTheHeadroomIsSeen) {
  Fog fog = FlatFog(80, 60, 0.04);
  FillBox(&fog, 0.0, 0.0, 3.2, 0.6, CellType::kObstacle, 0.5f);
  FillBox(&fog, 0.0, 1.8, 3.2, 2.4, CellType::kObstacle, 0.5f);
  FillBox(&fog, 1.4, 0.6, 1.56, 1.8, CellType::kTunnel, 0.0f);
  fog.headroom_seen.assign(fog.type.size(), 1);
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      const double x = fog.window.CellCenter(ix, iy).x();
      if (x > 1.4 && x < 2.0) fog.headroom_seen[size_t(fog.window.Index(ix, iy))] = 0;
    }
  }
  const PlannerParams p;
  auto get_up_x = [](const PlanResult& r) {
    for (size_t i = 1; i < r.path.size(); ++i) {
      if (r.path[i - 1].posture == Posture::kCrawling && r.path[i].posture == Posture::kUpright) {
        return r.path[i].pose_G.x;
      }
    }
    return -1.0;
  };
  const PlanResult r = Plan(fog, {0.50, 1.22, 0.0}, {3.10, 1.22}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_TRUE(r.reaches_goal);
  // the head's reach clear of the unseen cells
  EXPECT_GE(get_up_x(r), 2.0 + p.head_reach) << Moves(r);
  ExpectFootprintsClear(fog, r, p);
  ExpectMovesConsistent(r);

  fog.headroom_seen.clear();
  const PlanResult without = Plan(fog, {0.50, 1.22, 0.0}, {3.10, 1.22}, p);
  ASSERT_EQ(without.status, PlanStatus::kOk);
  EXPECT_GT(get_up_x(without), 1.56);
  EXPECT_LT(get_up_x(without), 2.0) << Moves(without);
}

// Getting up where the headroom is unseen (get_up_under_seen_headroom off, the mission's last
// resort), the standing origin keeps unseen_headroom_clearance from every tunnel cell: a table's
// underside seen from below may end short of its edge.
TEST(Planner, GetsUpUnderUnseenHeadroomClearOfTheTunnel) {
  const Fog fog = CorridorWithTable();  // tunnel cells up to x = 2.0
  PlannerParams p;
  p.get_up_under_seen_headroom = false;
  auto get_up_x = [](const PlanResult& r) {
    for (size_t i = 1; i < r.path.size(); ++i) {
      if (r.path[i - 1].posture == Posture::kCrawling && r.path[i].posture == Posture::kUpright) {
        return r.path[i].pose_G.x;
      }
    }
    return -1.0;
  };
  const PlanResult r = Plan(fog, {1.70, 1.22, 0.0}, {3.10, 1.22}, p, Posture::kCrawling);
  ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
  EXPECT_GE(get_up_x(r), 1.98 + p.unseen_headroom_clearance) << Moves(r);
  ExpectFootprintsClear(fog, r, p);

  p.unseen_headroom_clearance = 0.0;
  const PlanResult near = Plan(fog, {1.70, 1.22, 0.0}, {3.10, 1.22}, p, Posture::kCrawling);
  ASSERT_EQ(near.status, PlanStatus::kOk);
  EXPECT_GT(get_up_x(near), 0.0);
  EXPECT_LT(get_up_x(near), 1.98 + 0.4) << Moves(near);
}

// Crawling, the robot does not move forward onto cells it has not seen (crawl_stays_known):
// a table whose far side is unseen, no headroom seen to get up, the goal beyond the unseen band.
TEST(Planner, CrawlsForwardOnlyOverSeenCells) {
  Fog fog = CorridorWithTable();
  FillBox(&fog, 2.0, 0.6, 2.4, 1.8, CellType::kUnknown, -INFINITY);
  fog.headroom_seen.assign(fog.type.size(), 0);
  PlannerParams p;
  const PlanResult kept = Plan(fog, {1.60, 1.22, 0.0}, {2.60, 1.22}, p, Posture::kCrawling);
  EXPECT_FALSE(kept.status == PlanStatus::kOk && kept.reaches_goal) << Moves(kept);
  p.crawl_stays_known = false;
  const PlanResult blind = Plan(fog, {1.60, 1.22, 0.0}, {2.60, 1.22}, p, Posture::kCrawling);
  ASSERT_EQ(blind.status, PlanStatus::kOk) << NoPathReasonName(blind.reason);
  EXPECT_TRUE(blind.reaches_goal);
  EXPECT_EQ(blind.path.back().posture, Posture::kCrawling);
}

// Also where no floor's headroom has been seen, as in a room with nothing above the eyes: the
// crawl zone then spans all its floor, but the robot gets down only near a tunnel. Here a
// corridor between two blocks that goes on unseen, so that no side-step may enter it: walking,
// the hands touch the blocks, and crawling was the cheaper way in (with the eyes at the floor).
TEST(Planner, NeverCrawlsWithoutATunnel) {
  Fog fog = FlatFog(75, 50, 0.04);
  PlannerParams cheap;
  cheap.crawl_factor = 0.5 * cheap.walk_factor + 0.6;  // even if crawling were cheap
  cheap.posture_change_cost = 0.0;
  const PlanResult open = Plan(fog, {0.50, 1.02, 0.0}, {2.50, 1.02}, cheap);
  ASSERT_EQ(open.status, PlanStatus::kOk);
  EXPECT_EQ(Count(open, Move::kCrawl), 0) << Moves(open);

  const PlannerParams p;
  FillBox(&fog, 1.0, 0.0, 2.2, 0.88, CellType::kObstacle, 0.3f);
  FillBox(&fog, 1.0, 1.16, 2.2, 2.0, CellType::kObstacle, 0.3f);
  FillBox(&fog, 1.2, 0.88, 2.2, 1.16, CellType::kUnknown, 0.0f);
  for (bool headroom_known : {false, true}) {
    if (headroom_known) fog.headroom_seen.assign(fog.type.size(), 0);
    const PlanResult r = Plan(fog, {0.50, 1.02, 0.0}, {2.60, 1.02}, p);
    ASSERT_EQ(r.status, PlanStatus::kOk) << headroom_known;
    EXPECT_TRUE(r.reaches_goal) << headroom_known;
    EXPECT_EQ(Count(r, Move::kCrawl), 0) << headroom_known << ": " << Moves(r);
  }
}

// Open floor 3 m x 1.6 m crossed by treads spanning its width.
Fog Treads(const std::vector<std::pair<double, float>>& treads_x0_height, double end_x) {
  Fog fog = FlatFog(75, 40, 0.04);
  for (size_t i = 0; i < treads_x0_height.size(); ++i) {
    const double x1 = i + 1 < treads_x0_height.size() ? treads_x0_height[i + 1].first : end_x;
    FillBox(&fog, treads_x0_height[i].first, 0.0, x1, 1.6, CellType::kFloor,
            treads_x0_height[i].second);
  }
  ClassifyFloorChanges(&fog, 0.015, 0.05);
  return fog;
}

TEST(Planner, ClimbsA3cmTreadUpThenDown) {
  const Fog fog = Treads({{1.4, 0.03f}}, 1.72);
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.50, 0.82}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(Count(r, Move::kStairsUp), 1) << Moves(r);
  EXPECT_EQ(Count(r, Move::kStairsDown), 1) << Moves(r);
  const auto up = std::find_if(r.path.begin(), r.path.end(),
                               [](const PathPose& q) { return q.move == Move::kStairsUp; });
  const auto down = std::find_if(r.path.begin(), r.path.end(),
                                 [](const PathPose& q) { return q.move == Move::kStairsDown; });
  EXPECT_LT(up - r.path.begin(), down - r.path.begin());
  // each step from the last level pose before the riser (the footprint's front cell the last
  // one before it) to the first level pose after it: three cells, 0.12 m
  EXPECT_NEAR((up - 1)->pose_G.x, 1.34, 1e-9);
  EXPECT_NEAR(up->pose_G.x, 1.46, 1e-9);
  EXPECT_NEAR((down - 1)->pose_G.x, 1.66, 1e-9);
  EXPECT_NEAR(down->pose_G.x, 1.78, 1e-9);
  // the rise of each step from the poses' floor heights
  EXPECT_NEAR(up->floor_z - (up - 1)->floor_z, 0.03, 1e-6);
  EXPECT_NEAR(down->floor_z - (down - 1)->floor_z, -0.03, 1e-6);
  EXPECT_NEAR(r.path.front().floor_z, 0.0, 1e-9);
  EXPECT_EQ(Count(r, Move::kSidestep), 0) << Moves(r);
  EXPECT_EQ(ExpectStepsFit(fog, r, p), 2);
  ExpectFootprintsClear(fog, r, p);
}

TEST(Planner, FacesTheStepsItClimbs) {
  const Fog fog = Treads({{1.4, 0.03f}}, 1.72);
  const PlannerParams p;
  // start and goal diagonal to the treads: the robot still steps up and down facing +x
  const PlanResult r = Plan(fog, {0.50, 0.30, 0.6}, {2.50, 1.30}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  int steps = 0;
  for (const PathPose& q : r.path) {
    if (q.move == Move::kStairsUp || q.move == Move::kStairsDown) {
      ++steps;
      EXPECT_LE(std::abs(q.pose_G.yaw), p.max_stairs_heading_error) << Moves(r);
    }
  }
  EXPECT_EQ(steps, 2) << Moves(r);
}

TEST(Planner, ClimbsTheCourseStairs) {
  const Fog fog = Treads({{1.0, 0.03f}, {1.25, 0.06f}, {1.6, 0.03f}}, 1.85);
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.50, 0.82}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(Count(r, Move::kStairsUp), 2) << Moves(r);
  EXPECT_EQ(Count(r, Move::kStairsDown), 2) << Moves(r);
  EXPECT_EQ(ExpectStepsFit(fog, r, p), 4);
  ExpectFootprintsClear(fog, r, p);
}

// The scenario's treads (3, 6 and 3 cm, 0.25, 0.35 and 0.25 m deep) at offsets across a cell,
// approached straight and at an angle: every standing pose is level, so no footprint spans a
// riser (the toes never go into the next riser), and every step is one jump of at most
// max_step_length between two level poses.
TEST(Planner, StandsLevelAndStepsWithinReachOnTheScenarioTreads) {
  const PlannerParams p;
  for (const double offset : {0.0, 0.01, 0.02, 0.03}) {
    const double x0 = 1.0 + offset;
    const Fog fog = Treads({{x0, 0.03f}, {x0 + 0.25, 0.06f}, {x0 + 0.60, 0.03f}}, x0 + 0.85);
    for (const Pose2& start :
         {Pose2{0.50, 0.82, 0.0}, Pose2{0.40, 0.30, 0.5}, Pose2{0.60, 1.30, -0.3}}) {
      const PlanResult r = Plan(fog, start, {2.60, 0.82}, p);
      const std::string where =
          "treads from x = " + std::to_string(x0) + ", start y = " + std::to_string(start.y);
      ASSERT_EQ(r.status, PlanStatus::kOk) << where;
      EXPECT_EQ(Count(r, Move::kStairsUp), 2) << where << ": " << Moves(r);
      EXPECT_EQ(Count(r, Move::kStairsDown), 2) << where << ": " << Moves(r);
      EXPECT_EQ(ExpectStepsFit(fog, r, p), 4) << where;
      ExpectFootprintsClear(fog, r, p);
      ExpectMovesConsistent(r);
    }
  }
}

// 2 cm treads as the map holds them when each riser lies inside a cell: a column of cells at
// the mean of the two levels (1 and 3 cm). Each such cell is within h_floor of both treads, so
// a test against the origin's floor alone let a robot on that column stand across the riser
// (the closed-loop collision: a sole met a tread 9 mm deep as the robot turned there). The
// plan still climbs, but never stands on floors spanning more than h_floor.
TEST(Planner, NeverStandsAcrossARiserTheMapAveraged) {
  const Fog fog = Treads({{1.0, 0.01f}, {1.04, 0.02f}, {1.32, 0.03f}, {1.36, 0.04f}}, 1.68);
  const PlannerParams p;
  for (const Pose2& start : {Pose2{0.50, 0.82, 0.0}, Pose2{0.40, 0.30, 0.5}}) {
    const PlanResult r = Plan(fog, start, {2.50, 0.82}, p);
    ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
    ExpectFootprintsClear(fog, r, p);
    ExpectMovesConsistent(r);
    // up onto the 4 cm tread and down off it: somewhere on the way, a step
    EXPECT_GE(Count(r, Move::kStairsUp) + Count(r, Move::kStairsDown), 2) << Moves(r);
  }
}

// The closed-loop collision: standing on the 3 cm tread with the origin 3 cm before the 6 cm
// riser, the footprint reaches onto the higher tread. That start is not allowed: the robot
// shuffles back to a level pose, then steps up.
TEST(Planner, ShufflesBackFromAStartWhoseFootprintSpansARiser) {
  const Fog fog = Treads({{1.0, 0.03f}, {1.24, 0.06f}, {1.6, 0.03f}}, 1.84);
  const PlannerParams p;
  const PlanResult r = Plan(fog, {1.21, 0.82, 0.0}, {2.50, 0.82}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
  ASSERT_GE(r.path.size(), 3u);
  EXPECT_LT(r.path[1].pose_G.x, 1.21);  // back, off the riser
  EXPECT_NEAR(r.path[1].floor_z, 0.03, 1e-6);
  EXPECT_EQ(r.path[2].move, Move::kStairsUp) << Moves(r);
  EXPECT_EQ(ExpectStepsFit(fog, r, p), 3);
  ExpectFootprintsClear(fog, r, p);
}

// A tread shallower than the footprint (0.10 m deep, which the map holds as two cells where it
// starts in the first half of a cell; the footprint is three deep) has no level pose, and the
// step over it onto the next tread would be longer than max_step_length and rise more than
// h_stairs: with no other way up, there is no path. A 3 cm threshold strip as shallow is not
// crossed either.
TEST(Planner, NoPathOverATreadShallowerThanTheFootprint) {
  const PlannerParams p;
  for (const double x0 : {1.40, 1.41}) {
    const Fog fog = Treads({{x0, 0.03f}, {x0 + 0.10, 0.06f}, {x0 + 0.50, 0.03f}}, x0 + 0.75);
    const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.60, 0.82}, p);
    EXPECT_EQ(r.status, PlanStatus::kNoPath) << "tread from x = " << x0 << ": " << Moves(r);
    EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
  }
  {
    const Fog fog = Treads({{1.40, 0.03f}, {1.50, 0.0f}}, 3.0);
    const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.60, 0.82}, p);
    EXPECT_EQ(r.status, PlanStatus::kNoPath) << Moves(r);
  }
  // the same staircase with the first tread 0.25 m deep is climbed
  const Fog deep = Treads({{1.40, 0.03f}, {1.65, 0.06f}, {2.05, 0.03f}}, 2.30);
  const PlanResult r = Plan(deep, {0.50, 0.82, 0.0}, {2.60, 0.82}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(ExpectStepsFit(deep, r, p), 4);
}

// A riser across the heading takes a step of three 4 cm cells (0.12 m): refused when the
// controller's longest step is shorter.
TEST(Planner, StepsNoLongerThanMaxStepLength) {
  const Fog fog = Treads({{1.4, 0.03f}}, 1.72);
  PlannerParams p;
  p.max_step_length = 0.11;
  EXPECT_EQ(Plan(fog, {0.50, 0.82, 0.0}, {2.50, 0.82}, p).status, PlanStatus::kNoPath);
  p.max_step_length = 0.12;
  const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.50, 0.82}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(ExpectStepsFit(fog, r, p), 2);
}

// Treads of 4 cm, 0.3 m deep, turned by `yaw` on a 3 m x 2.4 m floor: the tread of a cell is
// the number of risers (at s = 1.2, 1.5, ... along the turned axis through (0, 1.2), shifted by
// `offset`) its centre has passed, or with `highest` the most that any part of the cell has (the
// ground-truth FOG's heights, sampled at 16 points).
Fog TurnedTreads(double yaw, int treads, double offset = 0, bool highest = false) {
  Fog fog = FlatFog(75, 60, 0.04);
  const Eigen::Vector2d up(std::cos(yaw), std::sin(yaw));
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      int tread = 0;
      for (int a = 0; a < (highest ? 4 : 1); ++a) {
        for (int b = 0; b < (highest ? 4 : 1); ++b) {
          const Eigen::Vector2d part =
              highest ? Eigen::Vector2d(0.01 * (a - 1.5), 0.01 * (b - 1.5)) : Eigen::Vector2d(0, 0);
          const Eigen::Vector2d x =
              fog.window.CellCenter(ix, iy) - Eigen::Vector2d(1.2 + offset, 1.2) + part;
          tread = std::max(tread, std::clamp(int(std::floor(x.dot(up) / 0.3)) + 1, 0, treads));
        }
      }
      fog.height[size_t(fog.window.Index(ix, iy))] = 0.04f * float(tread);
    }
  }
  ClassifyFloorChanges(&fog, 0.015, 0.05);
  return fog;
}

// Plans from 0.5 m before the first riser of TurnedTreads(yaw, 3, ...) to 1.1 m past it,
// starting at heading start_yaw, and checks that the three treads are climbed on level poses.
void ExpectClimbsThreeTreads(const Fog& fog, double yaw, double start_yaw, const PlannerParams& p,
                             const std::string& where) {
  const Eigen::Vector2d up(std::cos(yaw), std::sin(yaw));
  const Eigen::Vector2d start = Eigen::Vector2d(1.2, 1.2) - 0.5 * up;
  const Eigen::Vector2d goal = Eigen::Vector2d(1.2, 1.2) + 1.1 * up;
  const PlanResult r = Plan(fog, {start.x(), start.y(), start_yaw}, goal, p);
  if (r.status != PlanStatus::kOk) {
    ADD_FAILURE() << where << ": " << NoPathReasonName(r.reason);
    return;
  }
  EXPECT_EQ(Count(r, Move::kStairsUp), 3) << where << ": " << Moves(r);
  EXPECT_EQ(ExpectStepsFit(fog, r, p), 3) << where;
  ExpectFootprintsClear(fog, r, p);
  ExpectMovesConsistent(r);
}

// Stairs turned against the lattice: between its headings 0, 26.6 and 45 degrees a step up
// along the nearest heading needs a step a little across it.
TEST(Planner, ClimbsStairsTurnedAgainstTheLattice) {
  const PlannerParams p;
  for (const double deg : {0.0, 10.0, 15.0, 20.0, 30.0, 40.0, 45.0, 60.0}) {
    const double yaw = deg * M_PI / 180;
    ExpectClimbsThreeTreads(TurnedTreads(yaw, 3), yaw, yaw, p,
                            "stairs turned by " + std::to_string(deg) + " deg");
  }
}

// The same treads at every angle from 0 to 90 degrees in 2.5 degree steps, their risers at two
// offsets, with each cell's height the highest under it (as the ground-truth FOG's) and the
// robot starting at heading 0: all three climbed. With a level test as wide as the shoulders,
// 17.5 and 72.5 degrees (9 degrees from a lattice heading) failed.
TEST(Planner, ClimbsStairsTurnedByAnyAngle) {
  const PlannerParams p;
  for (double deg = 0; deg <= 90 + 1e-9; deg += 2.5) {
    for (const double offset : {0.0, 0.02}) {
      const double yaw = deg * M_PI / 180;
      ExpectClimbsThreeTreads(
          TurnedTreads(yaw, 3, offset, /*highest=*/true), yaw, 0.0, p,
          "stairs turned by " + std::to_string(deg) + " deg, offset " + std::to_string(offset));
    }
  }
}

TEST(Planner, RefusesAn8cmStep) {
  const PlannerParams p;
  {
    const Fog fog = Treads({{1.4, 0.08f}}, 1.72);  // the step edges are border
    const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.50, 0.82}, p);
    EXPECT_EQ(r.status, PlanStatus::kNoPath);
    EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
  }
  {
    // even when the map calls its edges stairs, an 8 cm height change is never crossed
    Fog fog = Treads({{1.4, 0.03f}}, 1.72);
    for (size_t i = 0; i < fog.height.size(); ++i) {
      if (fog.height[i] > 0.02f) fog.height[i] = 0.08f;
    }
    const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.50, 0.82}, p);
    EXPECT_EQ(r.status, PlanStatus::kNoPath);
  }
}

TEST(Planner, SeesAStepHiddenByUnknownCells) {
  // a 6 cm tread whose riser the map did not see: the row of cells at the step is unknown
  Fog fog = Treads({{1.4, 0.06f}}, 1.72);
  FillBox(&fog, 1.36, 0.0, 1.44, 1.6, CellType::kUnknown, -INFINITY);
  FillBox(&fog, 1.68, 0.0, 1.76, 1.6, CellType::kUnknown, -INFINITY);
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.50, 0.82, 0.0}, {2.50, 0.82}, p);
  EXPECT_EQ(r.status, PlanStatus::kNoPath) << Moves(r);
  // and a 3 cm one is climbed as a step, not walked over
  Fog low = Treads({{1.4, 0.03f}}, 1.72);
  FillBox(&low, 1.36, 0.0, 1.44, 1.6, CellType::kUnknown, -INFINITY);
  const PlanResult climb = Plan(low, {0.50, 0.82, 0.0}, {2.50, 0.82}, p);
  ASSERT_EQ(climb.status, PlanStatus::kOk);
  EXPECT_EQ(Count(climb, Move::kStairsUp), 1) << Moves(climb);
}

TEST(Planner, UnknownCellsBehindAWallWhoseTopWasSeenLieAtTheFloorAroundIt) {
  // a 0.3 m divider whose top the map holds as border, open beyond y = 2.2; everything behind
  // it unknown. The unknown cells there take the floor's height, not the top's, so the way
  // round the divider's end leads to the goal behind it
  Fog fog = FlatFog(75, 75, 0.04);
  FillBox(&fog, 1.5, 0.0, 3.0, 3.0, CellType::kUnknown, -INFINITY);
  FillBox(&fog, 1.4, 0.0, 1.52, 2.2, CellType::kBorder, 0.30f);
  const PlanResult r = Plan(fog, {0.40, 0.80, 0.0}, {2.20, 0.80}, PlannerParams());
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_TRUE(r.reaches_goal);
  EXPECT_EQ(Count(r, Move::kStairsUp) + Count(r, Move::kStairsDown), 0) << Moves(r);
  double max_y = 0;
  for (const PathPose& q : r.path) max_y = std::max(max_y, q.pose_G.y);
  EXPECT_GT(max_y, 2.2);  // round the end, not over the top
}

// A raised platform (10 cm) at the middle of open floor: its rim is border.
Fog RaisedPlatform() {
  Fog fog = FlatFog(75, 75, 0.04);  // 3 m x 3 m
  FillBox(&fog, 1.0, 1.0, 2.0, 2.0, CellType::kFloor, 0.10f);
  ClassifyFloorChanges(&fog, 0.015, 0.05);
  return fog;
}

TEST(Planner, NeverCrossesABorderRing) {
  const Fog fog = RaisedPlatform();
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.30, 1.50, 0.0}, {2.70, 1.50}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  ExpectFootprintsClear(fog, r, p);
  EXPECT_EQ(Count(r, Move::kStairsUp) + Count(r, Move::kStairsDown), 0);
  for (const PathPose& q : r.path) {
    EXPECT_FALSE(q.pose_G.x > 0.96 && q.pose_G.x < 2.04 && q.pose_G.y > 0.96 && q.pose_G.y < 2.04);
  }
}

TEST(Planner, GoalInsideABorderRingIsEnclosed) {
  const Fog fog = RaisedPlatform();
  const PlanResult r = Plan(fog, {0.30, 1.50, 0.0}, {1.50, 1.50}, PlannerParams());
  EXPECT_EQ(r.status, PlanStatus::kNoPath);
  EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
  EXPECT_STREQ(NoPathReasonName(r.reason), "goal_enclosed");
}

// A room of 0.3 m walls, x from 1.6 to 2.6 and y from 1.0 to 2.0, on 3 m x 3 m of floor.
Fog WalledRoom() {
  Fog fog = FlatFog(75, 75, 0.04);
  FillBox(&fog, 1.6, 1.0, 2.6, 1.08, CellType::kObstacle, 0.3f);
  FillBox(&fog, 1.6, 1.92, 2.6, 2.0, CellType::kObstacle, 0.3f);
  FillBox(&fog, 1.6, 1.0, 1.68, 2.0, CellType::kObstacle, 0.3f);
  FillBox(&fog, 2.52, 1.0, 2.6, 2.0, CellType::kObstacle, 0.3f);
  return fog;
}

TEST(Planner, GoalInsideAWalledRoomIsEnclosed) {
  const Fog fog = WalledRoom();
  const PlanResult r = Plan(fog, {0.30, 1.50, 0.0}, {2.10, 1.50}, PlannerParams());
  EXPECT_EQ(r.status, PlanStatus::kNoPath);
  EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
}

// Without a way in, PlanToward still leads as near the goal as the map allows: to the room's
// west wall, where the goal is 0.42 m beyond the wall's inner face
TEST(Planner, PlanTowardAnEnclosedGoalEndsAtTheNearestReachablePlace) {
  Fog fog = WalledRoom();
  const PlannerParams p;
  const PlanResult r = PlanToward(fog, {0.30, 1.50, 0.0}, {2.10, 1.50}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_FALSE(r.reaches_goal);
  const perception::Pose2& end = r.path.back().pose_G;
  // facing the wall, the footprint's front edge (depth / 2 + margin) just short of x = 1.6
  EXPECT_GT(end.x, 1.6 - p.depth / 2 - p.margin - 0.09);
  EXPECT_LT(end.x, 1.6);
  EXPECT_NEAR(end.y, 1.50, 0.05);
  ExpectFootprintsClear(fog, r, p);
  // with a way in it goes to the goal, as Plan does
  FillBox(&fog, 1.6, 1.3, 1.68, 1.7, CellType::kFloor, 0.0f);
  const PlanResult open = PlanToward(fog, {0.30, 1.50, 0.0}, {2.10, 1.50}, p);
  ASSERT_EQ(open.status, PlanStatus::kOk);
  EXPECT_LT((Eigen::Vector2d(open.path.back().pose_G.x, open.path.back().pose_G.y) -
             Eigen::Vector2d(2.10, 1.50)).norm(), p.goal_tolerance + 1e-9);
}

// A wall across the whole window at x = 1.5, the goal 0.5 m beyond it: inside the window the
// start cannot reach it, but the wall may end beyond the window, where the goal's region meets
// the window's edge (south, east and north of the wall's east side).
TEST(Planner, PlanBeyondLeadsToTheWindowEdgeWhereTheGoalsRegionMeetsIt) {
  Fog fog = FlatFog(75, 75, 0.04);  // 3 m x 3 m
  FillBox(&fog, 1.44, 0.0, 1.56, 3.0, CellType::kObstacle, 0.3f);
  const PlannerParams p;
  const perception::Pose2 start{1.0, 1.2, 0.0};
  const Eigen::Vector2d goal(2.0, 1.5);
  ASSERT_EQ(Plan(fog, start, goal, p).status, PlanStatus::kNoPath);
  PlanResult r = PlanBeyond(fog, start, goal, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_FALSE(r.reaches_goal);
  ExpectFootprintsClear(fog, r, p);
  // to the nearer edge, the south one, just west of the wall
  perception::Pose2 end = r.path.back().pose_G;
  EXPECT_LT(end.y, 0.04);
  EXPECT_GT(end.x, 1.1);
  EXPECT_LT(end.x, 1.44);
  // the goal's region closed at the south and east edges: to the north edge by the wall
  FillBox(&fog, 1.56, 0.0, 3.0, 0.12, CellType::kObstacle, 0.3f);
  FillBox(&fog, 2.88, 0.0, 3.0, 3.0, CellType::kObstacle, 0.3f);
  r = PlanBeyond(fog, start, goal, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  ExpectFootprintsClear(fog, r, p);
  end = r.path.back().pose_G;
  EXPECT_GT(end.y, 2.96);
  EXPECT_GT(end.x, 1.1);
  EXPECT_LT(end.x, 1.44);
  // the goal's side closed at the north edge by a block as high as the wall, whose border
  // cells the floor map smoothed into a ramp of 4.5 cm steps: its top is floor, but the goal's
  // region must not climb onto it over border cells, so there is no way
  FillBox(&fog, 1.56, 2.76, 3.0, 3.0, CellType::kFloor, 0.3f);
  for (int row = 0; row < 6; ++row) {
    FillBox(&fog, 1.56, 2.52 + 0.04 * row, 3.0, 2.56 + 0.04 * row, CellType::kBorder,
            0.045f * float(row + 1));
  }
  r = PlanBeyond(fog, start, goal, p);
  EXPECT_EQ(r.status, PlanStatus::kNoPath);
  EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
}

// A goal walled in within the window has no region at the window's edge: PlanBeyond finds no
// way, as Plan does, so a robot sent to it ends with no path instead of wandering off.
TEST(Planner, PlanBeyondFindsNoWayToAGoalWalledInWithinTheWindow) {
  const Fog fog = WalledRoom();
  const PlanResult r = PlanBeyond(fog, {0.30, 1.50, 0.0}, {2.10, 1.50}, PlannerParams());
  EXPECT_EQ(r.status, PlanStatus::kNoPath);
  EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
  // a goal outside the window is PlanToward's business
  const PlanResult outside = PlanBeyond(fog, {0.30, 1.50, 0.0}, {4.0, 1.50}, PlannerParams());
  EXPECT_EQ(outside.status, PlanStatus::kNoPath);
}

// A wall with an L-shaped slot 0.16 m wide: open to a robot without orientation, but too narrow
// to turn the corner in, so only the full search can tell that the goal is enclosed.
TEST(Planner, GoalBehindASlotTooNarrowToTurnInIsEnclosed) {
  Fog fog = FlatFog(100, 100, 0.04);
  FillBox(&fog, 2.0, 0.0, 2.4, 4.0, CellType::kObstacle, 0.3f);
  FillBox(&fog, 1.96, 1.0, 2.26, 1.16, CellType::kFloor, 0.0f);
  FillBox(&fog, 2.1, 1.0, 2.26, 1.8, CellType::kFloor, 0.0f);
  FillBox(&fog, 2.1, 1.64, 2.44, 1.8, CellType::kFloor, 0.0f);
  const PlanResult r = Plan(fog, {0.50, 2.02, 0.0}, {3.20, 2.02}, PlannerParams());
  EXPECT_EQ(r.status, PlanStatus::kNoPath);
  EXPECT_EQ(r.reason, NoPathReason::kGoalEnclosed);
  EXPECT_GT(r.expanded, 10000);  // it did search
}

TEST(Planner, CrawlsOnUnknownCellsNextToATunnel) {
  // the floor under the table's edge has gone unknown, as under a crawling robot
  Fog fog = CorridorWithTable();
  FillBox(&fog, 1.3, 0.6, 1.6, 1.8, CellType::kUnknown, -INFINITY);
  const PlannerParams p;
  const PlanResult r = Plan(fog, {1.50, 1.22, 0.0}, {2.70, 1.22}, p, Posture::kCrawling);
  ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
  EXPECT_EQ(r.path[1].posture, Posture::kCrawling);
  ExpectFootprintsClear(fog, r, p);
}

TEST(Planner, ReportsABlockedGoalAndABlockedStart) {
  Fog fog = FlatFog(75, 75, 0.04);
  FillBox(&fog, 2.0, 1.0, 2.6, 2.0, CellType::kObstacle, 0.3f);
  const PlanResult goal = Plan(fog, {0.30, 1.50, 0.0}, {2.30, 1.50}, PlannerParams());
  EXPECT_EQ(goal.status, PlanStatus::kNoPath);
  EXPECT_EQ(goal.reason, NoPathReason::kGoalBlocked);
  const PlanResult start = Plan(fog, {2.30, 1.50, 0.0}, {0.30, 1.50}, PlannerParams());
  EXPECT_EQ(start.status, PlanStatus::kNoPath);
  EXPECT_EQ(start.reason, NoPathReason::kStartBlocked);
  const PlanResult outside = Plan(fog, {-1.0, 1.50, 0.0}, {0.30, 1.50}, PlannerParams());
  EXPECT_EQ(outside.reason, NoPathReason::kStartBlocked);
}

TEST(Planner, ShufflesFreeFromAStartTouchingAnObstacle) {
  Fog fog = FlatFog(75, 50, 0.04);
  FillBox(&fog, 0.0, 1.12, 3.0, 1.16, CellType::kObstacle, 0.1f);  // 0.12 m left of the start
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.50, 1.02, 0.0}, {2.50, 1.02}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
  ASSERT_GE(r.path.size(), 2u);
  EXPECT_EQ(r.path[1].move, Move::kSidestep);
  EXPECT_LT(r.path[1].pose_G.y, 1.02);
  ExpectFootprintsClear(fog, r, p);
}

TEST(Planner, PlansIntoUnknownAtAPenalty) {
  // a band of unknown cells across the way: crossed straight, at the penalty per metre
  Fog fog = FlatFog(75, 75, 0.04);
  FillBox(&fog, 1.2, 0.0, 2.0, 3.0, CellType::kUnknown, -INFINITY);
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.30, 1.50, 0.0}, {2.70, 1.50}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  for (const PathPose& q : r.path) EXPECT_NEAR(q.pose_G.y, 1.50, 1e-9);
  EXPECT_NEAR(r.cost, r.length * p.walk_factor + 0.8 * p.unknown_penalty, 1e-9);
  PlannerParams no_unknown = p;
  no_unknown.unknown_penalty = 1e6;
  EXPECT_GT(Plan(fog, {0.30, 1.50, 0.0}, {2.70, 1.50}, no_unknown).cost, 1e4);
}

TEST(Planner, GoalOutsideTheWindowPlansToTheBestCellTowardIt) {
  Fog fog = FlatFog(50, 50, 0.04);  // 2 m x 2 m
  FillBox(&fog, 1.2, 0.0, 1.3, 1.4, CellType::kObstacle, 0.3f);  // wall open at the top
  const PlannerParams p;
  const PlanResult r = Plan(fog, {0.30, 1.00, 0.0}, {5.0, 1.0}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_FALSE(r.reaches_goal);
  EXPECT_GT(r.path.back().pose_G.x, 1.8);  // went round the wall to the far edge
  ExpectFootprintsClear(fog, r, p);
}

// A partition across the window between the robot and a goal just beyond the window, with a
// door at its north end: the plan goes through the door to the window's east edge. A plan that
// may end anywhere ends at the partition's face nearest the goal instead (the door's way ends
// 1.9 m from the goal, the face 1 m), and a robot whose window moves with it takes turns between
// that face and the door.
TEST(Planner, GoalOutsideTheWindowIsApproachedThroughTheWindowsFarSide) {
  Fog fog = FlatFog(100, 100, 0.04);  // 4 m x 4 m, the robot at its centre
  FillBox(&fog, 3.6, 0.0, 3.68, 3.4, CellType::kObstacle, 0.7f);  // door from y = 3.4 to 4.0
  const PlannerParams p;
  const Eigen::Vector2d goal(4.6, 1.9);
  const PlanResult r = Plan(fog, {2.0, 1.9, 0.0}, goal, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_FALSE(r.reaches_goal);
  EXPECT_GT(r.path.back().pose_G.x, 3.9);  // on the east edge
  bool through_door = false;
  for (const PathPose& q : r.path) through_door |= q.pose_G.x > 3.68 && q.pose_G.y > 3.3;
  EXPECT_TRUE(through_door);
  ExpectFootprintsClear(fog, r, p);
  // walled off from the east edge, the plan leads as near the goal as the window allows: to
  // the partition's face
  FillBox(&fog, 3.6, 3.4, 3.68, 4.0, CellType::kObstacle, 0.7f);
  const PlanResult shut = Plan(fog, {2.0, 1.9, 0.0}, goal, p);
  ASSERT_EQ(shut.status, PlanStatus::kOk);
  EXPECT_FALSE(shut.reaches_goal);
  EXPECT_GT(shut.path.back().pose_G.x, 3.6 - p.depth / 2 - p.margin - 0.09);
  EXPECT_LT(shut.path.back().pose_G.x, 3.6);
  EXPECT_NEAR(shut.path.back().pose_G.y, 1.9, 0.05);
}

TEST(Planner, RunsTheCourseThroughMapNoise) {
  // a map as stereo leaves it: holes of unknown cells and floor heights off by a few millimetres
  internal::Course course = internal::PaperCourse();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (size_t i = 0; i < course.fog.type.size(); ++i) {
    const CellType t = course.fog.type[i];
    if (t != CellType::kFloor && t != CellType::kStairs && t != CellType::kTunnel) continue;
    if (u(rng) < 0.05) {
      course.fog.type[i] = CellType::kUnknown;
      course.fog.height[i] = -INFINITY;
    } else {
      course.fog.height[i] += float(0.008 * (u(rng) - 0.5));
    }
  }
  const PlannerParams p;
  const PlanResult r = Plan(course.fog, course.start_G, course.goal_G, p);
  ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
  EXPECT_EQ(Count(r, Move::kStairsUp), 2) << Moves(r);
  EXPECT_EQ(Count(r, Move::kStairsDown), 2) << Moves(r);
  EXPECT_GT(Count(r, Move::kSidestep), 0) << Moves(r);
  EXPECT_GT(Count(r, Move::kCrawl), 0) << Moves(r);
  ExpectFootprintsClear(course.fog, r, p);
  EXPECT_EQ(ExpectStepsFit(course.fog, r, p), 4);
  ExpectMovesConsistent(r);
}

TEST(Planner, GoalBeyondTheWindowLeadsThroughTheCourseNotUpToItsHardPart) {
  // re-planning from where a partial path ends must make progress, so the path should not stop
  // in front of the table just because crawling costs more than walking
  const internal::Course course = internal::PaperCourse();
  const PlannerParams p;
  const PlanResult r = Plan(course.fog, course.start_G, {6.0, 0.3}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_FALSE(r.reaches_goal);
  EXPECT_GT(r.path.back().pose_G.x, 3.4) << Moves(r);
  EXPECT_GT(Count(r, Move::kCrawl), 0);
  ExpectFootprintsClear(course.fog, r, p);
}

TEST(Planner, StartsCrawlingUnderATable) {
  const Fog fog = CorridorWithTable();
  const PlannerParams p;
  const PlanResult r = Plan(fog, {1.70, 1.22, 0.0}, {2.70, 1.22}, p, Posture::kCrawling);
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(r.path[1].posture, Posture::kCrawling);
  EXPECT_EQ(r.path.back().posture, Posture::kUpright);
  ExpectFootprintsClear(fog, r, p);
}

TEST(Planner, RunsTheCourseWithEveryMove) {
  const internal::Course course = internal::PaperCourse();
  const PlannerParams p;
  const PlanResult r = Plan(course.fog, course.start_G, course.goal_G, p);
  ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
  EXPECT_TRUE(r.reaches_goal);
  EXPECT_EQ(Count(r, Move::kStairsUp), 2) << Moves(r);
  EXPECT_EQ(Count(r, Move::kStairsDown), 2) << Moves(r);
  EXPECT_GT(Count(r, Move::kSidestep), 0) << Moves(r);
  EXPECT_GT(Count(r, Move::kCrawl), 0) << Moves(r);
  EXPECT_GT(Count(r, Move::kWalk), 0) << Moves(r);
  ExpectFootprintsClear(course.fog, r, p);
  EXPECT_EQ(ExpectStepsFit(course.fog, r, p), 4);
  ExpectMovesConsistent(r);
  // between the 8 cm block (y > 0.12) and the 20 cm block (y < -0.22): nearer the low one
  EXPECT_GT(YAtX(r, 0.55), -0.05);
}

// An axis-aligned box from its centre and full size, for perception::GroundTruthFog.
perception::OrientedBox Box(double cx, double cy, double cz, double sx, double sy, double sz) {
  perception::OrientedBox b;
  b.X_FB.translation() = Eigen::Vector3d(cx, cy, cz);
  b.half_size = Eigen::Vector3d(sx, sy, sz) / 2;
  return b;
}

// The world of scenarios/stairs_and_table.yaml, box by box.
std::vector<perception::OrientedBox> StairsAndTableWorld() {
  std::vector<perception::OrientedBox> w;
  w.push_back(Box(2.2, 0.0, -0.005, 5.6, 1.6, 0.01));  // floor, top at z = 0
  w.push_back(Box(2.2, 0.65, 0.15, 5.6, 0.1, 0.3));    // walls
  w.push_back(Box(2.2, -0.65, 0.15, 5.6, 0.1, 0.3));
  w.push_back(Box(-0.5, 0.0, 0.15, 0.1, 1.2, 0.3));
  w.push_back(Box(4.9, 0.0, 0.15, 0.1, 1.2, 0.3));
  w.push_back(Box(0.75, 0.25, 0.04, 0.2, 0.2, 0.08));  // low and tall block
  w.push_back(Box(0.85, -0.3, 0.10, 0.2, 0.2, 0.2));
  w.push_back(Box(1.525, 0.0, 0.015, 0.25, 1.2, 0.03));  // treads of 3, 6, 3 cm
  w.push_back(Box(1.825, 0.0, 0.03, 0.35, 1.2, 0.06));
  w.push_back(Box(2.125, 0.0, 0.015, 0.25, 1.2, 0.03));
  w.push_back(Box(2.55, 0.3, 0.04, 0.15, 0.2, 0.08));  // the gap's blocks
  w.push_back(Box(2.85, 0.355, 0.10, 0.2, 0.49, 0.2));
  w.push_back(Box(2.85, -0.355, 0.10, 0.2, 0.49, 0.2));
  w.push_back(Box(3.65, 0.0, 0.585, 0.6, 1.16, 0.03));  // table top and legs
  for (double x : {3.65 - 0.28, 3.65 + 0.28}) {
    for (double y : {-0.56, 0.56}) w.push_back(Box(x, y, 0.285, 0.04, 0.04, 0.57));
  }
  return w;
}

// The whole course on the FOG its exact geometry gives (perception's ground truth), in one
// window that holds start and goal.
TEST(Planner, RunsTheStairsAndTableScenarioOnItsGroundTruthFog) {
  perception::GridWindow window;
  window.size_x = 140;  // x in [-0.52, 5.08)
  window.size_y = 50;   // y in [-1, 1)
  window.origin_ix = -13;
  window.origin_iy = -25;
  const Fog fog = perception::GroundTruthFog(StairsAndTableWorld(), window, perception::FogParams());
  PlannerParams p;
  p.goal_tolerance = 0.2;
  const PlanResult r = Plan(fog, {0.0, 0.0, 0.0}, {4.4, 0.0}, p);
  ASSERT_EQ(r.status, PlanStatus::kOk) << NoPathReasonName(r.reason);
  EXPECT_TRUE(r.reaches_goal);
  EXPECT_EQ(Count(r, Move::kStairsUp), 2) << Moves(r);
  EXPECT_EQ(Count(r, Move::kStairsDown), 2) << Moves(r);
  EXPECT_GT(Count(r, Move::kSidestep), 0) << Moves(r);
  EXPECT_GT(Count(r, Move::kCrawl), 0) << Moves(r);
  ExpectFootprintsClear(fog, r, p);
  EXPECT_EQ(ExpectStepsFit(fog, r, p), 4);
  ExpectMovesConsistent(r);
}

TEST(Planner, AbortsOnAFogWhoseArraysDoNotMatchItsWindow) {
  Fog fog = FlatFog(20, 20, 0.04);
  fog.height.pop_back();
  EXPECT_DEATH(Plan(fog, {0.4, 0.4, 0.0}, {0.6, 0.4}, PlannerParams()), "do not match");
}

TEST(Planner, SegmentsThePathIntoRunsOfMoves) {
  const internal::Course course = internal::PaperCourse();
  const PlanResult r = Plan(course.fog, course.start_G, course.goal_G, PlannerParams());
  ASSERT_EQ(r.status, PlanStatus::kOk);
  const std::vector<PathSegment> runs = SegmentPath(r);
  ASSERT_FALSE(runs.empty());
  // the runs tile the path and each holds one kind of move
  EXPECT_EQ(runs.front().first, 0);
  EXPECT_EQ(runs.back().last, int(r.path.size()) - 1);
  std::string kinds;
  for (size_t k = 0; k < runs.size(); ++k) {
    if (k > 0) {
      EXPECT_EQ(runs[k].first, runs[k - 1].last);
    }
    ASSERT_LT(runs[k].first, runs[k].last);
    for (int i = runs[k].first + 1; i <= runs[k].last; ++i) {
      EXPECT_EQ(r.path[size_t(i)].move, runs[k].move);
    }
    if (runs[k].move == Move::kStairsUp || runs[k].move == Move::kStairsDown) {
      EXPECT_EQ(runs[k].last - runs[k].first, 1);
    }
    kinds += std::string(MoveName(runs[k].move)) +
             (runs[k].posture == Posture::kCrawling ? "* " : " ");
  }
  // walk between the blocks, up and down the stairs, side-step through the gap, crawl under
  // the table
  EXPECT_NE(kinds.find("stairs_up walk stairs_up walk stairs_down walk stairs_down"),
            std::string::npos) << kinds;
  EXPECT_NE(kinds.find("turn sidestep"), std::string::npos) << kinds;
  // get down (a run of its own), then crawl on
  const size_t down = kinds.find("crawl* ");
  ASSERT_NE(down, std::string::npos) << kinds;
  EXPECT_NE(kinds.find("crawl* ", down + 1), std::string::npos) << kinds;
  EXPECT_TRUE(SegmentPath(PlanResult()).empty());
}

TEST(Planner, NamesMovesAndStates) {
  EXPECT_STREQ(MoveName(Move::kWalk), "walk");
  EXPECT_STREQ(MoveName(Move::kSidestep), "sidestep");
  EXPECT_STREQ(MoveName(Move::kTurn), "turn");
  EXPECT_STREQ(MoveName(Move::kStairsUp), "stairs_up");
  EXPECT_STREQ(MoveName(Move::kStairsDown), "stairs_down");
  EXPECT_STREQ(MoveName(Move::kCrawl), "crawl");
  EXPECT_STREQ(MoveName(Move::kNone), "none");
  EXPECT_STREQ(PostureName(Posture::kCrawling), "crawling");
  EXPECT_STREQ(PlanStatusName(PlanStatus::kNoPath), "no_path");
  EXPECT_STREQ(NoPathReasonName(NoPathReason::kStartBlocked), "start_blocked");
}

// `fog` with a 0.1 m square obstacle, 0.2 m high, centred on q
Fog WithBlockAt(const Fog& fog, const Pose2& q) {
  Fog blocked = fog;
  FillBox(&blocked, q.x - 0.05, q.y - 0.05, q.x + 0.05, q.y + 0.05, CellType::kObstacle, 0.2f);
  return blocked;
}

// The rest of an optimal plan is optimal from where it goes on, so continuing it on the same map
// costs what a new plan from there does; an obstacle put on it later ends it.
TEST(Planner, ContinuesAPlanWhileTheMapAllowsIt) {
  internal::Course course = internal::PaperCourse();
  const PlannerParams p;
  const PlanResult plan = Plan(course.fog, course.start_G, course.goal_G, p);
  ASSERT_EQ(plan.status, PlanStatus::kOk);
  ASSERT_GT(plan.path.size(), 40u);
  for (size_t k : {size_t(1), size_t(12), plan.path.size() / 2, plan.path.size() - 2}) {
    const Pose2 at = plan.path[k].pose_G;
    const PlanResult rest = ContinuePlan(course.fog, plan, k, at, course.goal_G, p);
    ASSERT_EQ(rest.status, PlanStatus::kOk) << k;
    EXPECT_TRUE(rest.reaches_goal);
    ASSERT_EQ(rest.path.size(), plan.path.size() - k) << k;
    for (size_t i = 1; i < rest.path.size(); ++i) {
      EXPECT_EQ(rest.path[i].move, plan.path[k + i].move);
      EXPECT_NEAR(rest.path[i].pose_G.x, plan.path[k + i].pose_G.x, 1e-9);
      EXPECT_NEAR(rest.path[i].pose_G.y, plan.path[k + i].pose_G.y, 1e-9);
    }
    const PlanResult fresh = Plan(course.fog, at, course.goal_G, p, plan.path[k].posture);
    ASSERT_EQ(fresh.status, PlanStatus::kOk);
    EXPECT_NEAR(rest.cost, fresh.cost, 1e-6) << k;
  }
  // a block on the far half of the path
  const size_t k = plan.path.size() * 3 / 4;
  const Fog blocked = WithBlockAt(course.fog, plan.path[k].pose_G);
  EXPECT_EQ(ContinuePlan(blocked, plan, 1, plan.path[1].pose_G, course.goal_G, p).status,
            PlanStatus::kNoPath);
  // past the block it goes on
  EXPECT_EQ(ContinuePlan(blocked, plan, k + 10, plan.path[k + 10].pose_G, course.goal_G, p).status,
            PlanStatus::kOk);
}

// FirstBlockedPose finds nothing on the map `plan` was made on; on that map with WithBlockAt on
// the plan's middle pose (`blocked`), the first pose blocked lies at most a body's length
// before the block. Returns that pose.
size_t ExpectStopsBeforeAMidPathBlock(const internal::Course& course, const PlanResult& plan,
                                      const PlannerParams& p, Fog* blocked) {
  EXPECT_EQ(FirstBlockedPose(course.fog, plan, course.goal_G, p), plan.path.size());
  const size_t k = plan.path.size() / 2;
  *blocked = WithBlockAt(course.fog, plan.path[k].pose_G);
  const size_t first = FirstBlockedPose(*blocked, plan, course.goal_G, p);
  EXPECT_LE(first, k);
  EXPECT_GT(first, k - 10);  // a body's length before the obstacle at most
  return first;
}

// A plan checked on the map it was made on has no blocked pose; on a map with an obstacle put on
// it, the first pose blocked is the first one whose footprint the obstacle reaches, and every
// pose before it is still allowed.
TEST(Planner, FindsWhereAMapStopsAPlan) {
  internal::Course course = internal::PaperCourse();
  const PlannerParams p;
  const PlanResult plan = Plan(course.fog, course.start_G, course.goal_G, p);
  ASSERT_EQ(plan.status, PlanStatus::kOk);
  ASSERT_GT(plan.path.size(), 40u);
  Fog blocked;
  const size_t first = ExpectStopsBeforeAMidPathBlock(course, plan, p, &blocked);
  // the path up to the pose before it goes on on the blocked map, the pose itself does not
  EXPECT_EQ(
      ContinuePlan(blocked, plan, first - 1, plan.path[first - 1].pose_G, course.goal_G, p).status,
      PlanStatus::kNoPath);
  PlanResult head = plan;
  head.path.resize(first);
  EXPECT_EQ(FirstBlockedPose(blocked, head, course.goal_G, p), head.path.size());
  // no plan, nothing to check
  EXPECT_EQ(FirstBlockedPose(blocked, PlanResult{}, course.goal_G, p), 0u);
}

// Odometry's yaw after noisy steps lies between the lattice's headings: the plan leaves that
// start by a seed move, and the check starts at its pose. Before, such a start made every plan
// blocked at its first pose, so the robot never went to look at far obstacle evidence.
TEST(Planner, FindsWhereAMapStopsAPlanFromAStartBetweenHeadings) {
  internal::Course course = internal::PaperCourse();
  const PlannerParams p;
  Pose2 start = course.start_G;
  start.yaw += 0.007;  // 0.4 degrees
  const PlanResult plan = Plan(course.fog, start, course.goal_G, p);
  ASSERT_EQ(plan.status, PlanStatus::kOk);
  ASSERT_GT(plan.path.size(), 40u);
  Fog blocked;
  ExpectStopsBeforeAMidPathBlock(course, plan, p, &blocked);
  // a start whose footprint an obstacle covers still cannot make its first move
  EXPECT_EQ(FirstBlockedPose(WithBlockAt(course.fog, start), plan, course.goal_G, p), 1u);
}

}  // namespace
}  // namespace fognav::navigation

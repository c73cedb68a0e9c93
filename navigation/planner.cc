#include "navigation/planner.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "navigation/internal/lattice.h"
#include "navigation/internal/open_list.h"

namespace fognav::navigation {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// per-state scratch arrays of this thread, reused by every query (one query at a time)
internal::SearchMemory& ThreadMemory() {
  thread_local internal::SearchMemory memory;
  return memory;
}

PlanResult NoPath(NoPathReason reason, int expanded = 0) {
  PlanResult r;
  r.status = PlanStatus::kNoPath;
  r.reason = reason;
  r.expanded = expanded;
  return r;
}

}  // namespace

const char* MoveName(Move move) {
  switch (move) {
    case Move::kNone: return "none";
    case Move::kWalk: return "walk";
    case Move::kSidestep: return "sidestep";
    case Move::kTurn: return "turn";
    case Move::kStairsUp: return "stairs_up";
    case Move::kStairsDown: return "stairs_down";
    case Move::kCrawl: return "crawl";
  }
  return "invalid";
}

const char* PostureName(Posture posture) {
  return posture == Posture::kUpright ? "upright" : "crawling";
}

const char* PlanStatusName(PlanStatus status) {
  return status == PlanStatus::kOk ? "ok" : "no_path";
}

const char* NoPathReasonName(NoPathReason reason) {
  switch (reason) {
    case NoPathReason::kNone: return "none";
    case NoPathReason::kStartBlocked: return "start_blocked";
    case NoPathReason::kGoalBlocked: return "goal_blocked";
    case NoPathReason::kGoalEnclosed: return "goal_enclosed";
  }
  return "invalid";
}

namespace {

bool GoalInWindow(const perception::GridWindow& w, const Eigen::Vector2d& goal_G) {
  int gx = 0, gy = 0;
  w.CellOf(goal_G.x(), goal_G.y(), &gx, &gy);
  return w.Contains(gx, gy);
}

// A* on `lattice` (built on `fog` with this thread's memory) from the start to the end state
// of least path cost plus terminal cost (internal::End)
PlanResult Search(internal::Lattice& lattice, const perception::Fog& fog,
                  const perception::Pose2& start_G, Posture start_posture) {
  // per-state arrays and the open list are reused between calls on this thread
  thread_local std::vector<internal::OpenEntry> thread_heap;
  internal::SearchMemory& memory = lattice.memory();
  if (!lattice.HasEnd()) return NoPath(NoPathReason::kGoalEnclosed);

  // where the search may start and end
  const std::vector<internal::Seed> seeds = lattice.StartSeeds(start_G, start_posture);
  if (seeds.empty()) return NoPath(NoPathReason::kStartBlocked);
  if (lattice.GoalInWindow() && !lattice.GoalRegionHasValidState()) {
    return NoPath(NoPathReason::kGoalBlocked);
  }
  const bool any_seed_connected = std::any_of(seeds.begin(), seeds.end(), [&](const auto& s) {
    return lattice.Heuristic(s.state) < kInf;
  });
  if (!any_seed_connected) return NoPath(NoPathReason::kGoalEnclosed);

  // search state: g, parent and move count only where the stamp is of this generation
  std::vector<uint32_t>& stamp = memory.search_stamp;
  std::vector<double>& g = memory.g;
  std::vector<int32_t>& parent = memory.parent;
  std::vector<Move>& move_in = memory.move;
  const uint32_t reached = memory.Begin(lattice.NumStates()) << 1, closed = reached | 1u;
  auto g_of = [&](size_t s) { return (stamp[s] & ~1u) == reached ? g[s] : kInf; };
  // a state is in the open list exactly while its stamp is `reached`
  internal::OpenList open(&thread_heap, &memory.heap_position);
  for (size_t i = 0; i < seeds.size(); ++i) {
    const internal::Seed& seed = seeds[i];
    const size_t s = size_t(seed.state);
    const double h = lattice.Heuristic(seed.state);
    if (h == kInf || seed.cost >= g_of(s)) continue;
    const bool queued = stamp[s] == reached;
    stamp[s] = reached;
    g[s] = seed.cost;
    parent[s] = -1 - int32_t(i);
    move_in[s] = seed.move;
    open.Push({seed.cost + h, float(seed.cost), seed.state}, queued);
  }

  // A*: with a consistent heuristic each state is expanded once, with its optimal g
  double best_total = kInf;
  int best_state = -1;
  int expanded = 0;
  internal::Successor succ[internal::kMaxSuccessors];
  while (!open.empty()) {
    const internal::OpenEntry top = open.Pop();
    if (top.f >= best_total) break;
    const size_t s = size_t(top.state);
    stamp[s] = closed;
    ++expanded;
    const double end = g[s] + lattice.TerminalCost(top.state);
    if (end < best_total) {
      best_total = end;
      best_state = top.state;
    }
    const int count = lattice.Successors(top.state, succ);
    for (int i = 0; i < count; ++i) {
      const size_t t = size_t(succ[i].state);
      if (stamp[t] == closed) continue;
      const double ng = g[s] + succ[i].cost;
      if (ng >= g_of(t)) continue;
      const double f = ng + lattice.Heuristic(succ[i].state);
      if (f >= best_total) continue;  // also drops states that cannot reach the goal (h = inf)
      const bool queued = stamp[t] == reached;
      stamp[t] = reached;
      g[t] = ng;
      parent[t] = int32_t(s);
      move_in[t] = succ[i].move;
      open.Push({f, float(ng), succ[i].state}, queued);
    }
  }
  if (best_state < 0) return NoPath(NoPathReason::kGoalEnclosed, expanded);

  // walk back from the best end state to its seed
  std::vector<int> chain;
  int s = best_state;
  for (; s >= 0; s = parent[size_t(s)]) chain.push_back(s);
  const internal::Seed& seed = seeds[size_t(-1 - s)];
  std::reverse(chain.begin(), chain.end());

  PlanResult r;
  r.status = PlanStatus::kOk;
  r.reason = NoPathReason::kNone;
  r.reaches_goal = lattice.GoalInWindow();
  r.cost = best_total;
  r.expanded = expanded;
  r.path.reserve(chain.size() + 1);
  int start_ix = 0, start_iy = 0;
  fog.window.CellOf(start_G.x, start_G.y, &start_ix, &start_iy);
  r.path.push_back({start_G, Move::kNone, start_posture,
                    lattice.FloorHeight(fog.window.Index(start_ix, start_iy))});
  r.length = seed.length;
  if (seed.move != Move::kNone) {
    r.path.push_back({lattice.PoseOf(chain.front()), seed.move,
                      lattice.PostureOfState(chain.front()),
                      lattice.FloorHeight(lattice.CellOfState(chain.front()))});
  }
  for (size_t i = 1; i < chain.size(); ++i) {
    const perception::Pose2 pose = lattice.PoseOf(chain[i]);
    const perception::Pose2 prev = lattice.PoseOf(chain[i - 1]);
    r.length += std::hypot(pose.x - prev.x, pose.y - prev.y);
    r.path.push_back({pose, move_in[size_t(chain[i])], lattice.PostureOfState(chain[i]),
                      lattice.FloorHeight(lattice.CellOfState(chain[i]))});
  }
  return r;
}

// the lattice state of a path pose in window cell (ix, iy): its heading if it is a lattice
// heading (else false), its posture
bool StateOfPose(const internal::Lattice& lattice, int ix, int iy, const PathPose& q, int* state) {
  const int heading = internal::NearestHeading(q.pose_G.yaw);
  const double off = q.pose_G.yaw - internal::HeadingYaw(heading);
  if (std::abs(std::atan2(std::sin(off), std::cos(off))) > 1e-3) return false;
  *state = lattice.StateIndex(ix, iy, heading, q.posture);
  return true;
}

// Follows `path` from path[from] on the lattice, calling on_move(k, edge, state) for each move
// the lattice allows, and returns where that ends: the index of the first pose its move cannot
// reach (`from` itself if that pose is no valid state), or path.size() when the path ends or
// leaves the window `w` (the lattice's).
template <typename OnMove>
size_t FollowPath(internal::Lattice& lattice, const perception::GridWindow& w,
                  const std::vector<PathPose>& path, size_t from, OnMove on_move) {
  int s = 0, ix = 0, iy = 0;
  w.CellOf(path[from].pose_G.x, path[from].pose_G.y, &ix, &iy);
  if (!w.Contains(ix, iy) || !StateOfPose(lattice, ix, iy, path[from], &s) || !lattice.Valid(s)) {
    return from;
  }
  on_move(from, nullptr, s);
  internal::Successor succ[internal::kMaxSuccessors];
  for (size_t k = from + 1; k < path.size(); ++k) {
    int t = 0;
    w.CellOf(path[k].pose_G.x, path[k].pose_G.y, &ix, &iy);
    if (!w.Contains(ix, iy)) return path.size();               // the rest lies beyond the window
    if (!StateOfPose(lattice, ix, iy, path[k], &t)) return k;  // not a lattice pose
    const int count = lattice.Successors(s, succ);
    const internal::Successor* edge = std::find_if(
        succ, succ + count, [&](const auto& e) { return e.state == t && e.move == path[k].move; });
    if (edge == succ + count) return k;
    on_move(k, edge, t);
    s = t;
  }
  return path.size();
}

}  // namespace

PlanResult ContinuePlan(const perception::Fog& fog, const PlanResult& earlier, size_t from,
                        const perception::Pose2& start_G, const Eigen::Vector2d& goal_G,
                        const PlannerParams& p) {
  if (earlier.status != PlanStatus::kOk || from >= earlier.path.size()) {
    return NoPath(NoPathReason::kStartBlocked);
  }
  internal::Lattice lattice(fog, goal_G, p, &ThreadMemory(), internal::End::kGoal,
                            /*heuristic=*/false);
  PlanResult r;
  int last = 0;
  const size_t end =
      FollowPath(lattice, fog.window, earlier.path, from,
                 [&](size_t k, const internal::Successor* edge, int state) {
                   last = state;
                   const float floor_z = lattice.FloorHeight(lattice.CellOfState(state));
                   if (edge == nullptr) {
                     r.path.push_back({start_G, Move::kNone, earlier.path[k].posture, floor_z});
                     return;
                   }
                   r.cost += edge->cost;
                   r.length += edge->length;
                   r.path.push_back(
                       {lattice.PoseOf(state), edge->move, lattice.PostureOfState(state), floor_z});
                 });
  if (end == from) return NoPath(NoPathReason::kStartBlocked);
  if (end < earlier.path.size()) return NoPath(NoPathReason::kGoalEnclosed);
  // with the goal outside the window, the window has moved since: the path ends at the old
  // edge, maybe inside the new window, and the walk beyond it is priced as at the edge
  double terminal = lattice.TerminalCost(last);
  if (!lattice.GoalInWindow()) {
    const Eigen::Vector2d at(r.path.back().pose_G.x, r.path.back().pose_G.y);
    terminal = (at - goal_G).norm() * p.exit_factor;
  }
  if (terminal == kInf) return NoPath(NoPathReason::kGoalEnclosed);
  r.status = PlanStatus::kOk;
  r.reaches_goal = lattice.GoalInWindow();
  r.cost += terminal;
  return r;
}

size_t FirstBlockedPose(const perception::Fog& fog, const PlanResult& plan,
                        const Eigen::Vector2d& goal_G, const PlannerParams& p) {
  const size_t n = plan.path.size();
  if (plan.status != PlanStatus::kOk || n < 2) return n;
  internal::Lattice lattice(fog, goal_G, p, &ThreadMemory(), internal::End::kGoal,
                            /*heuristic=*/false);
  // a start between the lattice's headings (odometry's yaw after noisy steps) is no lattice
  // state: the search left it by a seed move, so the check starts at that move's pose
  int ix = 0, iy = 0, state = 0;
  fog.window.CellOf(plan.path[0].pose_G.x, plan.path[0].pose_G.y, &ix, &iy);
  const size_t from =
      fog.window.Contains(ix, iy) && !StateOfPose(lattice, ix, iy, plan.path[0], &state) ? 1 : 0;
  const size_t end = FollowPath(lattice, fog.window, plan.path, from,
                                [](size_t, const internal::Successor*, int) {});
  return std::max<size_t>(end, 1);  // a first pose that is no valid state: its move cannot be made
}

PlanResult Plan(const perception::Fog& fog, const perception::Pose2& start_G,
                const Eigen::Vector2d& goal_G, const PlannerParams& p, Posture start_posture) {
  internal::Lattice lattice(fog, goal_G, p, &ThreadMemory(), internal::End::kGoal);
  PlanResult r = Search(lattice, fog, start_G, start_posture);
  if (r.status == PlanStatus::kNoPath && r.reason != NoPathReason::kStartBlocked &&
      !GoalInWindow(fog.window, goal_G)) {
    // no way out toward the goal yet (a table the window's edge cuts): as near it as may be, on
    // the same lattice (what it knows of the map and the valid states holds for any end)
    lattice.SetEnd(internal::End::kToward);
    r = Search(lattice, fog, start_G, start_posture);
  }
  return r;
}

PlanResult PlanToward(const perception::Fog& fog, const perception::Pose2& start_G,
                      const Eigen::Vector2d& goal_G, const PlannerParams& p,
                      Posture start_posture) {
  internal::Lattice lattice(fog, goal_G, p, &ThreadMemory(), internal::End::kToward);
  return Search(lattice, fog, start_G, start_posture);
}

PlanResult PlanBeyond(const perception::Fog& fog, const perception::Pose2& start_G,
                      const Eigen::Vector2d& goal_G, const PlannerParams& p,
                      Posture start_posture) {
  internal::Lattice lattice(fog, goal_G, p, &ThreadMemory(), internal::End::kBeyond);
  return Search(lattice, fog, start_G, start_posture);
}

std::vector<PathSegment> SegmentPath(const PlanResult& plan) {
  std::vector<PathSegment> runs;
  // +1 forward, -1 backward along the heading of the pose moved from, 0 for no translation
  auto direction = [&](size_t i) {
    const perception::Pose2& a = plan.path[i - 1].pose_G;
    const perception::Pose2& b = plan.path[i].pose_G;
    const double along = (b.x - a.x) * std::cos(a.yaw) + (b.y - a.y) * std::sin(a.yaw);
    return along > 1e-9 ? 1 : along < -1e-9 ? -1 : 0;
  };
  for (size_t i = 1; i < plan.path.size(); ++i) {
    const PathPose& q = plan.path[i];
    const PathPose& prev = plan.path[i - 1];
    const bool single = q.move == Move::kStairsUp || q.move == Move::kStairsDown ||
                        q.posture != prev.posture;
    bool extend = !runs.empty() && !single && runs.back().move == q.move &&
                  runs.back().posture == q.posture;
    if (extend) {
      const PathSegment& run = runs.back();
      const bool run_single = run.last - run.first == 1 &&
                              (plan.path[size_t(run.last)].posture !=
                                   plan.path[size_t(run.first)].posture ||
                               run.move == Move::kStairsUp || run.move == Move::kStairsDown);
      extend = !run_single && direction(i) == direction(size_t(run.first) + 1);
    }
    if (extend) {
      runs.back().last = int(i);
    } else {
      runs.push_back({q.move, q.posture, int(i) - 1, int(i)});
    }
  }
  return runs;
}

}  // namespace fognav::navigation

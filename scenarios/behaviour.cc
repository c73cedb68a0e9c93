#include "scenarios/behaviour.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace fognav::scenarios {
namespace {

namespace nav = navigation;
using perception::CellType;
using perception::Pose2;

bool Moves(const nav::PlanResult& p) { return p.status == nav::PlanStatus::kOk && p.path.size() >= 2; }

Eigen::Vector2d At(const Pose2& p) { return {p.x, p.y}; }

// Whether two poses are the same lattice pose: within half a cell and 0.05 rad.
bool SamePose(const Pose2& a, const Pose2& b, double resolution) {
  return std::hypot(a.x - b.x, a.y - b.y) < 0.5 * resolution &&
         std::abs(WrapAngle(a.yaw - b.yaw)) < 0.05;
}

// Where to look from at obstacle evidence seen only from farther than `range`
// (ExecutionLimits::inspect_range), in obstacle and tunnel cells and on the rims of raised
// tops: the map with those cells unknown may have a way on; the robot looks from the last pose
// of that way before the real map stops it. Left as they are:
// cells within the body's reach of where the robot stands (it has looked from here; they lie
// where its eyes do not reach, behind a low wall it stands at) and cells beside obstacle
// evidence seen from nearer (the hidden inside of a wall whose face was seen from nearby; no
// look shows it). Nothing if there is no such way or it stays where it is.
std::optional<Eigen::Vector2d> InspectionPose(const perception::Fog& fog,
                                              const perception::MapState& maps,
                                              const Pose2& believed, const MissionGoal& goal,
                                              const nav::PlannerParams& params,
                                              nav::Posture posture, double range) {
  if (maps.obstacle_range.size() != fog.type.size()) return std::nullopt;
  const perception::GridWindow& w = fog.window;
  auto solid = [&](int ix, int iy) {
    const CellType t = fog.TypeAt(ix, iy);
    return t == CellType::kObstacle || t == CellType::kTunnel;
  };
  auto seen_near = [&](int ix, int iy) {
    return w.Contains(ix, iy) && solid(ix, iy) &&
           !(maps.obstacle_range[size_t(w.Index(ix, iy))] > range);
  };
  // the body's reach: the shoulders standing, head and hands crawling
  const double reach =
      std::max(0.5 * params.shoulder_width, params.crawl_offset + 0.5 * params.crawl_length) +
      params.margin;
  const Eigen::Vector2d here = At(believed);
  // the rim of a raised top: a floor or border cell more than h_stairs above a 4-neighbour's
  // floor (a top seen from afar may reach a cell too far, and two such rims close a narrow way)
  const float h_stairs = float(params.h_stairs);
  auto known_floor = [&](int jx, int jy, float* h) {
    if (!w.Contains(jx, jy)) return false;
    const CellType t = fog.TypeAt(jx, jy);
    *h = fog.HeightAt(jx, jy);
    return (t == CellType::kFloor || t == CellType::kBorder || t == CellType::kStairs) &&
           std::isfinite(*h);
  };
  auto top_rim = [&](int ix, int iy) {
    float h = 0, g = 0;
    if (!known_floor(ix, iy, &h)) return false;
    const int nx[4] = {ix + 1, ix - 1, ix, ix}, ny[4] = {iy, iy, iy + 1, iy - 1};
    for (int k = 0; k < 4; ++k) {
      if (known_floor(nx[k], ny[k], &g) && g < h - h_stairs) return true;
    }
    return false;
  };
  perception::Fog hopeful = fog;
  int suspects = 0;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const size_t i = size_t(w.Index(ix, iy));
      if (!(solid(ix, iy) || top_rim(ix, iy)) || !(maps.obstacle_range[i] > range) ||
          (w.CellCenter(ix, iy) - here).norm() <= reach || seen_near(ix - 1, iy) ||
          seen_near(ix + 1, iy) || seen_near(ix, iy - 1) || seen_near(ix, iy + 1)) {
        continue;
      }
      hopeful.type[i] = CellType::kUnknown;
      hopeful.height[i] = -std::numeric_limits<float>::infinity();
      ++suspects;
    }
  }
  if (suspects == 0) return std::nullopt;
  const nav::PlanResult plan = PlanToGoal(hopeful, believed, goal, params, posture);
  if (plan.status != nav::PlanStatus::kOk) return std::nullopt;
  const size_t k = nav::FirstBlockedPose(fog, plan, goal.at, params);
  if (k >= plan.path.size()) return std::nullopt;
  return At(plan.path[k - 1].pose_G);
}

// The map with every unknown cell made floor at height `z`.
perception::Fog OpenUnknown(const perception::Fog& fog, float z) {
  perception::Fog open = fog;
  for (size_t i = 0; i < open.type.size(); ++i) {
    if (open.type[i] != CellType::kUnknown) continue;
    open.type[i] = CellType::kFloor;
    open.height[i] = z;
  }
  return open;
}

// Where to look from at the unseen cells a plan would move into blind: the robot may not
// side-step or back into cells its eyes have not seen (PlannerParams::blind_moves_stay_known),
// so a gap that only a side-step passes stays closed while the floor behind it is hidden (a
// gap in a divider the robot came to at an angle). The map with blind moves allowed may have a
// way on; the robot looks from the last pose of that way before its first blind move, at
// `lead` beyond the pose that move goes to, in its direction. If `open_unseen` and there is no
// such way, the same on the map with the unseen cells open floor (OpenUnknown): the first move
// the real map stops may then be a walk as well. `toward` is the real map's plan toward the
// goal (nav::PlanToward with `params`). Nothing if there is no such way or it stays put.
struct Peek {
  Eigen::Vector2d from, at;
};

std::optional<Peek> PeekPose(const perception::Fog& fog, const Pose2& believed,
                             const MissionGoal& goal, const nav::PlannerParams& params,
                             nav::Posture posture, const nav::PlanResult& toward,
                             double min_approach, double lead, bool open_unseen) {
  if (!params.blind_moves_stay_known) return std::nullopt;
  nav::PlannerParams blind = params;
  blind.blind_moves_stay_known = false;
  int gx = 0, gy = 0;
  fog.window.CellOf(goal.at.x(), goal.at.y(), &gx, &gy);
  auto end_distance = [&](const nav::PlanResult& p) {
    return (At(p.path.back().pose_G) - goal.at).norm();
  };
  // to the goal; else to where its region meets the window's edge; with the goal beyond the
  // window, min_approach nearer it than the real map leads
  auto blind_way = [&](const perception::Fog& map) {
    nav::PlanResult plan = PlanToGoal(map, believed, goal, blind, posture);
    if (plan.status == nav::PlanStatus::kOk && !plan.reaches_goal) {
      if (fog.window.Contains(gx, gy)) {
        plan = nav::PlanBeyond(map, believed, goal.at, blind, posture);
      } else if (toward.status == nav::PlanStatus::kOk &&
                 end_distance(plan) >= end_distance(toward) - min_approach) {
        plan = nav::PlanResult{};
      }
    }
    return plan;
  };
  auto first_blocked = [&](const nav::PlanResult& plan) {
    return plan.status == nav::PlanStatus::kOk
               ? nav::FirstBlockedPose(fog, plan, goal.at, params)
               : plan.path.size();
  };
  nav::PlanResult plan = blind_way(fog);
  size_t k = first_blocked(plan);
  if (k >= plan.path.size() && open_unseen) {
    // the unseen cells open at the height of the floor the robot stands on
    int rx = 0, ry = 0;
    fog.window.CellOf(believed.x, believed.y, &rx, &ry);
    const float z = fog.window.Contains(rx, ry) && std::isfinite(fog.HeightAt(rx, ry))
                        ? fog.HeightAt(rx, ry)
                        : 0.0f;
    plan = blind_way(OpenUnknown(fog, z));
    k = first_blocked(plan);
  }
  if (k >= plan.path.size()) return std::nullopt;
  const Eigen::Vector2d from = At(plan.path[k - 1].pose_G), to = At(plan.path[k].pose_G);
  const Eigen::Vector2d step = to - from;
  return Peek{from, step.norm() > 1e-9 ? Eigen::Vector2d(to + step.normalized() * lead) : to};
}

// The first run of moves of `plan`, cut to the longest walk, side-step or crawl of one command.
nav::PathSegment FirstRun(const nav::PlanResult& plan, const ExecutionLimits& limits) {
  nav::PathSegment run = nav::SegmentPath(plan).front();
  const double limit = run.move == nav::Move::kWalk       ? limits.walk
                       : run.move == nav::Move::kSidestep ? limits.sidestep
                       : run.move == nav::Move::kCrawl    ? limits.crawl
                                                          : 1e9;
  double travelled = 0;
  for (int k = run.first + 1; k <= run.last; ++k) {
    const Pose2& a = plan.path[k - 1].pose_G;
    const Pose2& b = plan.path[k].pose_G;
    travelled += std::hypot(b.x - a.x, b.y - a.y);
    if (travelled >= limit) {
      run.last = k;
      break;
    }
  }
  return run;
}

}  // namespace

nav::PlanResult PlanToGoal(const perception::Fog& fog, const Pose2& start, const MissionGoal& goal,
                           const nav::PlannerParams& planner, nav::Posture posture,
                           nav::PlannerParams* used) {
  if (used) *used = planner;
  nav::PlanResult plan = nav::Plan(fog, start, goal.at, planner, posture);
  if (plan.status == nav::PlanStatus::kOk || plan.reason != nav::NoPathReason::kGoalBlocked) {
    return plan;
  }
  nav::PlannerParams wider = planner;
  wider.goal_tolerance =
      std::max(planner.goal_tolerance, goal.tolerance - 0.5 * fog.window.resolution);
  if (used) *used = wider;
  return nav::Plan(fog, start, goal.at, wider, posture);
}

Behaviour::Behaviour(const MissionGoal& goal, const nav::PlannerParams& planner,
                     const ExecutionLimits& limits, const Pose2& start)
    : goal_(goal), planner_(planner), limits_(limits) {
  state_.looked_at = start;
}

Mode Behaviour::mode() const {
  if (!state_.explore) return Mode::kFollow;
  return state_.explore->to_look ? Mode::kGoLook : Mode::kExplore;
}

nav::PlannerParams Behaviour::planner() const {
  nav::PlannerParams p = planner_;
  if (state_.getting_up_unseen) p.get_up_under_seen_headroom = false;
  return p;
}

void Behaviour::Moved(const nav::PlanResult& plan, size_t reached) {
  state_.last_plan = plan;
  state_.last_plan_at = reached;
  state_.just_looked = false;
}

void Behaviour::LookedAround(const Pose2& at) {
  state_.looked_at = at;
  state_.just_looked = true;
}

bool Behaviour::LeadsNearer(const nav::PlanResult& p, const Eigen::Vector2d& target,
                            double distance) const {
  return Moves(p) && (At(p.path.back().pose_G) - target).norm() < distance - limits_.min_approach;
}

Decision Behaviour::Decide(const perception::Fog& fog, const perception::MapState& maps,
                           const Pose2& believed, nav::Posture posture) {
  MissionState& s = state_;
  const Eigen::Vector2d position = At(believed);
  s.nearest_to_goal = std::min(s.nearest_to_goal, (position - goal_.at).norm());
  if (posture == nav::Posture::kUpright) s.getting_up_unseen = false;
  const auto start = std::chrono::steady_clock::now();
  Decision d;
  nav::PlannerParams used;
  d.plan = PlanToGoal(fog, believed, goal_, planner(), posture, &used);
  const bool circling = NoteArrival(believed, fog.window.resolution);
  KeepLastPlan(fog, believed, posture, used, &d.plan);
  d.plan_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  d.found = Moves(d.plan) ? (d.plan.reaches_goal ? "goal" : "toward")
            : d.plan.status == nav::PlanStatus::kOk ? "here"
                                                    : nav::NoPathReasonName(d.plan.reason);
  d.found_cost = d.plan.cost;
  d.found_length = d.plan.length;

  if (s.explore && ExplorationEnds(position, &d)) return LookAround("look_on_arrival", believed, d);
  s.recent.push_back({position, s.nearest_to_goal});
  if (int(s.recent.size()) > limits_.thrash_cycles) s.recent.pop_front();
  const bool thrashing = !d.plan.reaches_goal && int(s.recent.size()) == limits_.thrash_cycles &&
                         s.nearest_to_goal > s.recent.front().second - limits_.min_approach &&
                         std::all_of(s.recent.begin(), s.recent.end(), [&](const auto& r) {
                           return (r.first - s.recent.front().first).norm() < limits_.thrash_radius;
                         });
  if (thrashing) {
    s.recent.clear();
    ++s.thrashes;
  }
  if (thrashing || circling) s.arrivals.clear();
  if (s.thrashes > 1) {  // the ways it finds take it back and forth
    d.action = Action::kGiveUp;
    d.name = "give_up";
    d.failure_detail = "no_progress";
    return d;
  }
  // exploring, only a plan to the goal itself takes over (a goal outside the window has plans
  // toward it that lead to where the way seemed to end, and the goal passes in and out of the
  // window as the robot goes); once it went back and forth, a plan short of the goal must lead
  // nearer than it has been
  const bool stuck = s.thrashes > 0 && !s.explore && !d.plan.reaches_goal &&
                     !LeadsNearer(d.plan, goal_.at, s.nearest_to_goal);
  // circling on plans that reach the goal, it looks around; it does not give up for it
  if (circling && !s.just_looked && !s.explore && Moves(d.plan) && d.plan.reaches_goal) {
    return LookAround("circling_look", believed, d);
  }
  if (!Moves(d.plan) || thrashing || stuck || (s.explore && !d.plan.reaches_goal)) {
    return WhenBlocked(fog, maps, believed, posture, std::move(d));
  }
  nav::PlanResult plan = std::move(d.plan);
  return Follow("follow", std::move(plan), std::move(d));
}

// Whether the robot came to `believed` by moving for the circling_arrivals-th time without
// getting min_approach nearer the goal than it was at the first time; notes the arrival.
bool Behaviour::NoteArrival(const Pose2& believed, double resolution) {
  MissionState& s = state_;
  auto same_pose = [&](const Pose2& a, const Pose2& b) { return SamePose(a, b, resolution); };
  const bool moved_here = s.arrivals.empty() || !same_pose(s.arrivals.back().first, believed);
  int times_here = 0;
  double nearest_then = 0;  // at the first time
  for (const auto& [pose, nearest] : s.arrivals) {
    if (!same_pose(pose, believed)) continue;
    if (times_here++ == 0) nearest_then = nearest;
  }
  const bool circling = moved_here && times_here + 1 >= limits_.circling_arrivals &&
                        s.nearest_to_goal > nearest_then - limits_.min_approach;
  if (moved_here) s.arrivals.push_back({believed, s.nearest_to_goal});
  if (int(s.arrivals.size()) > limits_.thrash_cycles) s.arrivals.pop_front();
  return circling;
}

// Keeps to the last plan where the robot got to its run's end and the rest of it is still
// allowed and about as cheap as the new plan.
void Behaviour::KeepLastPlan(const perception::Fog& fog, const Pose2& believed,
                             nav::Posture posture, const nav::PlannerParams& used,
                             nav::PlanResult* plan) const {
  const MissionState& s = state_;
  if (plan->status != nav::PlanStatus::kOk || s.last_plan.status != nav::PlanStatus::kOk ||
      s.last_plan_at >= s.last_plan.path.size()) {
    return;
  }
  const nav::PathPose& at = s.last_plan.path[s.last_plan_at];
  if (at.posture != posture || !SamePose(at.pose_G, believed, fog.window.resolution)) return;
  nav::PlanResult rest = nav::ContinuePlan(fog, s.last_plan, s.last_plan_at, believed, goal_.at, used);
  if (Moves(rest) && rest.cost <= plan->cost + std::max(limits_.keep_plan_margin,
                                                       limits_.keep_plan_share * plan->cost)) {
    *plan = std::move(rest);
  }
}

// Exploring goes on while the map's ways to the goal come and go (they may lead through cells
// not yet seen), until the robot is within reach of its target or has not got min_approach
// nearer to it for explore_patience cycles (turns and looks make cycles without a step, and a
// robot that gains a few centimetres a cycle is on its way). True if it came to look and is
// there: it looks around at once (following a way that opened elsewhere on the way, its eyes
// would see only where that way goes).
bool Behaviour::ExplorationEnds(const Eigen::Vector2d& position, Decision* d) {
  MissionState::Exploration& e = *state_.explore;
  const double distance = (position - e.target).norm();
  if (distance < e.best - limits_.min_approach) {
    e.stalls = 0;
    e.best = distance;
  } else {
    ++e.stalls;
  }
  if (distance >= e.reach && e.stalls <= limits_.explore_patience) return false;
  const bool there_to_look = e.to_look && distance < e.reach;
  if (there_to_look) d->target = e.target;
  state_.explore.reset();
  return there_to_look;
}

Decision Behaviour::LookAround(const char* name, const Pose2& at, Decision d) {
  d.action = Action::kLookAround;
  d.name = name;
  d.peek_at = state_.peek_at;
  state_.peek_at.reset();
  LookedAround(at);
  return d;
}

Decision Behaviour::Follow(const char* name, nav::PlanResult plan, Decision d) const {
  d.action = Action::kFollow;
  d.name = name;
  d.plan = std::move(plan);
  d.run = FirstRun(d.plan, limits_);
  return d;
}

void Behaviour::StartExploring(const Eigen::Vector2d& target, double reach, bool to_look,
                               const Eigen::Vector2d& from) {
  state_.explore = MissionState::Exploration{target, reach, to_look, (target - from).norm(), 0};
  ++state_.explorations;
}

// No way to follow: look around first; else get as near the goal as the map allows and look
// again from there (what was seen from afar may be wrong), unless that gains nothing (once it
// has explored: over the nearest it has been, else it would only go back); else a fresh look;
// else explore or go and look; else give up.
Decision Behaviour::WhenBlocked(const perception::Fog& fog, const perception::MapState& maps,
                                const Pose2& believed, nav::Posture posture, Decision d) {
  MissionState& s = state_;
  // exploring, the robot looks ahead each cycle; it looks around only once that way ends
  if (!s.just_looked && !s.explore) return LookAround("look_around", believed, std::move(d));
  const Eigen::Vector2d position = At(believed);
  const double here = (position - goal_.at).norm();
  nav::PlanResult toward;
  bool nearer = false;
  const char* why = "toward_goal";
  if (!s.explore) {
    toward = nav::PlanToward(fog, believed, goal_.at, planner(), posture);
    nearer = LeadsNearer(toward, goal_.at,
                         s.explorations > 0 || s.thrashes > 0 ? std::min(s.nearest_to_goal, here)
                                                               : here);
  }
  // crawling with no way on: beyond a table top as thick as the eyes are high the headroom stays
  // unseen from below, so the robot may get up where the map holds no ceiling, until it stands
  // again; with no way to the goal even so, it gets up where that leads nearer
  if (!nearer && posture == nav::Posture::kCrawling && planner().get_up_under_seen_headroom) {
    nav::PlannerParams unseen = planner();
    unseen.get_up_under_seen_headroom = false;
    nav::PlanResult up = PlanToGoal(fog, believed, goal_, unseen, posture);
    if (!Moves(up)) {
      up = nav::PlanToward(fog, believed, goal_.at, unseen, posture);
      if (!LeadsNearer(up, goal_.at, here)) up = nav::PlanResult{};
    }
    if (Moves(up)) {
      s.getting_up_unseen = true;
      toward = std::move(up);
      nearer = true;
      why = "get_up";
    }
  }
  if (!nearer && !s.explore &&
      (!s.fresh_at || std::hypot(believed.x - s.fresh_at->x, believed.y - s.fresh_at->y) >
                          limits_.fresh_look_distance)) {
    d.action = Action::kFreshLook;
    d.name = "fresh_look";
    s.fresh_at = believed;
    LookedAround(believed);
    return d;
  }
  if (!nearer && s.explore) {
    toward = nav::PlanToward(fog, believed, s.explore->target, planner(), posture);
    if (!LeadsNearer(toward, s.explore->target, (position - s.explore->target).norm())) {
      d.action = Action::kReplan;
      d.name = "explore_ends";
      d.target = s.explore->target;
      s.explore.reset();
      return d;
    }
    nearer = true;
    why = "explore";
    d.target = s.explore->target;
  } else if (!nearer && s.explorations < limits_.max_explorations) {
    nearer = FindLookout(fog, maps, believed, posture, &toward, &why);
    if (nearer) d.target = s.explore->target;
  }
  if (!nearer) {
    d.action = Action::kGiveUp;
    d.name = "give_up";
    // a plan that ends where it starts: the best reachable state toward the goal is here
    d.failure_detail = d.plan.status == nav::PlanStatus::kOk
                           ? "no_progress"
                           : nav::NoPathReasonName(d.plan.reason);
    return d;
  }
  return Follow(why, std::move(toward), std::move(d));
}

// Still no way: go and look, at obstacle evidence seen from afar or into the unseen cells a
// blind move needs (of the two, the one reached by the cheaper way), where that way is shorter
// than the one to the window's edge; else explore: the goal's region may be joined beyond the
// map window (a wall whose end lies outside it), so go to the window's edge where that region
// meets it, then on explore_beyond past it (the window moves with the robot and forgets what
// it leaves behind, so a new choice each cycle would go back and forth). `toward` holds the
// map's plan toward the goal, and gets the way to follow.
bool Behaviour::FindLookout(const perception::Fog& fog, const perception::MapState& maps,
                            const Pose2& believed, nav::Posture posture, nav::PlanResult* toward,
                            const char** why) {
  const nav::PlannerParams params = planner();
  const Eigen::Vector2d position = At(believed);
  std::optional<Eigen::Vector2d> suspect =
      InspectionPose(fog, maps, believed, goal_, params, posture, limits_.inspect_range);
  if (!suspect) {
    suspect = InspectionPose(fog, maps, believed, goal_, params, posture,
                             limits_.inspect_near_range);
  }
  const std::optional<Peek> peek = PeekPose(fog, believed, goal_, params, posture, *toward,
                                            limits_.min_approach, limits_.peek_lead, !suspect);
  const std::optional<Eigen::Vector2d> candidates[2] = {
      suspect, peek ? std::optional<Eigen::Vector2d>(peek->from) : std::nullopt};
  const double reaches[2] = {limits_.inspect_reach, limits_.peek_reach};
  int chosen = -1;
  nav::PlanResult look_way;
  state_.peek_at.reset();
  for (int c = 0; c < 2; ++c) {
    if (!candidates[c]) continue;
    nav::PlanResult way = nav::PlanToward(fog, believed, *candidates[c], params, posture);
    if (LeadsNearer(way, *candidates[c], (position - *candidates[c]).norm()) &&
        (chosen < 0 || way.cost < look_way.cost)) {
      chosen = c;
      look_way = std::move(way);
    }
  }
  nav::PlanResult edge = nav::PlanBeyond(fog, believed, goal_.at, params, posture);
  if (chosen >= 0 && (!Moves(edge) || look_way.length < edge.length)) {
    StartExploring(*candidates[chosen], reaches[chosen], true, position);
    *toward = std::move(look_way);
    if (chosen == 1) state_.peek_at = peek->at;
    *why = chosen == 1 ? "peek" : "inspect";
    return true;
  }
  if (!Moves(edge)) return BackOff(fog, believed, posture, toward, why);
  const Eigen::Vector2d end = At(edge.path.back().pose_G);
  StartExploring(end + (end - position).normalized() * limits_.explore_beyond,
                 limits_.explore_beyond, false, position);
  *toward = std::move(edge);
  *why = "explore_edge";
  return true;
}

// Nothing else left: what the eyes saw from here may close the way (a narrow gap smeared shut
// by the views from its mouth, where the body hides its floor), so back off back_off from the
// goal's side and look again from there, where the way lies in view.
bool Behaviour::BackOff(const perception::Fog& fog, const Pose2& believed, nav::Posture posture,
                        nav::PlanResult* toward, const char** why) {
  const Eigen::Vector2d position = At(believed);
  const Eigen::Vector2d to_goal = goal_.at - position;
  if (!(limits_.back_off > 0) || to_goal.norm() < 1e-9) return false;
  const Eigen::Vector2d target = position - to_goal.normalized() * limits_.back_off;
  nav::PlanResult way = nav::PlanToward(fog, believed, target, planner(), posture);
  if (!LeadsNearer(way, target, limits_.back_off)) return false;
  StartExploring(target, limits_.inspect_reach, true, position);
  *toward = std::move(way);
  *why = "back_off";
  return true;
}

}  // namespace fognav::scenarios

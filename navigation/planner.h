// The path navigator of the paper's Section 6: A* over the Floor and Obstacle Grid (FOG) that
// decides how the humanoid moves through each kind of terrain (walk, side-step, stairs, crawl),
// and a picture of the plan drawn over the map. Pure functions over value types; everything is
// in the grid frame G (the odometry frame) in metres and radians.
#ifndef FOGNAV_NAVIGATION_PLANNER_H_
#define FOGNAV_NAVIGATION_PLANNER_H_

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "perception/mapping.h"
#include "perception/types.h"

namespace fognav::navigation {

// How the robot carries its body: standing (walks, side-steps, climbs) or crawling (under
// tunnels only).
enum class Posture : uint8_t { kUpright = 0, kCrawling = 1 };

// The move that brings the robot to a path pose. kNone labels only the first pose (the start).
// kWalk is a step forward or backward, kSidestep one along the shoulders' axis, kTurn a turn in
// place to the next lattice heading (standing or crawling); kStairsUp / kStairsDown is one
// step forward from a standing pose on one level to a standing pose on a floor more than h_floor
// (and at most h_stairs) higher / lower, over as many lattice cells as that takes (at most
// max_step_length): the pose's displacement from the previous one is the whole step.
// kCrawl is a crawl forward or backward, or a posture change in place, where the pose's posture
// says whether the robot got down (kCrawling) or up (kUpright).
enum class Move : uint8_t { kNone = 0, kWalk, kSidestep, kTurn, kStairsUp, kStairsDown, kCrawl };
inline constexpr int kNumMoves = 7;

// Lower-case name of a move, as in report.json: "none", "walk", "sidestep", "turn",
// "stairs_up", "stairs_down", "crawl".
const char* MoveName(Move move);
// Lower-case name of a posture: "upright", "crawling".
const char* PostureName(Posture posture);

// Number of headings of the search lattice: the 16 directions of the cell steps (1,0), (2,1),
// (1,1), (1,2), (0,1), ... so every move ends on a cell centre. They are 18.4 to 26.6 degrees
// apart rather than exactly 22.5.
inline constexpr int kNumHeadings = 16;

// Parameters of the planner. Robot defaults are for a QRIO-sized (0.58 m) humanoid; terrain
// defaults are the paper's Section 6. Footprints are rectangles aligned with the heading:
// upright `depth` along it by `shoulder_width` across, centred on the robot's origin; crawling
// `crawl_length` by `crawl_width`, centred `crawl_offset` ahead; each grown by `margin` on every
// side. A FOG cell is under a footprint when its
// centre lies inside the grown rectangle. With the defaults the upright footprint is
// 0.15 m x 0.29 m, so on 4 cm cells it covers 3 cells along the heading and 7 across: a gap of
// 0.22 m (5 or 4 free cells once mapped) is too narrow to walk through facing it (7 cells) but
// wide enough to side-step through (3 cells); a gap of 2 free cells (0.08 m, narrower than the
// 0.12 m depth) is passable by no move. The crawling footprint is 0.53 m x 0.29 m, its centre
// 0.10 m ahead of the origin (the humanoid on knees and hands, head raised, toes behind).
// The shipped humanoid (models/humanoid.xml) is 0.11 m long at the soles, inside these sizes;
// its knees and head reach further (body_front, head_reach).
// What may lie under a footprint: standing, unknown cells and floor, stairs and border cells
// whose height is within h_floor of the floor under the robot's origin (unknown origins take the
// nearest known floor's), so a standing robot is always level: its feet never reach onto another
// tread, and it may stand at the foot of a wall or block or on the rim of a platform (the
// paper's border marks both sides of a drop) but never across the drop; crawling, tunnel cells
// and floor or unknown cells near them, and border cells near them on the origin's level (the
// foot of a wall beside a table). Obstacle cells never.
// Moves: walks, side-steps and crawls go to a neighbouring cell whose floor is within h_floor.
// A step up or down goes forward along the heading, facing the floor's height gradient, by the
// fewest lattice steps (at most max_step_length) that lead from a standing pose on floor h0 to
// one on floor h1 with h_floor < |h1 - h0| <= h_stairs; the poses it passes need not be
// allowed, but no cell its footprint sweeps may be an obstacle or tunnel cell or lie more than
// h_floor above or below both levels. So on 4 cm cells, where the upright footprint is three
// cells (0.12 m) along the heading, a riser across the heading takes a step of 0.12 m, from the
// origin 0.06 m before the riser (the shipped humanoid's toes 5 mm short of it) to 0.06 m past
// it; a tread the map holds as fewer than three cells is never stood on, and stepped over only
// if the step over it fits in max_step_length (with the defaults it never does: no path).
struct PlannerParams {
  // robot body, metres (the accounts of the values: docs/params.md, "Planner")
  double shoulder_width = 0.26;  // upright extent across the heading
  double depth = 0.12;           // upright extent along the heading (feet and torso)
  double crawl_length = 0.50;    // crawling extent along the heading (toes to head)
  double crawl_width = 0.26;     // crawling extent across the heading
  double crawl_offset = 0.10;    // centre of the crawling extent ahead of the robot's origin
  double margin = 0.015;         // safety margin added on every side of both footprints
  // standing, the footprint grown by this much holds only the origin's level; the ring beyond,
  // up to `margin`, may hold a tread (up to h_stairs off) too
  double level_margin = 0.01;
  // width across which the soles stand level; beyond it a tread's height may lie, as in the ring
  double stance_width = 0.20;
  // the knees' reach behind and ahead of the standing origin: an obstacle, tunnel or high floor
  // there, outside the soles' footprint, costs body_touch_cost
  double body_back = 0.055;
  double body_front = 0.09;
  // the hands' reach beside the origin: the body rectangle's half width less `margin`
  double arm_reach = 0.152;
  // tops higher than this above the origin's floor reach the hands: an unknown cell within
  // hidden_reach of such a top counts as the top (edge_touch_cost beside the legs)
  double hand_low = 0.21;
  double hidden_reach = 0.08;
  double body_touch_cost = 0.5;  // metres-equivalent per move
  double edge_touch_cost = 0.1;  // metres-equivalent per move
  // the standing head's reach from the origin: no tunnel cell's centre within it (plus margin)
  double head_reach = 0.12;
  // nor an obstacle or floor within it higher than this above the origin's floor
  double head_low = 0.40;

  // terrain limits (paper Section 6), metres
  double h_floor = 0.015;   // larger floor height changes between neighbouring cells are steps
  double h_stairs = 0.05;   // largest step the robot climbs; larger changes are never crossed
  // longest step up or down, pose to pose (the controller's max_climb_forward), metres
  double max_step_length = 0.16;
  // how far beside its heading a step up or down may end (max_climb_sideways), metres
  double max_step_sideways = 0.03;
  // largest angle between the heading and the floor's height gradient on a step, radians
  double max_stairs_heading_error = 0.35;
  // floor and unknown cells this near a tunnel cell (or, without seen headroom, floor) allow
  // crawling; getting down only this near a tunnel cell, metres
  double crawl_zone_radius = 0.8;
  // how far getting down moves the origin forward (getting up, back), metres
  double kneel_offset = 0.178;
  // getting down or up, the body is below a ceiling beyond this far ahead, metres
  double kneel_clear_reach = 0.46;
  // get up only where the headroom of the standing body has been seen (Fog::headroom_seen)
  bool get_up_under_seen_headroom = true;
  // without it, the standing origin keeps this far from every tunnel cell, metres
  double unseen_headroom_clearance = 0.4;
  // backward and side moves may not bring an unseen cell under the footprint
  bool blind_moves_stay_known = true;
  // nor may forward crawls
  bool crawl_stays_known = true;

  // costs: a translation costs its length times its factor plus the clearance and unknown costs
  // below; factors are per metre and >= walk_factor keeps the heuristic admissible
  double walk_factor = 1.0;         // forward walking
  double backward_factor = 1.5;     // walking backwards
  double sidestep_factor = 1.6;     // stepping along the shoulders' axis
  double stairs_factor = 2.0;       // steps up and down, and walks starting or ending on a
                                    // stairs cell
  double crawl_factor = 3.0;        // crawling forward (backward: times backward_factor)
  double turn_cost_per_rad = 0.15;  // turning in place, metres-equivalent per radian
                                    // (times crawl_factor when crawling)
  double posture_change_cost = 1.0;  // getting down or getting up, metres-equivalent
  double unknown_penalty = 0.5;      // added per metre on unknown cells

  // clearance cost, added per metre: clearance_weight * min(h, clearance_height_cap) /
  // clearance_height_ref * max(0, 1 - d / clearance_radius) for the worst obstacle cell at
  // centre distance d whose top is h above the neighbouring floor (a drop's upper edge counts
  // as an obstacle as high as the drop is deep)
  double clearance_weight = 1.0;
  double clearance_radius = 0.6;      // metres
  double clearance_height_ref = 0.2;  // metres
  double clearance_height_cap = 0.3;  // metres; walls and unknown heights count as this

  // goal and start
  double goal_tolerance = 0.1;  // a pose whose cell centre is this close to the goal reaches it
  // a goal outside the window: a path may end within exit_band of the window's side toward it,
  // at exit_factor times its straight-line distance to the goal
  double exit_factor = 8.0;
  double exit_band = 0.4;  // metres
  // a start pose not allowed: the search starts from allowed poses this near it, metres
  double start_escape_radius = 0.08;
};

// Whether a plan was found.
enum class PlanStatus : uint8_t { kOk = 0, kNoPath };

// Why there is no path (kNone when there is one).
enum class NoPathReason : uint8_t {
  kNone = 0,
  kStartBlocked,  // the start is outside the window, or no pose near it is allowed
  kGoalBlocked,   // the goal is in the window but no pose within the tolerance is allowed
  kGoalEnclosed,  // poses at the goal exist but none is connected to the start
};

// Lower-case name of a plan status ("ok", "no_path") and of a reason ("none",
// "start_blocked", "goal_blocked", "goal_enclosed").
const char* PlanStatusName(PlanStatus status);
const char* NoPathReasonName(NoPathReason reason);

// One pose of a path: where the robot is after `move`, in the grid frame, its posture, and the
// floor height under its origin (metres, grid frame; an unknown cell has the nearest known
// floor's, NaN if the map has none), so a step's rise is floor_z minus the previous pose's (for
// a step up or down, the new level h1 minus the old one h0, over the whole displacement).
struct PathPose {
  perception::Pose2 pose_G;
  Move move = Move::kNone;
  Posture posture = Posture::kUpright;
  double floor_z = 0;
};

// The answer of Plan. When status is kOk, path[0] is the start pose (move kNone) and each
// further pose is a lattice state (cell centre, lattice heading) labelled with the move that
// reaches it.
struct PlanResult {
  PlanStatus status = PlanStatus::kNoPath;
  NoPathReason reason = NoPathReason::kNone;
  std::vector<PathPose> path;
  // true when the path ends within the goal tolerance; false when the goal lies outside the
  // map window and the path ends near the window's edge toward it (PlannerParams::exit_band),
  // or where no way leads there, at the best reachable state toward it
  bool reaches_goal = false;
  double cost = 0;    // total cost (metres-equivalent), with the exit term if !reaches_goal
  double length = 0;  // travelled distance of the robot's origin, metres
  int expanded = 0;   // states the search expanded
};

// Plans from `start_G` (the robot in `start_posture`) to `goal_G` on the FOG: an optimal path
// for the costs of `p` over cells x kNumHeadings x posture. Never throws for "no answer": an
// unreachable goal is a result with status kNoPath and its reason. Aborts if the FOG's arrays do
// not match its window or `p` has non-positive sizes or factors or negative costs. Keeps per-state scratch arrays
// per thread between calls (about 8 MB for a 100 x 100 window), so repeated plans do not
// allocate them again; a plan on the 100 x 100 course takes about 10 ms (Planning/course).
PlanResult Plan(const perception::Fog& fog, const perception::Pose2& start_G,
                const Eigen::Vector2d& goal_G, const PlannerParams& p,
                Posture start_posture = Posture::kUpright);

// Plans as Plan does, but to the reachable state that minimises path cost + p.exit_factor times
// its straight-line distance to the goal, whether or not the goal itself can be reached;
// reaches_goal is false. A robot that finds no path uses it to get nearer and look again.
// kNoPath only with kStartBlocked.
PlanResult PlanToward(const perception::Fog& fog, const perception::Pose2& start_G,
                      const Eigen::Vector2d& goal_G, const PlannerParams& p,
                      Posture start_posture = Posture::kUpright);

// Plans as Plan does, but to the edge of the map window, for a goal in the window that the
// start cannot reach inside it (a wall whose end lies beyond the window): the goal's region
// (the cells a walk from the goal reaches over floor, stairs, tunnel and unknown cells, never
// across a border cell or a rise of more than h_stairs) meets the window's edge at some cells;
// each edge cell ends the search at exit_factor times its distance to the nearest of them plus
// that one's walk to the goal (at walk_factor). reaches_goal is false. kNoPath with
// kGoalEnclosed when the goal's region meets no edge cell (or the goal lies outside the
// window), so a goal walled in within the window still has no path.
PlanResult PlanBeyond(const perception::Fog& fog, const perception::Pose2& start_G,
                      const Eigen::Vector2d& goal_G, const PlannerParams& p,
                      Posture start_posture = Posture::kUpright);

// The rest of an earlier plan on a new map: the robot at start_G (on or near the lattice pose
// earlier.path[from]) follows the same moves on, priced as Plan prices them on `fog`, with the
// new map's floor heights, and where the goal is outside the window the walk beyond the path's
// end at exit_factor (the path is cut where it leaves the window, and may end inside it now
// that the window has moved). kNoPath when that pose or one of the moves is no longer
// allowed, or the path ends outside a goal region in the window. A robot that re-plans as it
// learns the map keeps to its plan while this costs about what a new plan does, so that two
// nearly equal ways do not take turns. Uses Plan's per-thread scratch arrays.
PlanResult ContinuePlan(const perception::Fog& fog, const PlanResult& earlier, size_t from,
                        const perception::Pose2& start_G, const Eigen::Vector2d& goal_G,
                        const PlannerParams& p);
// The index of the first pose of `plan` (from 1 on) that its move cannot reach on `fog` from the
// pose before, as Plan would allow the moves there (a pose outside the window ends the check);
// plan.path.size() if there is none. Paths planned on a map with some cells made unknown find
// here where the real map stops them. Uses Plan's per-thread scratch arrays.
size_t FirstBlockedPose(const perception::Fog& fog, const PlanResult& plan,
                        const Eigen::Vector2d& goal_G, const PlannerParams& p);

// A run of one kind of move along a path, from path[first] to path[last] (first < last): the
// robot frame at path[first] holds the run's displacement as one motion command. Walks and
// crawls split where the direction flips between forward and backward; each step up or down and
// each posture change is a run of its own.
struct PathSegment {
  Move move = Move::kWalk;
  Posture posture = Posture::kUpright;  // the posture at the end of the run
  int first = 0;
  int last = 0;
};

// The runs of moves of a plan's path, in order; empty without a path.
std::vector<PathSegment> SegmentPath(const PlanResult& plan);

}  // namespace fognav::navigation

#endif  // FOGNAV_NAVIGATION_PLANNER_H_

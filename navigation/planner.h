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
  // robot body, metres
  double shoulder_width = 0.26;  // upright extent across the heading
  double depth = 0.12;           // upright extent along the heading (feet and torso)
  double crawl_length = 0.50;    // crawling extent along the heading (toes to head)
  double crawl_width = 0.26;     // crawling extent across the heading
  double crawl_offset = 0.10;    // centre of the crawling extent ahead of the robot's origin
  double margin = 0.015;         // safety margin added on every side of both footprints
  // Standing, the floor under the footprint grown by only this much must lie on the origin's
  // level; in the outer ring up to `margin` a tread's (up to h_stairs off) may lie too, but no
  // higher or lower floor (a block's top, a drop). With the full margin the footprint's cells
  // at the lattice's 26.6 degree headings span 0.16 m across a riser turned a little from
  // them, more than a step reaches, and stairs turned by 20-35 degrees had no level pose
  // within a step of each other.
  double level_margin = 0.01;
  // Only the soles stand on the floor: the level test above holds across this width, not the
  // shoulders'; under the rest of the footprint a tread's height (up to h_stairs off) may lie,
  // as in the ring. The shipped humanoid's soles span 0.154 m (centres 0.09 m apart, 0.064 m
  // wide); 2.3 cm more on each side, since a 4 cm cell whose centre lies on the lower floor may
  // hold the last 2 cm of a riser (a riser turned by 12 degrees met a sole's front corner with
  // 0.16). As wide as the shoulders, the footprint spans 0.28 m across a riser that, turned 9
  // degrees from a lattice heading, lies 4.5 cm further ahead at one side than at the other:
  // stairs turned by 17.5 or 72.5 degrees had no two level poses within a step.
  double stance_width = 0.20;
  // Standing, the body reaches further than the soles: the knees come forward as a foot lifts
  // (the shipped humanoid, measured over side-steps and turns in tests/sim: from 0.055 m
  // behind its origin to 0.09 m ahead). A move that ends with an obstacle or tunnel cell, or a
  // floor more than h_stairs above the origin's, under this rectangle grown by `margin` but
  // outside the soles' footprint costs body_touch_cost more: the robot keeps its knees clear
  // where the map leaves room, and still passes where the map holds a passage a cell
  // narrower than the body (a 0.22 m gap whose blocks a noisy view widened). Across, the
  // body is the shoulders' width: the arms swing out to 0.152 m, 7 mm past the shoulders'
  // margin, but a wider rectangle on 4 cm cells would take 9 cells instead of 7 and close the
  // 0.34 m passages the robot walks through.
  double body_back = 0.055;
  double body_front = 0.09;
  // Across, the hands reach this far beside the origin (the arms swing out in side-steps and
  // with the pelvis's sway; measured in tests/sim): the body rectangle is as wide as that plus
  // `margin`, so the robot keeps a hand's clearance from a block where the map leaves room (on
  // the footprint's cells alone a block may stand 0.14 m beside the origin, 12 mm inside the
  // hands' reach: a slalom moved by 1-2 cm put a hand on a block in 3 of 4 copies)
  double arm_reach = 0.152;
  // An unknown cell within hidden_reach of a seen floor, stairs or border cell whose height
  // lies more than hand_low above the origin's floor counts against the body rectangle as that
  // top would: the eyes saw the solid from one side only, and its far face or hidden corner may
  // lie there (with 60-degree views a hand met the unseen end of a wall it walked round). The
  // shipped humanoid's hands hang with their lowest point 0.233 m above the soles; lower tops
  // (a 15 cm ottoman) pass under them. Before and behind the legs (the body rectangle within
  // the stance's width grown by margin) any top more than h_stairs high counts so: a robot
  // turning round the end of a 0.175 m block whose last 4-10 cm its eyes had never seen (too
  // near, beside the feet, once there) put a knee on it in 3 of 6 shifted copies of a room.
  // A border cell on the low side of a top above hand_low counts so too beside the legs:
  // stereo may end a top a cell short (a hand met the corner leg of a 0.28 m table whose top
  // the map ended 4 cm early, the cells beyond typed border at floor height). Not before and
  // behind the legs: every side-step through the course's 0.22 m gap would pay for it. Such a
  // cell is only a maybe, so it costs edge_touch_cost, not body_touch_cost: enough to keep a
  // cell further off where the way is as short, too little to turn the robot from a narrow
  // way (at 0.5 the noisy_gap mission turned back from its gap and gave up).
  double hand_low = 0.21;
  double hidden_reach = 0.08;
  double body_touch_cost = 0.5;  // metres-equivalent per move
  double edge_touch_cost = 0.1;  // metres-equivalent per move
  // how far the standing robot's head reaches from its origin (looking down, the head box tilts
  // forward); no tunnel cell's centre may lie within head_reach + margin of a standing robot's
  // origin, so it gets down before its head meets the underside, and up only once clear of it
  double head_reach = 0.12;
  // Nor may an obstacle or floor cell within that reach rise more than head_low above the floor
  // under the origin (the tilted head's lowest edge; a table top below the eyes, a tall block)
  double head_low = 0.40;

  // terrain limits (paper Section 6), metres
  double h_floor = 0.015;   // larger floor height changes between neighbouring cells are steps
  double h_stairs = 0.05;   // largest step the robot climbs; larger changes are never crossed
  // longest step up or down, from standing pose to standing pose (the controller's
  // max_climb_forward), metres
  double max_step_length = 0.16;
  // a step up or down may end this far beside its heading (the lead foot steps aside as it
  // climbs; sim::StepLimits::max_climb_sideways), metres
  double max_step_sideways = 0.03;
  // a step up or down is taken facing it: the heading may differ from the direction of the
  // floor's height gradient there by at most this angle, radians
  double max_stairs_heading_error = 0.35;
  // floor and unknown cells whose centre is within this distance of a tunnel cell's centre
  // allow crawling (the paper's "enlarged area" around a tunnel; unknown ones at the unknown
  // penalty, as the robot may lose sight of the floor under itself), metres. With
  // get_up_under_seen_headroom, so do cells within it of floor whose headroom is unseen, but
  // the robot gets down only within it of a tunnel cell: in a room with nothing above the eyes
  // no floor's headroom is seen, and a robot that got down in the open to pass a narrow way
  // crawled with its eyes at the floor, whose stereo then walled it in.
  double crawl_zone_radius = 0.8;
  // Getting down moves the robot's origin this far forward along its heading (the crawling
  // origin is at the knees, ahead of the feet; the shipped controller's KneelOffset()), getting
  // up as far back; on the lattice the nearest whole number of steps of the heading, metres.
  // Both happen in the open: no tunnel cell under the crawling footprint up to
  // kneel_clear_reach ahead of the standing origin, so the head is down before it comes under a
  // ceiling and up only once clear of it.
  double kneel_offset = 0.178;
  // While it gets down or up, the body stays below h_tunnel more than this far ahead of the
  // standing origin (the shipped controller reaches 0.46 m high up to 0.32 m ahead and falls
  // below 0.30 m by 0.46 m): tunnel cells under the crawling footprint beyond it do not count
  // against getting down or up "in the open", metres along the heading.
  double kneel_clear_reach = 0.46;
  // Getting up only where the FOG has seen the headroom (perception::Fog::headroom_seen) of the
  // standing footprint and of the cells the head reaches: a ceiling seen only at its edge (a
  // table top just above the eyes) may go on over floor cells the map holds as open.
  bool get_up_under_seen_headroom = true;
  // Without it, the standing origin keeps this far from every tunnel cell: a ceiling seen from
  // below ends short of its true edge where the crawling eyes could not look up at it, metres.
  double unseen_headroom_clearance = 0.4;

  // The cycle's views look ahead, so a robot walking backward, side-stepping or crawling
  // backward moves where its eyes have not looked: such a move may not bring an unknown cell
  // (or one beyond the window) under the footprint that it did not cover before. Forward moves
  // may, as the robot looks ahead after each. Cells the standing robot has stood on
  // (Fog::walked) count as known: it came over them.
  bool blind_moves_stay_known = true;
  // Crawling, the eyes are 0.24 m above the floor and tilted up for the ceiling: they do not
  // show whether a block ahead leaves room for the body, so a forward crawl may not bring an
  // unknown cell under the crawling footprint either. Beyond a table the robot gets up to look.
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
  // centre distance d whose top is h above the neighbouring floor, so the robot keeps further
  // from tall obstacles than from low ones when it has room; the upper edge of a drop (a border
  // cell, e.g. the rim of a box whose top the map holds as floor) counts as an obstacle as high
  // as the drop is deep
  double clearance_weight = 1.0;
  double clearance_radius = 0.6;      // metres
  double clearance_height_ref = 0.2;  // metres
  double clearance_height_cap = 0.3;  // metres; walls and unknown heights count as this

  // goal and start
  double goal_tolerance = 0.1;  // a pose whose cell centre is this close to the goal reaches it
  // A goal outside the map window is approached by planning to the cells within exit_band of
  // the window's sides beyond which it lies, each ending the path at exit_factor times its
  // straight-line distance to the goal; PlanToward ends at any reachable state so, and so
  // does Plan where the window shows no way to those cells yet. A plan for a goal outside the
  // window that may end anywhere ends at the wall nearest the goal, and the robot, whose
  // window moves with it, takes turns between that wall and the way round it. The factor is
  // high since the window forgets what it leaves: at 1.5 the robot went back to the edge
  // behind which the goal lay beyond a wall it had just walked along (long_wall).
  double exit_factor = 8.0;
  // About as far as the crawling footprint reaches ahead of its origin (crawl_offset +
  // crawl_length / 2 + margin): a robot may not crawl beyond the window, so where the window's
  // edge cuts a table the way out ends before it; and the outermost cells often lie in a
  // wall's unseen shadow. With the outermost cells alone, table_in_divider ended in
  // no_progress and the doorway world put a forearm on the partition. Metres.
  double exit_band = 0.4;
  // if the start pose itself is not allowed, the search starts from the allowed poses whose
  // cell centre is this close to the start (the robot shuffles free: a side-step standing, a
  // crawl crawling, a turn in place, a crawl move where the posture changes, close to where
  // the change puts the origin: kneel_offset back getting up, forward getting down); metres
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
// allocate them again; a plan on the 100 x 100 course takes about 13 ms (Planning/course).
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

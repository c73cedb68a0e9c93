// The search graph of the planner: states are FOG cells x 16 lattice headings x 2 postures,
// edges are the moves with their costs. Plan() runs A* on it; tests run a plain Dijkstra on the
// same graph to check that A* is optimal.
#ifndef FOGNAV_NAVIGATION_INTERNAL_LATTICE_H_
#define FOGNAV_NAVIGATION_INTERNAL_LATTICE_H_

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "navigation/internal/open_list.h"
#include "navigation/planner.h"
#include "perception/mapping.h"
#include "perception/types.h"

namespace fognav::navigation::internal {

// Cell step of lattice heading k (0..15, counter-clockwise from +x).
struct CellStep {
  int dx = 0, dy = 0;
};
// The 16 cell steps, counter-clockwise from +x.
inline constexpr CellStep kSteps[kNumHeadings] = {
    {1, 0},  {2, 1},   {1, 1},   {1, 2},   {0, 1},  {-1, 2}, {-1, 1}, {-2, 1},
    {-1, 0}, {-2, -1}, {-1, -1}, {-1, -2}, {0, -1}, {1, -2}, {1, -1}, {2, -1}};
CellStep HeadingStep(int heading);
// Yaw of lattice heading k in radians, in (-pi, pi].
double HeadingYaw(int heading);
// Lattice heading nearest to a yaw.
int NearestHeading(double yaw);
// An angle wrapped to (-pi, pi].
double WrapAngle(double a);

// One edge of the graph.
struct Successor {
  int state = 0;
  double cost = 0;    // metres-equivalent
  double length = 0;  // distance moved by the robot's origin, metres
  Move move = Move::kNone;
};
inline constexpr int kMaxSuccessors = 8;

// A state the search starts from, with the cost of shuffling there from the start pose.
struct Seed {
  int state = 0;
  double cost = 0;
  double length = 0;
  Move move = Move::kNone;  // kNone when it is the start pose itself (snapped to the lattice)
};

// Squared Euclidean distance transform on a size_x x size_y grid: out[i] is the squared distance
// in cells from cell i's centre to the nearest cell whose `feature` is set, or kFarSquared when
// there is none.
inline constexpr double kFarSquared = 1e20;
void SquaredDistanceTransform(const std::vector<uint8_t>& feature, int size_x, int size_y,
                              std::vector<double>* out);

// Per-state scratch arrays reused from query to query so that a search neither allocates nor
// clears them: an entry counts only if its stamp carries the generation of its query (a
// lattice's for the validity cache, a search's for the search state).
struct SearchMemory {
  uint32_t generation = 0;  // the latest query's
  // generation << 4 | 1 (valid) or 2 (invalid) | touch << 2 (valid and standing: how the body
  // meets the map, Lattice::kNoTouch, kEdgeTouch or kTouch)
  std::vector<uint32_t> valid_stamp;
  std::vector<uint32_t> search_stamp;  // generation << 1 (reached) | 1 (closed)
  std::vector<double> g;
  std::vector<int32_t> parent;  // a state, or -1 - seed index for seeds
  std::vector<Move> move;
  std::vector<int32_t> heap_position;  // index in the open list while a state is in it
  // Starts a query over num_states states: returns its new generation, arrays grown as needed.
  uint32_t Begin(int num_states);
};

// Where a search may end (Lattice::TerminalCost).
enum class End : uint8_t {
  kGoal,    // in the goal region at no cost; with the goal outside the window, as kExit
  kToward,  // anywhere, at exit_factor times the straight-line distance to the goal
  // within exit_band of the window's sides beyond which the goal lies (it lies outside the
  // window), each cell at exit_factor times its straight-line distance to the goal
  kExit,
  // at the window's edge, where the goal might be reached from beyond the window: each edge
  // cell at exit_factor times its distance to the nearest edge cell of the goal's region (the
  // cells a walk from the goal reaches over floor, stairs, tunnel and unknown cells, never
  // across a border cell or a rise of more than h_stairs), plus that cell's walk from the goal
  kBeyond,
};

// A step up or down from an origin at heading k: the cell offset of its end, its length and
// the part of it across the heading (PlannerParams::max_step_sideways), the cells the standing
// footprint sweeps and the origin cells along its line (the end included).
struct Climb {
  CellStep to;
  double length = 0, across = 0;  // metres
  std::vector<CellStep> swept, line;
};

// The lattice's shapes, which depend only on the robot's sizes in PlannerParams and the cell
// size, not on the map: footprints, the body's and the sweeps' cell offsets, the climbs. Each
// thread builds them once per robot and cell size (Lattice copies them); the members carry
// Lattice's names, whose private base this is.
struct ShapeFrame;  // the robot's extents and the headings' frames, while building
struct LatticeShapes {
  // Builds the shapes for `p`'s sizes on cells of `resolution` metres; aborts on sizes that
  // make no footprint.
  void Build(const PlannerParams& p, double resolution);
  // the parts of Build: footprints (and the soles' level cells), the standing body beyond
  // them, standing and crawling turns' sweeps, the head's disc, blind moves' leads, climbs
  void BuildFootprints(const ShapeFrame& f);
  void BuildBody(const ShapeFrame& f);
  void BuildTurnSweeps(const ShapeFrame& f);
  void BuildCrawlTurnSweeps(const ShapeFrame& f);
  void BuildHead(const ShapeFrame& f);
  void BuildBlindLeads();
  void BuildClimbs(const ShapeFrame& f);

  double step_length_[kNumHeadings] = {};  // metres
  double turn_angle_[kNumHeadings] = {};   // radians from heading k to k+1
  double cos_stairs_error_ = 1.0;          // cos(max_stairs_heading_error)
  int kneel_steps_[kNumHeadings] = {};     // lattice steps a posture change moves along heading k
  std::vector<CellStep> footprint_[2][kNumHeadings];  // cell offsets under each footprint
  // [k][j]: whether footprint_[0][k][j] lies in the standing footprint grown by level_margin
  std::vector<uint8_t> level_cell_[kNumHeadings];
  // standing: offsets under the body rectangle (PlannerParams::body_*) outside footprint_[0]
  std::vector<CellStep> body_extra_[kNumHeadings];
  // [k][j]: whether body_extra_[k][j] (turn_body_[k][j]) lies before or behind the legs, within
  // the stance's width grown by margin, rather than beside them, where only the arms reach
  std::vector<uint8_t> body_extra_legs_[kNumHeadings], turn_body_legs_[kNumHeadings];
  // [k]: offsets the soles' stance grown by level_margin, and the body's shape (legs and arms),
  // sweep in a turn in place between heading k and k + 1 beyond what both ends' checks cover
  std::vector<CellStep> turn_soles_[kNumHeadings], turn_body_[kNumHeadings];
  double turn_soles_radius_cells_ = 0;  // largest distance of an offset in turn_soles_, cells
  // [k]: offsets the crawling footprint (head, hands and knees) sweeps in a turn in place
  // between heading k and k + 1 beyond both ends' footprints
  std::vector<CellStep> turn_crawl_[kNumHeadings];
  double body_outer_radius_cells_ = 0;  // circumscribed radius of the body rectangle, cells
  // largest |offset| component of body_extra_, turn_soles_, turn_body_ and head_disc_
  int body_reach_cells_ = 0;
  std::vector<CellStep> head_disc_;  // offsets within head_reach + margin of the origin
  // [q][k][b]: offsets under the footprint after blind move b (0: backward, 1 and 2: across
  // +/-, by heading k + 4, 3: forward), relative to the new origin, that the footprint before
  // did not cover
  std::vector<CellStep> blind_lead_[2][kNumHeadings][4];
  double inner_radius_cells_[2] = {0, 0};  // inscribed radius of each footprint, cells
  double outer_radius_cells_[2] = {0, 0};  // circumscribed radius, cells
  int outer_reach_cells_[2] = {0, 0};      // largest |offset| component of each footprint
  // [k]: the climbs of heading k, shortest first: every cell offset ahead within
  // max_step_length whose part across the heading is at most max_step_sideways
  std::vector<Climb> climbs_[kNumHeadings];
};

// The shapes for p's sizes and the cell size, built on a thread's first use of them and kept (a
// few robots' worth: the oldest go when more come).
const LatticeShapes& CachedShapes(const PlannerParams& p, double resolution);

class Lattice : private LatticeShapes {
 public:
  // how a standing body meets the map around it (BodyMeets), in increasing order
  static constexpr int kNoTouch = 0, kEdgeTouch = 1, kTouch = 2;

  // Prepares per-cell permissions, costs, footprints and the heuristic for one query, using
  // `memory` (or memory of its own when null) for the per-state arrays, for a search that ends
  // as `end` says (GoalInWindow() is false unless it ends in the goal region). Without
  // `heuristic` the heuristic is 0 everywhere (for walking a given path, which needs none).
  // Aborts if the FOG's arrays do not match its window.
  Lattice(const perception::Fog& fog, const Eigen::Vector2d& goal_G, const PlannerParams& p,
          SearchMemory* memory = nullptr, End end = End::kGoal, bool heuristic = true);
  // Makes the lattice end searches as `end` says instead (terminal costs and heuristic anew),
  // keeping what it knows of the map and of which states are valid.
  void SetEnd(End end);
  SearchMemory& memory() { return *memory_; }

  int NumStates() const { return num_cells_ * 2 * kNumHeadings; }
  int StateIndex(int ix, int iy, int heading, Posture posture) const {
    return ((fog_.window.Index(ix, iy) * 2) + int(posture)) * kNumHeadings + heading;
  }
  int CellOfState(int s) const { return s / (2 * kNumHeadings); }
  int HeadingOfState(int s) const { return s % kNumHeadings; }
  Posture PostureOfState(int s) const { return Posture((s / kNumHeadings) % 2); }
  perception::Pose2 PoseOf(int s) const;
  // Floor height of a cell (unknown cells: the nearest known floor's), NaN if none.
  double FloorHeight(int cell) const {
    const float h = floor_h_[size_t(cell)];
    return std::isfinite(h) ? double(h) : std::numeric_limits<double>::quiet_NaN();
  }

  // Whether the footprint of state s lies on cells that permit its posture (cached).
  bool Valid(int s) { return (StateFlags(s) & 1u) != 0; }
  // Writes the successors of a valid state into out (at most kMaxSuccessors); returns how many.
  int Successors(int s, Successor* out);
  // Cost of ending the path at state s (see End); +infinity where it may not end.
  double TerminalCost(int s) const;
  // Whether the search may end anywhere (kBeyond: false when the goal's region reaches no edge
  // cell of the window, or the goal lies outside it).
  bool HasEnd() const { return has_end_; }
  // Consistent lower bound on the cost from state s to the end of a path (+infinity when the
  // relaxed problem already shows that none exists).
  // Settles the heuristic's Dijkstra as far as state s needs.
  double Heuristic(int s) {
    const size_t node = size_t(s / kNumHeadings);
    while (!h_heap_.empty() && h_stamp_[node] != 2) SettleNext();
    return heuristic_[node];
  }

  bool GoalInWindow() const { return goal_in_window_; }
  // Whether some valid state lies in the goal region (only meaningful with the goal in window).
  bool GoalRegionHasValidState();
  // States to start from: the start pose snapped to the lattice if valid, otherwise the valid
  // states within start_escape_radius. Empty if the start is outside the window or blocked.
  std::vector<Seed> StartSeeds(const perception::Pose2& start_G, Posture posture);

  // Per-cell extra cost per metre (clearance + unknown), for tests.
  double CellCost(int ix, int iy) const { return cell_cost_[size_t(fog_.window.Index(ix, iy))]; }
  bool CrawlAllowedAt(int ix, int iy) const {
    return ok_[1][size_t(fog_.window.Index(ix, iy))] != 0;
  }

 private:
  // The cached flags of state s (see SearchMemory::valid_stamp), computed on first use.
  uint32_t StateFlags(int s);
  // Whether the footprint of `posture` at `cell` and `heading` holds no obstacle or tunnel cell
  // and stands level: standing, the known floor heights under the soles' stance (grown by
  // level_margin) and the origin's span at most h_floor, and those in the ring beyond lie
  // within h_stairs of the origin's; crawling, every cell may be crawled on (ok_) or is a
  // border cell of the crawl zone on the origin's level.
  bool FootprintFits(int cell, int heading, int posture) const;
  // Whether an obstacle or floor cell within head_reach + margin of a standing origin at cell
  // (ix, iy), on floor centre_h, rises more than head_low above it.
  bool HeadMeetsSolid(int cell, int ix, int iy, float centre_h) const;
  // Whether the standing body at (cell, heading) reaches over an obstacle or tunnel cell, or a
  // floor more than h_stairs above the origin's, beyond the soles' footprint (kTouch), or
  // only a hand over the low side of a high top's edge (kEdgeTouch; see BodyMeets).
  int BodyTouches(int cell, int heading) const;
  // body_touch_cost, edge_touch_cost or 0 for kTouch, kEdgeTouch or kNoTouch
  double TouchCost(int touch) const;
  // Whether blind move b (see blind_lead_) to (ix, iy) would bring an unknown cell (or one
  // beyond the window) under the footprint of posture q and heading k.
  bool BlindIntoUnknown(int ix, int iy, int q, int k, int b) const;
  // Whether a cell is unknown and the robot has not stood on it (Fog::walked)
  bool UnseenUnwalked(size_t cell) const {
    return fog_.type[cell] == perception::CellType::kUnknown &&
           (fog_.walked.empty() || !fog_.walked[cell]);
  }
  // Whether cell may lie under a footprint of posture q if level with its origin: a border
  // cell, for crawling only in the crawl zone.
  bool MayBeLevelBorder(size_t cell, int q) const;
  // Whether the FOG has seen the headroom (Fog::headroom_seen) of every cell under the
  // standing footprint at (cell, heading) and within head_reach + margin of it; true if the FOG
  // does not say or get_up_under_seen_headroom is off.
  bool HeadroomSeen(int cell, int heading) const;
  // True if no tunnel cell lies under the crawling footprint at `cell`, `heading` up to
  // kneel_clear_reach ahead of the standing origin (kneel_steps_ behind `cell`).
  bool CrawlFootprintInOpen(int cell, int heading) const;
  // Whether the robot may get down with its crawling origin on cell: within crawl_zone_radius
  // of a tunnel cell. The crawl zone also spans floor of unseen headroom, where a ceiling seen
  // in part may go on, and in a room with nothing above the eyes that is all of its floor.
  bool MayGetDown(int cell) const;
  // Appends the step up or down forward from the valid standing state s, if there is one: the
  // shortest climb of its heading that ends in a valid standing state on a floor more than
  // h_floor and at most h_stairs higher or lower.
  void AddStairsMove(int s, Successor* out, int* n);
  // Whether the cells the standing footprint sweeps in climb c from `cell` are neither
  // obstacle nor tunnel and have floor heights within [lo, hi].
  bool SweepClear(int cell, const Climb& c, double lo, double hi) const;
  // Whether the floor's height gradient along the line of origin cells of climb c lies within
  // max_stairs_heading_error of `heading` (up or down); true where there is no gradient.
  bool FacesStep(int cell, int heading, const Climb& c) const;
  // Whether the known floor heights (not unknown or obstacle, finite) in the square of
  // level_lo_ / level_hi_ around `cell`, and the cell's own, span at most h_floor.
  bool LevelAround(int cell) const;
  // Whether the standing body at `cell`, as the offsets `offsets` (body_extra_, turn_body_),
  // meets an obstacle or tunnel cell or a floor more than h_stairs above the cell's, or an
  // unknown cell beside a top (hidden_top_) higher than the part of the body there reaches
  // down to: h_stairs where `legs` (parallel to `offsets`) is set, hand_low elsewhere; or,
  // where `legs` is not set, a border cell beside a top more than hand_low high (kEdgeTouch:
  // the map may have ended the top a cell short). Returns kTouch, kEdgeTouch or kNoTouch.
  int BodyMeets(int cell, const std::vector<CellStep>& offsets,
                const std::vector<uint8_t>& legs) const;
  // Whether a footprint may hold cell i with the floor under its origin at centre_h: not an
  // obstacle or tunnel cell, and a known floor within `tolerance` of centre_h (a border cell
  // only so; unknown cells and cells without heights to compare are allowed).
  bool OnLevel(size_t i, float centre_h, double tolerance) const;
  // For a standing turn in place at `cell` between heading k and k + 1: false if the soles
  // sweep an obstacle or tunnel cell, or if the known floors under the soles at both ends and
  // in between (the origin's among them) span more than h_floor (a corner would catch on a
  // riser); raises *touch to what the body sweeps, as BodyMeets.
  bool TurnSweepClear(int cell, int k, int* touch) const;
  // For a crawling turn in place at `cell` between heading k and k + 1: whether every cell the
  // crawling footprint sweeps beyond both ends' may lie under it (as FootprintFits crawling).
  bool CrawlTurnClear(int cell, int k) const;
  bool InGoalRegion(int cell) const;
  void ComputeFloorHeights();
  void ComputeLevelRanges();
  void ComputePermissions();
  void ComputeCellCosts();
  void ComputeTerminalCosts();
  // End::kBeyond: from the goal region's terminal costs to those of the window's edge
  void ComputeBeyondTerminalCosts();
  void ComputeHeuristic();
  // The heuristic's Dijkstra: lowers a node's tentative value; settles the next node.
  void Relax(int node, double h);
  void SettleNext();
  // Floor height change from one cell to another (0 if either has no floor height).
  double HeightStep(int from_cell, int to_cell) const;
  // Central-difference floor height gradient at a cell (metres per cell), over the neighbours
  // that have a floor height; zero where it cannot be formed.
  Eigen::Vector2d FloorGradient(int cell) const;

  const perception::Fog& fog_;
  PlannerParams p_;
  Eigen::Vector2d goal_G_;
  End end_ = End::kGoal;
  bool goal_in_window_ = false;
  bool has_end_ = false;
  int num_cells_ = 0;

  // per cell: floor height, unknown cells filled from the nearest walkable cell (else border)
  std::vector<float> floor_h_;
  // per cell: lowest and highest known floor height (cells neither unknown nor obstacle, with a
  // finite FOG height) in the square around it that holds the standing footprint and body;
  // +inf / -inf if none
  std::vector<float> level_lo_, level_hi_;
  // per unknown or border cell: the highest height of a floor, stairs or border cell within
  // hidden_reach, -inf if none (BodyMeets: the unseen side of a solid, or the low side of an
  // edge the map may have placed a cell short); per cell: the highest hidden_top_ in
  // the square around it that level_lo_ and level_hi_ cover
  std::vector<float> hidden_top_, hidden_hi_;
  std::vector<uint8_t> ok_[2];          // per cell: the posture may have this cell under it
  // per cell: HeadMeetsSolid for a standing origin there, 0 not yet known, 1 no, 2 yes
  mutable std::vector<uint8_t> head_meets_;
  // per cell: squared distance (cells) to a cell that blocks the posture, and to one that may
  // (border cells block a standing robot only off its own level)
  std::vector<double> blocked_d2_[2];
  std::vector<double> maybe_blocked_d2_[2];
  std::vector<double> tunnel_d2_;  // squared distance to the nearest tunnel cell, cells^2
  std::vector<double> unknown_d2_;  // squared distance to the nearest UnseenUnwalked cell
  // squared distance to the nearest tunnel cell or floor cell of unseen headroom, cells^2
  std::vector<double> zone_d2_;
  double zone_d2_max_ = 0;  // crawl_zone_radius squared, cells^2 (plus kEps)
  // [k]: footprint_[0][k] as offsets of the cell index in this map's window
  std::vector<int> footprint_index_[kNumHeadings];
  std::vector<double> cell_cost_;          // per cell: clearance + unknown cost per metre
  std::vector<double> terminal_;           // per cell: TerminalCost
  std::vector<double> heuristic_;          // per cell and posture (cell * 2 + posture)
  // the heuristic's Dijkstra, per node (cell * 2 + posture): open in the relaxed graph, stamp
  // (1 queued, 2 settled: heuristic_ is final), place in h_heap_; the climbs across a heading
  std::vector<uint8_t> h_open_, h_stamp_;
  std::vector<int32_t> h_position_;
  std::vector<OpenEntry> h_heap_;
  std::vector<std::pair<CellStep, double>> h_aside_;  // offset, length in metres
  SearchMemory own_memory_;
  SearchMemory* memory_ = nullptr;
  uint32_t valid_generation_ = 0;  // the generation of this lattice's valid_stamp entries
  bool heuristic_on_ = true;       // the constructor's `heuristic`
};

}  // namespace fognav::navigation::internal

#endif  // FOGNAV_NAVIGATION_INTERNAL_LATTICE_H_

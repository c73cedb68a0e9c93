// Every tunable of a run (stereo, segmentation, maps, localization, planner, the mission's
// behaviour) in one value, and one table that names each by `section.key` with its type, range
// and meaning: scenario files (`params:`), `--set`, report.json and `fognav params` all read it.
#ifndef FOGNAV_SCENARIOS_PARAMS_H_
#define FOGNAV_SCENARIOS_PARAMS_H_

#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "navigation/planner.h"
#include "perception/localization.h"
#include "perception/visual_odometry.h"
#include "perception/mapping.h"
#include "perception/segmentation.h"
#include "perception/step_edge.h"

namespace fognav::scenarios {

// The maps of the loop: the paper's, but a cell counts as hit in a frame only if two points end
// in it, so stray stereo matches make no obstacles, and a ray from less than half the range at
// which a column's obstacle evidence was seen sets its cells free, so far phantoms do not stay.
inline perception::MapParams MapDefaults() {
  perception::MapParams p;
  p.grid.min_hits_per_frame = 2;
  p.grid.overrule_ratio = 2.0;
  return p;
}

// The perception cycle: stereo, segmentation, labelled points, maps and localization. Why the
// defaults differ from the paper's where they do: docs/params.md.
struct PerceptionParams {
  perception::StereoParams stereo;
  perception::SegmentParams segment = perception::RayNoiseParams();            // stereo depth
  perception::SegmentParams segment_ideal = perception::PreciseRangeParams();  // ideal depth
  bool subsample = false;  // segment a 2x sub-sampled image (88x72 from 176x144) as on QRIO
  perception::LabelParams label;
  double rim_keep_height = 0.40;  // column-rim points this high above the robot's floor count
  perception::MapParams map = MapDefaults();
  perception::LocalizationParams localization;
  perception::VisualOdometryParams visual_odometry;
  int view_every_steps = 2;  // with noisy odometry, a view every this many footsteps walked; 0 = none
};

// The mission's behaviour: how far a motion command goes before the robot re-plans, and when it
// looks, explores, inspects, peeks and gives up. Why each value is what it is: docs/params.md.
struct ExecutionLimits {
  double walk = 0.16;            // longest walk per motion command, metres (about two strides)
  double sidestep = 0.10;        // longest side-step per motion command, metres
  double crawl = 0.12;           // longest crawl per motion command, metres
  double min_approach = 0.1;     // without a way, approach the goal only if that gains this, metres
  double fresh_look_keep = 0.5;  // share of the grid's log-odds kept before the fresh look
  double fresh_look_distance = 0.5;  // no second fresh look within this of the last, metres
  double explore_beyond = 1.0;       // an exploration goes this far past the window's edge, metres
  int max_explorations = 4;          // explorations (edge, inspect, peek) per mission
  int explore_patience = 5;          // cycles an exploration may go without a way showing
  double inspect_range = 1.5;       // obstacle evidence seen only from farther is inspected, metres
  double inspect_near_range = 1.0;  // the same, second round, metres
  double inspect_reach = 0.25;      // an inspection goes to within this of its pose, metres
  double peek_reach = 0.05;         // a peek goes to within this of its pose, metres
  double peek_lead = 0.5;      // a peek looks at the floor this far beyond the blind move, metres
  // with nothing else left, back off this far from the goal's side to look again, metres (0: never)
  double back_off = 0.6;
  int thrash_cycles = 20;      // cycles within thrash_radius that count as going back and forth
  double thrash_radius = 0.6;  // metres
  int circling_arrivals = 5;   // arrivals at one pose among thrash_cycles that call for a look
  double lost_yaw = 2.0 * M_PI / 180;  // crawling with more yaw sigma looks to both sides, rad
  double side_look_pan = 0.8;          // pan of the side looks, rad
  double high_ceiling = 0.46;          // a ceiling this high the standing eyes barely see, metres
  double high_ceiling_range = 1.0;     // such a ceiling within this counts as near, metres
  double underside_elevation = 0.15;   // look this far above the horizon before crawling, rad
  double look_ahead = 0.5;             // the looks aim at the plan's pose this far on, metres
  bool level_views = true;             // near a high ceiling every other view looks level
  double keep_plan_margin = 0.25;      // keep a plan costing at most this more than a new one
  double keep_plan_share = 0.05;       // ... or this share of the new plan's cost, if more
  double edge_lookahead = 0.8;         // step edges on the plan within this are measured, metres
  double edge_min_range = 0.2;         // not nearer than this (the body hides them), metres
  double edge_look_range = 0.45;       // a look of its own at a step edge within this, metres
  double heel_margin = 0.02;           // a step lands the heel this far past the edge, metres
  double toe_margin = 0.01;            // a walk up to a riser stops the toes this short, metres
  double edge_correction = 0.04;       // largest correction of a step from the plan's cells, metres
};

// All tunables of a run. Default-constructed: the defaults every run starts from.
struct RunParams {
  PerceptionParams perception;
  navigation::PlannerParams planner;
  ExecutionLimits mission;
  perception::StepEdgeParams step_edge;
};

enum class ParamType { kDouble, kInt, kBool, kChoice };

// One row of the table: a parameter's name, type, range, meaning and where it lives. Values
// pass as double (exact for the ints and bools here).
struct ParamInfo {
  std::string name;  // "section.key"
  ParamType type = ParamType::kDouble;
  double min = 0, max = 0;  // the sane range, inclusive; +inf allowed where max is +inf
  std::string meaning;      // one line
  std::vector<std::string> choices;  // kChoice: the names of the values 0, 1, ...
  std::function<double(const RunParams&)> get;
  std::function<void(RunParams*, double)> set;
  // extra rule beyond the range ("" if the value passes): multiple of 16, odd, ...
  std::function<std::string(double)> rule;
};

// The table, in section order. Each parameter appears once.
const std::vector<ParamInfo>& ParamTable();

// The row named `name`, or nullptr.
const ParamInfo* FindParam(const std::string& name);

// The section names, in table order ("stereo", "segmentation", ...).
std::vector<std::string> ParamSections();

// Parameter values by dotted name, as a scenario or --set gives them (already checked).
using ParamOverrides = std::map<std::string, double>;

// Parses `text` as a value of `info`: "" and *value set, or what is wrong ("expected an
// integer, got '1.5'", "expected a number from 0 to 10, got 20").
std::string ParseParamValue(const ParamInfo& info, const std::string& text, double* value);

// Applies one `--set section.key=value`. Throws InputError naming the flag, the key and what is
// wrong.
void ApplySetFlag(const std::string& assignment, ParamOverrides* overrides);

// Applies one parameter given by name and value text, as from the Python module's `params`
// dict. Throws InputError "SOURCE: NAME: what is wrong", as ApplySetFlag does.
void ApplyParam(const std::string& name, const std::string& value_text, const std::string& source,
                ParamOverrides* overrides);

// The defaults with `overrides` applied.
RunParams ResolveParams(const ParamOverrides& overrides);

// The parameters of `params` that differ from the defaults, in table order, as (name, value).
std::vector<std::pair<std::string, double>> ChangedParams(const RunParams& params);

// ChangedParams as report.json and perception.json hold them under "params": numbers, integers
// and bools; an infinite value as the string "inf".
nlohmann::json ParamsJson(const RunParams& params);

// A value as the table's type writes it: "1.4", "3", "true", "inf".
std::string FormatParamValue(const ParamInfo& info, double value);

// `fognav params`: one line per parameter: name, type, default, range, meaning.
void PrintParamTable(std::ostream& out);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_PARAMS_H_

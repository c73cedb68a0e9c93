// Scenario files (YAML, format in DESIGN.md): loading, validation and the exact world geometry
// they describe. Inside the program all angles are radians; degrees exist only in the files.
#ifndef FOGNAV_SCENARIOS_SCENARIO_H_
#define FOGNAV_SCENARIOS_SCENARIO_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "perception/types.h"

namespace fognav::scenarios {

// Bad user input: an unreadable or invalid scenario. The message names the file, the line and
// the key ("course.yaml:12: world.objects[2].box.size: expected 3 positive numbers").
// The program maps it to exit code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A solid box; `center` is the footprint centre (x, y), `size` the full extent (x, y, z) along
// its own axes, `yaw` the rotation about world z (rad) and `z` the height of its base.
struct BoxObject {
  std::string name;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  double yaw = 0;
  double z = 0;
};

// Consecutive treads along the stairs' +x, each a box from the floor to its height. `start` is
// the middle of the first tread's front edge; the treads are `width` wide across.
struct StairsObject {
  struct Step {
    double depth = 0;   // along the stairs' +x, metres
    double height = 0;  // top above the floor, metres
  };
  std::string name;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  double yaw = 0;
  double width = 0;
  std::vector<Step> steps;
};

// A top of thickness `top` whose upper surface is at `height` (underside at height - top), on
// four square legs of side `leg` at the corners of its `size` (x, y) footprint.
struct TableObject {
  std::string name;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  Eigen::Vector2d size = Eigen::Vector2d::Zero();
  double height = 0;
  double top = 0;
  double leg = 0;
  double yaw = 0;
};

using WorldObject = std::variant<BoxObject, StairsObject, TableObject>;

enum class DepthMode { kStereo, kIdeal };

struct SensorSettings {
  int width_px = 176;
  int height_px = 144;
  double hfov = 0.785398163397448;  // horizontal field of view, rad (45 deg)
  double baseline = 0.05;           // metres
  DepthMode depth = DepthMode::kStereo;
  // Samples per pixel side of the stereo images: 1 renders each pixel at its centre, k > 1
  // gathers its area from k x k points (sim::RenderRequest::pixel_samples), as a camera's
  // pixel does. Point samples alias texture finer than a pixel differently in each eye.
  int pixel_samples = 1;
};

constexpr int kMaxPixelSamples = 4;

// What a mission is expected to show; unset fields are not checked.
struct Expectations {
  std::optional<bool> reach_goal;
  std::vector<std::string> actions_used;
  std::optional<bool> no_collision;
  std::optional<std::string> failure;  // the failure the mission is meant to end with
};

struct Scenario {
  std::string source;  // the file it was read from, for messages
  std::string name;
  std::string description;
  uint64_t seed = 0;
  perception::Pose2 start;  // world frame
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  double goal_tolerance = 0.2;
  Eigen::Vector2d floor_size = Eigen::Vector2d::Zero();
  Eigen::Vector2d floor_center = Eigen::Vector2d::Zero();
  std::vector<WorldObject> objects;
  SensorSettings sensor;
  double odometry_noise_xy = 0;   // std-dev per step, metres
  double odometry_noise_yaw = 0;  // std-dev per step, rad
  // systematic, drawn once per mission: std-dev of the stride scale error (a fraction) and of
  // the yaw added every step (rad)
  double odometry_stride_scale = 0;
  double odometry_yaw_bias = 0;
  int max_cycles = 600;
  int max_steps = 2000;
  Expectations expect;
  // values of the `params:` key by dotted name ("planner.sidestep_factor"), checked against
  // the table of scenarios/params.h; `--set` adds to them
  std::map<std::string, double> params;
};

// Action names a scenario may list in expect.actions_used.
const std::vector<std::string>& ActionNames();
// Failure names a scenario may give in expect.failure.
const std::vector<std::string>& FailureNames();

// The largest scenario file, bytes (1 MB); the shipped ones are under 2 kB.
constexpr size_t kMaxScenarioBytes = size_t(1) << 20;

// Reads and validates a scenario file. Throws InputError naming file, line and key; a folder
// or a file larger than kMaxScenarioBytes is an InputError too.
Scenario LoadScenario(const std::string& path);

// Parses and validates scenario text (at most kMaxScenarioBytes); `source` names it in
// messages.
Scenario ParseScenario(const std::string& yaml_text, const std::string& source);

// A named solid of the world in the world frame; every object is made of these (a table is
// its top and four legs, stairs one box per tread). The floor is not included.
struct Solid {
  std::string name;  // object name, with a suffix for parts ("desk/leg2", "steps/tread1")
  perception::OrientedBox box;  // X_FB is the box pose in the world frame
};

// The exact geometry of the scenario's objects.
std::vector<Solid> WorldSolids(const Scenario& scenario);

// Whether the world point p_W (x, y) lies over the world's floor (its edges included).
bool OverFloor(const Scenario& scenario, const Eigen::Vector2d& p_W);

// One line describing the scenario ("stairs_and_table: 14 objects, goal 4.4 m away, ...").
std::string Summary(const Scenario& scenario);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_SCENARIO_H_

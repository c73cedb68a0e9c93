#include "scenarios/scenario.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

namespace fognav::scenarios {
namespace {

// a valid scenario; each test changes one line
const char* kValid = R"(name: unit
robot:
  start: [0.0, 0.0, 90.0]
goal:
  position: [3.0, 0.0]
world:
  floor: [6.0, 2.0]
  floor_center: [2.0, 0.0]
  objects:
    - box: {name: block, center: [1.0, 0.5], size: [0.2, 0.2, 0.08]}
    - stairs: {name: steps, start: [1.5, 0.0], width: 1.0, steps: [[0.25, 0.03], [0.3, 0.06]]}
    - table: {name: desk, center: [2.5, 0.0], size: [0.6, 1.0], height: 0.56}
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// the message of the InputError that parsing `text` throws, or "" if none
std::string ErrorOf(const std::string& text) {
  try {
    ParseScenario(text, "course.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Scenario, ParsesAValidFileWithDefaultsAndRadians) {
  Scenario s = ParseScenario(kValid, "course.yaml");
  EXPECT_EQ(s.name, "unit");
  EXPECT_NEAR(s.start.yaw, M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(s.goal_tolerance, 0.2);
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.sensor.width_px, 176);
  EXPECT_NEAR(s.sensor.hfov, M_PI / 4, 1e-12);
  EXPECT_EQ(s.sensor.depth, DepthMode::kStereo);
  EXPECT_EQ(s.sensor.pixel_samples, 1);
  const Scenario sampled =
      ParseScenario(Replace(kValid, "name: unit", "name: unit\nsensor: {pixel_samples: 3}"), "course.yaml");
  EXPECT_EQ(sampled.sensor.pixel_samples, 3);
  EXPECT_NE(Summary(sampled).find("sensor 176x144 stereo, 3x3 samples per pixel"), std::string::npos);
  EXPECT_EQ(Summary(s).find("samples"), std::string::npos);
  EXPECT_EQ(s.max_cycles, 600);
  ASSERT_EQ(s.objects.size(), 3u);
  const auto& table = std::get<TableObject>(s.objects[2]);
  EXPECT_DOUBLE_EQ(table.top, 0.03);
  EXPECT_DOUBLE_EQ(table.leg, 0.04);
  EXPECT_EQ(s.odometry_stride_scale, 0.0);
  EXPECT_EQ(s.odometry_yaw_bias, 0.0);
  const Scenario noisy = ParseScenario(
      Replace(kValid, "name: unit",
              "name: unit\nodometry_noise: {xy: 0.005, stride_scale: 0.03, yaw_bias_deg: 0.2}"),
      "course.yaml");
  EXPECT_DOUBLE_EQ(noisy.odometry_stride_scale, 0.03);
  EXPECT_NEAR(noisy.odometry_yaw_bias, 0.2 * M_PI / 180, 1e-12);
}

TEST(Scenario, WorldHoldsExactlyTheListedSolids) {
  Scenario s = ParseScenario(kValid, "course.yaml");
  std::vector<Solid> solids = WorldSolids(s);
  // one box, two treads, a table top and four legs
  ASSERT_EQ(solids.size(), 8u);
  EXPECT_EQ(solids[0].name, "block");
  EXPECT_TRUE(solids[0].box.X_FB.translation().isApprox(Eigen::Vector3d(1.0, 0.5, 0.04)));
  EXPECT_TRUE(solids[0].box.half_size.isApprox(Eigen::Vector3d(0.1, 0.1, 0.04)));
  // treads from the floor to their heights, consecutive along +x from the start
  EXPECT_EQ(solids[2].name, "steps/tread2");
  EXPECT_TRUE(solids[1].box.X_FB.translation().isApprox(Eigen::Vector3d(1.625, 0, 0.015)));
  EXPECT_TRUE(solids[2].box.X_FB.translation().isApprox(Eigen::Vector3d(1.9, 0, 0.03)));
  // table top: upper surface at the height, underside at height - top
  EXPECT_EQ(solids[3].name, "desk/top");
  EXPECT_NEAR(solids[3].box.X_FB.translation().z() + solids[3].box.half_size.z(), 0.56, 1e-12);
  EXPECT_NEAR(solids[3].box.X_FB.translation().z() - solids[3].box.half_size.z(), 0.53, 1e-12);
  // legs inside the corners, from the floor to the underside
  EXPECT_NEAR(solids[4].box.X_FB.translation().x(), 2.5 - 0.3 + 0.02, 1e-12);
  EXPECT_NEAR(solids[4].box.X_FB.translation().y(), -0.5 + 0.02, 1e-12);
  EXPECT_NEAR(2 * solids[4].box.half_size.z(), 0.53, 1e-12);
}

struct BadInput {
  std::string from, to;  // the change to kValid
  std::string expected;  // a part of the message: file:line: key: what
};

void PrintTo(const BadInput& bad, std::ostream* out) { *out << "'" << bad.expected << "'"; }

class ScenarioErrors : public ::testing::TestWithParam<BadInput> {};

TEST_P(ScenarioErrors, NameFileLineAndKey) {
  const BadInput& bad = GetParam();
  std::string message = ErrorOf(Replace(kValid, bad.from, bad.to));
  EXPECT_NE(message.find(bad.expected), std::string::npos)
      << "message: '" << message << "'\nexpected to contain: '" << bad.expected << "'";
}

INSTANTIATE_TEST_SUITE_P(
    AllKinds, ScenarioErrors,
    ::testing::Values(
        // unknown keys, at any depth
        BadInput{"name: unit", "name: unit\ncolour: red", "course.yaml:2: colour: unknown key"},
        BadInput{"floor: [6.0, 2.0]", "floor: [6.0, 2.0]\n  gravity: 9.8",
                 "course.yaml:8: world.gravity: unknown key"},
        BadInput{"height: 0.56}", "height: 0.56, colour: red}",
                 "course.yaml:12: world.objects[2].table.colour: unknown key"},
        // wrong types
        BadInput{"position: [3.0, 0.0]", "position: [3.0, east]",
                 "course.yaml:5: goal.position[1]: expected a number, got 'east'"},
        BadInput{"start: [0.0, 0.0, 90.0]", "start: [0.0, 0.0]",
                 "course.yaml:3: robot.start: expected a list of 3 numbers"},
        BadInput{"name: unit", "name: Unit Course", "course.yaml:1: name: expected lower-case"},
        BadInput{"name: unit", "name: unit\nodometry_noise: {stride_scale: -0.03}",
                 "course.yaml:2: odometry_noise.stride_scale:"},
        BadInput{"name: unit", "name: unit\nodometry_noise: {yaw_bias: 0.2}",
                 "course.yaml:2: odometry_noise.yaw_bias: unknown key"},
        // missing required keys
        BadInput{"goal:\n  position: [3.0, 0.0]\n", "",
                 "course.yaml:1: goal: missing required key"},
        BadInput{"{name: block, center: [1.0, 0.5], ", "{center: [1.0, 0.5], ",
                 "course.yaml:10: world.objects[0].box.name: missing required key"},
        // impossible values
        BadInput{"size: [0.2, 0.2, 0.08]", "size: [0.2, -0.2, 0.08]",
                 "course.yaml:10: world.objects[0].box.size: expected 3 positive sizes"},
        BadInput{"size: [0.2, 0.2, 0.08]", "size: [0.2, 0.0, 0.08]",
                 "course.yaml:10: world.objects[0].box.size: expected 3 positive sizes"},
        BadInput{"[0.3, 0.06]", "[0.3, -0.06]",
                 "course.yaml:11: world.objects[1].stairs.steps[1]: expected a positive depth"},
        BadInput{"floor: [6.0, 2.0]", "floor: [6.0, 0.0]",
                 "course.yaml:7: world.floor: expected 2 positive sizes"},
        // sizes and places the maps cannot hold (a 1e9 m floor aborted the ground-truth plan)
        BadInput{"floor: [6.0, 2.0]", "floor: [6.0, 31.0]",
                 "course.yaml:7: world.floor: expected sides of at most 30 m"},
        BadInput{"floor_center: [2.0, 0.0]", "floor_center: [2.0, 1e9]",
                 "course.yaml:8: world.floor_center[1]: expected a number within +-1000, got 1e9"},
        // a camera image larger than the offscreen buffer it is rendered in (exit code 3 from
        // the renderer before, at the first view)
        BadInput{"name: unit", "name: unit\nsensor: {width: 1281}",
                 "course.yaml:2: sensor: images up to 1280x1024 pixels are supported, got "
                 "1281x144"},
        // pixel samples: at least one, at most four per side, and within the buffer
        BadInput{"name: unit", "name: unit\nsensor: {pixel_samples: 0}",
                 "course.yaml:2: sensor.pixel_samples: expected an integer from 1 to 1e9"},
        BadInput{"name: unit", "name: unit\nsensor: {pixel_samples: 5}",
                 "course.yaml:2: sensor.pixel_samples: expected 1 to 4 samples per pixel side, got 5"},
        BadInput{"name: unit", "name: unit\nsensor: {width: 640, height: 480, pixel_samples: 3}",
                 "course.yaml:2: sensor.pixel_samples: 3 samples per pixel side of a 640x480 image "
                 "render 1920x1440 pixels; at most 1280x1024 are supported"},
        // goal and start off the floor
        BadInput{"position: [3.0, 0.0]", "position: [9.0, 0.0]",
                 "course.yaml:5: goal.position: the goal is off the floor"},
        BadInput{"start: [0.0, 0.0, 90.0]", "start: [-2.0, 0.0, 90.0]",
                 "course.yaml:3: robot.start: the start is off the floor"},
        // the start overlapping an object
        BadInput{"center: [1.0, 0.5]", "center: [0.05, 0.05]",
                 "course.yaml:10: world.objects[0]: object 'block' overlaps the robot's start"},
        // a duplicate object name
        BadInput{"name: steps", "name: block",
                 "course.yaml:11: world.objects[1]: duplicate object name 'block'"},
        // an object entry with two kinds
        BadInput{"- box: {name: block, center: [1.0, 0.5], size: [0.2, 0.2, 0.08]}",
                 "- box: {name: block, center: [1.0, 0.5], size: [0.2, 0.2, 0.08]}\n      table: {}",
                 "course.yaml:10: world.objects[0]: expected exactly one of the keys box, stairs, table"},
        // bad enumerations
        BadInput{"name: unit", "name: unit\nsensor: {depth: lidar}",
                 "course.yaml:2: sensor.depth: expected stereo or ideal, got 'lidar'"},
        BadInput{"name: unit", "name: unit\nexpect: {actions_used: [walk, fly]}",
                 "course.yaml:2: expect.actions_used[1]: unknown action 'fly'"},
        BadInput{"name: unit", "name: unit\nexpect: {failure: fell}",
                 "course.yaml:2: expect.failure: unknown failure 'fell' (expected no_path, "
                 "collision, off_floor or timeout)"},
        // a failure no mission ends with (a scenario that expected it could never pass)
        BadInput{"name: unit", "name: unit\nexpect: {failure: goal_not_reached}",
                 "course.yaml:2: expect.failure: unknown failure 'goal_not_reached'"},
        BadInput{"name: unit", "name: unit\nlimits: {max_cycles: 0}",
                 "course.yaml:2: limits.max_cycles: expected an integer from 1"},
        // not YAML at all
        BadInput{"name: unit", "name: [unit", "course.yaml:"},
        // a list or a mapping as a key, at the top level or inside an object (yaml-cpp's
        // conversion error escaped before, exit code 3)
        BadInput{"name: unit", "[a, b]: 1\nname: unit",
                 "course.yaml:1: expected a plain name as a key, got a list"},
        BadInput{"floor: [6.0, 2.0]", "floor: [6.0, 2.0]\n  ? {x: 1}\n  : 1",
                 "course.yaml:8: world: expected a plain name as a key, got a mapping"},
        BadInput{"height: 0.56}", "height: 0.56, [leg]: 0.1}",
                 "course.yaml:12: world.objects[2].table: expected a plain name as a key, got a "
                 "list"}));

// A document that is not a mapping is named with its line and what it is instead
TEST(Scenario, TopLevelThatIsNotAMappingNamesItsLine) {
  EXPECT_EQ(ErrorOf("- name: unit\n- robot: {}\n"),
            "course.yaml:1: expected a mapping (name, robot, goal, world) at the top level, got a "
            "list");
  EXPECT_EQ(ErrorOf("# a number\n\n42\n"),
            "course.yaml:3: expected a mapping (name, robot, goal, world) at the top level, got "
            "'42'");
  EXPECT_EQ(ErrorOf(""),
            "course.yaml:1: expected a mapping (name, robot, goal, world) at the top level, got an "
            "empty document");
}

TEST(Scenario, FolderIsNamedAsAFolder) {
  try {
    LoadScenario("scenarios");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scenarios: is a folder, expected a scenario file");
  }
}

// kMaxScenarioBytes is read and no more: an endless file stops there (/dev/zero grew to 2.1 GB
// and ended in std::bad_alloc before)
TEST(Scenario, SizeIsBoundedToOneMegabyte) {
  const std::string too_large = "course.yaml: the scenario is larger than 1 MB (1048576 bytes)";
  std::string padded = kValid;
  padded += "#" + std::string(kMaxScenarioBytes - padded.size() - 2, 'x') + "\n";
  ASSERT_EQ(padded.size(), kMaxScenarioBytes);
  EXPECT_EQ(ParseScenario(padded, "course.yaml").name, "unit");
  EXPECT_EQ(ErrorOf(padded + "\n").find(too_large), 0u) << ErrorOf(padded + "\n");
  try {
    LoadScenario("/dev/zero");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("/dev/zero: the scenario is larger than 1 MB"), 0u)
        << e.what();
  }
}

// where the robot may stand: over the floor rectangle, edges included (floor 6 x 2 at (2, 0))
TEST(Scenario, OverFloorIsTheFloorRectangle) {
  const Scenario s = ParseScenario(kValid, "course.yaml");
  EXPECT_TRUE(OverFloor(s, {2.0, 0.0}));
  EXPECT_TRUE(OverFloor(s, {-1.0, 1.0}));
  EXPECT_TRUE(OverFloor(s, {4.99, -0.99}));
  EXPECT_FALSE(OverFloor(s, {-1.01, 0.0}));
  EXPECT_FALSE(OverFloor(s, {5.01, 0.0}));
  EXPECT_FALSE(OverFloor(s, {2.0, 1.01}));
  EXPECT_FALSE(OverFloor(s, {2.0, -1.01}));
  EXPECT_EQ(ParseScenario(Replace(kValid, "name: unit", "name: unit\nexpect: {failure: off_floor}"),
                          "course.yaml")
                .expect.failure,
            "off_floor");
}

TEST(Scenario, UnreadableFileNamesThePath) {
  try {
    LoadScenario("/nonexistent/course.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/course.yaml: cannot read"), std::string::npos);
  }
}

TEST(Scenario, ShippedScenariosAreValid) {
  for (const char* path : {"scenarios/stairs_and_table.yaml"}) {
    EXPECT_NO_THROW(LoadScenario(path)) << path;
  }
}

}  // namespace
}  // namespace fognav::scenarios

#include "scenarios/scenario.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "scenarios/params.h"
#include "sim/world.h"

namespace fognav::scenarios {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
// the robot's footprint radius at its start pose, for the start-overlap check
constexpr double kStartClearance = 0.15;
// the largest magnitude of any number in a scenario
constexpr double kMaxMagnitude = 1000.0;
// the longest side of the floor, metres: the ground-truth plan maps the whole floor in 4 cm
// cells (30 m: 0.8 GB, 5 s)
constexpr double kMaxFloorSide = 30.0;

// An image size as messages name it, "176x144".
std::string Dims(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// Typed access to a YAML document that reports every problem as file:line: key: message.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  // throws InputError "source:line: key: what" (no key at the top level)
  [[noreturn]] void Fail(const YAML::Node& at, const std::string& key,
                         const std::string& what) const {
    std::ostringstream message;
    message << source_;
    if (at.IsDefined() && at.Mark().line >= 0) message << ":" << at.Mark().line + 1;
    message << ": " << (key.empty() ? "" : key + ": ") << what;
    throw InputError(message.str());
  }

  // checks that `node` is a mapping whose keys are all in `allowed` and holds every `required`
  void Map(const YAML::Node& node, const std::string& key, const std::set<std::string>& allowed,
           const std::set<std::string>& required = {}) const {
    if (!node.IsMap()) Fail(node, key, "expected a mapping");
    for (const auto& entry : node) {
      // a list or a mapping used as a key names nothing the format knows
      if (!entry.first.IsScalar()) {
        Fail(entry.first, key, "expected a plain name as a key, got " + Kind(entry.first));
      }
      std::string name = entry.first.Scalar();
      if (!allowed.count(name)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        Fail(entry.first, Join(key, name), "unknown key (expected one of: " + list + ")");
      }
    }
    for (const auto& name : required) {
      if (!node[name]) Fail(node, Join(key, name), "missing required key");
    }
  }

  double Number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(node, key, "expected a number");
    double value = 0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      Fail(node, key, "expected a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) Fail(node, key, "expected a finite number");
    // metres and degrees alike: far larger values only overflow the maps' cell indices
    if (std::abs(value) > kMaxMagnitude) {
      Fail(node, key, "expected a number within +-1000, got " + node.Scalar());
    }
    return value;
  }

  double Positive(const YAML::Node& node, const std::string& key) const {
    double value = Number(node, key);
    if (value <= 0) Fail(node, key, "expected a positive number, got " + node.Scalar());
    return value;
  }

  double NonNegative(const YAML::Node& node, const std::string& key) const {
    double value = Number(node, key);
    if (value < 0) Fail(node, key, "expected a number >= 0, got " + node.Scalar());
    return value;
  }

  int Integer(const YAML::Node& node, const std::string& key, int min_value) const {
    if (!node.IsScalar()) Fail(node, key, "expected an integer");
    long long value = 0;
    try {
      value = node.as<long long>();
    } catch (const YAML::Exception&) {
      Fail(node, key, "expected an integer, got '" + node.Scalar() + "'");
    }
    if (value < min_value || value > 1000000000) {
      Fail(node, key, "expected an integer from " + std::to_string(min_value) + " to 1e9");
    }
    return int(value);
  }

  bool Bool(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(node, key, "expected true or false");
    try {
      return node.as<bool>();
    } catch (const YAML::Exception&) {
      Fail(node, key, "expected true or false, got '" + node.Scalar() + "'");
    }
  }

  std::string String(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(node, key, "expected a string");
    return node.Scalar();
  }

  // a sequence of exactly n numbers
  std::vector<double> Numbers(const YAML::Node& node, const std::string& key, size_t n) const {
    if (!node.IsSequence() || node.size() != n) {
      Fail(node, key, "expected a list of " + std::to_string(n) + " numbers");
    }
    std::vector<double> values;
    for (size_t i = 0; i < n; ++i) values.push_back(Number(node[i], Index(key, i)));
    return values;
  }

  Eigen::Vector2d Vec2(const YAML::Node& node, const std::string& key) const {
    auto v = Numbers(node, key, 2);
    return {v[0], v[1]};
  }

  // what a node is, for messages
  static std::string Kind(const YAML::Node& node) {
    if (node.IsSequence()) return "a list";
    if (node.IsMap()) return "a mapping";
    if (node.IsScalar()) return "'" + node.Scalar() + "'";
    return "nothing";
  }

  static std::string Join(const std::string& parent, const std::string& child) {
    return parent.empty() ? child : parent + "." + child;
  }
  static std::string Index(const std::string& parent, size_t i) {
    return parent + "[" + std::to_string(i) + "]";
  }

 private:
  std::string source_;
};

BoxObject ReadBox(const Reader& r, const YAML::Node& n, const std::string& key) {
  r.Map(n, key, {"name", "center", "size", "yaw", "z"}, {"name", "center", "size"});
  BoxObject box;
  box.name = r.String(n["name"], key + ".name");
  box.center = r.Vec2(n["center"], key + ".center");
  auto size = r.Numbers(n["size"], key + ".size", 3);
  for (size_t i = 0; i < 3; ++i) {
    if (size[i] <= 0) r.Fail(n["size"][i], key + ".size", "expected 3 positive sizes");
  }
  box.size = {size[0], size[1], size[2]};
  if (n["yaw"]) box.yaw = r.Number(n["yaw"], key + ".yaw") * kDegToRad;
  if (n["z"]) box.z = r.NonNegative(n["z"], key + ".z");
  return box;
}

StairsObject ReadStairs(const Reader& r, const YAML::Node& n, const std::string& key) {
  r.Map(n, key, {"name", "start", "yaw", "width", "steps"}, {"name", "start", "width", "steps"});
  StairsObject stairs;
  stairs.name = r.String(n["name"], key + ".name");
  stairs.start = r.Vec2(n["start"], key + ".start");
  if (n["yaw"]) stairs.yaw = r.Number(n["yaw"], key + ".yaw") * kDegToRad;
  stairs.width = r.Positive(n["width"], key + ".width");
  const YAML::Node steps = n["steps"];
  if (!steps.IsSequence() || steps.size() == 0) {
    r.Fail(steps, key + ".steps", "expected a list of [depth, height] pairs");
  }
  for (size_t i = 0; i < steps.size(); ++i) {
    std::string step_key = Reader::Index(key + ".steps", i);
    auto v = r.Numbers(steps[i], step_key, 2);
    if (v[0] <= 0 || v[1] <= 0) r.Fail(steps[i], step_key, "expected a positive depth and height");
    stairs.steps.push_back({v[0], v[1]});
  }
  return stairs;
}

TableObject ReadTable(const Reader& r, const YAML::Node& n, const std::string& key) {
  r.Map(n, key, {"name", "center", "size", "height", "top", "leg", "yaw"},
        {"name", "center", "size", "height"});
  TableObject table;
  table.name = r.String(n["name"], key + ".name");
  table.center = r.Vec2(n["center"], key + ".center");
  table.size = r.Vec2(n["size"], key + ".size");
  if (table.size.minCoeff() <= 0) r.Fail(n["size"], key + ".size", "expected 2 positive sizes");
  table.height = r.Positive(n["height"], key + ".height");
  table.top = n["top"] ? r.Positive(n["top"], key + ".top") : 0.03;
  table.leg = n["leg"] ? r.Positive(n["leg"], key + ".leg") : 0.04;
  if (n["yaw"]) table.yaw = r.Number(n["yaw"], key + ".yaw") * kDegToRad;
  if (table.top >= table.height) {
    r.Fail(n["top"] ? n["top"] : n, key + ".top", "the top must be thinner than the table is high");
  }
  if (2 * table.leg >= table.size.minCoeff()) {
    r.Fail(n["leg"] ? n["leg"] : n, key + ".leg", "the legs must fit inside the top");
  }
  return table;
}

// footprint of a solid as an oriented rectangle: centre, half sizes, yaw
struct Footprint {
  Eigen::Vector2d center;
  Eigen::Vector2d half;
  double yaw;
};

Footprint FootprintOf(const perception::OrientedBox& box) {
  Eigen::Vector3d x_axis = box.X_FB.rotation().col(0);
  return {box.X_FB.translation().head<2>(), box.half_size.head<2>(),
          std::atan2(x_axis.y(), x_axis.x())};
}

// distance from point p to an oriented rectangle (0 inside)
double DistanceToFootprint(const Footprint& f, const Eigen::Vector2d& p) {
  Eigen::Vector2d d = p - f.center;
  double c = std::cos(f.yaw), s = std::sin(f.yaw);
  Eigen::Vector2d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
  Eigen::Vector2d outside = (local.cwiseAbs() - f.half).cwiseMax(0.0);
  return outside.norm();
}

void Validate(const Reader& r, const YAML::Node& root, const Scenario& s) {
  if (!OverFloor(s, {s.start.x, s.start.y})) {
    r.Fail(root["robot"]["start"], "robot.start", "the start is off the floor");
  }
  if (!OverFloor(s, s.goal)) r.Fail(root["goal"]["position"], "goal.position", "the goal is off the floor");

  std::set<std::string> names;
  const YAML::Node objects = root["world"]["objects"];
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const std::string& name = std::visit([](const auto& o) -> const std::string& { return o.name; },
                                         s.objects[i]);
    std::string key = Reader::Index("world.objects", i);
    if (!names.insert(name).second) r.Fail(objects[i], key, "duplicate object name '" + name + "'");
    Scenario one = s;
    one.objects = {s.objects[i]};
    for (const Solid& solid : WorldSolids(one)) {
      // a solid whose top is below the sole is terrain the robot may stand on only if low
      if (DistanceToFootprint(FootprintOf(solid.box), {s.start.x, s.start.y}) < kStartClearance) {
        r.Fail(objects[i], key, "object '" + name + "' overlaps the robot's start pose");
      }
    }
  }
}

}  // namespace

const std::vector<std::string>& ActionNames() {
  static const std::vector<std::string> kNames = {"walk",     "sidestep",    "turn",
                                                  "stairs_up", "stairs_down", "crawl"};
  return kNames;
}

const std::vector<std::string>& FailureNames() {
  static const std::vector<std::string> kNames = {"no_path", "collision", "off_floor",
                                                  "timeout"};
  return kNames;
}

namespace {

// `params: {section: {key: value}}`, each checked against the parameter table
void ReadParams(const Reader& r, const YAML::Node& params, std::map<std::string, double>* out) {
  const std::vector<std::string> sections = ParamSections();
  r.Map(params, "params", {sections.begin(), sections.end()});
  for (const auto& entry : params) {
    const std::string prefix = entry.first.Scalar() + ".";
    const YAML::Node section = entry.second;
    std::set<std::string> keys;
    for (const ParamInfo& info : ParamTable()) {
      if (info.name.compare(0, prefix.size(), prefix) == 0) {
        keys.insert(info.name.substr(prefix.size()));
      }
    }
    r.Map(section, "params." + entry.first.Scalar(), keys);
    for (const auto& item : section) {
      const std::string name = prefix + item.first.Scalar();
      const YAML::Node value = item.second;
      const ParamInfo& info = *FindParam(name);
      // a quoted scalar is a string, whatever it spells
      if (!value.IsScalar() || (value.Tag() == "!" && info.type != ParamType::kChoice)) {
        const std::string got =
            value.IsScalar() ? "the string \"" + value.Scalar() + "\"" : Reader::Kind(value);
        const char* expected = info.type == ParamType::kBool     ? "expected true or false"
                               : info.type == ParamType::kInt    ? "expected an integer"
                               : info.type == ParamType::kChoice ? "expected a name"
                                                                 : "expected a number";
        r.Fail(value, "params." + name, std::string(expected) + ", got " + got);
      }
      double parsed = 0;
      const std::string wrong = ParseParamValue(info, value.Scalar(), &parsed);
      if (!wrong.empty()) r.Fail(value, "params." + name, wrong);
      (*out)[name] = parsed;
    }
  }
}

// world: the floor and the objects on it
void ReadWorld(const Reader& r, const YAML::Node& world, Scenario* out) {
  Scenario& s = *out;
  r.Map(world, "world", {"floor", "floor_center", "objects"}, {"floor"});
  s.floor_size = r.Vec2(world["floor"], "world.floor");
  if (s.floor_size.minCoeff() <= 0) r.Fail(world["floor"], "world.floor", "expected 2 positive sizes");
  if (s.floor_size.maxCoeff() > kMaxFloorSide) {
    r.Fail(world["floor"], "world.floor", "expected sides of at most 30 m");
  }
  if (world["floor_center"]) s.floor_center = r.Vec2(world["floor_center"], "world.floor_center");
  if (world["objects"]) {
    const YAML::Node objects = world["objects"];
    if (!objects.IsSequence()) r.Fail(objects, "world.objects", "expected a list of objects");
    for (size_t i = 0; i < objects.size(); ++i) {
      std::string key = Reader::Index("world.objects", i);
      const YAML::Node entry = objects[i];
      if (!entry.IsMap() || entry.size() != 1) {
        r.Fail(entry, key, "expected exactly one of the keys box, stairs, table");
      }
      r.Map(entry, key, {"box", "stairs", "table"});
      std::string kind = entry.begin()->first.as<std::string>();
      const YAML::Node body = entry.begin()->second;
      if (kind == "box") s.objects.push_back(ReadBox(r, body, key + ".box"));
      if (kind == "stairs") s.objects.push_back(ReadStairs(r, body, key + ".stairs"));
      if (kind == "table") s.objects.push_back(ReadTable(r, body, key + ".table"));
    }
  }

}

// sensor: the head camera's images and the depth they give
void ReadSensor(const Reader& r, const YAML::Node& sensor, Scenario* out) {
  Scenario& s = *out;
  r.Map(sensor, "sensor", {"width", "height", "hfov_deg", "baseline", "depth", "pixel_samples"});
  if (sensor["width"]) s.sensor.width_px = r.Integer(sensor["width"], "sensor.width", 16);
  if (sensor["height"]) s.sensor.height_px = r.Integer(sensor["height"], "sensor.height", 16);
  if (s.sensor.width_px > sim::kMaxViewWidth || s.sensor.height_px > sim::kMaxViewHeight) {
    r.Fail(sensor, "sensor",
           "images up to " + Dims(sim::kMaxViewWidth, sim::kMaxViewHeight) +
               " pixels are supported, got " + Dims(s.sensor.width_px, s.sensor.height_px));
  }
  if (sensor["hfov_deg"]) {
    double hfov_deg = r.Number(sensor["hfov_deg"], "sensor.hfov_deg");
    if (hfov_deg <= 1 || hfov_deg >= 170) {
      r.Fail(sensor["hfov_deg"], "sensor.hfov_deg", "expected a field of view from 1 to 170");
    }
    s.sensor.hfov = hfov_deg * kDegToRad;
  }
  if (sensor["baseline"]) s.sensor.baseline = r.Positive(sensor["baseline"], "sensor.baseline");
  if (sensor["depth"]) {
    std::string depth = r.String(sensor["depth"], "sensor.depth");
    if (depth == "stereo") {
      s.sensor.depth = DepthMode::kStereo;
    } else if (depth == "ideal") {
      s.sensor.depth = DepthMode::kIdeal;
    } else {
      r.Fail(sensor["depth"], "sensor.depth", "expected stereo or ideal, got '" + depth + "'");
    }
  }
  if (const YAML::Node samples = sensor["pixel_samples"]) {
    s.sensor.pixel_samples = r.Integer(samples, "sensor.pixel_samples", 1);
    const int k = s.sensor.pixel_samples;
    if (k > kMaxPixelSamples) {
      r.Fail(samples, "sensor.pixel_samples",
             "expected 1 to " + std::to_string(kMaxPixelSamples) +
                 " samples per pixel side, got " + std::to_string(k));
    }
    const int w = s.sensor.width_px, h = s.sensor.height_px;
    if (k * w > sim::kMaxViewWidth || k * h > sim::kMaxViewHeight) {
      r.Fail(samples, "sensor.pixel_samples",
             std::to_string(k) + " samples per pixel side of a " + Dims(w, h) + " image render " +
                 Dims(k * w, k * h) + " pixels; at most " +
                 Dims(sim::kMaxViewWidth, sim::kMaxViewHeight) + " are supported");
    }
  }
}

// expect: what the mission must end with
void ReadExpect(const Reader& r, const YAML::Node& expect, Scenario* out) {
  Scenario& s = *out;
  r.Map(expect, "expect", {"reach_goal", "actions_used", "no_collision", "failure"});
  if (expect["reach_goal"]) s.expect.reach_goal = r.Bool(expect["reach_goal"], "expect.reach_goal");
  if (expect["no_collision"]) {
    s.expect.no_collision = r.Bool(expect["no_collision"], "expect.no_collision");
  }
  if (const YAML::Node actions = expect["actions_used"]) {
    if (!actions.IsSequence()) r.Fail(actions, "expect.actions_used", "expected a list of actions");
    for (size_t i = 0; i < actions.size(); ++i) {
      std::string key = Reader::Index("expect.actions_used", i);
      std::string action = r.String(actions[i], key);
      const auto& known = ActionNames();
      if (std::find(known.begin(), known.end(), action) == known.end()) {
        r.Fail(actions[i], key, "unknown action '" + action +
                                    "' (expected walk, sidestep, turn, stairs_up, stairs_down or crawl)");
      }
      s.expect.actions_used.push_back(action);
    }
  }
  if (expect["failure"]) {
    std::string failure = r.String(expect["failure"], "expect.failure");
    const auto& known = FailureNames();
    if (std::find(known.begin(), known.end(), failure) == known.end()) {
      r.Fail(expect["failure"], "expect.failure",
             "unknown failure '" + failure +
                 "' (expected no_path, collision, off_floor or timeout)");
    }
    s.expect.failure = failure;
    if (s.expect.reach_goal.value_or(false)) {
      r.Fail(expect["failure"], "expect.failure", "a mission cannot both reach the goal and fail");
    }
  }
}

Scenario ParseRoot(const Reader& r, const YAML::Node& root, const std::string& source) {
  if (!root.IsMap()) {
    // an empty file has no mark: its first line is meant
    const int line = root.IsDefined() && root.Mark().line >= 0 ? root.Mark().line + 1 : 1;
    throw InputError(source + ":" + std::to_string(line) +
                     ": expected a mapping (name, robot, goal, world) at the top level, got " +
                     (root.IsNull() ? std::string("an empty document") : Reader::Kind(root)));
  }
  r.Map(root, "",
        {"name", "description", "seed", "robot", "goal", "world", "sensor", "odometry_noise",
         "limits", "expect", "params"},
        {"name", "robot", "goal", "world"});

  Scenario s;
  s.source = source;
  s.name = r.String(root["name"], "name");
  auto name_char = [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; };
  if (s.name.empty() || !std::all_of(s.name.begin(), s.name.end(), name_char)) {
    r.Fail(root["name"], "name", "expected lower-case letters, digits and _ only");
  }
  if (root["description"]) s.description = r.String(root["description"], "description");
  if (root["seed"]) s.seed = uint64_t(r.Integer(root["seed"], "seed", 0));

  r.Map(root["robot"], "robot", {"start"}, {"start"});
  auto start = r.Numbers(root["robot"]["start"], "robot.start", 3);
  s.start = {start[0], start[1], start[2] * kDegToRad};

  r.Map(root["goal"], "goal", {"position", "tolerance"}, {"position"});
  s.goal = r.Vec2(root["goal"]["position"], "goal.position");
  if (root["goal"]["tolerance"]) s.goal_tolerance = r.Positive(root["goal"]["tolerance"], "goal.tolerance");

  ReadWorld(r, root["world"], &s);

  if (const YAML::Node sensor = root["sensor"]) ReadSensor(r, sensor, &s);

  if (const YAML::Node noise = root["odometry_noise"]) {
    r.Map(noise, "odometry_noise", {"xy", "yaw_deg", "stride_scale", "yaw_bias_deg"});
    if (noise["xy"]) s.odometry_noise_xy = r.NonNegative(noise["xy"], "odometry_noise.xy");
    if (noise["yaw_deg"]) {
      s.odometry_noise_yaw = r.NonNegative(noise["yaw_deg"], "odometry_noise.yaw_deg") * kDegToRad;
    }
    if (noise["stride_scale"]) {
      s.odometry_stride_scale = r.NonNegative(noise["stride_scale"], "odometry_noise.stride_scale");
    }
    if (noise["yaw_bias_deg"]) {
      s.odometry_yaw_bias =
          r.NonNegative(noise["yaw_bias_deg"], "odometry_noise.yaw_bias_deg") * kDegToRad;
    }
  }

  if (const YAML::Node limits = root["limits"]) {
    r.Map(limits, "limits", {"max_cycles", "max_steps"});
    if (limits["max_cycles"]) s.max_cycles = r.Integer(limits["max_cycles"], "limits.max_cycles", 1);
    if (limits["max_steps"]) s.max_steps = r.Integer(limits["max_steps"], "limits.max_steps", 1);
  }

  if (const YAML::Node expect = root["expect"]) ReadExpect(r, expect, &s);

  if (const YAML::Node params = root["params"]) ReadParams(r, params, &s.params);

  Validate(r, root, s);
  return s;
}

}  // namespace

Scenario ParseScenario(const std::string& yaml_text, const std::string& source) {
  if (yaml_text.size() > kMaxScenarioBytes) {
    throw InputError(source + ": the scenario is larger than 1 MB (" +
                     std::to_string(kMaxScenarioBytes) + " bytes); no scenario is that large");
  }
  Reader r(source);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  try {
    return ParseRoot(r, root, source);
  } catch (const YAML::Exception& e) {
    // the reader checks every node before it converts it; should a conversion still fail, the
    // input is at fault, not the program
    const std::string line = e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1);
    throw InputError(source + line + ": " + e.msg);
  }
}

Scenario LoadScenario(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path + ": is a folder, expected a scenario file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot read the scenario file");
  // read one byte past the bound, so that an endless file (/dev/zero) stops there
  std::string text(kMaxScenarioBytes + 1, '\0');
  file.read(text.data(), std::streamsize(text.size()));
  if (file.bad()) throw InputError(path + ": cannot read the scenario file");
  text.resize(size_t(file.gcount()));
  return ParseScenario(text, path);
}

bool OverFloor(const Scenario& scenario, const Eigen::Vector2d& p_W) {
  const Eigen::Vector2d lo = scenario.floor_center - scenario.floor_size / 2;
  const Eigen::Vector2d hi = scenario.floor_center + scenario.floor_size / 2;
  return (p_W.array() >= lo.array()).all() && (p_W.array() <= hi.array()).all();
}

std::vector<Solid> WorldSolids(const Scenario& scenario) {
  std::vector<Solid> solids;
  // a box of full size `size` whose base centre is at `base` (world), rotated by yaw about z
  auto add = [&](const std::string& name, const Eigen::Vector3d& base, const Eigen::Vector3d& size,
                 double yaw) {
    perception::OrientedBox box;
    box.X_FB = Eigen::Translation3d(base + Eigen::Vector3d(0, 0, size.z() / 2)) *
               Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    box.half_size = size / 2;
    solids.push_back({name, box});
  };
  auto rotate = [](double yaw, const Eigen::Vector2d& v) {
    return Eigen::Rotation2Dd(yaw) * v;
  };
  for (const WorldObject& object : scenario.objects) {
    if (const auto* box = std::get_if<BoxObject>(&object)) {
      add(box->name, {box->center.x(), box->center.y(), box->z}, box->size, box->yaw);
    } else if (const auto* stairs = std::get_if<StairsObject>(&object)) {
      double along = 0;
      for (size_t i = 0; i < stairs->steps.size(); ++i) {
        const auto& step = stairs->steps[i];
        Eigen::Vector2d c = stairs->start + rotate(stairs->yaw, {along + step.depth / 2, 0});
        add(stairs->name + "/tread" + std::to_string(i + 1), {c.x(), c.y(), 0},
            {step.depth, stairs->width, step.height}, stairs->yaw);
        along += step.depth;
      }
    } else if (const auto* table = std::get_if<TableObject>(&object)) {
      double underside = table->height - table->top;
      add(table->name + "/top", {table->center.x(), table->center.y(), underside},
          {table->size.x(), table->size.y(), table->top}, table->yaw);
      Eigen::Vector2d corner = table->size / 2 - Eigen::Vector2d::Constant(table->leg / 2);
      int leg = 0;
      for (double sx : {-1.0, 1.0}) {
        for (double sy : {-1.0, 1.0}) {
          Eigen::Vector2d c =
              table->center + rotate(table->yaw, {sx * corner.x(), sy * corner.y()});
          add(table->name + "/leg" + std::to_string(++leg), {c.x(), c.y(), 0},
              {table->leg, table->leg, underside}, table->yaw);
        }
      }
    }
  }
  return solids;
}

std::string Summary(const Scenario& s) {
  std::ostringstream out;
  out.precision(3);
  out << s.name << ": " << s.objects.size() << " objects, floor " << s.floor_size.x() << " x "
      << s.floor_size.y() << " m, start (" << s.start.x << ", " << s.start.y << "), goal ("
      << s.goal.x() << ", " << s.goal.y() << ") "
      << (s.goal - Eigen::Vector2d(s.start.x, s.start.y)).norm() << " m away, sensor "
      << s.sensor.width_px << "x" << s.sensor.height_px << " "
      << (s.sensor.depth == DepthMode::kStereo ? "stereo" : "ideal");
  if (s.sensor.pixel_samples > 1) {
    out << ", " << s.sensor.pixel_samples << "x" << s.sensor.pixel_samples << " samples per pixel";
  }
  if (!s.params.empty()) {
    out << ", params";
    for (const auto& [name, value] : s.params) {
      out << " " << name << "=" << FormatParamValue(*FindParam(name), value);
    }
  }
  return out.str();
}

}  // namespace fognav::scenarios

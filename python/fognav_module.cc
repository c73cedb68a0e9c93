// fognav's Python module (fognav._core, re-exported by the fognav package): scenarios, whole
// missions, missions stepped from Python, and the perception stack on any range data. A thin
// layer over the public C++ API: errors keep their messages, arrays view the C++ values.
#include <pybind11/stl.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "navigation/planner.h"
#include "python/arrays.h"
#include "scenarios/mission.h"
#include "scenarios/mission_session.h"
#include "scenarios/output.h"
#include "scenarios/params.h"
#include "scenarios/scenario.h"
#include "sim/model.h"

namespace fognav::python {

namespace nav = navigation;
using scenarios::Scenario;

py::array_t<double> Matrix4(const Eigen::Isometry3d& X) {
  py::array_t<double> out({4, 4});
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out.mutable_at(r, c) = X.matrix()(r, c);
  }
  return out;
}

Eigen::Isometry3d ToIsometry(const py::handle& array, const std::string& what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    throw py::value_error(what + ": expected a 4 x 4 float array (a rigid transform)");
  }
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) M(r, c) = a.at(r, c);
  }
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  if (!M.allFinite() || (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-3) {
    throw py::value_error(what + ": expected a rigid transform (a rotation and a translation)");
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = M.topRightCorner<3, 1>();
  return X;
}

py::dict FogDict(perception::Fog fog) {
  perception::Fog* held = nullptr;
  const py::capsule base = Own(std::move(fog), &held);
  const perception::GridWindow& w = held->window;
  const std::vector<py::ssize_t> shape = {w.size_y, w.size_x};
  static_assert(sizeof(perception::CellType) == 1, "cell types are bytes");
  py::dict out;
  out["types"] = View(reinterpret_cast<const uint8_t*>(held->type.data()), shape, base);
  out["heights"] = View(held->height.data(), shape, base);
  if (!held->ceiling.empty()) out["ceiling"] = View(held->ceiling.data(), shape, base);
  if (!held->headroom_seen.empty()) {
    out["headroom_seen"] = View(held->headroom_seen.data(), shape, base);
  }
  if (!held->walked.empty()) out["walked"] = View(held->walked.data(), shape, base);
  out["origin"] = py::make_tuple(w.origin_ix * w.resolution, w.origin_iy * w.resolution);
  out["resolution"] = w.resolution;
  return out;
}

void ApplyParamsDict(const py::handle& params, const std::string& source,
                     const std::string& default_section, const std::vector<std::string>& sections,
                     scenarios::ParamOverrides* overrides) {
  if (params.is_none()) return;
  if (!py::isinstance<py::dict>(params)) {
    throw scenarios::InputError(source + ": expected a dict of \"section.key\": value");
  }
  for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(params)) {
    if (!py::isinstance<py::str>(k)) throw scenarios::InputError(source + ": keys are strings");
    std::string name = k.cast<std::string>();
    if (name.find('.') == std::string::npos && !default_section.empty()) {
      name = default_section + "." + name;
    }
    const std::string section = name.substr(0, name.find('.'));
    if (!sections.empty() &&
        std::find(sections.begin(), sections.end(), section) == sections.end()) {
      std::string allowed;
      for (const std::string& s : sections) allowed += (allowed.empty() ? "" : ", ") + s;
      throw scenarios::InputError(source + ": " + name +
                                  ": not a parameter here (sections: " + allowed + ")");
    }
    // the value as --set would spell it
    std::string text;
    if (py::isinstance<py::bool_>(v)) {
      text = v.cast<bool>() ? "true" : "false";
    } else if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) ||
               py::isinstance<py::str>(v)) {
      text = py::str(v).cast<std::string>();
    } else {
      throw scenarios::InputError(source + ": " + name + ": expected a number or a bool, got " +
                                  py::str(py::type::of(v)).cast<std::string>());
    }
    scenarios::ApplyParam(name, text, source, overrides);
  }
}

namespace {

// A folder of its own under the temporary directory, removed with this value.
class TempDir {
 public:
  TempDir() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "fognav-python-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      throw scenarios::OutputError(pattern + ": cannot create a temporary folder");
    }
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code error;
    std::filesystem::remove_all(path_, error);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A scenario given as a loaded Scenario or a path, with params and seed applied as `fognav run
// --set ... --seed N` applies them.
Scenario ScenarioFor(const py::handle& scenario, const py::handle& params, const py::handle& seed) {
  Scenario s = py::isinstance<Scenario>(scenario)
                   ? scenario.cast<Scenario>()
                   : scenarios::LoadScenario(py::str(scenario).cast<std::string>());
  ApplyParamsDict(params, "params", "", {}, &s.params);
  if (!seed.is_none()) {
    const long long n = seed.cast<long long>();
    if (n < 0) throw scenarios::InputError("seed: expected an integer >= 0");
    s.seed = uint64_t(n);
  }
  return s;
}

py::object JsonToPython(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

py::tuple PoseTuple(const perception::Pose2& p) { return py::make_tuple(p.x, p.y, p.yaw); }

py::dict PlanDict(const nav::PlanResult& plan) {
  const py::ssize_t n = py::ssize_t(plan.path.size());
  py::array_t<double> poses({n, py::ssize_t(3)}), floor_z(n);
  py::list moves, postures;
  for (py::ssize_t k = 0; k < n; ++k) {
    const nav::PathPose& q = plan.path[size_t(k)];
    poses.mutable_at(k, 0) = q.pose_G.x;
    poses.mutable_at(k, 1) = q.pose_G.y;
    poses.mutable_at(k, 2) = q.pose_G.yaw;
    floor_z.mutable_at(k) = q.floor_z;
    moves.append(nav::MoveName(q.move));
    postures.append(nav::PostureName(q.posture));
  }
  py::list runs;
  for (const nav::PathSegment& r : nav::SegmentPath(plan)) {
    runs.append(py::make_tuple(nav::MoveName(r.move), r.first, r.last));
  }
  py::dict out;
  out["status"] = nav::PlanStatusName(plan.status);
  out["reason"] = nav::NoPathReasonName(plan.reason);
  out["reaches_goal"] = plan.reaches_goal;
  out["cost"] = plan.cost;
  out["length"] = plan.length;
  out["poses"] = poses;
  out["moves"] = moves;
  out["postures"] = postures;
  out["floor_z"] = floor_z;
  out["runs"] = runs;
  return out;
}

template <typename Enum>
Enum NamedValue(const std::string& name, int count, const char* (*name_of)(Enum),
                const std::string& what) {
  for (int i = 0; i < count; ++i) {
    if (name == name_of(Enum(i))) return Enum(i);
  }
  throw py::value_error(what + ": unknown name '" + name + "'");
}

// A path as plan() returns it (poses N x 3, moves; postures and floor_z optional) as path poses.
std::vector<nav::PathPose> PathFrom(const py::handle& path, const scenarios::MissionSession& s) {
  if (!py::isinstance<py::dict>(path) || !path.contains("poses") || !path.contains("moves")) {
    throw py::value_error(
        "execute: path: expected a dict with 'poses' (N x 3) and 'moves' "
        "(N names), as plan() returns");
  }
  const auto poses =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(path["poses"]);
  if (!poses || poses.ndim() != 2 || poses.shape(1) != 3) {
    throw py::value_error("execute: path['poses']: expected an N x 3 float array (x, y, yaw)");
  }
  const size_t n = size_t(poses.shape(0));
  const auto moves = path["moves"].cast<std::vector<std::string>>();
  if (moves.size() != n) {
    throw py::value_error("execute: path['moves']: expected " + std::to_string(n) +
                          " move names, one per pose, got " + std::to_string(moves.size()));
  }
  std::vector<std::string> postures(n, nav::PostureName(s.posture()));
  if (path.contains("postures")) postures = path["postures"].cast<std::vector<std::string>>();
  std::vector<double> floor_z(n, std::numeric_limits<double>::quiet_NaN());
  if (path.contains("floor_z")) floor_z = path["floor_z"].cast<std::vector<double>>();
  if (postures.size() != n || floor_z.size() != n) {
    throw py::value_error("execute: path: 'postures' and 'floor_z' need one entry per pose");
  }
  std::vector<nav::PathPose> out(n);
  double last_z = s.BelievedFloorZ();
  for (size_t k = 0; k < n; ++k) {
    out[k].pose_G = {poses.at(k, 0), poses.at(k, 1), poses.at(k, 2)};
    out[k].move = NamedValue<nav::Move>(moves[k], nav::kNumMoves, nav::MoveName,
                                        "execute: path['moves'][" + std::to_string(k) + "]");
    out[k].posture =
        NamedValue<nav::Posture>(postures[k], 2, nav::PostureName, "execute: path['postures']");
    // without a floor height: the previous pose's (a step's comes from the plan)
    out[k].floor_z = std::isfinite(floor_z[k]) ? floor_z[k] : last_z;
    last_z = out[k].floor_z;
  }
  return out;
}

// The arrays of one look, viewing the look's own copy of the view.
py::dict LookDict(scenarios::SessionView look) {
  scenarios::SessionView* held = nullptr;
  const py::capsule base = Own(std::move(look), &held);
  const scenarios::StereoView& stereo = held->stereo;
  const scenarios::ViewResult& view = held->view;
  static_assert(sizeof(perception::Rgb) == 3, "pixels are packed");
  py::dict out;
  auto rgb = [&](const perception::RgbImage& image) {
    return View(reinterpret_cast<const uint8_t*>(image.data.data()), {image.height, image.width, 3},
                base);
  };
  out["left"] = rgb(stereo.left);
  out["right"] = rgb(stereo.right);
  const perception::PointImage& points = view.points;
  const float* p = reinterpret_cast<const float*>(points.points.data());
  const py::ssize_t h = points.height, w = points.width, row = w * 12;
  out["points_camera"] = View(p, {h, w, 3}, base);
  out["depth"] = View(p + 2, {h, w}, base, {row, 12});  // z of the camera-frame points
  py::array_t<float> points_grid({h, w, py::ssize_t(3)});
  float* g = points_grid.mutable_data();
  const Eigen::Matrix3f R = view.X_GC.linear().cast<float>();
  const Eigen::Vector3f t = view.X_GC.translation().cast<float>();
  for (size_t i = 0; i < points.points.size(); ++i) {
    Eigen::Map<Eigen::Vector3f>(g + 3 * i) = R * points.points[i] + t;
  }
  out["points_grid"] = points_grid;
  out["labels"] = View(view.planes.labels.data.data(),
                       {view.planes.labels.height, view.planes.labels.width}, base);
  out["planes"] = PlanesDict(view.planes.planes);
  const py::ssize_t n = py::ssize_t(view.labelled_G.size());
  static_assert(sizeof(perception::LabelledPoint) == 20, "labelled points are packed");
  const float* lp = reinterpret_cast<const float*>(view.labelled_G.data());
  out["labelled_grid"] = View(lp, {n, 3}, base, {20, 4});
  out["labelled_heights"] = View(lp + 3, {n}, base, {20});
  out["camera_pose"] = Matrix4(view.X_GC);
  out["camera_pose_true"] = Matrix4(stereo.X_WL);
  out["robot_pose"] = PoseTuple(view.robot_G);
  out["depth_true"] =
      View(stereo.depth.data.data(), {stereo.depth.height, stereo.depth.width}, base);
  const perception::CameraIntrinsics& K = stereo.intrinsics;
  out["intrinsics"] = py::dict(py::arg("fx") = K.fx, py::arg("fy") = K.fy, py::arg("cx") = K.cx,
                               py::arg("cy") = K.cy, py::arg("baseline") = K.baseline);
  return out;
}

// Mission: a MissionSession with its output folder (a temporary one unless given).
class Mission {
 public:
  Mission(const py::handle& scenario, const py::handle& params, const py::handle& seed,
          const py::handle& out) {
    const Scenario s = ScenarioFor(scenario, params, seed);
    std::string dir;
    if (out.is_none()) {
      temp_ = std::make_unique<TempDir>();
      dir = temp_->path();
    } else {
      dir = py::str(out).cast<std::string>();
    }
    py::gil_scoped_release release;
    session_ = std::make_unique<scenarios::MissionSession>(s, dir);
  }

  void LookAround() {
    py::gil_scoped_release release;
    session_->LookAround();
  }
  py::dict Look(double pan, double tilt) {
    std::optional<scenarios::SessionView> look;
    {
      py::gil_scoped_release release;
      look = session_->Look(pan, tilt);
    }
    return LookDict(std::move(*look));
  }
  py::dict Fog() const { return FogDict(session_->Fog()); }
  py::dict Plan(const py::handle& goal) {
    std::optional<Eigen::Vector2d> goal_G;
    if (!goal.is_none()) {
      const auto g = goal.cast<std::vector<double>>();
      if (g.size() != 2) throw py::value_error("plan: goal: expected (x, y) in the grid frame");
      goal_G = Eigen::Vector2d(g[0], g[1]);
    }
    nav::PlanResult plan;
    {
      py::gil_scoped_release release;
      plan = session_->Plan(goal_G);
    }
    return PlanDict(plan);
  }
  py::dict Execute(const py::handle& path) {
    const std::vector<nav::PathPose> poses = PathFrom(path, *session_);
    scenarios::SessionExecution r;
    {
      py::gil_scoped_release release;
      r = session_->Execute(poses);
    }
    py::dict out;
    out["blocked_at"] =
        r.blocked_at < poses.size() ? py::object(py::int_(r.blocked_at)) : py::object(py::none());
    out["reached"] = r.reached;
    out["steps"] = r.steps;
    out["collisions"] = r.collisions;
    out["ended"] = r.ended;
    return out;
  }
  bool Step() {
    py::gil_scoped_release release;
    return session_->Step();
  }
  py::tuple BelievedPose() const { return PoseTuple(session_->BelievedPose()); }
  py::tuple TruePose() const { return PoseTuple(session_->TruePose()); }
  bool Done() { return session_->Done(); }
  py::object Report() {
    std::string text;
    {
      py::gil_scoped_release release;
      text = session_->Report().report_json;
    }
    return JsonToPython(text);
  }
  const scenarios::MissionSession& session() const { return *session_; }

 private:
  std::unique_ptr<TempDir> temp_;  // destroyed after the session that writes into it
  std::unique_ptr<scenarios::MissionSession> session_;
};

py::object Run(const py::handle& scenario, const py::handle& out, const py::handle& params,
               const py::handle& seed) {
  const Scenario s = ScenarioFor(scenario, params, seed);
  std::unique_ptr<TempDir> temp;
  scenarios::MissionOptions options;
  options.quiet = true;
  if (out.is_none()) {
    temp = std::make_unique<TempDir>();
    options.out_dir = temp->path();
  } else {
    options.out_dir = py::str(out).cast<std::string>();
  }
  scenarios::MissionOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = scenarios::RunMission(s, options);
  }
  return JsonToPython(outcome.report_json);
}

void DefineScenario(py::module_& m) {
  py::class_<Scenario>(m, "Scenario", "A validated scenario file (load_scenario).")
      .def_readonly("name", &Scenario::name)
      .def_readonly("description", &Scenario::description)
      .def_readonly("source", &Scenario::source, "the file it was read from")
      .def_readonly("seed", &Scenario::seed)
      .def_property_readonly(
          "start", [](const Scenario& s) { return PoseTuple(s.start); },
          "the robot's start (x, y, yaw), world frame, metres and radians")
      .def_property_readonly(
          "goal", [](const Scenario& s) { return py::make_tuple(s.goal.x(), s.goal.y()); },
          "the goal (x, y), world frame, metres")
      .def_readonly("goal_tolerance", &Scenario::goal_tolerance, "metres")
      .def_readonly("params", &Scenario::params, "the file's params, by \"section.key\"")
      .def_readonly("max_cycles", &Scenario::max_cycles)
      .def_readonly("max_steps", &Scenario::max_steps)
      .def("summary", &scenarios::Summary, "one line describing the scenario")
      .def("__repr__", [](const Scenario& s) {
        return "<fognav.Scenario " + s.name + " from " + s.source + ">";
      });
}

void DefineMission(py::module_& m) {
  py::class_<Mission>(m, "Mission", R"(A mission stepped from Python: the robot, its maps and the
end conditions of `fognav run`, with the decisions left to the caller. Poses are (x, y, yaw) in
metres and radians; the grid frame G is the robot's belief (odometry corrected by localization),
which starts equal to the world frame.)")
      .def(py::init<const py::handle&, const py::handle&, const py::handle&, const py::handle&>(),
           py::arg("scenario"), py::arg("params") = py::none(), py::arg("seed") = py::none(),
           py::arg("out") = py::none(),
           R"(scenario: a Scenario or a path; params and seed as run() takes them; out: the folder
for trajectory.csv and the report's pictures (a temporary folder, removed with the Mission, if
None). The robot stands at the start and has not looked yet.)")
      .def("look_around", &Mission::LookAround,
           "The start sweep of head views that `fognav run` begins with, each perceived.")
      .def("look", &Mission::Look, py::arg("pan"), py::arg("tilt"),
           R"(Turns the head (pan left, tilt down, radians) and perceives the view into the maps.
Returns a dict: left, right (H x W x 3 uint8), depth (H x W float32, metres, NaN invalid),
depth_true (the renderer's), points_camera and points_grid (H x W x 3 float32), labels (H x W
int32, -1 none), planes (as perception.segment), labelled_grid (N x 3) and labelled_heights (N,
-inf off the floor) as the maps took them, camera_pose (4 x 4 X_GC), camera_pose_true (X_WC),
robot_pose (the pose the maps used), intrinsics.)")
      .def("fog", &Mission::Fog,
           R"(The FOG the planner sees (floor under the feet and walked cells marked): types,
heights, ceiling, headroom_seen, walked (rows y, columns x), origin and resolution.)")
      .def("plan", &Mission::Plan, py::arg("goal") = py::none(),
           R"(The built-in planner's way from the believed pose to goal (x, y, grid frame; the
scenario's goal if None): a dict with status, reason, reaches_goal, cost, length, poses (N x
3), moves, postures, floor_z and runs ((move, first, last) per motion command).)")
      .def("execute", &Mission::Execute, py::arg("path"),
           R"(Executes a path: a dict with poses (N x 3, poses[0] the believed pose, then lattice
poses: cell centres and HEADINGS) and moves (N names from MOVES; postures and floor_z optional),
as plan() returns. Moves are checked by the planner's body rules on fog(); execution stops
before the first that breaks them. Returns blocked_at (that index, or None), reached (the last
pose executed to), steps, collisions (new contacts) and ended.)")
      .def("step", &Mission::Step,
           R"(One cycle with the built-in decisions, as `fognav run` runs it (the first call
looks around first). Returns False once the mission has ended; stepping until then gives the
report of run().)")
      .def("believed_pose", &Mission::BelievedPose, "(x, y, yaw) in the grid frame")
      .def("true_pose", &Mission::TruePose, "(x, y, yaw) in the world frame")
      .def("done", &Mission::Done,
           "Whether the mission has ended: goal reached, off the floor, a collision the "
           "scenario forbids, the limits, or report() called.")
      .def("report", &Mission::Report,
           "Ends the mission and returns report.json as a dict (written to out with the maps).")
      .def_property_readonly(
          "cycles", [](const Mission& s) { return s.session().cycles(); },
          "execute() calls so far (the limit is the scenario's max_cycles)");
}

}  // namespace

}  // namespace fognav::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace fognav;
  m.doc() = "fognav: closed-loop humanoid navigation (MuJoCo, stereo, FOG, A*) from Python.";
  py::register_exception<scenarios::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<perception::OutputError>(m, "OutputError", PyExc_OSError);
  py::register_exception<sim::SimError>(m, "SimError", PyExc_RuntimeError);

  for (int t = 0; t < perception::kNumCellTypes; ++t) {
    std::string name = perception::CellTypeName(perception::CellType(t));
    for (char& c : name) c = char(std::toupper(static_cast<unsigned char>(c)));
    m.attr(name.c_str()) = t;
  }
  py::list cell_types, moves;
  for (int t = 0; t < perception::kNumCellTypes; ++t) {
    cell_types.append(perception::CellTypeName(perception::CellType(t)));
  }
  for (int k = 0; k < navigation::kNumMoves; ++k) {
    moves.append(navigation::MoveName(navigation::Move(k)));
  }
  m.attr("CELL_TYPES") = cell_types;
  m.attr("MOVES") = moves;
  // the planner's 16 lattice headings: the directions of the cell steps (1,0), (2,1), (1,1), ...
  py::list headings;
  const int steps[4][2] = {{1, 0}, {2, 1}, {1, 1}, {1, 2}};
  for (int quarter = 0; quarter < 4; ++quarter) {
    for (const auto& s : steps) {
      const double a = std::atan2(s[1], s[0]) + quarter * M_PI / 2;
      headings.append(std::atan2(std::sin(a), std::cos(a)));
    }
  }
  m.attr("HEADINGS") = headings;

  m.def(
      "load_scenario", [](const std::string& path) { return scenarios::LoadScenario(path); },
      py::arg("path"),
      R"(Reads and validates a scenario file as `fognav validate` does; raises InputError (a
ValueError) naming the file, the line and the key.)");
  python::DefineScenario(m);
  m.def("run", &python::Run, py::arg("scenario"), py::arg("out") = py::none(),
        py::arg("params") = py::none(), py::arg("seed") = py::none(),
        R"(Runs a whole mission as `fognav run` does and returns report.json as a dict.

scenario: a Scenario or a path; out: the output folder (a temporary one, removed, if None);
params: {"section.key": value} as --set takes them, over the file's params (InputError if
unknown or out of range); seed: replaces the scenario's seed as --seed does.)");
  m.def(
      "param_defaults",
      []() {
        const scenarios::RunParams defaults;
        py::dict out;
        for (const scenarios::ParamInfo& info : scenarios::ParamTable()) {
          out[info.name.c_str()] = info.get(defaults);
        }
        return out;
      },
      "Every tunable's default by \"section.key\", as `fognav params` lists them.");
  python::DefineMission(m);
  py::module_ perception = m.def_submodule("perception", "The perception stack on any range data.");
  python::DefinePerception(perception);
}

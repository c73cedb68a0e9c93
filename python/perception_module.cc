// fognav.perception: the paper's segmentation and maps on the caller's own range data.
#include <cmath>
#include <cstring>
#include <sstream>

#include "perception/mapping.h"
#include "perception/segmentation.h"
#include "python/arrays.h"
#include "scenarios/scenario.h"

namespace fognav::python {
namespace {

using perception::PlaneSet;

std::string ShapeOf(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

std::string DtypeOf(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

// A float array of `ndim` dimensions whose last is `last` (0: any), as C-ordered float32 (a
// copy only when it is not that already); ValueError naming `what` and `expected` otherwise.
py::array_t<float, py::array::c_style> FloatArray(const py::handle& object, int ndim,
                                                  py::ssize_t last, const std::string& what,
                                                  const std::string& expected) {
  if (!py::isinstance<py::array>(object)) {
    throw py::value_error(what + ": expected " + expected + " numpy array, got " +
                          py::str(py::type::of(object)).cast<std::string>());
  }
  const py::array a = py::reinterpret_borrow<py::array>(object);
  const char kind = a.dtype().kind();
  if (a.ndim() != ndim || (last > 0 && a.shape(ndim - 1) != last) || a.size() == 0 ||
      (kind != 'f' && kind != 'i' && kind != 'u')) {
    throw py::value_error(what + ": expected " + expected + " array, got shape " + ShapeOf(a) +
                          " of " + DtypeOf(a));
  }
  return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
}

// The planes of a `planes` dict as segment() returns it (normal, rms), for `labels`.
std::vector<perception::Plane> PlanesFromDict(const py::handle& planes, int max_label) {
  if (!py::isinstance<py::dict>(planes)) {
    throw py::value_error("insert: planes: expected the planes dict that segment() returns");
  }
  const py::dict d = py::reinterpret_borrow<py::dict>(planes);
  if (!d.contains("normal") || !d.contains("rms")) {
    throw py::value_error("insert: planes: expected the keys 'normal' and 'rms'");
  }
  const auto normal =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(d["normal"]);
  const auto rms = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(d["rms"]);
  if (!normal || normal.ndim() != 2 || normal.shape(1) != 3 || !rms || rms.ndim() != 1 ||
      rms.shape(0) != normal.shape(0)) {
    throw py::value_error("insert: planes: expected 'normal' P x 3 and 'rms' of P");
  }
  if (max_label >= normal.shape(0)) {
    throw py::value_error("insert: labels: label " + std::to_string(max_label) + " but " +
                          std::to_string(normal.shape(0)) + " planes");
  }
  std::vector<perception::Plane> out(size_t(normal.shape(0)));
  for (size_t k = 0; k < out.size(); ++k) {
    out[k].n = Eigen::Vector3d(normal.at(k, 0), normal.at(k, 1), normal.at(k, 2)).normalized();
    out[k].rms = rms.at(k);
  }
  return out;
}

perception::SegmentParams SegmentParamsFrom(const py::handle& params) {
  scenarios::RunParams run;
  run.perception.segment = perception::SegmentParams();  // the paper's Table 1
  scenarios::ParamOverrides overrides;
  ApplyParamsDict(params, "segment: params", "segmentation", {"segmentation"}, &overrides);
  for (const auto& [name, value] : overrides) scenarios::FindParam(name)->set(&run, value);
  return run.perception.segment;
}

// The maps of the paper's Section 5 over the caller's frames.
class Maps {
 public:
  explicit Maps(const py::handle& params) {
    scenarios::ParamOverrides overrides;
    ApplyParamsDict(params, "Maps: params", "", {"label", "grid", "floor", "fog", "void"},
                    &overrides);
    const scenarios::RunParams run = scenarios::ResolveParams(overrides);
    map_ = run.perception.map;
    label_ = run.perception.label;
  }

  void Insert(const py::handle& points, py::object labels, const py::handle& camera_pose,
              py::object planes, py::object robot_pose) {
    if (py::isinstance<py::tuple>(labels) && py::len(labels) == 2 && planes.is_none()) {
      const py::tuple t = py::reinterpret_borrow<py::tuple>(labels);
      labels = t[0];
      planes = t[1];
    }
    if (planes.is_none()) {
      throw py::value_error(
          "insert: planes: required (the planes dict of segment(), or pass "
          "segment()'s (labels, planes) as labels)");
    }
    perception::PointImage points_C = ToPointImage(points, "insert: points");
    const auto labels_a =
        py::array_t<int32_t, py::array::c_style | py::array::forcecast>::ensure(labels);
    if (!labels_a || labels_a.ndim() != 2 || labels_a.shape(0) != points_C.height ||
        labels_a.shape(1) != points_C.width) {
      throw py::value_error(
          "insert: labels: expected an H x W integer array of the points' "
          "size (" +
          std::to_string(points_C.height) + " x " + std::to_string(points_C.width) + ")");
    }
    PlaneSet set;
    set.labels = perception::LabelImage(points_C.width, points_C.height);
    std::memcpy(set.labels.data.data(), labels_a.data(), set.labels.data.size() * 4);
    int max_label = -1;
    for (const int32_t l : set.labels.data) max_label = std::max(max_label, int(l));
    set.planes = PlanesFromDict(planes, max_label);
    const Eigen::Isometry3d X_GC = ToIsometry(camera_pose, "insert: camera_pose");
    perception::Pose2 robot_G;
    if (robot_pose.is_none()) {
      // the camera's place and heading on the floor
      const Eigen::Vector3d forward = X_GC.linear().col(2);
      robot_G = {X_GC.translation().x(), X_GC.translation().y(),
                 std::atan2(forward.y(), forward.x())};
    } else {
      const auto r = robot_pose.cast<std::vector<double>>();
      if (r.size() != 3) throw py::value_error("insert: robot_pose: expected (x, y, yaw)");
      robot_G = {r[0], r[1], r[2]};
    }
    py::gil_scoped_release release;
    perception::MapInput input;
    input.robot_G = robot_G;
    input.p_GC = X_GC.translation();
    input.points = perception::LabelPoints(label_, points_C, set, X_GC, {});
    perception::UpdateMaps(map_, input, &state_);
  }

  py::dict Fog() const {
    if (state_.Empty()) throw py::value_error("fog: nothing inserted yet");
    perception::Fog fog;
    {
      py::gil_scoped_release release;
      fog = perception::ComputeFog(map_, state_);
    }
    return FogDict(std::move(fog));
  }

 private:
  perception::MapParams map_;
  perception::LabelParams label_;
  perception::MapState state_;
};

}  // namespace

py::dict PlanesDict(const std::vector<perception::Plane>& planes) {
  const py::ssize_t n = py::ssize_t(planes.size());
  py::array_t<double> normal({n, py::ssize_t(3)}), centroid({n, py::ssize_t(3)});
  py::array_t<double> d(n), rms(n);
  py::array_t<int64_t> count(n);
  for (py::ssize_t k = 0; k < n; ++k) {
    const perception::Plane& p = planes[size_t(k)];
    const Eigen::Vector3d c = p.Centroid();
    for (int i = 0; i < 3; ++i) {
      normal.mutable_at(k, i) = p.n[i];
      centroid.mutable_at(k, i) = c[i];
    }
    d.mutable_at(k) = p.d;
    rms.mutable_at(k) = p.rms;
    count.mutable_at(k) = p.num_points;
  }
  py::dict out;
  out["normal"] = normal;
  out["d"] = d;
  out["num_points"] = count;
  out["rms"] = rms;
  out["centroid"] = centroid;
  return out;
}

perception::PointImage ToPointImage(const py::handle& array, const std::string& what) {
  const auto a = FloatArray(array, 3, 3, what, "an H x W x 3 float");
  perception::PointImage points(int(a.shape(1)), int(a.shape(0)));
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "points are packed");
  std::memcpy(static_cast<void*>(points.points.data()), a.data(), size_t(a.size()) * sizeof(float));
  return points;
}

void DefinePerception(py::module_& m) {
  m.def(
      "segment",
      [](const py::handle& points, const py::handle& params) {
        const perception::SegmentParams p = SegmentParamsFrom(params);
        perception::PointImage image = ToPointImage(points, "segment: points");
        PlaneSet set;
        {
          py::gil_scoped_release release;
          set = perception::SegmentPlanes(image, p);
        }
        py::dict planes = PlanesDict(set.planes);
        PlaneSet* held = nullptr;
        const py::capsule base = Own(std::move(set), &held);
        const py::array_t<int32_t> labels =
            View(held->labels.data.data(), {held->labels.height, held->labels.width}, base);
        return py::make_tuple(labels, planes);
      },
      py::arg("points"), py::arg("params") = py::none(),
      R"(Segments an organised point image into planes by extended scan-line grouping.

points: H x W x 3 float array, camera frame (x right, y down, z forward), metres; NaN where
    there is no point.
params: dict of segmentation parameters ("n_min" or "segmentation.n_min", as `fognav params`
    lists them); defaults are the paper's Table 1.
Returns (labels, planes): labels an H x W int32 array (plane index, -1 none); planes a dict of
arrays over the P planes, largest first: normal (P x 3, toward the camera), d (p . n = d),
num_points, rms (metres), centroid (P x 3).)");

  m.def(
      "depth_to_points",
      [](const py::handle& depth, double fx, double fy, double cx, double cy, double scale) {
        const auto a = FloatArray(depth, 2, 0, "depth_to_points: depth", "an H x W");
        perception::DepthImage d(int(a.shape(1)), int(a.shape(0)));
        for (size_t i = 0; i < d.data.size(); ++i) {
          const float z = a.data()[i] * float(scale);
          d.data[i] = z > 0 ? z : std::numeric_limits<float>::quiet_NaN();
        }
        perception::CameraIntrinsics K;
        K.width_px = d.width;
        K.height_px = d.height;
        K.fx = fx;
        K.fy = fy;
        K.cx = cx;
        K.cy = cy;
        perception::PointImage* held = nullptr;
        const py::capsule base = Own(perception::DepthPointImage(d, K), &held);
        return View(reinterpret_cast<const float*>(held->points.data()),
                    {held->height, held->width, 3}, base);
      },
      py::arg("depth"), py::arg("fx"), py::arg("fy"), py::arg("cx"), py::arg("cy"),
      py::arg("scale") = 1.0,
      R"(Points of a depth image: pixel (u, v) of depth z becomes z ((u - cx) / fx, (v - cy) / fy, 1).

depth: H x W array along the optical axis, times `scale` in metres (0.001 for a 16-bit PNG in
    millimetres); 0 or NaN is no depth. Returns an H x W x 3 float32 array, NaN without depth.)");

  py::class_<Maps>(m, "Maps", R"(The paper's maps (3D occupancy grid, floor height map, FOG)
built from the caller's frames, in the caller's grid frame G (z up, the floor at z = 0).)")
      .def(py::init<const py::handle&>(), py::arg("params") = py::none(),
           R"(params: dict of "section.key": value for the sections label, grid, floor, fog and
void (`fognav params`); defaults are the mission's.)")
      .def("insert", &Maps::Insert, py::arg("points"), py::arg("labels"), py::arg("camera_pose"),
           py::arg("planes") = py::none(), py::arg("robot_pose") = py::none(),
           R"(Adds one frame: points (H x W x 3, camera frame), labels (H x W) and planes as
segment() returns them (or segment()'s (labels, planes) tuple as labels), and camera_pose, the
4 x 4 pose of the camera in the grid frame (X_GC). The window centres on robot_pose (x, y, yaw),
by default the camera's place and heading.)")
      .def("fog", &Maps::Fog,
           R"(The FOG of the window: a dict with types (rows y, columns x; uint8, the module's
UNKNOWN ... OBSTACLE), heights (float32 metres, -inf unknown), ceiling, headroom_seen, origin
(x, y of the window's corner, metres) and resolution (metres).)");
}

}  // namespace fognav::python

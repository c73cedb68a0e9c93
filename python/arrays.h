// numpy views onto fognav's values (no copies: each array's base owns the value it views) and
// the conversions the module shares.
#ifndef FOGNAV_PYTHON_ARRAYS_H_
#define FOGNAV_PYTHON_ARRAYS_H_

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "perception/mapping.h"
#include "perception/types.h"
#include "scenarios/params.h"

namespace fognav::python {

namespace py = pybind11;

// Moves `value` to the heap, owned by the capsule returned: the base of the arrays that view it.
template <typename T>
py::capsule Own(T value, T** ptr) {
  T* held = new T(std::move(value));
  *ptr = held;
  return py::capsule(held, [](void* p) { delete static_cast<T*>(p); });
}

// An array of `shape` (C order unless `strides` given, bytes) over `data`, kept alive by `base`.
template <typename T>
py::array_t<T> View(const T* data, std::vector<py::ssize_t> shape, const py::capsule& base,
                    std::vector<py::ssize_t> strides = {}) {
  if (strides.empty()) {
    strides.assign(shape.size(), py::ssize_t(sizeof(T)));
    for (size_t i = shape.size(); i-- > 1;) strides[i - 1] = strides[i] * shape[i];
  }
  return py::array_t<T>(shape, strides, data, base);
}

// A 4 x 4 homogeneous transform as a new float64 array.
py::array_t<double> Matrix4(const Eigen::Isometry3d& X);

// A 4 x 4 float array (camera pose) as a transform; `what` names the argument in the error.
Eigen::Isometry3d ToIsometry(const py::handle& array, const std::string& what);

// An H x W x 3 float array as a point image (NaN = no point): ValueError naming `what` and the
// expected shape otherwise.
perception::PointImage ToPointImage(const py::handle& array, const std::string& what);

// The array views of a FOG: types, heights, ceiling, headroom_seen, walked, origin, resolution.
py::dict FogDict(perception::Fog fog);

// The planes of a segmentation as a dict of arrays: normal, d, num_points, rms, centroid.
py::dict PlanesDict(const std::vector<perception::Plane>& planes);

// Applies a params dict ("section.key": value, or "key" for `default_section`) to `overrides`,
// each checked as --set checks it (InputError naming the key otherwise). Sections other than
// `sections` (when not empty) are refused.
void ApplyParamsDict(const py::handle& params, const std::string& source,
                     const std::string& default_section, const std::vector<std::string>& sections,
                     scenarios::ParamOverrides* overrides);

// Registers the perception submodule's functions and classes.
void DefinePerception(py::module_& m);

}  // namespace fognav::python

#endif  // FOGNAV_PYTHON_ARRAYS_H_

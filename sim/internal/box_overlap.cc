#include "sim/internal/box_overlap.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fognav::sim::internal {

double BoxPenetration(const Box& a, const Box& b) {
  const Eigen::Vector3d t = b.center - a.center;
  double least = std::numeric_limits<double>::infinity();
  // overlap of the projections on the unit axis u
  auto overlap = [&](const Eigen::Vector3d& u) {
    const double ra = (a.axes.transpose() * u).cwiseAbs().dot(a.half);
    const double rb = (b.axes.transpose() * u).cwiseAbs().dot(b.half);
    least = std::min(least, ra + rb - std::abs(t.dot(u)));
  };
  for (int i = 0; i < 3; ++i) {
    overlap(a.axes.col(i));
    overlap(b.axes.col(i));
  }
  // edge-edge axes; nearly parallel edges give no axis the face axes have not covered
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d u = a.axes.col(i).cross(b.axes.col(j));
      const double norm = u.norm();
      if (norm > 1e-6) overlap(u / norm);
    }
  }
  return least;
}

}  // namespace fognav::sim::internal

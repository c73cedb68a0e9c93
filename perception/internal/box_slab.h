// The slab test of a line against a box, shared by the synthetic renderer and EmptyRays.
#ifndef FOGNAV_PERCEPTION_INTERNAL_BOX_SLAB_H_
#define FOGNAV_PERCEPTION_INTERNAL_BOX_SLAB_H_

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Core>

namespace fognav::perception::internal {

// The line o + t dir, in the frame of a box centred at the origin with half sizes `half`: the
// interval [*t_in, *t_out] of t that lies in all three slabs, and the face the line enters by
// (2k at -half[k], 2k+1 at +half[k]; -1 if no slab bounds the entry). False if the line runs
// parallel to a slab outside it; the interval may be empty (*t_in > *t_out).
inline bool SlabInterval(const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                         const Eigen::Vector3d& half, double* t_in, double* t_out, int* face) {
  *t_in = -std::numeric_limits<double>::infinity();
  *t_out = std::numeric_limits<double>::infinity();
  *face = -1;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(dir[k]) < 1e-12) {
      if (std::abs(o[k]) > half[k]) return false;
      continue;
    }
    double t1 = (-half[k] - o[k]) / dir[k], t2 = (half[k] - o[k]) / dir[k];
    int f1 = 2 * k, f2 = 2 * k + 1;
    if (t1 > t2) {
      std::swap(t1, t2);
      std::swap(f1, f2);
    }
    if (t1 > *t_in) {
      *t_in = t1;
      *face = f1;
    }
    *t_out = std::min(*t_out, t2);
  }
  return true;
}

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_BOX_SLAB_H_

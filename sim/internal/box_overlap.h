// Penetration depth of two oriented boxes by the separating-axis test.
#ifndef FOGNAV_SIM_INTERNAL_BOX_OVERLAP_H_
#define FOGNAV_SIM_INTERNAL_BOX_OVERLAP_H_

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross

namespace fognav::sim::internal {

// An oriented box: centre, rotation (columns = box axes in the common frame), half extents.
struct Box {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
};

// The least overlap of the two boxes' projections over the 15 separating axes (the faces of
// each and the cross products of their edges): for convex boxes the depth by which they
// interpenetrate, the distance one must move to part them. Zero or negative when a separating
// axis exists (then it is minus the gap along that axis, a lower bound of the distance).
double BoxPenetration(const Box& a, const Box& b);

}  // namespace fognav::sim::internal

#endif  // FOGNAV_SIM_INTERNAL_BOX_OVERLAP_H_

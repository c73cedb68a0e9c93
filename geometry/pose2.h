// The planar pose every stage shares: the simulator's true and believed poses, perception's
// robot in the grid frame, the planner's lattice poses.
#ifndef FOGNAV_GEOMETRY_POSE2_H_
#define FOGNAV_GEOMETRY_POSE2_H_

#include <cmath>

namespace fognav {

// A planar pose: position (x, y) in metres and heading yaw in radians, in the frame named where
// it is used (world, odometry or grid).
struct Pose2 {
  double x = 0, y = 0, yaw = 0;
};

// An angle in radians wrapped to [-pi, pi].
inline double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace fognav

#endif  // FOGNAV_GEOMETRY_POSE2_H_

// Visual odometry of the head camera against keyframes: each view (grey image and depth)
// is registered to the keyframe that overlaps it best, seeded with the pose the robot believes
// (footstep odometry and the head's kinematics), and the registration gives a measurement of the
// robot's planar pose in the grid frame. Errors add up only where a new keyframe is taken, not
// at every view. The registration is OpenCV contrib's RgbdOdometry (photometric and depth).
#ifndef FOGNAV_PERCEPTION_VISUAL_ODOMETRY_H_
#define FOGNAV_PERCEPTION_VISUAL_ODOMETRY_H_

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "perception/types.h"

namespace fognav::perception {

struct VisualOdometryParams {
  double min_depth = 0.2;        // metres; nearer points are not used
  double max_depth = 6.0;        // metres; farther points are not used
  double max_depth_diff = 0.07;  // metres; a correspondence's largest depth difference
  int iterations = 10;           // per pyramid level (of three)
  double max_points_part = 0.2;  // share of the image's points used
  // a registration is used only if it moves the seed by at most this much
  double max_correction = 0.12;        // metres
  double max_correction_angle = 0.12;  // rad
  // its depth agreement: the share of the keyframe's points that land within
  // agree_depth + agree_depth_per_m * depth of the view's depth
  double agree_depth = 0.02;         // metres
  double agree_depth_per_m = 0.03;   // metres per metre of depth
  double min_agreement = 0.5;        // fewest such points, as a share of those that land
  double min_overlap = 0.35;         // share of a keyframe's points inside the view to register
  double keyframe_overlap = 0.6;     // a new keyframe when no keyframe overlaps more
  int max_keyframes = 60;            // the oldest beyond the start's are dropped
  // the registration's own noise on the robot's pose (on rendered course pairs with stereo)
  double sigma_xy = 0.004;   // metres
  double sigma_yaw = 0.004;  // rad
  double gate = 3.0;  // Mahalanobis distance to the odometry beyond which it is rejected
};

// A view kept to register later views against.
struct Keyframe {
  GrayImage gray;
  DepthImage depth;  // camera z, metres; NaN where none
  CameraIntrinsics intrinsics;
  Pose2 robot_G;            // the robot's pose when it was taken, as the filter now holds it
  double floor_z = 0;       // the robot's floor then
  Eigen::Isometry3d X_RC = Eigen::Isometry3d::Identity();  // the camera in the robot frame
  Eigen::Isometry3d X_GC = Eigen::Isometry3d::Identity();  // the camera in the grid frame
  // the first of its pose's three columns in the localization filter's state; -1 for a
  // keyframe whose pose is exact (taken before the odometry had any error)
  Eigen::Index column = -1;
};

struct VisualOdometryState {
  std::vector<Keyframe> keyframes;
  int views = 0;    // views registered or tried (LocalizeView counts them)
  int tracked = 0;  // views whose registration was fused
  // views by outcome: "fused", "gated" (beyond the odometry's uncertainty) or why it failed
  std::map<std::string, int> outcomes;
};

// What one view's registration gave.
struct VisualOdometryResult {
  bool tracked = false;  // a measurement the caller may fuse
  int keyframe = -1;     // index registered against, -1 for none
  double overlap = 0;    // share of that keyframe's points inside the view at the seed
  double agreement = 0;  // depth agreement after registration
  Pose2 robot_G;         // the measured robot pose (valid when tracked)
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // the registration's noise
  std::string why;       // when not tracked: "no keyframe", "no overlap", "failed", ...
};

// A grey image (ITU-R 601 luma) of an RGB image.
GrayImage ToGray(const RgbImage& image);
// The depth (camera z) of a point image, NaN where it has no point.
DepthImage DepthOf(const PointImage& points);

// Registers the view (`gray`, `depth`, intrinsics K) against the best keyframe. The seed is the
// robot's believed pose robot_G on a floor floor_z high with the camera at X_RC in the robot
// frame. Does not change the keyframes.
VisualOdometryResult RegisterView(const VisualOdometryParams& params, const GrayImage& gray,
                                  const DepthImage& depth, const CameraIntrinsics& K,
                                  const Eigen::Isometry3d& X_RC, const Pose2& robot_G,
                                  double floor_z, const VisualOdometryState& state);

// Share of the keyframe's points (sampled) that fall inside a view of intrinsics K taken with
// the camera at X_GC.
double KeyframeOverlap(const VisualOdometryParams& params, const Keyframe& keyframe,
                       const CameraIntrinsics& K,
                       const Eigen::Isometry3d& X_GC);

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_VISUAL_ODOMETRY_H_

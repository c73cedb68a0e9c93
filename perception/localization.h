// Localization against walls: an extended Kalman filter over the planar robot pose in the grid
// frame, whose landmarks are the vertical planes the segmentation finds (walls, the faces of
// blocks and steps). The paper's robot trusts footstep odometry alone; with noisy footsteps that
// drifts by decimetres over a course, so the loop corrects the odometry pose with the walls it
// has seen before. Each landmark is the line a vertical plane leaves on the floor, stored in the
// grid frame when first seen:
//   angle theta of its normal (pointing to the side it was seen from) and offset rho with
//   n(theta) . p = rho for its points p (an infinite line: a wall seen further along matches).
// One cycle: PredictPose with the odometry increment and its covariance, then CorrectPose with
// the view's planes in the robot frame. With zero covariance (noise-free odometry) the pose is
// never changed, only landmarks are recorded.
#ifndef FOGNAV_PERCEPTION_LOCALIZATION_H_
#define FOGNAV_PERCEPTION_LOCALIZATION_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "perception/segmentation.h"
#include "perception/types.h"
#include "perception/visual_odometry.h"

namespace fognav::perception {

// Where the robot's belief of its pose comes from.
enum class LocalizationMode {
  kOdometry,  // footstep odometry alone (the paper's robot)
  kWalls,     // odometry corrected by the walls seen
  kVisual,    // odometry fused with visual odometry and the walls
  kTruth,     // the true pose (a ceiling for experiments)
};

struct LocalizationParams {
  LocalizationMode mode = LocalizationMode::kVisual;
  // which planes are walls: on the suite's noise-free stereo views these limits keep 210 of
  // 637 vertical planes, all within 2.2 deg and 3 cm of their true face (the others include
  // planes off by up to 20 deg: merged corners, leg slivers, spurious matches)
  double max_normal_z = 0.1;         // |n_z| of a plane that counts as vertical
  double min_image_fraction = 0.03;  // fewest points, as a fraction of the image's pixels
  double max_rms = 0.01;             // largest RMS residual of its points, metres
  double min_length = 0.3;           // shortest horizontal extent, metres
  double max_range = 2.5;            // farthest plane centroid used, metres from the camera
  // measurement noise of a plane's line: angle, and offset growing with range r as stereo does
  double angle_sigma = 0.02;           // rad
  double offset_sigma = 0.01;          // metres at r = 0
  double offset_sigma_per_m2 = 0.004;  // metres per square metre of range
  double gate = 3.0;  // Mahalanobis distance within which a plane matches a landmark
  // a plane that no landmark gates but that lies this near one is ambiguous and not added
  double near_angle = 0.2;    // rad
  double near_offset = 0.15;  // metres
  int max_landmarks = 200;    // no more are added beyond this (the state grows with them)
};

// The line on the floor of a vertical plane, grid frame.
struct WallLandmark {
  double angle = 0;   // of the unit normal n = (cos, sin), radians
  double offset = 0;  // rho, metres: n . p = rho
  int matches = 0;    // views of it since it was added
  Eigen::Index column = 3;  // its first column in the filter's state
};

// The filter's state: the pose is the caller's (the odometry pose it corrects); the covariance
// is joint over (x, y, yaw) and (angle, offset) of each landmark in order, so a landmark
// added while the pose was uncertain carries that uncertainty (EKF SLAM).
struct LocalizationState {
  std::vector<WallLandmark> landmarks;
  VisualOdometryState visual;  // keyframes and counts of the visual odometry
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(3, 3);
  // the pose block of the covariance
  Eigen::Matrix3d PoseCovariance() const { return covariance.topLeftCorner<3, 3>(); }
};

// Propagates the covariance over one odometry increment from `before` to `after` (grid frame)
// whose own covariance in the robot frame of `before` is `increment_covariance`.
void PredictPose(const Pose2& before, const Pose2& after,
                 const Eigen::Matrix3d& increment_covariance, LocalizationState* state);

// The vertical planes of `planes_C` (camera frame, segmented from an image of `image_pixels`
// pixels) as seen from the robot: X_RC is the camera in the robot frame (kinematics). Returns
// the corrected pose in the grid frame given the odometry pose `pose_G`: each vertical plane
// that matches exactly one landmark within the gate
// updates pose, landmarks and covariance; one that matches none and lies near none becomes a
// new landmark; one that matches several is ambiguous and unused. Within one call a landmark
// is matched at most once and landmarks it adds are not matched (pieces of one wall in one view
// are not independent measurements).
Pose2 CorrectPose(const LocalizationParams& params, const std::vector<Plane>& planes_C,
                  int image_pixels, const Eigen::Isometry3d& X_RC, const Pose2& pose_G,
                  LocalizationState* state);

// One view as localization sees it.
struct LocalizationView {
  const std::vector<Plane>* planes_C = nullptr;  // the view's planes, camera frame
  int image_pixels = 0;                          // of the image they were segmented from
  const GrayImage* gray = nullptr;               // left image (visual odometry)
  const DepthImage* depth = nullptr;             // its depth, camera z, NaN where none
  CameraIntrinsics intrinsics;                   // of gray and depth
  Eigen::Isometry3d X_RC = Eigen::Isometry3d::Identity();  // camera in the robot frame
  double floor_z = 0;                                      // the robot's floor height
};

// What localizing one view did.
struct LocalizationReport {
  Pose2 pose_G;                 // the corrected pose
  VisualOdometryResult visual;  // the registration (mode kVisual)
  bool visual_fused = false;    // the registration passed the gate and was fused
};

// Localizes one view taken at the odometry pose pose_G: in mode kVisual the view is registered
// to the keyframes and the measurement fused (FusePose, gated), then in kWalls and kVisual the
// walls correct the pose (CorrectPose); kVisual then keeps the view as a keyframe where none
// overlaps it. kOdometry and kTruth return pose_G unchanged.
LocalizationReport LocalizeView(const LocalizationParams& params,
                                const VisualOdometryParams& visual, const LocalizationView& view,
                                const Pose2& pose_G, LocalizationState* state);

// Fuses a measurement `measured_G` of the pose (grid frame) with noise covariance R into the
// filter whose pose is pose_G: returns the corrected pose and updates the state. With
// `keyframe` (an index into state->visual.keyframes) the measurement is relative to that
// keyframe, whose cloned pose it also corrects. A measurement farther than `gate`
// (Mahalanobis) is rejected: pose_G is returned and *accepted (if given) set false.
Pose2 FusePose(const Pose2& pose_G, const Pose2& measured_G, const Eigen::Matrix3d& R,
               double gate, LocalizationState* state, bool* accepted = nullptr,
               int keyframe = -1);

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_LOCALIZATION_H_

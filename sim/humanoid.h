// The humanoid of models/humanoid.xml seen from code: joint, geom, site and camera ids, its
// posture (base pose + joint angles), the head camera pose from kinematics, and its body as
// boxes for perception's self-filter.
#ifndef FOGNAV_SIM_HUMANOID_H_
#define FOGNAV_SIM_HUMANOID_H_

#include <array>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <mujoco/mujoco.h>

#include "sim/internal/leg_ik.h"

namespace fognav::sim {

// The robot's joints (besides the free base joint), in a fixed order.
enum Joint : int {
  kWaist,
  kNeckPan,   // positive looks left
  kNeckTilt,  // positive looks down
  kLeftShoulderPitch,
  kLeftShoulderRoll,
  kLeftElbow,  // negative flexes
  kRightShoulderPitch,
  kRightShoulderRoll,
  kRightElbow,
  kLeftHipYaw,  // the six leg joints of a side are consecutive, in LegAngles order
  kLeftHipRoll,
  kLeftHipPitch,
  kLeftKnee,
  kLeftAnklePitch,
  kLeftAnkleRoll,
  kRightHipYaw,
  kRightHipRoll,
  kRightHipPitch,
  kRightKnee,
  kRightAnklePitch,
  kRightAnkleRoll,
  kNumJoints
};

// MJCF name of a joint ("robot_left_knee").
const char* JointName(Joint j);

enum class Side { kLeft = 0, kRight = 1 };
enum class Eye { kLeft = 0, kRight = 1 };

// A whole-body configuration: base (pelvis) pose in the world and joint angles, radians.
struct JointPosture {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::array<double, kNumJoints> q{};
};

// An oriented box in the robot frame: pose of its centre and half extents, metres.
struct RobotBox {
  Eigen::Isometry3d X_RB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half_size = Eigen::Vector3d::Zero();
  int geom_id = -1;  // the MuJoCo geom it bounds
};

// Ids and dimensions of the humanoid inside a compiled model (alone or included in a world).
// Read-only after construction; cheap to copy.
class Humanoid {
 public:
  // Looks everything up by name; throws SimError naming what is missing.
  explicit Humanoid(const mjModel* m);

  int base_body() const { return base_body_; }
  int root_qpos() const { return root_qpos_; }  // qpos address of the free joint (x y z qw qx qy qz)
  int joint_qpos(Joint j) const { return joint_qpos_[j]; }
  int sole_site(Side s) const { return sole_site_[int(s)]; }
  int camera(Eye e) const { return camera_[int(e)]; }
  int head_body() const { return head_body_; }

  // Geoms of the robot that collide (contype != 0), ascending.
  const std::vector<int>& geom_ids() const { return geom_ids_; }
  // True if geom g belongs to the robot (collision or visual).
  bool IsRobotGeom(int g) const { return g >= 0 && g < int(is_robot_geom_.size()) && is_robot_geom_[g]; }
  // Geoms touching the ground by design: the two sole plates, hands and knee pads.
  int sole_geom(Side s) const { return sole_geom_[int(s)]; }
  int hand_geom(Side s) const { return hand_geom_[int(s)]; }
  int knee_geom(Side s) const { return knee_geom_[int(s)]; }
  double hand_radius() const { return hand_radius_; }  // m, sphere radius of a hand
  double knee_radius() const { return knee_radius_; }  // m, sphere radius of a knee pad
  double sole_half_length() const { return sole_half_length_; }  // m, sole centre to toe

  // Limb dimensions read from the model, for the closed-form IK.
  const internal::LegGeometry& leg(Side s) const { return leg_[int(s)]; }
  const internal::ArmGeometry& arm(Side s) const { return arm_[int(s)]; }
  // Waist joint position in the base frame (the torso frame's origin).
  const Eigen::Vector3d& p_BT() const { return p_BT_; }
  double joint_min(Joint j) const { return range_[j][0]; }
  double joint_max(Joint j) const { return range_[j][1]; }

 private:
  int base_body_ = -1, root_qpos_ = -1, head_body_ = -1;
  std::array<int, kNumJoints> joint_qpos_{};
  std::array<std::array<double, 2>, kNumJoints> range_{};
  std::array<int, 2> sole_site_{}, camera_{}, sole_geom_{}, hand_geom_{}, knee_geom_{};
  std::array<internal::LegGeometry, 2> leg_;
  std::array<internal::ArmGeometry, 2> arm_;
  Eigen::Vector3d p_BT_ = Eigen::Vector3d::Zero();
  double hand_radius_ = 0, knee_radius_ = 0, sole_half_length_ = 0;
  std::vector<int> geom_ids_;
  std::vector<char> is_robot_geom_;
};

// Writes a posture into qpos (joint angles clamped to their ranges); call mj_kinematics after.
void SetPosture(const Humanoid& h, const JointPosture& posture, mjData* d);

// Reads the posture back from qpos.
JointPosture GetPosture(const Humanoid& h, const mjData* d);

// The robot frame R in the world from the current kinematics (d after mj_kinematics), z up.
// Standing (soles level, below the knees): origin midway between the two sole sites, x along
// the mean heading of the feet. Otherwise (crawling): origin on the floor midway between the
// knee pads, x along the pelvis' forward axis projected on the floor.
Eigen::Isometry3d RobotFrameInWorld(const Humanoid& h, const mjData* d);

// Pose of a head camera in the robot frame, OpenCV convention (x right, y down, z forward),
// from joint angles only: the base pose cancels, so no ground truth enters. Needs d after
// mj_kinematics (or mj_forward).
Eigen::Isometry3d HeadCameraPose(const Humanoid& h, const mjData* d, Eye eye);

// Pose of a head camera in the world, OpenCV convention (ground truth, for rendering/scoring).
Eigen::Isometry3d HeadCameraPoseInWorld(const Humanoid& h, const mjData* d, Eye eye);

// The robot's collision geoms as boxes in the robot frame (capsules and spheres by their
// bounding boxes), for removing the robot's own body from its range data. Needs mj_kinematics.
std::vector<RobotBox> RobotBodyBoxes(const Humanoid& h, const mjModel* m, const mjData* d);

// Lowest and highest world z of the robot's collision geoms, metres (standing on z = 0:
// 0 and 0.58). Needs mj_kinematics.
std::array<double, 2> RobotVerticalExtent(const Humanoid& h, const mjModel* m, const mjData* d);

// How far the robot's collision geoms reach in the robot frame: {min x, max x, min y, max y}
// (x ahead, y to the left), metres. Needs mj_kinematics.
std::array<double, 4> RobotPlanarExtent(const Humanoid& h, const mjModel* m, const mjData* d);

}  // namespace fognav::sim

#endif  // FOGNAV_SIM_HUMANOID_H_

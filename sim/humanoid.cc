#include "sim/humanoid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/model.h"

namespace fognav::sim {
namespace {

constexpr const char* kJointNames[kNumJoints] = {
    "robot_waist",           "robot_neck_pan",         "robot_neck_tilt",
    "robot_left_shoulder_pitch", "robot_left_shoulder_roll", "robot_left_elbow",
    "robot_right_shoulder_pitch", "robot_right_shoulder_roll", "robot_right_elbow",
    "robot_left_hip_yaw",    "robot_left_hip_roll",    "robot_left_hip_pitch",
    "robot_left_knee",       "robot_left_ankle_pitch", "robot_left_ankle_roll",
    "robot_right_hip_yaw",   "robot_right_hip_roll",   "robot_right_hip_pitch",
    "robot_right_knee",      "robot_right_ankle_pitch", "robot_right_ankle_roll"};

int Id(const mjModel* m, mjtObj type, const std::string& name) {
  int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw SimError("the humanoid model has no element named '" + name + "'");
  return id;
}

Eigen::Vector3d BodyPos(const mjModel* m, int body) {
  return Eigen::Vector3d(m->body_pos[3 * body], m->body_pos[3 * body + 1], m->body_pos[3 * body + 2]);
}

Eigen::Isometry3d Pose(const mjtNum* pos, const mjtNum* mat) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pos[0], pos[1], pos[2]);
  X.linear() = Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>>(mat);
  return X;
}

// MuJoCo camera (looks along -z, y up) to OpenCV camera (looks along +z, y down)
Eigen::Isometry3d MujocoToOpenCv() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return X;
}

// half extents of a geom's bounding box in its own frame
Eigen::Vector3d GeomHalfBox(const mjModel* m, int g) {
  const mjtNum* s = m->geom_size + 3 * g;
  switch (m->geom_type[g]) {
    case mjGEOM_BOX:
      return Eigen::Vector3d(s[0], s[1], s[2]);
    case mjGEOM_SPHERE:
      return Eigen::Vector3d(s[0], s[0], s[0]);
    case mjGEOM_CAPSULE:
      return Eigen::Vector3d(s[0], s[0], s[1] + s[0]);
    case mjGEOM_CYLINDER:
      return Eigen::Vector3d(s[0], s[0], s[1]);
    default:
      return Eigen::Vector3d::Constant(m->geom_rbound[g]);
  }
}

}  // namespace

const char* JointName(Joint j) { return kJointNames[j]; }

Humanoid::Humanoid(const mjModel* m) {
  base_body_ = Id(m, mjOBJ_BODY, "robot_base");
  head_body_ = Id(m, mjOBJ_BODY, "robot_head");
  root_qpos_ = m->jnt_qposadr[Id(m, mjOBJ_JOINT, "robot_root")];
  for (int j = 0; j < kNumJoints; ++j) {
    int id = Id(m, mjOBJ_JOINT, kJointNames[j]);
    joint_qpos_[j] = m->jnt_qposadr[id];
    range_[j] = {m->jnt_range[2 * id], m->jnt_range[2 * id + 1]};
  }
  const char* sides[2] = {"left", "right"};
  for (int s = 0; s < 2; ++s) {
    const std::string p = std::string("robot_") + sides[s] + "_";
    sole_site_[s] = Id(m, mjOBJ_SITE, p + "sole");
    camera_[s] = Id(m, mjOBJ_CAMERA, p + "eye");
    sole_geom_[s] = Id(m, mjOBJ_GEOM, p + "sole_plate");
    hand_geom_[s] = Id(m, mjOBJ_GEOM, p + "hand");
    knee_geom_[s] = Id(m, mjOBJ_GEOM, p + "knee_pad");
    // limb dimensions from the body offsets, so the IK matches the model
    leg_[s].p_BH = BodyPos(m, Id(m, mjOBJ_BODY, p + "thigh"));
    leg_[s].thigh = -BodyPos(m, Id(m, mjOBJ_BODY, p + "shin")).z();
    leg_[s].shin = -BodyPos(m, Id(m, mjOBJ_BODY, p + "foot")).z();
    leg_[s].ankle_height = -m->site_pos[3 * sole_site_[s] + 2];
    arm_[s].p_TS = BodyPos(m, Id(m, mjOBJ_BODY, p + "upper_arm"));
    arm_[s].upper = -BodyPos(m, Id(m, mjOBJ_BODY, p + "forearm")).z();
    arm_[s].fore = -m->geom_pos[3 * hand_geom_[s] + 2];
  }
  p_BT_ = BodyPos(m, Id(m, mjOBJ_BODY, "robot_torso"));
  hand_radius_ = m->geom_size[3 * hand_geom_[0]];
  knee_radius_ = m->geom_size[3 * knee_geom_[0]];
  sole_half_length_ = m->geom_size[3 * sole_geom_[0]];

  is_robot_geom_.assign(m->ngeom, 0);
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->body_rootid[m->geom_bodyid[g]] != base_body_) continue;
    is_robot_geom_[g] = 1;
    if (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0) geom_ids_.push_back(g);
  }
}

void SetPosture(const Humanoid& h, const JointPosture& posture, mjData* d) {
  mjtNum* root = d->qpos + h.root_qpos();
  const Eigen::Vector3d p = posture.X_WB.translation();
  const Eigen::Quaterniond quat(posture.X_WB.linear());
  root[0] = p.x();
  root[1] = p.y();
  root[2] = p.z();
  root[3] = quat.w();
  root[4] = quat.x();
  root[5] = quat.y();
  root[6] = quat.z();
  for (int j = 0; j < kNumJoints; ++j) {
    d->qpos[h.joint_qpos(Joint(j))] =
        std::clamp(posture.q[j], h.joint_min(Joint(j)), h.joint_max(Joint(j)));
  }
}

JointPosture GetPosture(const Humanoid& h, const mjData* d) {
  JointPosture posture;
  const mjtNum* root = d->qpos + h.root_qpos();
  posture.X_WB.translation() = Eigen::Vector3d(root[0], root[1], root[2]);
  posture.X_WB.linear() =
      Eigen::Quaterniond(root[3], root[4], root[5], root[6]).normalized().toRotationMatrix();
  for (int j = 0; j < kNumJoints; ++j) posture.q[j] = d->qpos[h.joint_qpos(Joint(j))];
  return posture;
}

Eigen::Isometry3d RobotFrameInWorld(const Humanoid& h, const mjData* d) {
  Eigen::Vector3d p_sole = Eigen::Vector3d::Zero(), p_knee = Eigen::Vector3d::Zero();
  Eigen::Vector2d heading = Eigen::Vector2d::Zero();
  bool standing = true;
  for (int s = 0; s < 2; ++s) {
    const int site = h.sole_site(Side(s));
    const Eigen::Vector3d p(d->site_xpos[3 * site], d->site_xpos[3 * site + 1],
                            d->site_xpos[3 * site + 2]);
    p_sole += 0.5 * p;
    const int knee = h.knee_geom(Side(s));
    p_knee += 0.5 * Eigen::Vector3d(d->geom_xpos[3 * knee], d->geom_xpos[3 * knee + 1],
                                    d->geom_xpos[3 * knee + 2]);
    // a level sole has its z axis (third column) up; its x axis (first column) is the heading
    standing = standing && d->site_xmat[9 * site + 8] > 0.85 && p.z() < d->geom_xpos[3 * knee + 2];
    heading += Eigen::Vector2d(d->site_xmat[9 * site], d->site_xmat[9 * site + 3]).normalized();
  }
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  if (standing) {
    X_WR.translation() = p_sole;
  } else {
    const int base = h.base_body();
    heading = Eigen::Vector2d(d->xmat[9 * base], d->xmat[9 * base + 3]);
    X_WR.translation() = p_knee - Eigen::Vector3d(0, 0, h.knee_radius());
  }
  X_WR.linear() = Eigen::AngleAxisd(std::atan2(heading.y(), heading.x()), Eigen::Vector3d::UnitZ())
                      .toRotationMatrix();
  return X_WR;
}

Eigen::Isometry3d HeadCameraPoseInWorld(const Humanoid& h, const mjData* d, Eye eye) {
  const int c = h.camera(eye);
  return Pose(d->cam_xpos + 3 * c, d->cam_xmat + 9 * c) * MujocoToOpenCv();
}

Eigen::Isometry3d HeadCameraPose(const Humanoid& h, const mjData* d, Eye eye) {
  return RobotFrameInWorld(h, d).inverse() * HeadCameraPoseInWorld(h, d, eye);
}

std::vector<RobotBox> RobotBodyBoxes(const Humanoid& h, const mjModel* m, const mjData* d) {
  const Eigen::Isometry3d X_RW = RobotFrameInWorld(h, d).inverse();
  std::vector<RobotBox> boxes;
  boxes.reserve(h.geom_ids().size());
  for (int g : h.geom_ids()) {
    RobotBox box;
    box.X_RB = X_RW * Pose(d->geom_xpos + 3 * g, d->geom_xmat + 9 * g);
    box.half_size = GeomHalfBox(m, g);
    box.geom_id = g;
    boxes.push_back(box);
  }
  return boxes;
}

std::array<double, 2> RobotVerticalExtent(const Humanoid& h, const mjModel* m, const mjData* d) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int g : h.geom_ids()) {
    const Eigen::Isometry3d X_WG = Pose(d->geom_xpos + 3 * g, d->geom_xmat + 9 * g);
    double reach = 0;
    if (m->geom_type[g] == mjGEOM_SPHERE) {
      reach = m->geom_size[3 * g];
    } else if (m->geom_type[g] == mjGEOM_CAPSULE) {
      reach = std::abs(X_WG.linear()(2, 2)) * m->geom_size[3 * g + 1] + m->geom_size[3 * g];
    } else {
      const Eigen::Vector3d half = GeomHalfBox(m, g);
      for (int i = 0; i < 3; ++i) reach += std::abs(X_WG.linear()(2, i)) * half[i];
    }
    lo = std::min(lo, X_WG.translation().z() - reach);
    hi = std::max(hi, X_WG.translation().z() + reach);
  }
  return {lo, hi};
}

std::array<double, 4> RobotPlanarExtent(const Humanoid& h, const mjModel* m, const mjData* d) {
  const Eigen::Isometry3d X_RW = RobotFrameInWorld(h, d).inverse();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::array<double, 4> e = {kInf, -kInf, kInf, -kInf};
  for (int g : h.geom_ids()) {
    const Eigen::Isometry3d X_RG = X_RW * Pose(d->geom_xpos + 3 * g, d->geom_xmat + 9 * g);
    for (int axis = 0; axis < 2; ++axis) {
      double reach = 0;
      if (m->geom_type[g] == mjGEOM_SPHERE) {
        reach = m->geom_size[3 * g];
      } else if (m->geom_type[g] == mjGEOM_CAPSULE) {
        reach = std::abs(X_RG.linear()(axis, 2)) * m->geom_size[3 * g + 1] + m->geom_size[3 * g];
      } else {
        const Eigen::Vector3d half = GeomHalfBox(m, g);
        for (int i = 0; i < 3; ++i) reach += std::abs(X_RG.linear()(axis, i)) * half[i];
      }
      const double c = X_RG.translation()[axis];
      e[size_t(2 * axis)] = std::min(e[size_t(2 * axis)], c - reach);
      e[size_t(2 * axis + 1)] = std::max(e[size_t(2 * axis + 1)], c + reach);
    }
  }
  return e;
}

}  // namespace fognav::sim

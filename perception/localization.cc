#include "perception/localization.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fognav::perception {
namespace {

double WrapAngle(double a) { return std::remainder(a, 2 * M_PI); }

// A vertical plane as a line on the floor, robot frame.
struct LineObservation {
  double angle = 0;  // of its normal
  Eigen::Vector2d centroid_R = Eigen::Vector2d::Zero();
  double half_length = 0;  // along the line, metres
  double range = 0;        // camera to centroid, metres
};

bool ObserveLine(const LocalizationParams& params, const Plane& plane_C, int image_pixels,
                 const Eigen::Isometry3d& X_RC, LineObservation* line) {
  if (plane_C.num_points < std::max(1.0, params.min_image_fraction * image_pixels)) return false;
  if (plane_C.rms > params.max_rms) return false;
  const Eigen::Vector3d n_R = X_RC.linear() * plane_C.n;
  if (std::abs(n_R.z()) > params.max_normal_z) return false;
  const Eigen::Vector3d c_C = plane_C.Centroid();
  line->range = c_C.norm();
  if (line->range > params.max_range) return false;
  const Eigen::Vector2d n = n_R.head<2>().normalized();
  line->angle = std::atan2(n.y(), n.x());
  line->centroid_R = (X_RC * c_C).head<2>();
  // extent from the points' spread along the line (uniform: half length sqrt(3) sigma)
  const Eigen::Vector3d t_C = X_RC.linear().transpose() * Eigen::Vector3d(-n.y(), n.x(), 0);
  const Eigen::Matrix3d spread = plane_C.A / plane_C.num_points - c_C * c_C.transpose();
  line->half_length = std::sqrt(3 * std::max(0.0, t_C.dot(spread * t_C)));
  return 2 * line->half_length >= params.min_length;
}

// The observation in the grid frame for the robot at `pose`.
struct GridLine {
  double angle = 0;
  Eigen::Vector2d centroid_G = Eigen::Vector2d::Zero();
};

GridLine ToGrid(const LineObservation& line, const Pose2& pose) {
  return {WrapAngle(line.angle + pose.yaw),
          Eigen::Rotation2Dd(pose.yaw) * line.centroid_R + Eigen::Vector2d(pose.x, pose.y)};
}

Eigen::Vector2d Normal(double angle) { return {std::cos(angle), std::sin(angle)}; }

// The state's columns an observation of a landmark depends on: the pose's and the landmark's.
std::array<Eigen::Index, 5> StateColumns(const WallLandmark& landmark) {
  const Eigen::Index k = landmark.column;
  return {0, 1, 2, k, k + 1};
}

// applies a correction of the whole state: the pose, every landmark, every keyframe clone
Pose2 ApplyDelta(const Pose2& pose_G, const Eigen::VectorXd& delta, LocalizationState* state) {
  Pose2 pose = pose_G;
  pose.x += delta(0);
  pose.y += delta(1);
  pose.yaw = WrapAngle(pose.yaw + delta(2));
  for (WallLandmark& l : state->landmarks) {
    l.angle = WrapAngle(l.angle + delta(l.column));
    l.offset += delta(l.column + 1);
  }
  for (Keyframe& kf : state->visual.keyframes) {
    if (kf.column < 0) continue;
    kf.robot_G.x += delta(kf.column);
    kf.robot_G.y += delta(kf.column + 1);
    kf.robot_G.yaw = WrapAngle(kf.robot_G.yaw + delta(kf.column + 2));
    kf.X_GC = Planar(kf.robot_G, kf.floor_z) * kf.X_RC;
  }
  return pose;
}

}  // namespace

void PredictPose(const Pose2& before, const Pose2& after,
                 const Eigen::Matrix3d& increment_covariance, LocalizationState* state) {
  // pose' = pose (+) increment: the Jacobians with respect to the pose and the increment
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 2) = -(after.y - before.y);
  F(1, 2) = after.x - before.x;
  Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
  G.topLeftCorner<2, 2>() = Eigen::Rotation2Dd(before.yaw).toRotationMatrix();
  Eigen::MatrixXd& P = state->covariance;
  const Eigen::Index n = P.rows();
  P.topLeftCorner<3, 3>() =
      F * P.topLeftCorner<3, 3>() * F.transpose() + G * increment_covariance * G.transpose();
  P.topRightCorner(3, n - 3) = F * P.topRightCorner(3, n - 3);
  P.bottomLeftCorner(n - 3, 3) = P.topRightCorner(3, n - 3).transpose();
}

Pose2 CorrectPose(const LocalizationParams& params, const std::vector<Plane>& planes_C,
                  int image_pixels, const Eigen::Isometry3d& X_RC, const Pose2& pose_G,
                  LocalizationState* state) {
  Pose2 pose = pose_G;
  Eigen::MatrixXd& P = state->covariance;
  // planes of this view match only landmarks from earlier views, each at most once (pieces of
  // one wall in one view are not independent measurements)
  const size_t landmarks_before = state->landmarks.size();
  std::vector<bool> used(landmarks_before, false);
  for (const Plane& plane : planes_C) {
    LineObservation line;
    if (!ObserveLine(params, plane, image_pixels, X_RC, &line)) continue;
    const GridLine g = ToGrid(line, pose);
    const double offset_sigma =
        params.offset_sigma + params.offset_sigma_per_m2 * line.range * line.range;
    const Eigen::Matrix2d R =
        Eigen::Vector2d(params.angle_sigma * params.angle_sigma, offset_sigma * offset_sigma)
            .asDiagonal();
    const Eigen::Vector2d arm_G = g.centroid_G - Eigen::Vector2d(pose.x, pose.y);
    const Eigen::Vector2d perp_arm(-arm_G.y(), arm_G.x());
    const Eigen::Index n_state = P.rows();

    // for each landmark: the error e = (angle difference, distance of the centroid from its
    // line), zero if pose and landmark are right, and e's Jacobian over the state, which is
    // nonzero only in the pose's 3 and the landmark's 2 columns; the line must gate exactly
    // one landmark
    int matched = -1, gated = 0;
    bool near_one = false;
    Eigen::Vector2d error;
    Eigen::Matrix<double, 2, 5> J;  // over (x, y, yaw, angle_L, offset_L) of the match
    for (size_t i = 0; i < state->landmarks.size(); ++i) {
      const WallLandmark& landmark = state->landmarks[i];
      const Eigen::Vector2d n = Normal(landmark.angle), t(-n.y(), n.x());
      const Eigen::Vector2d e(WrapAngle(g.angle - landmark.angle),
                              n.dot(g.centroid_G) - landmark.offset);
      near_one |= std::abs(e.x()) < params.near_angle && std::abs(e.y()) < params.near_offset;
      if (i >= landmarks_before || used[i]) continue;
      Eigen::Matrix<double, 2, 5> J_i;
      J_i << 0, 0, 1, -1, 0,                                       // angle
          n.x(), n.y(), n.dot(perp_arm), t.dot(g.centroid_G), -1;  // offset
      Eigen::Matrix<double, 5, 5> P_i;
      const std::array<Eigen::Index, 5> idx = StateColumns(state->landmarks[i]);
      for (int r = 0; r < 5; ++r) {
        for (int c = 0; c < 5; ++c) P_i(r, c) = P(idx[r], idx[c]);
      }
      const Eigen::Matrix2d S = J_i * P_i * J_i.transpose() + R;
      if (e.dot(S.inverse() * e) > params.gate * params.gate) continue;
      ++gated;
      matched = int(i);
      error = e;
      J = J_i;
    }

    if (gated == 0 && !near_one && int(state->landmarks.size()) < params.max_landmarks) {
      // a new landmark: (angle, offset) from the pose and the observation, with both their
      // uncertainties in the grown covariance
      const Eigen::Vector2d n = Normal(g.angle), t(-n.y(), n.x());
      state->landmarks.push_back({g.angle, n.dot(g.centroid_G), 0, n_state});
      Eigen::Matrix<double, 2, 3> G_pose;
      G_pose << 0, 0, 1, n.x(), n.y(), t.dot(g.centroid_G) + n.dot(perp_arm);
      Eigen::Matrix2d G_obs;
      G_obs << 1, 0, t.dot(g.centroid_G), 1;
      P.conservativeResize(n_state + 2, n_state + 2);
      P.bottomRightCorner<2, 2>() =
          G_pose * P.topLeftCorner<3, 3>() * G_pose.transpose() + G_obs * R * G_obs.transpose();
      P.block(n_state, 0, 2, n_state) = G_pose * P.topLeftCorner(3, n_state);
      P.block(0, n_state, n_state, 2) = P.block(n_state, 0, 2, n_state).transpose();
      continue;
    }
    if (gated != 1) continue;

    // the Kalman update of pose and landmarks, in O(state^2): P J^T from the five columns J
    // touches, K = P J^T S^-1, P -= K (P J^T)^T; noise-free odometry leaves the pose alone
    // (its rows of the covariance stay zero) and refines only the landmarks
    const std::array<Eigen::Index, 5> idx = StateColumns(state->landmarks[size_t(matched)]);
    Eigen::MatrixXd PJt = Eigen::MatrixXd::Zero(n_state, 2);
    for (int c = 0; c < 5; ++c) PJt += P.col(idx[c]) * J.col(c).transpose();
    Eigen::Matrix2d S = R;
    for (int c = 0; c < 5; ++c) S += J.col(c) * PJt.row(idx[c]);
    const Eigen::MatrixXd K = PJt * S.inverse();
    const Eigen::VectorXd delta = -K * error;
    pose = ApplyDelta(pose, delta, state);
    P.noalias() -= K * PJt.transpose();
    P = 0.5 * (P + P.transpose()).eval();
    ++state->landmarks[size_t(matched)].matches;
    used[size_t(matched)] = true;
  }
  return pose;
}

Pose2 FusePose(const Pose2& pose_G, const Pose2& measured_G, const Eigen::Matrix3d& R,
               double gate, LocalizationState* state, bool* accepted, int keyframe) {
  Eigen::MatrixXd& P = state->covariance;
  const Eigen::Index n = P.rows();
  const Eigen::Vector3d error(measured_G.x - pose_G.x, measured_G.y - pose_G.y,
                              WrapAngle(measured_G.yaw - pose_G.yaw));
  // r = pose - (keyframe (+) delta) is zero up to R: H = [I, -J] over the pose's and the
  // keyframe clone's columns (H = [I] against a keyframe whose pose is exact)
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(3, n);
  H.leftCols<3>().setIdentity();
  const Keyframe* kf =
      keyframe >= 0 ? &state->visual.keyframes[size_t(keyframe)] : nullptr;
  if (kf != nullptr && kf->column >= 0) {
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    J(0, 2) = -(measured_G.y - kf->robot_G.y);
    J(1, 2) = measured_G.x - kf->robot_G.x;
    H.block<3, 3>(0, kf->column) = -J;
  }
  const Eigen::MatrixXd PHt = P * H.transpose();
  const Eigen::Matrix3d S = H * PHt + R;
  const Eigen::LDLT<Eigen::Matrix3d> S_ldlt(S);
  const bool ok = S_ldlt.info() == Eigen::Success && S.determinant() > 0 &&
                  error.dot(S_ldlt.solve(error)) <= gate * gate;
  if (accepted != nullptr) *accepted = ok;
  if (!ok) return pose_G;
  const Eigen::MatrixXd K = S_ldlt.solve(PHt.transpose()).transpose();
  const Pose2 pose = ApplyDelta(pose_G, K * error, state);
  P.noalias() -= K * PHt.transpose();
  P = 0.5 * (P + P.transpose()).eval();
  return pose;
}

namespace {
// removes `count` state columns from `column` on, and renumbers the later ones
void RemoveColumns(Eigen::Index column, Eigen::Index count, LocalizationState* state) {
  Eigen::MatrixXd& P = state->covariance;
  const Eigen::Index n = P.rows(), tail = n - column - count;
  Eigen::MatrixXd Q(n - count, n - count);
  Q.topLeftCorner(column, column) = P.topLeftCorner(column, column);
  Q.topRightCorner(column, tail) = P.topRightCorner(column, tail);
  Q.bottomLeftCorner(tail, column) = P.bottomLeftCorner(tail, column);
  Q.bottomRightCorner(tail, tail) = P.bottomRightCorner(tail, tail);
  P = std::move(Q);
  for (WallLandmark& l : state->landmarks) {
    if (l.column > column) l.column -= count;
  }
  for (Keyframe& kf : state->visual.keyframes) {
    if (kf.column > column) kf.column -= count;
  }
}

// keeps the view as a keyframe where none overlaps it; an uncertain pose is cloned into the
// state, so that later registrations to it are correlated with the pose as they are
void AddKeyframe(const VisualOdometryParams& params, const LocalizationView& view,
                 const Pose2& pose_G, LocalizationState* state) {
  VisualOdometryState& vo = state->visual;
  const Eigen::Isometry3d X_GC = Planar(pose_G, view.floor_z) * view.X_RC;
  for (const Keyframe& kf : vo.keyframes) {
    if (KeyframeOverlap(params, kf, view.intrinsics, X_GC) >= params.keyframe_overlap) return;
  }
  if (int(vo.keyframes.size()) >= params.max_keyframes) {
    // the oldest that is not exact goes first
    auto oldest = std::find_if(vo.keyframes.begin(), vo.keyframes.end(),
                               [](const Keyframe& k) { return k.column >= 0; });
    if (oldest == vo.keyframes.end()) oldest = vo.keyframes.begin();
    const Eigen::Index column = oldest->column;
    vo.keyframes.erase(oldest);
    if (column >= 0) RemoveColumns(column, 3, state);
  }
  Keyframe kf;
  kf.gray = *view.gray;
  kf.depth = *view.depth;
  kf.intrinsics = view.intrinsics;
  kf.robot_G = pose_G;
  kf.floor_z = view.floor_z;
  kf.X_RC = view.X_RC;
  kf.X_GC = X_GC;
  Eigen::MatrixXd& P = state->covariance;
  if (P.topLeftCorner<3, 3>().trace() > 0) {
    const Eigen::Index n = P.rows();
    P.conservativeResize(n + 3, n + 3);
    P.bottomRightCorner<3, 3>() = P.topLeftCorner<3, 3>();
    P.block(n, 0, 3, n) = P.topLeftCorner(3, n);
    P.block(0, n, n, 3) = P.block(n, 0, 3, n).transpose();
    kf.column = n;
  }
  vo.keyframes.push_back(std::move(kf));
}
}  // namespace

LocalizationReport LocalizeView(const LocalizationParams& params,
                                const VisualOdometryParams& visual, const LocalizationView& view,
                                const Pose2& pose_G, LocalizationState* state) {
  LocalizationReport report;
  report.pose_G = pose_G;
  if (params.mode == LocalizationMode::kOdometry || params.mode == LocalizationMode::kTruth) {
    return report;
  }
  const bool use_visual = params.mode == LocalizationMode::kVisual && view.gray != nullptr &&
                          view.depth != nullptr && !view.gray->empty();
  // noise-free odometry is exact: nothing to correct, the keyframes are anchors
  const bool uncertain = state->PoseCovariance().trace() > 0;
  if (use_visual && uncertain) {
    report.visual = RegisterView(visual, *view.gray, *view.depth, view.intrinsics, view.X_RC,
                                 pose_G, view.floor_z, state->visual);
    if (report.visual.tracked) {
      report.pose_G = FusePose(pose_G, report.visual.robot_G, report.visual.covariance,
                               visual.gate, state, &report.visual_fused, report.visual.keyframe);
    }
    ++state->visual.views;
    if (report.visual_fused) ++state->visual.tracked;
    ++state->visual.outcomes[report.visual_fused  ? "fused"
                             : report.visual.tracked ? "gated"
                                                     : report.visual.why];
  }
  if (view.planes_C != nullptr) {
    report.pose_G = CorrectPose(params, *view.planes_C, view.image_pixels, view.X_RC,
                                report.pose_G, state);
  }
  if (use_visual) AddKeyframe(visual, view, report.pose_G, state);
  return report;
}

}  // namespace fognav::perception

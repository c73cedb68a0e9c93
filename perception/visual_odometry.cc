#include "perception/visual_odometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/rgbd.hpp>

namespace fognav::perception {
namespace {

constexpr int kSampleStep = 6;  // pixels between the keyframe points that overlap samples

cv::Mat CameraMatrix(const CameraIntrinsics& K) {
  return (cv::Mat_<double>(3, 3) << K.fx, 0, K.cx, 0, K.fy, K.cy, 0, 0, 1);
}

// the keyframe's depth pixels on a grid, as points in its camera frame
std::vector<Eigen::Vector3d> SamplePoints(const Keyframe& kf, double min_depth, double max_depth) {
  std::vector<Eigen::Vector3d> points;
  const CameraIntrinsics& K = kf.intrinsics;
  for (int v = kSampleStep / 2; v < kf.depth.height; v += kSampleStep) {
    for (int u = kSampleStep / 2; u < kf.depth.width; u += kSampleStep) {
      const double z = kf.depth.at(u, v);
      if (!(z >= min_depth && z <= max_depth)) continue;
      points.emplace_back((u - K.cx) / K.fx * z, (v - K.cy) / K.fy * z, z);
    }
  }
  return points;
}

bool Project(const CameraIntrinsics& K, const Eigen::Vector3d& p_C, int* u, int* v) {
  if (!(p_C.z() > 1e-3)) return false;
  const double fu = K.fx * p_C.x() / p_C.z() + K.cx, fv = K.fy * p_C.y() / p_C.z() + K.cy;
  *u = int(std::lround(fu));
  *v = int(std::lround(fv));
  return *u >= 0 && *v >= 0 && *u < K.width_px && *v < K.height_px;
}

// the share of the keyframe's points that land in the view (X_VK: keyframe camera in the view's)
// and, of those with a depth there, the share whose depth agrees
void Agreement(const VisualOdometryParams& params, const Keyframe& kf,
               const Eigen::Isometry3d& X_VK, const DepthImage& depth, const CameraIntrinsics& K,
               double* landed_share, double* agree_share) {
  const std::vector<Eigen::Vector3d> points = SamplePoints(kf, params.min_depth, params.max_depth);
  int landed = 0, compared = 0, agree = 0;
  for (const Eigen::Vector3d& p_K : points) {
    const Eigen::Vector3d p_V = X_VK * p_K;
    int u = 0, v = 0;
    if (!Project(K, p_V, &u, &v)) continue;
    ++landed;
    const double z = depth.empty() ? std::numeric_limits<double>::quiet_NaN() : depth.at(u, v);
    if (!std::isfinite(z)) continue;
    ++compared;
    if (std::abs(z - p_V.z()) <= params.agree_depth + params.agree_depth_per_m * z) ++agree;
  }
  *landed_share = points.empty() ? 0.0 : double(landed) / double(points.size());
  *agree_share = compared == 0 ? 0.0 : double(agree) / double(compared);
}

cv::Mat GrayMat(const GrayImage& g) {
  return cv::Mat(g.height, g.width, CV_8UC1, const_cast<uint8_t*>(g.data.data())).clone();
}

// depth in metres, 0 where none or out of range (RgbdOdometry's mask)
void DepthMat(const VisualOdometryParams& params, const DepthImage& d, cv::Mat* depth,
              cv::Mat* mask) {
  *depth = cv::Mat(d.height, d.width, CV_32FC1);
  *mask = cv::Mat(d.height, d.width, CV_8UC1);
  for (int v = 0; v < d.height; ++v) {
    for (int u = 0; u < d.width; ++u) {
      const float z = d.at(u, v);
      const bool ok = z >= params.min_depth && z <= params.max_depth;
      depth->at<float>(v, u) = ok ? z : std::numeric_limits<float>::quiet_NaN();
      mask->at<uint8_t>(v, u) = ok ? 255 : 0;
    }
  }
}

Pose2 PlanarOf(const Eigen::Isometry3d& X_GR) {
  const Eigen::Matrix3d R = X_GR.linear();
  return {X_GR.translation().x(), X_GR.translation().y(), std::atan2(R(1, 0), R(0, 0))};
}

}  // namespace

GrayImage ToGray(const RgbImage& image) {
  GrayImage gray(image.width, image.height);
  for (size_t i = 0; i < image.data.size(); ++i) {
    const Rgb& p = image.data[i];
    gray.data[i] = uint8_t(std::lround(0.299 * p.r + 0.587 * p.g + 0.114 * p.b));
  }
  return gray;
}

DepthImage DepthOf(const PointImage& points) {
  DepthImage depth(points.width, points.height, std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < points.points.size(); ++i) {
    if (PointImage::Valid(points.points[i])) depth.data[i] = points.points[i].z();
  }
  return depth;
}

double KeyframeOverlap(const VisualOdometryParams& params, const Keyframe& keyframe,
                       const CameraIntrinsics& K,
                       const Eigen::Isometry3d& X_GC) {
  double landed = 0, agree = 0;
  Agreement(params, keyframe, X_GC.inverse() * keyframe.X_GC, DepthImage(), K, &landed, &agree);
  return landed;
}

VisualOdometryResult RegisterView(const VisualOdometryParams& params, const GrayImage& gray,
                                  const DepthImage& depth, const CameraIntrinsics& K,
                                  const Eigen::Isometry3d& X_RC, const Pose2& robot_G,
                                  double floor_z, const VisualOdometryState& state) {
  VisualOdometryResult result;
  if (state.keyframes.empty()) {
    result.why = "no keyframe";
    return result;
  }
  const Eigen::Isometry3d X_GC_seed = Planar(robot_G, floor_z) * X_RC;
  // the keyframe that overlaps most; among those that overlap enough, the oldest (exact ones
  // come first)
  int best = -1;
  double best_overlap = 0, best_certainty = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < state.keyframes.size(); ++i) {
    const Keyframe& kf = state.keyframes[i];
    const double overlap = KeyframeOverlap(params, kf, K, X_GC_seed);
    const double trace = kf.column < 0 ? -1.0 : double(i);
    const bool enough = overlap >= params.keyframe_overlap;
    const bool best_enough = best_overlap >= params.keyframe_overlap;
    if (best < 0 || (enough && (!best_enough || trace < best_certainty)) ||
        (!enough && !best_enough && overlap > best_overlap)) {
      best = int(i);
      best_overlap = overlap;
      best_certainty = trace;
    }
  }
  result.keyframe = best;
  result.overlap = best_overlap;
  if (best_overlap < params.min_overlap) {
    result.why = "no overlap";
    return result;
  }
  const Keyframe& kf = state.keyframes[size_t(best)];

  // register: Rt maps keyframe camera points into the view's camera (X_VK)
  cv::Mat src_depth, src_mask, dst_depth, dst_mask;
  DepthMat(params, kf.depth, &src_depth, &src_mask);
  DepthMat(params, depth, &dst_depth, &dst_mask);
  const Eigen::Isometry3d X_VK_seed = X_GC_seed.inverse() * kf.X_GC;
  cv::Mat init_rt, rt;
  cv::eigen2cv(Eigen::Matrix4d(X_VK_seed.matrix()), init_rt);
  const std::vector<int> iterations(3, params.iterations);
  const std::vector<float> gradients(3, 10.f);
  bool ok = false;
  try {
    cv::Ptr<cv::rgbd::RgbdOdometry> odometry = cv::rgbd::RgbdOdometry::create(
        CameraMatrix(K), float(params.min_depth), float(params.max_depth),
        float(params.max_depth_diff), iterations, gradients, float(params.max_points_part));
    ok = odometry->compute(GrayMat(kf.gray), src_depth, src_mask, GrayMat(gray), dst_depth,
                           dst_mask, rt, init_rt);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok || rt.empty()) {
    result.why = "failed";
    return result;
  }
  Eigen::Matrix4d rt_e;
  cv::cv2eigen(rt, rt_e);
  Eigen::Isometry3d X_VK(rt_e);
  const Eigen::Isometry3d X_GC = kf.X_GC * X_VK.inverse();

  // checks of its own: the correction is bounded and the depths agree
  const Eigen::Isometry3d correction = X_GC_seed.inverse() * X_GC;
  if (correction.translation().norm() > params.max_correction ||
      Eigen::AngleAxisd(correction.linear()).angle() > params.max_correction_angle) {
    result.why = "too far";
    return result;
  }
  double landed = 0;
  Agreement(params, kf, X_VK, depth, K, &landed, &result.agreement);
  if (result.agreement < params.min_agreement) {
    result.why = "disagrees";
    return result;
  }
  result.tracked = true;
  result.robot_G = PlanarOf(X_GC * X_RC.inverse());
  result.covariance = Eigen::Matrix3d::Zero();
  result.covariance.diagonal() = Eigen::Vector3d(params.sigma_xy * params.sigma_xy,
                                                  params.sigma_xy * params.sigma_xy,
                                                  params.sigma_yaw * params.sigma_yaw);
  return result;
}

}  // namespace fognav::perception

// Plain value types shared by every perception and navigation stage.
#ifndef FOGNAV_PERCEPTION_TYPES_H_
#define FOGNAV_PERCEPTION_TYPES_H_

#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/pose2.h"

namespace fognav::perception {

// A row-major image; pixel (u, v) is column u, row v.
template <typename T>
struct Image {
  int width = 0;
  int height = 0;
  std::vector<T> data;

  Image() = default;
  Image(int w, int h, const T& fill = T()) : width(w), height(h), data(size_t(w) * h, fill) {}
  T& at(int u, int v) { return data[size_t(v) * width + u]; }
  const T& at(int u, int v) const { return data[size_t(v) * width + u]; }
  bool empty() const { return data.empty(); }
};

// 8-bit RGB pixel.
struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
};

using RgbImage = Image<Rgb>;
using GrayImage = Image<uint8_t>;
// Metric depth along the optical axis in metres; NaN where there is none.
using DepthImage = Image<float>;
// Integer labels per pixel; the meaning of values is given where the image is produced.
using LabelImage = Image<int32_t>;

// Pinhole intrinsics of a rendered camera, OpenCV convention (x right, y down, z forward).
struct CameraIntrinsics {
  int width_px = 176;
  int height_px = 144;
  double fx = 0, fy = 0;  // focal lengths in pixels
  double cx = 0, cy = 0;  // principal point in pixels (pixel centres at integer + 0.5 is NOT used:
                          // pixel (u, v) has its centre at (u, v))
  double baseline = 0.05;  // stereo baseline in metres (right camera at +x of the left)
};

// One 3D point per pixel in the camera frame (metres); NaN components where there is no
// measurement. Organised: scan line v is row v.
struct PointImage {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3f> points;

  PointImage() = default;
  PointImage(int w, int h)
      : width(w),
        height(h),
        points(size_t(w) * h, Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN())) {}
  Eigen::Vector3f& at(int u, int v) { return points[size_t(v) * width + u]; }
  const Eigen::Vector3f& at(int u, int v) const { return points[size_t(v) * width + u]; }
  static bool Valid(const Eigen::Vector3f& p) { return p.allFinite(); }
};

using fognav::Pose2;

// The planar pose as a rigid transform, its origin lifted to height z (metres).
inline Eigen::Isometry3d Planar(const Pose2& p, double z = 0) {
  return Eigen::Isometry3d(Eigen::Translation3d(p.x, p.y, z) *
                           Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()));
}

// A solid box: pose of its centre in some frame F (named where it is used) and half extents
// along its own axes in metres. World objects and the robot's body parts are given as these.
struct OrientedBox {
  Eigen::Isometry3d X_FB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half_size = Eigen::Vector3d::Zero();
};

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_TYPES_H_

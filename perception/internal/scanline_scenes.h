// Analytic range images for the segmentation tests and benchmarks: a floor and axis-aligned
// boxes ray-cast exactly from a pinhole camera, with optional depth noise that grows with the
// square of the distance as stereo noise does.
#ifndef FOGNAV_PERCEPTION_INTERNAL_SCANLINE_SCENES_H_
#define FOGNAV_PERCEPTION_INTERNAL_SCANLINE_SCENES_H_

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "perception/types.h"

namespace fognav::perception::internal {

// World frame z up; boxes are axis-aligned, given by their min and max corners in metres.
struct SceneBox {
  Eigen::Vector3d lo, hi;
};

// A floor at z = 0 (optional) and boxes. Surface ids: floor 0, face f of box i 1 + 6 i + f with
// f = 0..5 for the -x, +x, -y, +y, -z, +z faces; -1 where the ray hits nothing.
struct Scene {
  bool floor = true;
  std::vector<SceneBox> boxes;
};

// Depth (metres along the optical axis, NaN where nothing is hit) and surface ids of a view.
struct SceneView {
  DepthImage depth;
  LabelImage surface;
};

// Intrinsics of a w x h camera with 45° horizontal field of view and square pixels.
inline CameraIntrinsics SceneIntrinsics(int w, int h) {
  CameraIntrinsics K;
  K.width_px = w;
  K.height_px = h;
  K.fx = K.fy = 0.5 * w / std::tan(0.5 * 45.0 * M_PI / 180.0);
  K.cx = 0.5 * (w - 1);
  K.cy = 0.5 * (h - 1);
  return K;
}

// Pose of a camera at (x, y, height) looking along world +x, pitched down by pitch_rad.
inline Eigen::Isometry3d SceneCamera(double x, double y, double height, double pitch_rad) {
  const Eigen::Vector3d z_c(std::cos(pitch_rad), 0, -std::sin(pitch_rad));
  const Eigen::Vector3d x_c(0, -1, 0);
  const Eigen::Vector3d y_c = z_c.cross(x_c);
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear().col(0) = x_c;
  X_WC.linear().col(1) = y_c;
  X_WC.linear().col(2) = z_c;
  X_WC.translation() = Eigen::Vector3d(x, y, height);
  return X_WC;
}

// Ray-casts the scene from camera pose X_WC.
inline SceneView RenderScene(const Scene& scene, const CameraIntrinsics& K,
                             const Eigen::Isometry3d& X_WC) {
  SceneView view;
  view.depth = DepthImage(K.width_px, K.height_px, std::numeric_limits<float>::quiet_NaN());
  view.surface = LabelImage(K.width_px, K.height_px, -1);
  const Eigen::Vector3d o = X_WC.translation();
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector3d ray_C((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      const Eigen::Vector3d dir = X_WC.linear() * ray_C;  // t along dir = depth along the axis
      double best_t = std::numeric_limits<double>::infinity();
      int best_id = -1;
      if (scene.floor && dir.z() < 0) {
        best_t = -o.z() / dir.z();
        best_id = 0;
      }
      for (size_t i = 0; i < scene.boxes.size(); ++i) {
        const SceneBox& b = scene.boxes[i];
        double t0 = -std::numeric_limits<double>::infinity();
        double t1 = std::numeric_limits<double>::infinity();
        int face = -1;
        for (int a = 0; a < 3; ++a) {
          if (std::abs(dir[a]) < 1e-12) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) t0 = std::numeric_limits<double>::infinity();
            continue;
          }
          double ta = (b.lo[a] - o[a]) / dir[a], tb = (b.hi[a] - o[a]) / dir[a];
          int fa = 2 * a, fb = 2 * a + 1;
          if (ta > tb) {
            std::swap(ta, tb);
            std::swap(fa, fb);
          }
          if (ta > t0) {
            t0 = ta;
            face = fa;
          }
          t1 = std::min(t1, tb);
        }
        if (t0 <= t1 && t0 > 0 && t0 < best_t) {
          best_t = t0;
          best_id = 1 + 6 * int(i) + face;
        }
      }
      if (best_id < 0) continue;
      view.depth.at(u, v) = float(best_t);
      view.surface.at(u, v) = best_id;
    }
  }
  return view;
}

// Adds Gaussian depth noise of standard deviation sigma_at_1m * z^2 (stereo-like: constant
// disparity error) from a generator seeded with seed.
inline void AddDepthNoise(DepthImage* depth, double sigma_at_1m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (float& z : depth->data)
    if (std::isfinite(z)) z = float(z + sigma_at_1m * double(z) * z * normal(rng));
}

// Smooth random texture in [0, 1] on world points: value noise of two octaves (cells of 30 mm
// and 12 mm), the same from every view, so that rendered stereo pairs can be matched.
inline double SceneTexture(const Eigen::Vector3d& p_W) {
  auto lattice = [](int64_t x, int64_t y, int64_t z) {
    uint64_t h = uint64_t(x) * 0x9E3779B97F4A7C15ull ^ uint64_t(y) * 0xC2B2AE3D27D4EB4Full ^
                 uint64_t(z) * 0x165667B19E3779F9ull;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
    return double(h & 0xFFFF) / 65535.0;
  };
  auto noise = [&](const Eigen::Vector3d& q) {
    const Eigen::Vector3d f = q.array().floor();
    const Eigen::Vector3d t = q - f;
    const int64_t x = int64_t(f.x()), y = int64_t(f.y()), z = int64_t(f.z());
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
      const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
      const double w = (dx ? t.x() : 1 - t.x()) * (dy ? t.y() : 1 - t.y()) *
                       (dz ? t.z() : 1 - t.z());
      sum += w * lattice(x + dx, y + dy, z + dz);
    }
    return sum;
  };
  return 0.65 * noise(p_W / 0.03) + 0.35 * noise(p_W / 0.012 + Eigen::Vector3d(17, 5, 3));
}

// Grey image of the textured scene seen from X_WC (black where nothing is hit).
inline RgbImage RenderTextured(const Scene& scene, const CameraIntrinsics& K,
                               const Eigen::Isometry3d& X_WC) {
  const SceneView view = RenderScene(scene, K, X_WC);
  RgbImage image(K.width_px, K.height_px);
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const double z = view.depth.at(u, v);
      if (!std::isfinite(z)) continue;
      const Eigen::Vector3d p_C((u - K.cx) / K.fx * z, (v - K.cy) / K.fy * z, z);
      const auto g = uint8_t(std::lround(30 + 200 * SceneTexture(X_WC * p_C)));
      image.at(u, v) = Rgb{g, g, g};
    }
  }
  return image;
}

// A rectified stereo pair of the textured scene: left camera X_WC, right camera K.baseline
// along the left camera's x axis.
inline void RenderStereoPair(const Scene& scene, const CameraIntrinsics& K,
                             const Eigen::Isometry3d& X_WC, RgbImage* left, RgbImage* right) {
  *left = RenderTextured(scene, K, X_WC);
  Eigen::Isometry3d X_WR = X_WC;
  X_WR.translation() += X_WC.linear().col(0) * K.baseline;
  *right = RenderTextured(scene, K, X_WR);
}

// A staircase in front of a camera at the origin: num_steps boxes along +x starting at x0, each
// tread `depth` deep and `rise` higher than the one before, width 1.2 m centred on y = 0.
inline Scene Staircase(double x0, int num_steps, double depth, double rise) {
  Scene s;
  for (int i = 0; i < num_steps; ++i)
    s.boxes.push_back({Eigen::Vector3d(x0 + i * depth, -0.6, 0),
                       Eigen::Vector3d(x0 + num_steps * depth, 0.6, rise * (i + 1))});
  return s;
}

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_SCANLINE_SCENES_H_

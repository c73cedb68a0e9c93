#include "perception/internal/map_synthetic.h"

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>

#include "perception/internal/box_slab.h"

namespace fognav::perception::internal {

CameraIntrinsics MakeIntrinsics(int width, int height, double hfov_deg) {
  CameraIntrinsics K;
  K.width_px = width;
  K.height_px = height;
  K.fx = K.fy = 0.5 * width / std::tan(0.5 * hfov_deg * M_PI / 180.0);
  K.cx = 0.5 * (width - 1);
  K.cy = 0.5 * (height - 1);
  return K;
}

Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - eye).normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ());
  if (x.norm() < 1e-9) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear().col(0) = x;
  X_WC.linear().col(1) = y;
  X_WC.linear().col(2) = z;
  X_WC.translation() = eye;
  return X_WC;
}

Plane WallPlane(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double height,
                const Eigen::Isometry3d& X_WC) {
  Plane plane;
  const Eigen::Isometry3d X_CW = X_WC.inverse();
  for (int i = 0; i <= 60; ++i) {
    for (int k = 0; k <= 20; ++k) {
      const Eigen::Vector2d q = a + (b - a) * (i / 60.0);
      const Eigen::Vector3d p_C = X_CW * Eigen::Vector3d(q.x(), q.y(), height * k / 20.0);
      ++plane.num_points;
      plane.b += p_C;
      plane.A += p_C * p_C.transpose();
    }
  }
  const Eigen::Vector2d along = (b - a).normalized();
  Eigen::Vector3d n_W(-along.y(), along.x(), 0);
  const Eigen::Vector3d c_W = X_WC * plane.Centroid();
  if (n_W.dot(X_WC.translation() - c_W) < 0) n_W = -n_W;  // towards the camera
  plane.n = X_WC.linear().transpose() * n_W;
  plane.d = plane.n.dot(plane.Centroid());
  return plane;
}

SyntheticFrame RenderBoxes(const std::vector<OrientedBox>& solids_W, const Eigen::Isometry3d& X_WC,
                           const CameraIntrinsics& K, double max_range) {
  SyntheticFrame frame;
  frame.points_C = PointImage(K.width_px, K.height_px);
  frame.planes.labels = LabelImage(K.width_px, K.height_px, -1);
  std::map<std::pair<int, int>, int> plane_of_face;  // (box, face) -> plane index

  const Eigen::Matrix3d R_WC = X_WC.linear();
  const Eigen::Vector3d p_WC = X_WC.translation();
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector3d d_C((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      const Eigen::Vector3d d_W = R_WC * d_C;
      double best_t = std::numeric_limits<double>::infinity();
      int best_box = -1, best_face = -1;
      // slab test per box in its own frame; the entering face is the hit face
      for (size_t b = 0; b < solids_W.size(); ++b) {
        const OrientedBox& box = solids_W[b];
        const Eigen::Matrix3d R_BW = box.X_FB.linear().transpose();
        const Eigen::Vector3d o = R_BW * (p_WC - box.X_FB.translation());
        double t_in = 0, t_out = 0;
        int face = -1;
        if (!SlabInterval(o, R_BW * d_W, box.half_size, &t_in, &t_out, &face) || t_in > t_out ||
            t_in <= 0.0 || face < 0) {
          continue;
        }
        if (t_in < best_t) {
          best_t = t_in;
          best_box = int(b);
          best_face = face;
        }
      }
      if (best_box < 0) continue;
      const Eigen::Vector3d p_C = best_t * d_C;
      if (p_C.norm() > max_range) continue;
      frame.points_C.at(u, v) = p_C.cast<float>();

      const auto key = std::make_pair(best_box, best_face);
      auto it = plane_of_face.find(key);
      if (it == plane_of_face.end()) {
        const OrientedBox& box = solids_W[size_t(best_box)];
        Eigen::Vector3d n_B = Eigen::Vector3d::Zero();
        n_B[best_face / 2] = (best_face % 2) ? 1.0 : -1.0;
        Plane plane;
        plane.n = R_WC.transpose() * (box.X_FB.linear() * n_B);
        plane.d = plane.n.dot(p_C);
        it = plane_of_face.emplace(key, int(frame.planes.planes.size())).first;
        frame.planes.planes.push_back(plane);
      }
      Plane& plane = frame.planes.planes[size_t(it->second)];
      plane.num_points += 1;
      plane.b += p_C;
      plane.A += p_C * p_C.transpose();
      frame.planes.labels.at(u, v) = it->second;
    }
  }
  return frame;
}

OrientedBox AlignedBox(double x0, double x1, double y0, double y1, double z0, double z1) {
  OrientedBox box;
  box.X_FB.translation() = Eigen::Vector3d(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1));
  box.half_size = Eigen::Vector3d(0.5 * (x1 - x0), 0.5 * (y1 - y0), 0.5 * (z1 - z0));
  return box;
}

std::vector<OrientedBox> Fig9World(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  std::vector<OrientedBox> world;
  // floor and two raised levels: 0, 3 cm, 11 cm
  world.push_back(AlignedBox(-1.5, 1.5, -1.5, 1.5, -0.01, 0.0));
  world.push_back(AlignedBox(0.26, 1.26, -1.18, 0.02, 0.0, 0.03));
  world.push_back(AlignedBox(0.74, 1.26, -1.18, -0.50, 0.0, 0.11));
  // block with a rough top: 10 x 10 posts of 4 cm
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const double x0 = -0.90 + 0.04 * i, y0 = 0.30 + 0.04 * j;
      world.push_back(AlignedBox(x0, x0 + 0.04, y0, y0 + 0.04, 0.0, 0.16 + jitter(rng)));
    }
  }
  // table-like obstacle: slab on four legs, rough top of 6 cm posts
  const double tx0 = -0.82, tx1 = -0.22, ty0 = -1.02, ty1 = -0.42;
  world.push_back(AlignedBox(tx0, tx1, ty0, ty1, 0.38, 0.42));
  for (double x : {tx0, tx1 - 0.04}) {
    for (double y : {ty0, ty1 - 0.04}) world.push_back(AlignedBox(x, x + 0.04, y, y + 0.04, 0.0, 0.38));
  }
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const double x0 = tx0 + 0.06 * i, y0 = ty0 + 0.06 * j;
      world.push_back(AlignedBox(x0, x0 + 0.06, y0, y0 + 0.06, 0.42, 0.45 + 0.5 * jitter(rng)));
    }
  }
  return world;
}

std::vector<Eigen::Isometry3d> Fig9Cameras() {
  std::vector<Eigen::Isometry3d> cameras;
  const Eigen::Vector3d centre(0.0, -0.2, 0.0);
  for (int k = 0; k < 12; ++k) {
    const double a = 2.0 * M_PI * k / 12.0;
    const Eigen::Vector3d eye = centre + Eigen::Vector3d(1.7 * std::cos(a), 1.7 * std::sin(a), 0.5);
    for (double reach : {0.5, 1.2}) {
      const Eigen::Vector3d target = eye + reach * (centre - eye).normalized();
      cameras.push_back(LookAt(eye, Eigen::Vector3d(target.x(), target.y(), 0.0)));
    }
  }
  // from the corners of the grid, at the outer parts of the world
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      cameras.push_back(LookAt(Eigen::Vector3d(1.95 * sx, 1.95 * sy, 0.5),
                               Eigen::Vector3d(1.1 * sx, 1.1 * sy, 0.0)));
    }
  }
  // under the table, from each side, at crawling height
  const Eigen::Vector3d table(-0.52, -0.72, 0.2);
  for (int k = 0; k < 8; ++k) {
    const double a = 2.0 * M_PI * (k + 0.5) / 8.0;
    const Eigen::Vector3d eye = table + Eigen::Vector3d(0.9 * std::cos(a), 0.9 * std::sin(a), 0.0);
    cameras.push_back(LookAt(eye, Eigen::Vector3d(table.x(), table.y(), 0.12)));
  }
  return cameras;
}

}  // namespace fognav::perception::internal

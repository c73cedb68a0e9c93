// Localization: one view's correction against maps of 30 landmarks (the course) and of 200
// (the most the filter keeps).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "perception/localization.h"

namespace fognav::perception {
namespace {

// The head camera 0.5 m above the floor looking along the robot's x (OpenCV axes).
Eigen::Isometry3d CameraInRobot() {
  Eigen::Isometry3d X_RC = Eigen::Isometry3d::Identity();
  X_RC.linear().col(0) = -Eigen::Vector3d::UnitY();
  X_RC.linear().col(1) = -Eigen::Vector3d::UnitZ();
  X_RC.linear().col(2) = Eigen::Vector3d::UnitX();
  X_RC.translation() = Eigen::Vector3d(0, 0, 0.5);
  return X_RC;
}

// A wall 1 m long and 0.3 m high whose floor line runs from a to b (robot frame = grid frame),
// as the segmentation would give it: the moments of a grid of its points.
Plane Wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Isometry3d X_CR = CameraInRobot().inverse();
  Plane plane;
  for (int i = 0; i <= 60; ++i) {
    for (int k = 0; k <= 20; ++k) {
      const Eigen::Vector2d q = a + (b - a) * (i / 60.0);
      const Eigen::Vector3d p_C = X_CR * Eigen::Vector3d(q.x(), q.y(), 0.3 * k / 20.0);
      ++plane.num_points;
      plane.b += p_C;
      plane.A += p_C * p_C.transpose();
    }
  }
  const Eigen::Vector2d along = (b - a).normalized();
  Eigen::Vector3d n_R(-along.y(), along.x(), 0);
  const Eigen::Vector3d c_R = X_CR.inverse() * plane.Centroid();
  if (n_R.dot(Eigen::Vector3d(0, 0, 0.5) - c_R) < 0) n_R = -n_R;
  plane.n = X_CR.linear() * n_R;
  plane.d = plane.n.dot(plane.Centroid());
  return plane;
}

void BM_LocalizationCorrect(benchmark::State& bench) {
  const int num_landmarks = int(bench.range(0));
  // a corridor's two walls and a wall across it, then far walls that match nothing in view
  LocalizationState map;
  const std::vector<Plane> view = {Wall({1, 0.6}, {2, 0.6}), Wall({1, -0.6}, {2, -0.6}),
                                   Wall({2.2, -0.5}, {2.2, 0.5})};
  CorrectPose({}, view, 176 * 144, CameraInRobot(), {}, &map);
  for (int i = int(map.landmarks.size()); i < num_landmarks; ++i) {
    const double angle = 0.3 * i, offset = 5.0 + 0.5 * i;  // beyond every gate
    map.landmarks.push_back({angle, offset, 0});
  }
  const Eigen::Index n = 3 + 2 * Eigen::Index(map.landmarks.size());
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n) * 1e-4;
  P.topLeftCorner<3, 3>() = Eigen::Vector3d(4e-4, 4e-4, 3e-4).asDiagonal();
  map.covariance = P;
  for (auto _ : bench) {
    bench.PauseTiming();
    LocalizationState state = map;
    bench.ResumeTiming();
    const Pose2 pose = CorrectPose({}, view, 176 * 144, CameraInRobot(), {0.01, 0.02, 0.01}, &state);
    benchmark::DoNotOptimize(pose);
  }
  bench.counters["landmarks"] = double(map.landmarks.size());
}
BENCHMARK(BM_LocalizationCorrect)->Name("LocalizationCorrect")->Arg(30)->Arg(200)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fognav::perception

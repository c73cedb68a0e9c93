// Localization: one view's correction against maps of 30 landmarks (the course) and of 200
// (the most the filter keeps).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "perception/internal/map_synthetic.h"
#include "perception/localization.h"

namespace fognav::perception {
namespace {

// The head camera 0.5 m above the floor looking along the robot's x (OpenCV axes); the robot
// stands at the grid origin.
Eigen::Isometry3d CameraInRobot() { return internal::LookAt({0, 0, 0.5}, {1, 0, 0.5}); }

// A wall 0.3 m high whose floor line runs from a to b, as the segmentation would give it.
Plane Wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return internal::WallPlane(a, b, 0.3, CameraInRobot());
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
    map.landmarks.push_back({angle, offset, 0, 3 + 2 * Eigen::Index(i)});
  }
  const Eigen::Index n = 3 + 2 * Eigen::Index(map.landmarks.size());
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n) * 1e-4;
  P.topLeftCorner<3, 3>() = Eigen::Vector3d(4e-4, 4e-4, 3e-4).asDiagonal();
  map.covariance = P;
  for (auto _ : bench) {
    bench.PauseTiming();
    LocalizationState state = map;
    bench.ResumeTiming();
    const Pose2 pose =
        CorrectPose({}, view, 176 * 144, CameraInRobot(), {0.01, 0.02, 0.01}, &state);
    benchmark::DoNotOptimize(pose);
  }
  bench.counters["landmarks"] = double(map.landmarks.size());
}
BENCHMARK(BM_LocalizationCorrect)
    ->Name("LocalizationCorrect")
    ->Arg(30)
    ->Arg(200)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fognav::perception

// Map update for one 176x144 frame: labelled points, ray tracing into the 3D grid, floor map,
// and the FOG of the 100x100 window (paper Section 5).
#include <vector>

#include <benchmark/benchmark.h>

#include "perception/internal/map_synthetic.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

void BM_Mapping(benchmark::State& bench) {
  // the Fig. 9 world seen by a perfect sensor from the standing camera height
  const std::vector<OrientedBox> world = internal::Fig9World();
  const CameraIntrinsics K = internal::MakeIntrinsics(176, 144, 45.0);
  const std::vector<Eigen::Isometry3d> cameras = internal::Fig9Cameras();
  std::vector<internal::SyntheticFrame> frames;
  for (size_t k = 0; k < 8; ++k) frames.push_back(internal::RenderBoxes(world, cameras[3 * k], K));
  const MapParams params;
  const LabelParams label_params;
  MapState state;
  const Pose2 robot;
  size_t k = 0;
  int64_t points = 0;
  for (auto _ : bench) {
    const internal::SyntheticFrame& frame = frames[k];
    const Eigen::Isometry3d& X_GC = cameras[3 * k];
    k = (k + 1) % frames.size();
    MapInput in;
    in.robot_G = robot;
    in.p_GC = X_GC.translation();
    in.points = LabelPoints(label_params, frame.points_C, frame.planes, X_GC, {});
    UpdateMaps(params, in, &state);
    const Fog fog = ComputeFog(params, state);
    benchmark::DoNotOptimize(fog.type.data());
    points += int64_t(in.points.size());
  }
  bench.counters["points"] = benchmark::Counter(double(points) / double(bench.iterations()));
  bench.counters["map_MB"] = double(state.MemoryBytes()) / (1024.0 * 1024.0);
}
BENCHMARK(BM_Mapping)->Name("Mapping/176x144")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fognav::perception

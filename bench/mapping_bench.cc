// Map update for one 176x144 frame: labelled points, ray tracing into the 3D grid, floor map,
// and the FOG of the 100x100 window (paper Section 5). When liboctomap-dev is installed, OctoMap
// inserts the same points from the same camera origins at the same resolution beside it.
#include <vector>

#include <benchmark/benchmark.h>
#ifdef FOGNAV_HAVE_OCTOMAP
#include <octomap/octomap.h>
#endif

#include "perception/internal/map_synthetic.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

// The Fig. 9 world seen by a perfect sensor from the standing camera height: eight frames,
// labelled once (labelling is part of the loop below, the frames are not).
struct Frames {
  std::vector<internal::SyntheticFrame> frames;
  std::vector<Eigen::Isometry3d> cameras;
};

const Frames& Fig9Frames() {
  static const Frames f = [] {
    Frames out;
    const std::vector<OrientedBox> world = internal::Fig9World();
    const CameraIntrinsics K = internal::MakeIntrinsics(176, 144, 45.0);
    const std::vector<Eigen::Isometry3d> cameras = internal::Fig9Cameras();
    for (size_t k = 0; k < 8; ++k) {
      out.cameras.push_back(cameras[3 * k]);
      out.frames.push_back(internal::RenderBoxes(world, cameras[3 * k], K));
    }
    return out;
  }();
  return f;
}

// arg 0: the paper's update; 1: the mission loop's (two hits per frame, near misses overrule)
void BM_Mapping(benchmark::State& bench) {
  const Frames& f = Fig9Frames();
  MapParams params;
  if (bench.range(0) == 1) {
    params.grid.min_hits_per_frame = 2;
    params.grid.overrule_ratio = 2.0;
  }
  const LabelParams label_params;
  MapState state;
  const Pose2 robot;
  size_t k = 0;
  int64_t points = 0;
  for (auto _ : bench) {
    const internal::SyntheticFrame& frame = f.frames[k];
    const Eigen::Isometry3d& X_GC = f.cameras[k];
    k = (k + 1) % f.frames.size();
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
BENCHMARK(BM_Mapping)->Name("Mapping/176x144")->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Mapping)->Name("Mapping/176x144/loop")->Arg(1)->Unit(benchmark::kMillisecond);

#ifdef FOGNAV_HAVE_OCTOMAP
// OctoMap's insertPointCloud (exact ray casting, every ray's free cells and end cell, no lazy
// evaluation) of the points that LabelPoints keeps, at our 4 cm; it builds no floor map and no
// FOG, so it does less than Mapping/176x144 above.
void BM_OctoMapInsert(benchmark::State& bench) {
  const Frames& f = Fig9Frames();
  const MapParams params;
  const LabelParams label_params;
  std::vector<octomap::Pointcloud> clouds(f.frames.size());
  for (size_t k = 0; k < f.frames.size(); ++k) {
    for (const LabelledPoint& p :
         LabelPoints(label_params, f.frames[k].points_C, f.frames[k].planes, f.cameras[k], {}))
      clouds[k].push_back(p.p_G.x(), p.p_G.y(), p.p_G.z());
  }
  octomap::OcTree tree(params.grid.resolution);
  size_t k = 0;
  int64_t points = 0;
  for (auto _ : bench) {
    const Eigen::Vector3d o = f.cameras[k].translation();
    tree.insertPointCloud(clouds[k], octomap::point3d(float(o.x()), float(o.y()), float(o.z())));
    points += int64_t(clouds[k].size());
    k = (k + 1) % clouds.size();
  }
  bench.counters["points"] = benchmark::Counter(double(points) / double(bench.iterations()));
  bench.counters["map_MB"] = double(tree.memoryUsage()) / (1024.0 * 1024.0);
}
BENCHMARK(BM_OctoMapInsert)->Name("OctoMapInsert/176x144")->Unit(benchmark::kMillisecond);
#endif

}  // namespace
}  // namespace fognav::perception

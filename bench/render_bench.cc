// StereoRender/<size>: one stereo pair with left depth and surface ids, off-screen through OSMesa;
// StereoRender/176x144/samples3 with each pixel gathered from 3 x 3 samples (sensor.pixel_samples).
#include <benchmark/benchmark.h>

#include "scenarios/scenario.h"
#include "scenarios/views.h"

namespace {

using fognav::scenarios::ParseScenario;

void BM_StereoRender(benchmark::State& state, int width, int height, int pixel_samples) {
  // a small course: floor, a box, a staircase and a table in front of the camera
  const char* kYaml = R"(
name: bench
robot: {start: [0, 0, 0]}
goal: {position: [3, 0]}
world:
  floor: [6, 4]
  floor_center: [2, 0]
  objects:
    - box: {name: block, center: [1.0, 0.3], size: [0.2, 0.2, 0.2]}
    - stairs: {name: steps, start: [1.5, -0.3], width: 0.8, steps: [[0.25, 0.03], [0.3, 0.06]]}
    - table: {name: desk, center: [2.6, 0.0], size: [0.6, 1.0], height: 0.56}
)";
  auto scenario = ParseScenario(kYaml, "bench");
  scenario.sensor.width_px = width;
  scenario.sensor.height_px = height;
  scenario.sensor.pixel_samples = pixel_samples;
  fognav::sim::World world(fognav::scenarios::MakeWorldSpec(scenario, /*with_robot=*/false));
  fognav::sim::Renderer renderer(world.model());
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
  X_WL.linear() << 0, 0.0, 1, -1, 0, 0, 0, -1, 0;  // looking along world +x
  X_WL.linear() = X_WL.linear() * Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X_WL.translation() = Eigen::Vector3d(0, 0, 0.5);
  for (auto _ : state) {
    auto view = fognav::scenarios::RenderStereo(&renderer, world, X_WL, scenario.sensor);
    benchmark::DoNotOptimize(view.depth.data.data());
  }
}
// real time: llvmpipe renders on worker threads, so the calling thread's CPU time understates it;
// five repetitions so the median is printed
BENCHMARK_CAPTURE(BM_StereoRender, 176x144, 176, 144, 1)
    ->Name("StereoRender/176x144")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_StereoRender, 352x288, 352, 288, 1)
    ->Name("StereoRender/352x288")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_StereoRender, 176x144_samples3, 176, 144, 3)
    ->Name("StereoRender/176x144/samples3")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace

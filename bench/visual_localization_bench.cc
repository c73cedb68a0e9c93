// Localization/176x144: one view's visual odometry and fusion (LocalizeView in mode visual):
// a rendered course view registered to the keyframe taken 8 cm before it, with stereo depth,
// fused into a filter of 30 wall landmarks and 20 keyframe clones; no wall planes.
#include <string>

#include <benchmark/benchmark.h>

#include "perception/localization.h"
#include "perception/segmentation.h"
#include "scenarios/params.h"
#include "scenarios/scenario.h"
#include "scenarios/views.h"
#include "sim/render.h"
#include "sim/world.h"

namespace fognav::scenarios {
namespace {

void BM_Localization(benchmark::State& bench) {
  const Scenario scenario =
      LoadScenario(std::string(FOGNAV_SOURCE_DIR) + "/scenarios/stairs_and_table.yaml");
  sim::World world(MakeWorldSpec(scenario));
  sim::Renderer renderer(world.model());
  const Eigen::Isometry3d X_RC = PlaceRobot(&world, perception::Pose2{0, 0, 0}) *
                                 Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitX());
  PlaceRobot(&world, perception::Pose2{-0.3, 0, 0});
  auto frame = [&](double x, perception::GrayImage* gray, perception::DepthImage* depth) {
    const StereoView v = RenderStereo(&renderer, world,
                                      perception::Planar(perception::Pose2{x, 0, 0}) * X_RC,
                                      scenario.sensor);
    *gray = perception::ToGray(v.left);
    *depth = perception::DepthOf(
        perception::StereoPointImage(v.left, v.right, v.intrinsics, PerceptionParams{}.stereo));
    return v.intrinsics;
  };
  perception::GrayImage gray_a, gray_b;
  perception::DepthImage depth_a, depth_b;
  const perception::CameraIntrinsics K = frame(0.0, &gray_a, &depth_a);
  frame(0.08, &gray_b, &depth_b);
  // the filter: pose, 30 landmarks, then the keyframe and 19 others that overlap nothing
  perception::LocalizationState filter;
  const int n = 3 + 2 * 30 + 3 * 20;
  filter.covariance = Eigen::MatrixXd::Identity(n, n) * 1e-4;
  for (int i = 0; i < 30; ++i) {
    filter.landmarks.push_back({0.3 * i, 5.0 + 0.5 * i, 0, 3 + 2 * Eigen::Index(i)});
  }
  for (int i = 0; i < 20; ++i) {
    perception::Keyframe kf;
    kf.gray = gray_a;
    kf.depth = depth_a;
    kf.intrinsics = K;
    kf.X_RC = X_RC;
    kf.robot_G = i == 0 ? perception::Pose2{0, 0, 0} : perception::Pose2{0, 0, 3.0 + 0.1 * i};
    kf.X_GC = perception::Planar(kf.robot_G) * X_RC;
    kf.column = 3 + 60 + 3 * i;
    filter.visual.keyframes.push_back(kf);
  }
  const perception::LocalizationParams params;
  const perception::VisualOdometryParams visual;
  perception::LocalizationView in;
  in.gray = &gray_b;
  in.depth = &depth_b;
  in.intrinsics = K;
  in.X_RC = X_RC;
  int fused = 0;
  for (auto _ : bench) {
    bench.PauseTiming();
    perception::LocalizationState state = filter;
    bench.ResumeTiming();
    const perception::LocalizationReport r =
        LocalizeView(params, visual, in, perception::Pose2{0.09, 0.005, 0.01}, &state);
    fused += r.visual_fused ? 1 : 0;
    benchmark::DoNotOptimize(r.pose_G);
  }
  bench.counters["fused"] = double(fused) / double(bench.iterations());
}
BENCHMARK(BM_Localization)->Name("Localization/176x144")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fognav::scenarios

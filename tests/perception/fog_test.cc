#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "perception/internal/map_synthetic.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

using internal::Fig9Cameras;
using internal::Fig9World;
using internal::MakeIntrinsics;
using internal::RenderBoxes;

void PrintScore(const FogScore& s) {
  std::printf("observed %d correct %d accuracy %.4f height cells %d median %.4f max %.4f\n",
              s.observed, s.correct, s.accuracy, s.height_cells, s.height_error_median,
              s.height_error_max);
  std::printf("truth \\ estimate: unknown floor stairs border tunnel obstacle\n");
  for (int t = 0; t < kNumCellTypes; ++t) {
    std::printf("%9s:", CellTypeName(CellType(t)));
    for (int e = 0; e < kNumCellTypes; ++e) std::printf(" %6d", s.confusion[t][e]);
    std::printf("\n");
  }
}

TEST(FogFig9, PerfectSensorMatchesGroundTruth) {
  const std::vector<OrientedBox> world = Fig9World();
  const CameraIntrinsics K = MakeIntrinsics(176, 144, 45.0);
  MapParams params;
  MapState state;
  const Pose2 robot;
  for (const Eigen::Isometry3d& X_GC : Fig9Cameras()) {
    const internal::SyntheticFrame frame = RenderBoxes(world, X_GC, K);
    MapInput in;
    in.robot_G = robot;
    in.p_GC = X_GC.translation();
    in.points = LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_GC, {});
    UpdateMaps(params, in, &state);
  }
  const Fog fog = ComputeFog(params, state);
  const Fog truth = GroundTruthFog(world, fog.window, params.fog);
  const FogScore s = ScoreFog(fog, truth);
  PrintScore(s);
  for (int iy = 0; iy < fog.window.size_y; ++iy) {
    for (int ix = 0; ix < fog.window.size_x; ++ix) {
      const CellType e = fog.TypeAt(ix, iy), t = truth.TypeAt(ix, iy);
      if (e == CellType::kUnknown || e == t) continue;
      const Eigen::Vector2d c = fog.window.CellCenter(ix, iy);
      std::printf("cell (%.2f, %.2f): truth %s %.3f estimate %s %.3f\n", c.x(), c.y(),
                  CellTypeName(t), truth.HeightAt(ix, iy), CellTypeName(e), fog.HeightAt(ix, iy));
    }
  }
  WriteMapPictures("/tmp/fig9_est", fog, state, params, robot);
  WriteMapPictures("/tmp/fig9_truth", truth, state, params, robot);
  EXPECT_GE(s.accuracy, 0.99);
  EXPECT_LE(s.height_error_max, 0.005);
}

}  // namespace
}  // namespace fognav::perception

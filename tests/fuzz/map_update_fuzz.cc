// libFuzzer target: the map update (3D grid, floor map) and the FOG from arbitrary labelled
// points (NaN, infinite and far ones included), empty rays and poses: one to three updates from
// poses up to 1000 m out (a scenario's bound), which scroll the maps between them.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "perception/mapping.h"
#include "tests/fuzz/fuzz_input.h"

namespace {

void Check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "map_update_fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fognav::perception;
  fognav::fuzz::FuzzInput in(data, size);
  const MapParams params;
  MapState state;
  const bool far = in.Byte() & 1;
  const double range = far ? 1000.0 : 2.0;
  const int updates = in.Int(1, 3);
  for (int k = 0; k < updates; ++k) {
    MapInput input;
    input.robot_G = {in.Finite(-range, range), in.Finite(-range, range),
                     in.Finite(-4 * M_PI, 4 * M_PI)};
    const Eigen::Vector3d robot(input.robot_G.x, input.robot_G.y, 0);
    input.p_GC =
        robot + Eigen::Vector3d{in.Finite(-0.2, 0.2), in.Finite(-0.2, 0.2), in.Finite(0.0, 0.7)};
    const int points = in.Int(0, 400);
    for (int i = 0; i < points && in.left() > 0; ++i) {
      LabelledPoint p;
      p.p_G = robot.cast<float>() +
              Eigen::Vector3f{in.Value(-3, 3), in.Value(-3, 3), in.Value(-0.5f, 1.5f)};
      p.h = (in.Byte() & 1) ? in.Value(-0.2f, 0.6f) : -std::numeric_limits<float>::infinity();
      p.h_sigma = in.Value(0, 0.1f);
      input.points.push_back(p);
    }
    const int rays = in.Int(0, 30);
    for (int i = 0; i < rays && in.left() > 0; ++i) {
      input.empty_rays_G.push_back(
          Eigen::Vector3f{in.Value(-1, 1), in.Value(-1, 1), in.Value(-1, 1)});
    }
    input.floor_z = in.Finite(-0.3, 0.3);
    if (in.Byte() & 1) FadeGrid(params, 0.5, &state);
    UpdateMaps(params, input, &state);
    const Fog fog = ComputeFog(params, state);
    const size_t cells = size_t(fog.window.size_x) * size_t(fog.window.size_y);
    Check(fog.type.size() == cells && fog.height.size() == cells,
          "the FOG does not cover its window");
  }
  return 0;
}

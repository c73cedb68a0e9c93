#include "navigation/internal/test_worlds.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fognav::navigation::internal {

using perception::CellType;
using perception::Fog;

Fog FlatFog(int size_x, int size_y, double resolution, CellType type, float height) {
  perception::GridWindow w;
  w.size_x = size_x;
  w.size_y = size_y;
  w.resolution = resolution;
  w.origin_ix = 0;
  w.origin_iy = 0;
  Fog fog(w);
  std::fill(fog.type.begin(), fog.type.end(), type);
  std::fill(fog.height.begin(), fog.height.end(), height);
  return fog;
}

void FillBox(Fog* fog, double x0, double y0, double x1, double y1, CellType type, float height) {
  const perception::GridWindow& w = fog->window;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const double cx0 = (w.origin_ix + ix) * w.resolution, cy0 = (w.origin_iy + iy) * w.resolution;
      const double cx1 = cx0 + w.resolution, cy1 = cy0 + w.resolution;
      const double eps = 1e-9;
      if (cx1 <= x0 + eps || cx0 >= x1 - eps || cy1 <= y0 + eps || cy0 >= y1 - eps) continue;
      const size_t i = size_t(w.Index(ix, iy));
      fog->type[i] = type;
      fog->height[i] = height;
    }
  }
}

Fog CorridorWithTable() {
  Fog fog = FlatFog(80, 60, 0.04);
  FillBox(&fog, 0.0, 0.0, 3.2, 0.6, CellType::kObstacle, 0.5f);
  FillBox(&fog, 0.0, 1.8, 3.2, 2.4, CellType::kObstacle, 0.5f);
  FillBox(&fog, 1.4, 0.6, 2.0, 1.8, CellType::kTunnel, 0.0f);
  for (double x : {1.4, 1.96}) {
    for (double y : {0.6, 1.76}) {
      FillBox(&fog, x, y, x + 0.04, y + 0.04, CellType::kObstacle, 0.56f);
    }
  }
  return fog;
}

void ClassifyFloorChanges(Fog* fog, double h_floor, double h_stairs) {
  const perception::GridWindow& w = fog->window;
  auto floorish = [](CellType t) {
    return t == CellType::kFloor || t == CellType::kStairs || t == CellType::kBorder;
  };
  std::vector<CellType> out = fog->type;
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      if (!floorish(fog->TypeAt(ix, iy))) continue;
      const float h = fog->HeightAt(ix, iy);
      double delta = 0;
      for (int ny = iy - 1; ny <= iy + 1; ++ny) {
        for (int nx = ix - 1; nx <= ix + 1; ++nx) {
          if (!w.Contains(nx, ny) || !floorish(fog->TypeAt(nx, ny))) continue;
          if (!std::isfinite(fog->HeightAt(nx, ny))) continue;
          delta = std::max(delta, double(std::abs(fog->HeightAt(nx, ny) - h)));
        }
      }
      out[size_t(w.Index(ix, iy))] =
          delta < h_floor ? CellType::kFloor : delta < h_stairs ? CellType::kStairs : CellType::kBorder;
    }
  }
  fog->type = out;
}

Course PaperCourse() {
  perception::GridWindow w;  // 100 x 100 cells of 4 cm
  w.origin_ix = -3;
  w.origin_iy = -50;
  Course c;
  c.fog = Fog(w);
  const double x0 = -0.12, x1 = 3.88;
  // corridor floor, walls, unknown behind them
  FillBox(&c.fog, x0, -0.7, x1, 0.7, CellType::kFloor, 0.0f);
  FillBox(&c.fog, x0, 0.7, x1, 0.78, CellType::kObstacle, 0.40f);
  FillBox(&c.fog, x0, -0.78, x1, -0.7, CellType::kObstacle, 0.40f);
  // stairs of 3, 6, 3 cm across the corridor
  FillBox(&c.fog, 0.95, -0.7, 1.20, 0.7, CellType::kFloor, 0.03f);
  FillBox(&c.fog, 1.20, -0.7, 1.55, 0.7, CellType::kFloor, 0.06f);
  FillBox(&c.fog, 1.55, -0.7, 1.80, 0.7, CellType::kFloor, 0.03f);
  ClassifyFloorChanges(&c.fog, 0.015, 0.05);
  // two blocks, 8 cm and 20 cm, to walk between
  FillBox(&c.fog, 0.45, 0.12, 0.65, 0.32, CellType::kObstacle, 0.08f);
  FillBox(&c.fog, 0.45, -0.45, 0.65, -0.22, CellType::kObstacle, 0.20f);
  // a row of 20, 20 and 8 cm obstacles leaving a 0.22 m gap
  FillBox(&c.fog, 2.15, -0.7, 2.35, -0.11, CellType::kObstacle, 0.20f);
  FillBox(&c.fog, 2.15, 0.11, 2.35, 0.42, CellType::kObstacle, 0.20f);
  FillBox(&c.fog, 2.15, 0.42, 2.35, 0.7, CellType::kObstacle, 0.08f);
  // a table across the corridor: tunnel under the top, legs at the corners
  FillBox(&c.fog, 2.80, -0.7, 3.40, 0.7, CellType::kTunnel, 0.0f);
  for (double lx : {2.80, 3.36}) {
    for (double ly : {-0.70, 0.66}) FillBox(&c.fog, lx, ly, lx + 0.04, ly + 0.04, CellType::kObstacle, 0.56f);
  }
  c.start_G = {0.0, 0.0, 0.0};
  c.goal_G = {3.55, 0.0};
  return c;
}

}  // namespace fognav::navigation::internal

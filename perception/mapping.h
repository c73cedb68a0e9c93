// Environment maps of the paper's Section 5: 3D occupancy grid, floor height map and the
// Floor and Obstacle Grid (FOG). All maps live in the grid frame (the odometry frame).
#ifndef FOGNAV_PERCEPTION_MAPPING_H_
#define FOGNAV_PERCEPTION_MAPPING_H_

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "perception/types.h"

namespace fognav::perception {

// Environment type of a FOG cell (paper Section 5.4).
enum class CellType : uint8_t { kUnknown = 0, kFloor, kStairs, kBorder, kTunnel, kObstacle };
inline constexpr int kNumCellTypes = 6;

// Lower-case name of a cell type ("floor", "stairs", ...).
const char* CellTypeName(CellType type);

// A square 2D window of cells in the grid frame. Cell (ix, iy) covers
// [(origin_ix + ix) * resolution, (origin_ix + ix + 1) * resolution) in x, likewise in y, so
// scrolling the window by whole cells keeps world-fixed content on the same global cells.
struct GridWindow {
  int size_x = 100;          // cells along x
  int size_y = 100;          // cells along y
  double resolution = 0.04;  // cell side in metres
  int origin_ix = -50;       // global index of local cell (0, *) along x
  int origin_iy = -50;       // global index of local cell (*, 0) along y

  int NumCells() const { return size_x * size_y; }
  int Index(int ix, int iy) const { return iy * size_x + ix; }
  bool Contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < size_x && iy < size_y; }
  // Local cell holding grid-frame point (x, y); may lie outside the window.
  void CellOf(double x, double y, int* ix, int* iy) const {
    *ix = int(std::floor(x / resolution)) - origin_ix;
    *iy = int(std::floor(y / resolution)) - origin_iy;
  }
  // Grid-frame centre of local cell (ix, iy).
  Eigen::Vector2d CellCenter(int ix, int iy) const {
    return {(origin_ix + ix + 0.5) * resolution, (origin_iy + iy + 0.5) * resolution};
  }
};

// The Floor and Obstacle Grid: a type and a height per cell (eq. 17, 25). Heights are metres in
// the grid frame; -infinity for unknown cells.
struct Fog {
  GridWindow window;
  std::vector<CellType> type;  // window.NumCells() entries, indexed by window.Index(ix, iy)
  std::vector<float> height;   // same indexing

  Fog() = default;
  explicit Fog(const GridWindow& w)
      : window(w),
        type(size_t(w.NumCells()), CellType::kUnknown),
        height(size_t(w.NumCells()), -std::numeric_limits<float>::infinity()) {}
  CellType TypeAt(int ix, int iy) const { return type[size_t(window.Index(ix, iy))]; }
  float HeightAt(int ix, int iy) const { return height[size_t(window.Index(ix, iy))]; }
};

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_MAPPING_H_

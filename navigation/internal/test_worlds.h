// Hand-made FOGs for the planner's tests and benchmark: flat maps, boxes of a type and height,
// the paper's floor-change classification, and a 4 m course like the paper's Section 6.
#ifndef FOGNAV_NAVIGATION_INTERNAL_TEST_WORLDS_H_
#define FOGNAV_NAVIGATION_INTERNAL_TEST_WORLDS_H_

#include <Eigen/Core>

#include "perception/mapping.h"
#include "perception/types.h"

namespace fognav::navigation::internal {

// A size_x x size_y map of `resolution` cells whose cell (0, 0) starts at the grid origin, every
// cell of `type` at `height` metres.
perception::Fog FlatFog(int size_x, int size_y, double resolution,
                        perception::CellType type = perception::CellType::kFloor,
                        float height = 0.0f);

// Sets every cell that overlaps the open box (x0, x1) x (y0, y1) (grid frame, metres) to `type`
// at `height`, as a map marks any cell an object reaches into.
void FillBox(perception::Fog* fog, double x0, double y0, double x1, double y1,
             perception::CellType type, float height);

// The floor branch of the paper's classify (Section 5.4): every floor, stairs or border cell
// becomes floor, stairs or border by the largest height difference to its 8 neighbours of
// those types.
void ClassifyFloorChanges(perception::Fog* fog, double h_floor, double h_stairs);

// A 3.2 m x 2.4 m corridor of 4 cm cells (walls 0.5 m high at y < 0.6 and y >= 1.8) crossed
// by a table at x in [1.4, 2.0): tunnel cells with four 0.56 m corner legs.
perception::Fog CorridorWithTable();

// A FOG resembling the paper's course on a 100 x 100 window of 4 cm (x in [-0.12, 3.88),
// y in [-2, 2)): a 1.4 m corridor between walls with unknown space behind them; an 8 cm and a
// 20 cm block to walk between; stairs of 3, 6 and 3 cm across the corridor; a row of obstacles
// (20, 20 and 8 cm) leaving a 0.22 m gap; a table (tunnel with corner legs) across the corridor;
// the goal behind the table.
struct Course {
  perception::Fog fog;
  perception::Pose2 start_G;
  Eigen::Vector2d goal_G;
};
Course PaperCourse();

}  // namespace fognav::navigation::internal

#endif  // FOGNAV_NAVIGATION_INTERNAL_TEST_WORLDS_H_

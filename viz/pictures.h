// Pictures of fognav's data for people: camera frames, the maps in the paper's scheme with a
// legend, plans and whole missions, and the PNG and map_server files they are written to. The
// core libraries (perception, navigation) neither draw nor write files; this layer does.
#ifndef FOGNAV_VIZ_PICTURES_H_
#define FOGNAV_VIZ_PICTURES_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "navigation/planner.h"
#include "perception/mapping.h"
#include "perception/segmentation.h"
#include "perception/types.h"

namespace fognav::viz {

// The height scale every map picture shares, metres: grey from light (0) to dark (0.6 m and
// above), so one grey means one height in every picture.
inline constexpr double kHeightScaleMin = 0.0;
inline constexpr double kHeightScaleMax = 0.6;

// ---- camera frames ----

// The segment picture of the paper's Fig. 4-5: each plane a distinct colour, plane borders
// black, unsegmented pixels white.
perception::RgbImage DrawSegments(const perception::PlaneSet& planes);
// A disparity image in false colour (near = red, far = blue, scaled to its largest value),
// invalid (NaN) pixels black.
perception::RgbImage DrawDisparity(const perception::Image<float>& disparity_px);

// ---- maps ----

// The FOG in the paper's scheme: floor grey by height, stairs brown crosses over the grey,
// border solid brown, a cell with no floor under it (border without a height) lavender with
// a hatch, tunnel red "+" over the grey, obstacle black with a grey cross, unknown background;
// +x to the right, +y up; the robot (position and heading) on top. The map fills the top-left
// size_x * pixels_per_cell columns and size_y * pixels_per_cell rows (see CellPixel); below it
// a legend of the types, the height scale (kHeightScaleMin..Max) and a metre scale.
perception::RgbImage DrawFog(const perception::Fog& fog, const perception::Pose2& robot_G,
                             int pixels_per_cell = 6);
// Where the FOG `estimate` differs from `truth` (perception::CompareFog): each observed cell
// coloured by its comparison (right light grey, right nearby pale green, standable edge orange,
// wrong height yellow, wrong class blue, unsafe red with a black cross), the robot in dark grey;
// below, a legend with the cell counts and a metre scale.
perception::RgbImage DrawFogErrors(const perception::Fog& estimate, const perception::Fog& truth,
                                   const perception::FogParams& params,
                                   const perception::Pose2& robot_G, int pixels_per_cell = 6);
// The floor height map in grey (the shared scale), cells without a floor in the background
// colour; the legend and metre scale below.
perception::RgbImage DrawFloorMap(const perception::MapState& state, int pixels_per_cell = 6);
// Side views of the 3D grid: occupied layers projected along y (x-z, top) and along x (y-z,
// bottom), darker where more cells of the column are occupied, free seen white; each view with
// labelled axes in metres (grid frame) and a legend.
perception::RgbImage DrawGridSideViews(const perception::MapState& state, double p_occ,
                                       int pixels_per_cell = 6);

// ---- plans ----

// Pixel of the centre of FOG cell (ix, iy) in a map picture with `px_per_cell` pixels per cell:
// x to the right, y up (row 0 holds the cells of largest iy).
Eigen::Vector2i CellPixel(const perception::GridWindow& window, int px_per_cell, int ix, int iy);
// Colour (r, g, b) of a move in every picture: walk blue, sidestep magenta, turn cyan, stairs
// orange, crawl red; anything else (none, look) grey.
perception::Rgb MoveColour(navigation::Move move);
// Draws the path onto a map picture of the window such as DrawFog's (the map in the top-left
// size_x * px_per_cell columns and size_y * px_per_cell rows; the rest is left alone): a
// polyline coloured by move with a heading tick at each pose and the start as a green square;
// what falls outside the map is clipped. Aborts if the picture is smaller than the map.
void DrawPath(const navigation::PlanResult& plan, const perception::GridWindow& window,
              int px_per_cell, perception::RgbImage* picture);
// Marks the goal on a map picture (a yellow-ringed cross); clipped if it is outside the window.
void DrawGoal(const Eigen::Vector2d& goal_G, const perception::GridWindow& window, int px_per_cell,
              perception::RgbImage* picture);
// The map picture of a plan: DrawFog with the path and the goal drawn on top and the moves
// added to the legend.
perception::RgbImage DrawPlanPicture(const perception::Fog& fog, const perception::Pose2& robot_G,
                                     const navigation::PlanResult& plan,
                                     const Eigen::Vector2d& goal_G, int pixels_per_cell = 6);

// ---- missions ----

// One logged step of a mission (trajectory.csv): the true and the believed (odometry) pose in
// the world frame and the move that made the step ("walk", ... as navigation::MoveName, or
// "look").
struct TrackPoint {
  perception::Pose2 true_W;
  perception::Pose2 believed_W;
  std::string move;
};

// The whole floor of a mission: `floor_fog` (the ground-truth FOG of the whole floor, world
// frame) with the optimal path on it as a thin dark green line, the true trajectory coloured by
// the move that made each step, the believed trajectory as a thin black dashed line, the start
// (green square) and the goal; the legend lists the FOG types, moves and lines, with the
// height and metre scales.
perception::RgbImage DrawMissionMap(const perception::Fog& floor_fog,
                                    const navigation::PlanResult& optimal,
                                    const perception::Pose2& start_W, const Eigen::Vector2d& goal_W,
                                    const std::vector<TrackPoint>& track, int pixels_per_cell = 6);

// ---- files ----

// Writes an RGB image as PNG. Throws perception::OutputError naming the path if it cannot.
void WritePng(const perception::RgbImage& image, const std::string& path);
// The types of `fog` as a map_server image (row 0 the highest y; grey values as in fog.yaml).
// Throws perception::OutputError naming the file if it cannot be written.
void WriteFogTypes(const std::string& path, const perception::Fog& fog);
// Writes into `dir` (created if needed): fog.png, floor.png, grid_side.png (pictures above);
// fog_types.png + fog.yaml (ROS map_server: resolution, origin, trinary mode, and a
// `fognav_types` legend of the grey value of each type: floor 254, stairs 190, tunnel 160,
// unknown 205, border 40, obstacle 0 — so map_server reads floor free, border and obstacle
// occupied, the rest unknown); fog_heights.png (16-bit, value = 1000 + height in millimetres,
// clamped to [1, 65535], 0 where the height is -infinity). Throws perception::OutputError naming
// the file if one cannot be written.
void WriteMapPictures(const std::string& dir, const perception::Fog& fog,
                      const perception::MapState& state, const perception::MapParams& params,
                      const perception::Pose2& robot_G);

}  // namespace fognav::viz

#endif  // FOGNAV_VIZ_PICTURES_H_

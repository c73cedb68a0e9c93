// Drawing helpers every picture of viz shares: the colours of the FOG types, the shared height
// scale, and the legend rows, scales and axes drawn under or beside a map. Images are OpenCV
// 8-bit 3-channel matrices in r, g, b order (as perception::Rgb), so colours read as (r, g, b).
#ifndef FOGNAV_VIZ_INTERNAL_CANVAS_H_
#define FOGNAV_VIZ_INTERNAL_CANVAS_H_

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "perception/mapping.h"
#include "perception/types.h"

namespace fognav::viz::internal {

// colours (r, g, b)
inline const cv::Scalar kBackground(225, 235, 245);  // unknown: pale blue
inline const cv::Scalar kPaper(255, 255, 255);       // legend panel
inline const cv::Scalar kBrown(139, 69, 19);
inline const cv::Scalar kNoFloor(190, 175, 220);  // no floor under the cell: lavender
inline const cv::Scalar kNoFloorHatch(105, 75, 150);
inline const cv::Scalar kBlack(0, 0, 0);
inline const cv::Scalar kRed(220, 40, 40);
inline const cv::Scalar kText(30, 30, 30);
inline const cv::Scalar kStartGreen(0, 170, 0);
inline const cv::Scalar kGoalYellow(255, 200, 0);
inline const cv::Scalar kOptimalGreen(0, 110, 40);

// Legend rows are this many pixels high; a picture with a legend is at least kLegendWidth wide.
inline constexpr int kRowHeight = 22;
inline constexpr int kLegendWidth = 660;

// Grey of a height on the shared scale (viz::kHeightScaleMin..Max): light low, dark high.
cv::Scalar HeightGrey(double height);
// Draws one FOG cell of the given type and height with its top-left pixel at p0.
void DrawCell(cv::Mat* img, perception::CellType type, float height, cv::Point p0, int ppc);
// A canvas for a map of map_w x map_h pixels in the top-left (background colour) with
// `legend_rows` legend rows below it (white), at least kLegendWidth wide.
cv::Mat NewMapCanvas(int map_w, int map_h, int legend_rows);
// Text in the pictures' font at baseline-left `at`.
void Text(cv::Mat* img, const std::string& text, cv::Point at, double scale = 0.4,
          const cv::Scalar& colour = kText);

// Legend rows, each drawn at row top y and returning the next free x (or nothing):
// the FOG types (floor, stairs, border, no floor, tunnel, obstacle, unknown).
void DrawFogTypesRow(cv::Mat* img, int y);
// The height scale as a grey bar with ticks every 10 cm, then a bar of one metre (or half a
// metre if the map is narrow) at `px_per_metre`.
void DrawScalesRow(cv::Mat* img, int y, double px_per_metre);
// A metre bar (1 m, or 0.5 m if that does not fit) at `px_per_metre` from x on the row at top y;
// returns the next free x.
int DrawMetreScale(cv::Mat* img, int x, int y, double px_per_metre);
// A row's title at its left end; returns the next free x.
int DrawRowTitle(cv::Mat* img, const std::string& title, int y);
// A filled swatch of `colour` and its label from x on the row at top y; returns the next free x.
int DrawSwatch(cv::Mat* img, const cv::Scalar& colour, const std::string& label, int x, int y);
// The moves' colours (walk, sidestep, turn, stairs up/down, crawl) and the start, goal and
// robot marks.
void DrawMovesRow(cv::Mat* img, int y);
// Line samples with labels: the true path (coloured by move), the believed path (black dashed)
// and the optimal path (dark green).
void DrawTracksRow(cv::Mat* img, int y);

// A dashed polyline (dash and gap `dash` pixels), anti-aliased.
void DashedPolyline(cv::Mat* img, const std::vector<cv::Point2d>& points, const cv::Scalar& colour,
                    int thickness, double dash);
// The robot's mark: a ring with a heading line (red unless said), centre c (pixels), yaw in the
// picture's +x right, +y up convention.
void DrawRobot(cv::Mat* img, cv::Point2d c, double yaw, int radius,
               const cv::Scalar& colour = kRed);
// The goal's mark: a yellow ring with a cross.
void DrawGoalMark(cv::Mat* img, cv::Point2d c, int radius, int thickness);
// The start's mark: a green square with a heading line.
void DrawStartMark(cv::Mat* img, cv::Point2d c, double yaw, int half, int thickness);

// The whole canvas as an RgbImage (the matrix is in r, g, b order already).
perception::RgbImage ToRgbImage(const cv::Mat& rgb);

}  // namespace fognav::viz::internal

#endif  // FOGNAV_VIZ_INTERNAL_CANVAS_H_

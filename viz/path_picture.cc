// Plans and missions drawn over the map pictures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "viz/internal/canvas.h"
#include "viz/pictures.h"

namespace fognav::viz {
namespace {

using navigation::Move;
using perception::GridWindow;
using perception::RgbImage;
using namespace internal;

void CheckPicture(const GridWindow& window, int px_per_cell, const RgbImage& picture) {
  if (px_per_cell <= 0 || picture.width < window.size_x * px_per_cell ||
      picture.height < window.size_y * px_per_cell ||
      picture.data.size() != size_t(picture.width) * size_t(picture.height)) {
    std::fprintf(stderr,
                 "fognav::viz: map picture is %dx%d, expected at least %dx%d for %d px per cell\n",
                 picture.width, picture.height, window.size_x * px_per_cell,
                 window.size_y * px_per_cell, px_per_cell);
    std::abort();
  }
}

// the map part of the picture's pixels as an OpenCV image, so drawing clips to it
cv::Mat Wrap(const GridWindow& window, int px_per_cell, RgbImage* picture) {
  const cv::Mat all(picture->height, picture->width, CV_8UC3, picture->data.data());
  return all(cv::Rect(0, 0, window.size_x * px_per_cell, window.size_y * px_per_cell));
}

// sub-pixel position of a grid-frame point in the picture
cv::Point2d PointPixel(const GridWindow& window, int px_per_cell, double x, double y) {
  const double fx = x / window.resolution - window.origin_ix;  // cells from the left edge
  const double fy = y / window.resolution - window.origin_iy;  // cells from the bottom edge
  return {fx * px_per_cell, (window.size_y - fy) * px_per_cell};
}

cv::Scalar Scalar(const perception::Rgb& c) { return cv::Scalar(c.r, c.g, c.b); }

Move MoveNamed(const std::string& name) {
  for (int m = 0; m < navigation::kNumMoves; ++m) {
    if (name == navigation::MoveName(Move(m))) return Move(m);
  }
  return Move::kNone;
}

constexpr int kShift = 4;  // sub-pixel bits for smooth lines
cv::Point Fixed(const cv::Point2d& q) {
  return cv::Point(int(std::lround(q.x * (1 << kShift))), int(std::lround(q.y * (1 << kShift))));
}

// the picture with `rows` more legend rows (white) at its bottom
cv::Mat WithRows(const RgbImage& picture, int rows) {
  cv::Mat img(picture.height + rows * kRowHeight, picture.width, CV_8UC3, kPaper);
  const cv::Mat old(picture.height, picture.width, CV_8UC3,
                    const_cast<perception::Rgb*>(picture.data.data()));
  old.copyTo(img(cv::Rect(0, 0, picture.width, picture.height)));
  return img;
}

}  // namespace

perception::Rgb MoveColour(Move move) {
  switch (move) {
    case Move::kWalk:
      return {40, 90, 230};
    case Move::kSidestep:
      return {220, 40, 220};
    case Move::kTurn:
      return {0, 200, 220};
    case Move::kStairsUp:
    case Move::kStairsDown:
      return {255, 140, 0};
    case Move::kCrawl:
      return {230, 20, 20};
    case Move::kNone:
      break;
  }
  return {130, 130, 130};
}

Eigen::Vector2i CellPixel(const GridWindow& window, int px_per_cell, int ix, int iy) {
  return {ix * px_per_cell + px_per_cell / 2,
          (window.size_y - 1 - iy) * px_per_cell + px_per_cell / 2};
}

void DrawPath(const navigation::PlanResult& plan, const GridWindow& window, int px_per_cell,
              RgbImage* picture) {
  CheckPicture(window, px_per_cell, *picture);
  if (plan.path.empty()) return;
  cv::Mat image = Wrap(window, px_per_cell, picture);
  const int thickness = std::max(1, px_per_cell / 3);
  // segments coloured by the move that makes them
  for (size_t i = 1; i < plan.path.size(); ++i) {
    const perception::Pose2& a = plan.path[i - 1].pose_G;
    const perception::Pose2& b = plan.path[i].pose_G;
    cv::line(image, Fixed(PointPixel(window, px_per_cell, a.x, a.y)),
             Fixed(PointPixel(window, px_per_cell, b.x, b.y)),
             Scalar(MoveColour(plan.path[i].move)), thickness, cv::LINE_AA, kShift);
  }
  // heading ticks, every pose
  const double tick = 0.6 * px_per_cell;
  for (size_t i = 1; i < plan.path.size(); ++i) {
    const perception::Pose2& q = plan.path[i].pose_G;
    const cv::Point2d c = PointPixel(window, px_per_cell, q.x, q.y);
    const cv::Point2d tip = c + cv::Point2d(tick * std::cos(q.yaw), -tick * std::sin(q.yaw));
    cv::line(image, Fixed(c), Fixed(tip), Scalar(MoveColour(plan.path[i].move)), 1, cv::LINE_AA,
             kShift);
  }
  const perception::Pose2& s = plan.path.front().pose_G;
  DrawStartMark(&image, PointPixel(window, px_per_cell, s.x, s.y), s.yaw, std::max(2, px_per_cell),
                thickness);
}

void DrawGoal(const Eigen::Vector2d& goal_G, const GridWindow& window, int px_per_cell,
              RgbImage* picture) {
  CheckPicture(window, px_per_cell, *picture);
  cv::Mat image = Wrap(window, px_per_cell, picture);
  DrawGoalMark(&image, PointPixel(window, px_per_cell, goal_G.x(), goal_G.y()),
               std::max(3, 2 * px_per_cell), std::max(1, px_per_cell / 3));
}

RgbImage DrawPlanPicture(const perception::Fog& fog, const perception::Pose2& robot_G,
                         const navigation::PlanResult& plan, const Eigen::Vector2d& goal_G,
                         int px_per_cell) {
  // DrawFog uses at least 2 pixels per cell
  px_per_cell = std::max(px_per_cell, 2);
  RgbImage picture = DrawFog(fog, robot_G, px_per_cell);
  DrawPath(plan, fog.window, px_per_cell, &picture);
  DrawGoal(goal_G, fog.window, px_per_cell, &picture);
  cv::Mat img = WithRows(picture, 1);
  DrawMovesRow(&img, picture.height - 4);
  return ToRgbImage(img);
}

RgbImage DrawMissionMap(const perception::Fog& floor_fog, const navigation::PlanResult& optimal,
                        const perception::Pose2& start_W, const Eigen::Vector2d& goal_W,
                        const std::vector<TrackPoint>& track, int px_per_cell) {
  px_per_cell = std::max(px_per_cell, 2);
  const GridWindow& w = floor_fog.window;
  // the map without a robot: the marks below say where it went
  RgbImage base = DrawFog(floor_fog, start_W, px_per_cell);
  cv::Mat img = WithRows(base, 2);
  {
    // DrawFog's robot mark is covered by redrawing the cells under it
    cv::Mat map = img(cv::Rect(0, 0, w.size_x * px_per_cell, w.size_y * px_per_cell));
    for (int iy = 0; iy < w.size_y; ++iy) {
      for (int ix = 0; ix < w.size_x; ++ix) {
        DrawCell(&map, floor_fog.TypeAt(ix, iy), floor_fog.HeightAt(ix, iy),
                 {ix * px_per_cell, (w.size_y - 1 - iy) * px_per_cell}, px_per_cell);
      }
    }
  }
  cv::Mat map = img(cv::Rect(0, 0, w.size_x * px_per_cell, w.size_y * px_per_cell));
  auto pixel = [&](const perception::Pose2& p) { return PointPixel(w, px_per_cell, p.x, p.y); };
  // the optimal path, thin, under the robot's ways
  for (size_t i = 1; i < optimal.path.size(); ++i) {
    cv::line(map, Fixed(pixel(optimal.path[i - 1].pose_G)), Fixed(pixel(optimal.path[i].pose_G)),
             kOptimalGreen, 2, cv::LINE_AA, kShift);
  }
  // the true way, each step coloured by its move
  const int thickness = std::max(2, px_per_cell / 2);
  perception::Pose2 from = start_W;
  for (const TrackPoint& t : track) {
    cv::line(map, Fixed(pixel(from)), Fixed(pixel(t.true_W)), Scalar(MoveColour(MoveNamed(t.move))),
             thickness, cv::LINE_AA, kShift);
    from = t.true_W;
  }
  // the believed way, dashed on top
  std::vector<cv::Point2d> believed{pixel(start_W)};
  for (const TrackPoint& t : track) believed.push_back(pixel(t.believed_W));
  DashedPolyline(&map, believed, kBlack, 1, 4);
  DrawStartMark(&map, pixel(start_W), start_W.yaw, std::max(3, px_per_cell), 2);
  DrawGoalMark(&map, PointPixel(w, px_per_cell, goal_W.x(), goal_W.y()),
               std::max(3, 2 * px_per_cell), 2);
  if (!track.empty()) {
    DrawRobot(&map, pixel(track.back().true_W), track.back().true_W.yaw, std::max(4, px_per_cell));
  }
  DrawMovesRow(&img, base.height - 4);
  DrawTracksRow(&img, base.height - 4 + kRowHeight);
  return ToRgbImage(img);
}

}  // namespace fognav::viz

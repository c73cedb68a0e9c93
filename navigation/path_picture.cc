#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "navigation/planner.h"

namespace fognav::navigation {
namespace {

using perception::RgbImage;

void CheckPicture(const perception::GridWindow& window, int px_per_cell, const RgbImage& picture) {
  if (px_per_cell <= 0 || picture.width < window.size_x * px_per_cell ||
      picture.height != window.size_y * px_per_cell ||
      picture.data.size() != size_t(picture.width) * size_t(picture.height)) {
    std::fprintf(stderr,
                 "fognav::navigation: map picture is %dx%d, expected at least %d wide and %d high "
                 "for %d px per cell\n",
                 picture.width, picture.height, window.size_x * px_per_cell,
                 window.size_y * px_per_cell, px_per_cell);
    std::abort();
  }
}

// the map part of the picture's pixels as an OpenCV image, so drawing clips to it (channel
// order r, g, b; colours are given that way)
cv::Mat Wrap(const perception::GridWindow& window, int px_per_cell, RgbImage* picture) {
  const cv::Mat all(picture->height, picture->width, CV_8UC3, picture->data.data());
  return all(cv::Rect(0, 0, window.size_x * px_per_cell, window.size_y * px_per_cell));
}

// sub-pixel position of a grid-frame point in the picture
cv::Point2d PointPixel(const perception::GridWindow& window, int px_per_cell, double x, double y) {
  const double fx = x / window.resolution - window.origin_ix;  // cells from the left edge
  const double fy = y / window.resolution - window.origin_iy;  // cells from the bottom edge
  return {fx * px_per_cell, (window.size_y - fy) * px_per_cell};
}

cv::Scalar MoveColor(Move move) {
  switch (move) {
    case Move::kWalk: return {40, 90, 230};
    case Move::kSidestep: return {220, 40, 220};
    case Move::kTurn: return {0, 200, 220};
    case Move::kStairsUp:
    case Move::kStairsDown: return {255, 140, 0};
    case Move::kCrawl: return {230, 20, 20};
    case Move::kNone: break;
  }
  return {40, 90, 230};
}

}  // namespace

Eigen::Vector2i CellPixel(const perception::GridWindow& window, int px_per_cell, int ix, int iy) {
  return {ix * px_per_cell + px_per_cell / 2, (window.size_y - 1 - iy) * px_per_cell + px_per_cell / 2};
}

void DrawPath(const PlanResult& plan, const perception::GridWindow& window, int px_per_cell,
              RgbImage* picture) {
  CheckPicture(window, px_per_cell, *picture);
  if (plan.path.empty()) return;
  cv::Mat image = Wrap(window, px_per_cell, picture);
  const int thickness = std::max(1, px_per_cell / 3);
  const int shift = 4;  // sub-pixel bits for smooth lines
  auto fixed = [&](const cv::Point2d& q) {
    return cv::Point(int(std::lround(q.x * (1 << shift))), int(std::lround(q.y * (1 << shift))));
  };
  // segments coloured by the move that makes them
  for (size_t i = 1; i < plan.path.size(); ++i) {
    const perception::Pose2& a = plan.path[i - 1].pose_G;
    const perception::Pose2& b = plan.path[i].pose_G;
    cv::line(image, fixed(PointPixel(window, px_per_cell, a.x, a.y)),
             fixed(PointPixel(window, px_per_cell, b.x, b.y)), MoveColor(plan.path[i].move),
             thickness, cv::LINE_AA, shift);
  }
  // heading ticks, every pose
  const double tick = 0.6 * px_per_cell;
  for (size_t i = 1; i < plan.path.size(); ++i) {
    const perception::Pose2& q = plan.path[i].pose_G;
    const cv::Point2d c = PointPixel(window, px_per_cell, q.x, q.y);
    const cv::Point2d tip = c + cv::Point2d(tick * std::cos(q.yaw), -tick * std::sin(q.yaw));
    cv::line(image, fixed(c), fixed(tip), MoveColor(plan.path[i].move), 1, cv::LINE_AA, shift);
  }
  // the start
  const perception::Pose2& s = plan.path.front().pose_G;
  const cv::Point2d c = PointPixel(window, px_per_cell, s.x, s.y);
  const int half = std::max(2, px_per_cell);
  cv::rectangle(image, cv::Point(int(c.x) - half, int(c.y) - half),
                cv::Point(int(c.x) + half, int(c.y) + half), cv::Scalar(0, 170, 0), cv::FILLED);
  const cv::Point2d tip = c + cv::Point2d(2.0 * half * std::cos(s.yaw), -2.0 * half * std::sin(s.yaw));
  cv::line(image, fixed(c), fixed(tip), cv::Scalar(0, 170, 0), thickness, cv::LINE_AA, shift);
}

void DrawGoal(const Eigen::Vector2d& goal_G, const perception::GridWindow& window, int px_per_cell,
              RgbImage* picture) {
  CheckPicture(window, px_per_cell, *picture);
  cv::Mat image = Wrap(window, px_per_cell, picture);
  const cv::Point2d c = PointPixel(window, px_per_cell, goal_G.x(), goal_G.y());
  const int r = std::max(3, 2 * px_per_cell);
  const cv::Point p(int(std::lround(c.x)), int(std::lround(c.y)));
  cv::circle(image, p, r, cv::Scalar(255, 220, 0), std::max(1, px_per_cell / 3), cv::LINE_AA);
  cv::line(image, p - cv::Point(r, 0), p + cv::Point(r, 0), cv::Scalar(255, 220, 0), 1);
  cv::line(image, p - cv::Point(0, r), p + cv::Point(0, r), cv::Scalar(255, 220, 0), 1);
}

RgbImage DrawPlanPicture(const perception::Fog& fog, const perception::Pose2& robot_G,
                         const PlanResult& plan, const Eigen::Vector2d& goal_G, int px_per_cell) {
  // DrawFog uses at least 2 pixels per cell
  px_per_cell = std::max(px_per_cell, 2);
  RgbImage picture = perception::DrawFog(fog, robot_G, px_per_cell);
  DrawPath(plan, fog.window, px_per_cell, &picture);
  DrawGoal(goal_G, fog.window, px_per_cell, &picture);
  return picture;
}

}  // namespace fognav::navigation

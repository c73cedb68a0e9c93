#include "viz/internal/canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "navigation/planner.h"
#include "viz/pictures.h"

namespace fognav::viz::internal {

using perception::CellType;

cv::Scalar HeightGrey(double height) {
  const double t =
      std::clamp((height - kHeightScaleMin) / (kHeightScaleMax - kHeightScaleMin), 0.0, 1.0);
  const double g = 240.0 - t * 180.0;
  return cv::Scalar(g, g, g);
}

void DrawCell(cv::Mat* img, CellType type, float height, cv::Point p0, int ppc) {
  const cv::Point p1 = p0 + cv::Point(ppc - 1, ppc - 1);
  const cv::Point mid = p0 + cv::Point(ppc / 2, ppc / 2);
  switch (type) {
    case CellType::kUnknown:
      cv::rectangle(*img, p0, p1, kBackground, cv::FILLED);
      break;
    case CellType::kFloor:
      cv::rectangle(*img, p0, p1, HeightGrey(height), cv::FILLED);
      break;
    case CellType::kStairs:
      cv::rectangle(*img, p0, p1, HeightGrey(height), cv::FILLED);
      cv::line(*img, p0, p1, kBrown);
      cv::line(*img, {p0.x, p1.y}, {p1.x, p0.y}, kBrown);
      break;
    case CellType::kBorder:
      if (std::isfinite(height)) {
        cv::rectangle(*img, p0, p1, kBrown, cv::FILLED);
      } else {
        // no floor under the cell: its own mark, a hatch rising to the right
        cv::rectangle(*img, p0, p1, kNoFloor, cv::FILLED);
        cv::line(*img, {p0.x, p1.y}, {p1.x, p0.y}, kNoFloorHatch);
      }
      break;
    case CellType::kTunnel:
      cv::rectangle(*img, p0, p1, HeightGrey(height), cv::FILLED);
      cv::line(*img, {p0.x, mid.y}, {p1.x, mid.y}, kRed);
      cv::line(*img, {mid.x, p0.y}, {mid.x, p1.y}, kRed);
      break;
    case CellType::kObstacle: {
      // black with a cross whose grey is the obstacle's height on the shared scale
      cv::rectangle(*img, p0, p1, kBlack, cv::FILLED);
      const cv::Scalar cross = HeightGrey(height);
      cv::line(*img, p0, p1, cross);
      cv::line(*img, {p0.x, p1.y}, {p1.x, p0.y}, cross);
      break;
    }
  }
}

cv::Mat NewMapCanvas(int map_w, int map_h, int legend_rows) {
  const int width = std::max(map_w, kLegendWidth);
  const int legend_h = legend_rows > 0 ? legend_rows * kRowHeight + 8 : 0;
  cv::Mat img(map_h + legend_h, width, CV_8UC3, kPaper);
  img(cv::Rect(0, 0, map_w, map_h)).setTo(kBackground);
  return img;
}

void Text(cv::Mat* img, const std::string& text, cv::Point at, double scale,
          const cv::Scalar& colour) {
  cv::putText(*img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

namespace {

constexpr int kSwatch = 12;  // legend swatch side, pixels

// a label after a swatch; returns the x after it
int Label(cv::Mat* img, const std::string& text, int x, int y) {
  Text(img, text, {x, y + kSwatch - 2});
  int baseline = 0;
  return x + cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &baseline).width + 12;
}

}  // namespace

void DrawFogTypesRow(cv::Mat* img, int y) {
  y += 5;
  int x = Label(img, "FOG:", 6, y);
  struct Item {
    CellType type;
    float height;
    const char* label;
  };
  const float no_height = -std::numeric_limits<float>::infinity();
  const Item items[] = {
      {CellType::kFloor, 0.0f, "floor"},         {CellType::kStairs, 0.03f, "stairs"},
      {CellType::kBorder, 0.1f, "border"},       {CellType::kBorder, no_height, "no floor"},
      {CellType::kTunnel, 0.0f, "tunnel"},       {CellType::kObstacle, 0.3f, "obstacle"},
      {CellType::kUnknown, no_height, "unknown"}};
  for (const Item& item : items) {
    DrawCell(img, item.type, item.height, {x, y}, kSwatch);
    cv::rectangle(*img, {x, y}, {x + kSwatch - 1, y + kSwatch - 1}, cv::Scalar(150, 150, 150));
    x = Label(img, item.label, x + kSwatch + 4, y);
  }
}

void DrawScalesRow(cv::Mat* img, int y, double px_per_metre) {
  y += 5;
  int x = Label(img, "height:", 6, y);
  // the shared height scale, 0-60 cm, ticks every 10 cm
  const int bar_w = 240;
  for (int i = 0; i < bar_w; ++i) {
    const double h = kHeightScaleMin + (kHeightScaleMax - kHeightScaleMin) * i / (bar_w - 1);
    cv::line(*img, {x + i, y}, {x + i, y + 7}, HeightGrey(h));
  }
  cv::rectangle(*img, {x, y}, {x + bar_w - 1, y + 7}, cv::Scalar(130, 130, 130));
  const int ticks = int(std::lround((kHeightScaleMax - kHeightScaleMin) / 0.1));
  for (int k = 0; k <= ticks; ++k) {
    const int tx = x + (bar_w - 1) * k / ticks;
    cv::line(*img, {tx, y + 7}, {tx, y + 10}, kText);
    char label[16];
    std::snprintf(label, sizeof(label), "%d", int(std::lround(100 * (kHeightScaleMin + 0.1 * k))));
    Text(img, label, {tx - 6, y + 19}, 0.3);
  }
  x = Label(img, "cm", x + bar_w + 6, y);
  DrawMetreScale(img, x, y - 5, px_per_metre);
}

int DrawMetreScale(cv::Mat* img, int x, int y, double px_per_metre) {
  y += 5;
  // 1 m, or 0.5 m if that does not fit
  double metres = 1.0;
  if (px_per_metre * metres > img->cols - x - 60) metres = 0.5;
  const int len = int(std::lround(px_per_metre * metres));
  x += 10;
  cv::rectangle(*img, {x, y + 2}, {x + len, y + 6}, kText, cv::FILLED);
  cv::rectangle(*img, {x + len / 2, y + 3}, {x + len - 1, y + 5}, kPaper, cv::FILLED);
  return Label(img, metres == 1.0 ? "1 m" : "0.5 m", x + len + 6, y);
}

int DrawSwatch(cv::Mat* img, const cv::Scalar& colour, const std::string& label, int x, int y) {
  y += 5;
  cv::rectangle(*img, {x, y}, {x + kSwatch - 1, y + kSwatch - 1}, colour, cv::FILLED);
  cv::rectangle(*img, {x, y}, {x + kSwatch - 1, y + kSwatch - 1}, cv::Scalar(150, 150, 150));
  return Label(img, label, x + kSwatch + 4, y);
}

int DrawRowTitle(cv::Mat* img, const std::string& title, int y) { return Label(img, title, 6, y + 5); }

void DrawMovesRow(cv::Mat* img, int y) {
  y += 5;
  int x = Label(img, "moves:", 6, y);
  using navigation::Move;
  for (Move move : {Move::kWalk, Move::kSidestep, Move::kTurn, Move::kStairsUp, Move::kCrawl}) {
    const perception::Rgb c = MoveColour(move);
    cv::rectangle(*img, {x, y + 3}, {x + 16, y + 7}, cv::Scalar(c.r, c.g, c.b), cv::FILLED);
    x = Label(img, move == Move::kStairsUp ? "stairs" : navigation::MoveName(move), x + 20, y);
  }
  DrawStartMark(img, {x + 6.0, y + 6.0}, 0.0, 4, 1);
  x = Label(img, "start", x + 18, y);
  DrawGoalMark(img, {x + 6.0, y + 6.0}, 6, 1);
  x = Label(img, "goal", x + 16, y);
  DrawRobot(img, {x + 6.0, y + 6.0}, 0.0, 5);
  Label(img, "robot", x + 20, y);
}

void DrawTracksRow(cv::Mat* img, int y) {
  y += 5;
  int x = Label(img, "ways:", 6, y);
  const perception::Rgb walk = MoveColour(navigation::Move::kWalk);
  cv::line(*img, {x, y + 6}, {x + 24, y + 6}, cv::Scalar(walk.r, walk.g, walk.b), 3, cv::LINE_AA);
  x = Label(img, "true (coloured by move)", x + 28, y);
  DashedPolyline(img, {{double(x), y + 6.0}, {x + 24.0, y + 6.0}}, kBlack, 1, 4);
  x = Label(img, "believed (odometry)", x + 28, y);
  cv::line(*img, {x, y + 6}, {x + 24, y + 6}, kOptimalGreen, 2, cv::LINE_AA);
  Label(img, "optimal (ground truth)", x + 28, y);
}

void DashedPolyline(cv::Mat* img, const std::vector<cv::Point2d>& points, const cv::Scalar& colour,
                    int thickness, double dash) {
  double phase = 0;  // length drawn along the current dash or gap
  bool on = true;
  for (size_t i = 1; i < points.size(); ++i) {
    cv::Point2d a = points[i - 1];
    const cv::Point2d b = points[i];
    double left = cv::norm(b - a);
    while (left > 1e-9) {
      const double piece = std::min(left, dash - phase);
      const cv::Point2d c = a + (b - a) * (piece / left);
      if (on) {
        cv::line(*img, cv::Point(int(std::lround(a.x)), int(std::lround(a.y))),
                 cv::Point(int(std::lround(c.x)), int(std::lround(c.y))), colour, thickness,
                 cv::LINE_AA);
      }
      phase += piece;
      left -= piece;
      a = c;
      if (phase >= dash - 1e-9) {
        phase = 0;
        on = !on;
      }
    }
  }
}

void DrawRobot(cv::Mat* img, cv::Point2d c, double yaw, int radius, const cv::Scalar& colour) {
  const cv::Point centre(int(std::lround(c.x)), int(std::lround(c.y)));
  const cv::Point tip(int(std::lround(c.x + 2.2 * radius * std::cos(yaw))),
                      int(std::lround(c.y - 2.2 * radius * std::sin(yaw))));
  cv::circle(*img, centre, radius, colour, 2, cv::LINE_AA);
  cv::line(*img, centre, tip, colour, 2, cv::LINE_AA);
}

void DrawGoalMark(cv::Mat* img, cv::Point2d c, int radius, int thickness) {
  const cv::Point p(int(std::lround(c.x)), int(std::lround(c.y)));
  cv::circle(*img, p, radius, kGoalYellow, thickness, cv::LINE_AA);
  cv::line(*img, p - cv::Point(radius, 0), p + cv::Point(radius, 0), kGoalYellow, 1);
  cv::line(*img, p - cv::Point(0, radius), p + cv::Point(0, radius), kGoalYellow, 1);
}

void DrawStartMark(cv::Mat* img, cv::Point2d c, double yaw, int half, int thickness) {
  const cv::Point p(int(std::lround(c.x)), int(std::lround(c.y)));
  cv::rectangle(*img, p - cv::Point(half, half), p + cv::Point(half, half), kStartGreen,
                cv::FILLED);
  const cv::Point tip(int(std::lround(c.x + 2.0 * half * std::cos(yaw))),
                      int(std::lround(c.y - 2.0 * half * std::sin(yaw))));
  cv::line(*img, p, tip, kStartGreen, thickness, cv::LINE_AA);
}

perception::RgbImage ToRgbImage(const cv::Mat& rgb) {
  perception::RgbImage out(rgb.cols, rgb.rows);
  for (int v = 0; v < rgb.rows; ++v) {
    for (int u = 0; u < rgb.cols; ++u) {
      const cv::Vec3b p = rgb.at<cv::Vec3b>(v, u);
      out.at(u, v) = perception::Rgb{p[0], p[1], p[2]};
    }
  }
  return out;
}

}  // namespace fognav::viz::internal

// Pictures of the maps in the paper's scheme (Fig. 9, 12-15) with a legend, and the map files.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/mapping.h"
#include "viz/internal/canvas.h"
#include "viz/pictures.h"

namespace fognav::viz {
namespace {

using perception::CellType;
using perception::Fog;
using perception::GridWindow;
using perception::MapState;
using perception::RgbImage;
using namespace internal;

// Top-left pixel of local cell (ix, iy) in an image with +y up.
cv::Point CellCorner(const GridWindow& w, int ix, int iy, int ppc) {
  return {ix * ppc, (w.size_y - 1 - iy) * ppc};
}

cv::Mat ToBgr(const RgbImage& rgb) {
  cv::Mat out(rgb.height, rgb.width, CV_8UC3);
  for (int v = 0; v < rgb.height; ++v) {
    for (int u = 0; u < rgb.width; ++u) {
      const perception::Rgb& p = rgb.at(u, v);
      out.at<cv::Vec3b>(v, u) = cv::Vec3b(p.b, p.g, p.r);
    }
  }
  return out;
}

void Write(const std::string& path, const cv::Mat& img) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, img);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw perception::OutputError(path + ": cannot write the picture");
}

uint8_t RosValue(CellType t) {
  switch (t) {
    case CellType::kFloor:
      return 254;
    case CellType::kStairs:
      return 190;
    case CellType::kTunnel:
      return 160;
    case CellType::kUnknown:
      return 205;
    case CellType::kBorder:
      return 40;
    case CellType::kObstacle:
      return 0;
  }
  return 205;
}

// 1 decimal of a metre value for axis labels
std::string Metres(double m) {
  char label[16];
  std::snprintf(label, sizeof(label), "%.1f", m);
  return label;
}

}  // namespace

void WritePng(const RgbImage& image, const std::string& path) { Write(path, ToBgr(image)); }

RgbImage DrawFog(const Fog& fog, const perception::Pose2& robot_G, int ppc) {
  const GridWindow& w = fog.window;
  ppc = std::max(ppc, 2);
  cv::Mat img = NewMapCanvas(w.size_x * ppc, w.size_y * ppc, 2);
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const CellType t = fog.TypeAt(ix, iy);
      if (t == CellType::kUnknown) continue;
      DrawCell(&img, t, fog.HeightAt(ix, iy), CellCorner(w, ix, iy, ppc), ppc);
    }
  }
  // robot position and heading
  const double u = (robot_G.x / w.resolution - w.origin_ix) * ppc;
  const double v = (w.size_y - (robot_G.y / w.resolution - w.origin_iy)) * ppc;
  cv::Mat map = img(cv::Rect(0, 0, w.size_x * ppc, w.size_y * ppc));
  DrawRobot(&map, {u, v}, robot_G.yaw, std::max(4, 2 * ppc));

  const int legend_y = w.size_y * ppc + 4;
  DrawFogTypesRow(&img, legend_y);
  DrawScalesRow(&img, legend_y + kRowHeight, ppc / w.resolution);
  return ToRgbImage(img);
}

RgbImage DrawFogErrors(const Fog& estimate, const Fog& truth, const perception::FogParams& params,
                       const perception::Pose2& robot_G, int ppc) {
  using C = perception::FogCellComparison;
  // colour (r, g, b) and legend label per comparison, in FogCellComparison order
  const cv::Scalar colours[perception::kNumFogCellComparisons] = {
      kBackground, {215, 215, 215}, {170, 225, 170}, {255, 140, 0},
      {235, 215, 0}, {40, 90, 200}, {230, 0, 0}};
  const char* labels[perception::kNumFogCellComparisons] = {
      "unobserved", "right", "right nearby", "standable edge", "wrong height", "wrong class",
      "unsafe"};
  const GridWindow& w = estimate.window;
  ppc = std::max(ppc, 2);
  cv::Mat img = NewMapCanvas(w.size_x * ppc, w.size_y * ppc, 3);
  const std::vector<C> compared = perception::CompareFog(estimate, truth, params);
  std::vector<int> counts(perception::kNumFogCellComparisons, 0);
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const C k = compared[size_t(w.Index(ix, iy))];
      ++counts[size_t(k)];
      if (k == C::kUnobserved) continue;
      const cv::Point p0 = CellCorner(w, ix, iy, ppc);
      const cv::Point p1 = p0 + cv::Point(ppc - 1, ppc - 1);
      cv::rectangle(img, p0, p1, colours[int(k)], cv::FILLED);
      if (k == C::kUnsafe) {
        cv::line(img, p0, p1, kBlack);
        cv::line(img, {p0.x, p1.y}, {p1.x, p0.y}, kBlack);
      }
    }
  }
  const double u = (robot_G.x / w.resolution - w.origin_ix) * ppc;
  const double v = (w.size_y - (robot_G.y / w.resolution - w.origin_iy)) * ppc;
  cv::Mat map = img(cv::Rect(0, 0, w.size_x * ppc, w.size_y * ppc));
  DrawRobot(&map, {u, v}, robot_G.yaw, std::max(4, 2 * ppc), kText);  // red marks unsafe here

  // legend: each comparison with its cell count on two rows, then a metre scale
  const int legend_y = w.size_y * ppc + 4;
  for (int row = 0; row < 2; ++row) {
    const int y = legend_y + row * kRowHeight;
    int x = DrawRowTitle(&img, row == 0 ? "map vs truth:" : "wrong:", y);
    for (int k = 1 + 3 * row; k < 4 + 3 * row; ++k) {
      x = DrawSwatch(&img, colours[k], std::string(labels[k]) + " " + std::to_string(counts[size_t(k)]),
                     x, y);
    }
  }
  DrawMetreScale(&img, 6, legend_y + 2 * kRowHeight, ppc / w.resolution);
  return ToRgbImage(img);
}

RgbImage DrawFloorMap(const MapState& state, int ppc) {
  const GridWindow& w = state.window;
  ppc = std::max(ppc, 1);
  cv::Mat img = NewMapCanvas(w.size_x * ppc, std::max(1, w.size_y * ppc), 2);
  if (!state.Empty()) {
    for (int iy = 0; iy < w.size_y; ++iy) {
      for (int ix = 0; ix < w.size_x; ++ix) {
        const float h = state.floor[size_t(w.Index(ix, iy))];
        if (!std::isfinite(h)) continue;
        const cv::Point p0 = CellCorner(w, ix, iy, ppc);
        cv::rectangle(img, p0, p0 + cv::Point(ppc - 1, ppc - 1), HeightGrey(h), cv::FILLED);
      }
    }
  }
  const int legend_y = std::max(1, w.size_y * ppc) + 4;
  Text(&img, "floor height map: grey = floor height, pale blue = no floor seen",
       {6, legend_y + 15});
  DrawScalesRow(&img, legend_y + kRowHeight, ppc / w.resolution);
  return ToRgbImage(img);
}

RgbImage DrawGridSideViews(const MapState& state, double p_occ, int ppc) {
  const GridWindow& w = state.window;
  ppc = std::max(ppc, 1);
  const int nz = std::max(state.size_z, 1);
  const int n_max = std::max(w.size_x, w.size_y);
  // margins for the axes: z labels left, the horizontal axis and title under each view
  const int left = 46, right = 16, top = 22, under = 34;
  const int view_h = nz * ppc;
  const int width = std::max(left + n_max * ppc + right, kLegendWidth);
  const int height = 2 * (top + view_h + under) + kRowHeight + 8;
  cv::Mat img(height, width, CV_8UC3, kPaper);
  const float l_occ = state.Empty() ? 0.0f : float(std::log(p_occ / (1.0 - p_occ)));

  // view 0 projects along y onto x-z, view 1 along x onto y-z; z up
  for (int view = 0; view < 2; ++view) {
    const int n_across = view == 0 ? w.size_x : w.size_y;
    const int n_along = view == 0 ? w.size_y : w.size_x;
    const int origin = view == 0 ? w.origin_ix : w.origin_iy;
    const int y0 = view * (top + view_h + under) + top;
    Text(&img,
         view == 0 ? "side view along y (x-z): occupied layers of each column"
                   : "side view along x (y-z): occupied layers of each row",
         {left, y0 - 7});
    cv::rectangle(img, {left, y0}, {left + n_across * ppc - 1, y0 + view_h - 1}, kBackground,
                  cv::FILLED);
    for (int a = 0; a < n_across && !state.Empty(); ++a) {
      for (int iz = 0; iz < nz; ++iz) {
        int occupied = 0;
        bool free_seen = false;
        for (int b = 0; b < n_along; ++b) {
          const int ix = view == 0 ? a : b, iy = view == 0 ? b : a;
          const float l = state.log_odds[size_t(w.Index(ix, iy)) * nz + iz];
          occupied += l > l_occ;
          free_seen |= l < 0.0f;
        }
        cv::Scalar colour = kBackground;
        if (occupied > 0) {
          const double g = std::max(0.0, 160.0 - 160.0 * std::min(1.0, occupied / 20.0));
          colour = cv::Scalar(g, g, g);
        } else if (free_seen) {
          colour = kPaper;
        }
        const cv::Point p0(left + a * ppc, y0 + (nz - 1 - iz) * ppc);
        cv::rectangle(img, p0, p0 + cv::Point(ppc - 1, ppc - 1), colour, cv::FILLED);
      }
    }
    cv::rectangle(img, {left - 1, y0 - 1}, {left + n_across * ppc, y0 + view_h}, kText);
    // vertical axis: z in metres every 0.2 m
    for (double z = 0.0; z <= state.z_min + nz * w.resolution + 1e-9; z += 0.2) {
      const int v = y0 + view_h - int(std::lround((z - state.z_min) / w.resolution * ppc));
      if (v < y0 || v > y0 + view_h) continue;
      cv::line(img, {left - 5, v}, {left - 1, v}, kText);
      Text(&img, Metres(z), {left - 30, v + 4}, 0.33);
    }
    Text(&img, "z [m]", {2, y0 - 7}, 0.33);
    // horizontal axis: grid-frame metres, a tick every 0.5 m, a label every metre
    const double first = origin * w.resolution;
    for (double m = std::ceil(first * 2) / 2; m <= first + n_across * w.resolution + 1e-9;
         m += 0.5) {
      const int u = left + int(std::lround((m - first) / w.resolution * ppc));
      const bool whole = std::abs(m - std::round(m)) < 1e-6;
      cv::line(img, {u, y0 + view_h}, {u, y0 + view_h + (whole ? 6 : 3)}, kText);
      if (whole) Text(&img, Metres(m), {u - 10, y0 + view_h + 17}, 0.33);
    }
    Text(&img, view == 0 ? "x [m]" : "y [m]", {left + n_across * ppc - 30, y0 + view_h + 30}, 0.33);
  }
  // legend
  const int y = height - kRowHeight - 4;
  int x = 6;
  for (const auto& [colour, label] :
       {std::pair{cv::Scalar(0, 0, 0), "occupied (darker: more cells)"},
        std::pair{kPaper, "free seen"}, std::pair{kBackground, "unknown"}}) {
    cv::rectangle(img, {x, y + 5}, {x + 11, y + 16}, colour, cv::FILLED);
    cv::rectangle(img, {x, y + 5}, {x + 11, y + 16}, cv::Scalar(150, 150, 150));
    Text(&img, label, {x + 16, y + 15});
    int baseline = 0;
    x += 28 + cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &baseline).width;
  }
  return ToRgbImage(img);
}

void WriteFogTypes(const std::string& path, const Fog& fog) {
  const GridWindow& w = fog.window;
  cv::Mat types(w.size_y, w.size_x, CV_8UC1);
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      types.at<uint8_t>(w.size_y - 1 - iy, ix) = RosValue(fog.TypeAt(ix, iy));
    }
  }
  Write(path, types);
}

void WriteMapPictures(const std::string& dir, const Fog& fog, const MapState& state,
                      const perception::MapParams& params, const perception::Pose2& robot_G) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw perception::OutputError(dir + ": cannot create the folder: " + ec.message());
  const std::filesystem::path d(dir);
  WritePng(DrawFog(fog, robot_G), (d / "fog.png").string());
  WritePng(DrawFloorMap(state), (d / "floor.png").string());
  WritePng(DrawGridSideViews(state, params.grid.p_occ), (d / "grid_side.png").string());

  // ROS map_server image (row 0 is the highest y) and 16-bit heights
  WriteFogTypes((d / "fog_types.png").string(), fog);
  const GridWindow& w = fog.window;
  cv::Mat heights(w.size_y, w.size_x, CV_16UC1);
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const int row = w.size_y - 1 - iy;
      const float h = fog.HeightAt(ix, iy);
      uint16_t value = 0;
      if (std::isfinite(h)) {
        value = uint16_t(std::clamp(1000.0 + std::round(double(h) * 1000.0), 1.0, 65535.0));
      }
      heights.at<uint16_t>(row, ix) = value;
    }
  }
  Write((d / "fog_heights.png").string(), heights);

  const std::string yaml_path = (d / "fog.yaml").string();
  std::ofstream yaml(yaml_path);
  yaml << "# FOG of fognav (ROS map_server format); grid frame = odometry frame\n"
       << "image: fog_types.png\n"
       << "resolution: " << w.resolution << "\n"
       << "origin: [" << w.origin_ix * w.resolution << ", " << w.origin_iy * w.resolution
       << ", 0.0]\n"
       << "negate: 0\n"
       << "occupied_thresh: 0.65\n"
       << "free_thresh: 0.196\n"
       << "mode: trinary\n"
       << "fognav_types: {floor: 254, stairs: 190, tunnel: 160, unknown: 205, border: 40, "
          "obstacle: 0}\n"
       << "fognav_heights: {image: fog_heights.png, value: \"1000 + height_mm\", "
          "unknown: 0}\n"
       << "robot: [" << robot_G.x << ", " << robot_G.y << ", " << robot_G.yaw << "]\n";
  if (!yaml) throw perception::OutputError(yaml_path + ": cannot write the map file");
}

}  // namespace fognav::viz

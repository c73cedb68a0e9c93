// Pictures of the maps in the paper's scheme (Fig. 9, 12-15) and a machine-readable dump.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/internal/map_update.h"
#include "perception/mapping.h"

namespace fognav::perception {
namespace {

// colours, BGR
const cv::Scalar kBackground(245, 235, 225);  // unknown: pale blue
const cv::Scalar kBrown(19, 69, 139);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kRed(40, 40, 220);
const cv::Scalar kText(30, 30, 30);
constexpr int kBarWidth = 70;

// Grey shades for heights: low is light, high is dark.
struct HeightScale {
  double lo = 0, hi = 0.1;
  cv::Scalar Grey(double h) const {
    const double t = std::clamp((h - lo) / std::max(hi - lo, 1e-6), 0.0, 1.0);
    const double g = 235.0 - t * 150.0;
    return cv::Scalar(g, g, g);
  }
};

HeightScale ScaleOf(const std::vector<float>& heights, const std::vector<bool>& use) {
  HeightScale s;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t i = 0; i < heights.size(); ++i) {
    if (!use[i] || !std::isfinite(heights[i])) continue;
    lo = std::min(lo, double(heights[i]));
    hi = std::max(hi, double(heights[i]));
  }
  if (lo <= hi) {
    s.lo = lo;
    s.hi = std::max(hi, lo + 0.01);
  }
  return s;
}

// Top-left pixel of local cell (ix, iy) in an image with +y up.
cv::Point CellCorner(const GridWindow& w, int ix, int iy, int ppc) {
  return {ix * ppc, (w.size_y - 1 - iy) * ppc};
}

void DrawColourBar(cv::Mat* img, int x0, const HeightScale& s) {
  const int top = 20, bottom = img->rows - 20;
  if (bottom - top < 10) return;
  for (int v = top; v <= bottom; ++v) {
    const double h = s.hi - (s.hi - s.lo) * (v - top) / double(bottom - top);
    cv::line(*img, {x0 + 8, v}, {x0 + 22, v}, s.Grey(h));
  }
  cv::rectangle(*img, {x0 + 8, top}, {x0 + 22, bottom}, kText);
  for (int k = 0; k <= 4; ++k) {
    const int v = top + (bottom - top) * k / 4;
    const double h = s.hi - (s.hi - s.lo) * k / 4.0;
    char label[32];
    std::snprintf(label, sizeof(label), "%.1fcm", h * 100.0);
    cv::putText(*img, label, {x0 + 25, v + 4}, cv::FONT_HERSHEY_PLAIN, 0.8, kText);
  }
}

RgbImage ToRgb(const cv::Mat& bgr) {
  RgbImage out(bgr.cols, bgr.rows);
  for (int v = 0; v < bgr.rows; ++v) {
    for (int u = 0; u < bgr.cols; ++u) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(v, u);
      out.at(u, v) = Rgb{p[2], p[1], p[0]};
    }
  }
  return out;
}

cv::Mat ToBgr(const RgbImage& rgb) {
  cv::Mat out(rgb.height, rgb.width, CV_8UC3);
  for (int v = 0; v < rgb.height; ++v) {
    for (int u = 0; u < rgb.width; ++u) {
      const Rgb& p = rgb.at(u, v);
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
  if (!ok) throw OutputError(path + ": cannot write the map picture");
}

uint8_t RosValue(CellType t) {
  switch (t) {
    case CellType::kFloor: return 254;
    case CellType::kStairs: return 190;
    case CellType::kTunnel: return 160;
    case CellType::kUnknown: return 205;
    case CellType::kBorder: return 40;
    case CellType::kObstacle: return 0;
  }
  return 205;
}

}  // namespace

RgbImage DrawFog(const Fog& fog, const Pose2& robot_G, int ppc) {
  const GridWindow& w = fog.window;
  ppc = std::max(ppc, 2);
  cv::Mat img(w.size_y * ppc, w.size_x * ppc + kBarWidth, CV_8UC3, kBackground);
  std::vector<bool> use(fog.type.size());
  for (size_t i = 0; i < use.size(); ++i) {
    use[i] = fog.type[i] != CellType::kUnknown && fog.type[i] != CellType::kObstacle;
  }
  const HeightScale scale = ScaleOf(fog.height, use);

  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const CellType t = fog.TypeAt(ix, iy);
      if (t == CellType::kUnknown) continue;
      const float h = fog.HeightAt(ix, iy);
      const cv::Point p0 = CellCorner(w, ix, iy, ppc);
      const cv::Point p1 = p0 + cv::Point(ppc - 1, ppc - 1);
      const cv::Point mid = p0 + cv::Point(ppc / 2, ppc / 2);
      switch (t) {
        case CellType::kFloor:
          cv::rectangle(img, p0, p1, scale.Grey(h), cv::FILLED);
          break;
        case CellType::kStairs:
          cv::rectangle(img, p0, p1, scale.Grey(h), cv::FILLED);
          cv::line(img, p0, p1, kBrown);
          cv::line(img, {p0.x, p1.y}, {p1.x, p0.y}, kBrown);
          break;
        case CellType::kBorder:
          cv::rectangle(img, p0, p1, kBrown, cv::FILLED);
          break;
        case CellType::kTunnel:
          cv::rectangle(img, p0, p1, scale.Grey(h), cv::FILLED);
          cv::line(img, {p0.x, mid.y}, {p1.x, mid.y}, kRed);
          cv::line(img, {mid.x, p0.y}, {mid.x, p1.y}, kRed);
          break;
        case CellType::kObstacle: {
          // black with a cross whose shade is the coarse obstacle height
          HeightScale obstacle_scale{0.0, 0.6};
          cv::rectangle(img, p0, p1, kBlack, cv::FILLED);
          cv::Scalar cross = obstacle_scale.Grey(h);
          cv::line(img, p0, p1, cross);
          cv::line(img, {p0.x, p1.y}, {p1.x, p0.y}, cross);
          break;
        }
        case CellType::kUnknown: break;
      }
    }
  }

  // robot position and heading
  const double u = (robot_G.x / w.resolution - w.origin_ix) * ppc;
  const double v = (w.size_y - (robot_G.y / w.resolution - w.origin_iy)) * ppc;
  const cv::Point c(int(std::lround(u)), int(std::lround(v)));
  const int r = std::max(4, 2 * ppc);
  const cv::Point tip(int(std::lround(u + 2.5 * r * std::cos(robot_G.yaw))),
                      int(std::lround(v - 2.5 * r * std::sin(robot_G.yaw))));
  cv::circle(img, c, r, kRed, 2, cv::LINE_AA);
  cv::line(img, c, tip, kRed, 2, cv::LINE_AA);

  DrawColourBar(&img, w.size_x * ppc, scale);
  return ToRgb(img);
}

RgbImage DrawFloorMap(const MapState& state, int ppc) {
  const GridWindow& w = state.window;
  ppc = std::max(ppc, 1);
  cv::Mat img(std::max(1, w.size_y * ppc), w.size_x * ppc + kBarWidth, CV_8UC3, kBackground);
  if (state.Empty()) return ToRgb(img);
  const HeightScale scale = ScaleOf(state.floor, std::vector<bool>(state.floor.size(), true));
  for (int iy = 0; iy < w.size_y; ++iy) {
    for (int ix = 0; ix < w.size_x; ++ix) {
      const float h = state.floor[size_t(w.Index(ix, iy))];
      if (!std::isfinite(h)) continue;
      const cv::Point p0 = CellCorner(w, ix, iy, ppc);
      cv::rectangle(img, p0, p0 + cv::Point(ppc - 1, ppc - 1), scale.Grey(h), cv::FILLED);
    }
  }
  DrawColourBar(&img, w.size_x * ppc, scale);
  return ToRgb(img);
}

RgbImage DrawGridSideViews(const MapState& state, double p_occ, int ppc) {
  const GridWindow& w = state.window;
  ppc = std::max(ppc, 1);
  const int nz = std::max(state.size_z, 1);
  const int width = std::max(w.size_x, w.size_y) * ppc;
  const int gap = 8;
  cv::Mat img(2 * nz * ppc + gap, width, CV_8UC3, kBackground);
  if (state.Empty()) return ToRgb(img);
  const float l_occ = internal::LogOdds(p_occ);

  // view 0 projects along y onto x-z, view 1 along x onto y-z; z up
  for (int view = 0; view < 2; ++view) {
    const int n_across = view == 0 ? w.size_x : w.size_y;
    const int n_along = view == 0 ? w.size_y : w.size_x;
    const int y0 = view * (nz * ppc + gap);
    for (int a = 0; a < n_across; ++a) {
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
          colour = cv::Scalar(255, 255, 255);
        }
        const cv::Point p0(a * ppc, y0 + (nz - 1 - iz) * ppc);
        cv::rectangle(img, p0, p0 + cv::Point(ppc - 1, ppc - 1), colour, cv::FILLED);
      }
    }
  }
  return ToRgb(img);
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
                      const MapParams& params, const Pose2& robot_G) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError(dir + ": cannot create the folder: " + ec.message());
  const std::filesystem::path d(dir);
  Write((d / "fog.png").string(), ToBgr(DrawFog(fog, robot_G)));
  Write((d / "floor.png").string(), ToBgr(DrawFloorMap(state)));
  Write((d / "grid_side.png").string(), ToBgr(DrawGridSideViews(state, params.grid.p_occ)));

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
  if (!yaml) throw OutputError(yaml_path + ": cannot write the map file");
}

}  // namespace fognav::perception

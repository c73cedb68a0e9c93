// Writes the fuzzers' seed corpora in their input encoding (fuzz_input.h) from the analytic
// scenes of the perception tests: range images and stereo pairs of a staircase, a table and a
// bare floor, and range data of the paper's Fig. 9 world from three camera poses.
// Usage: make_seeds DIR  (writes DIR/segmentation/, DIR/stereo/, DIR/map_update/)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "perception/internal/map_synthetic.h"
#include "perception/internal/scanline_scenes.h"

namespace {

using namespace fognav::perception;
using Bytes = std::vector<uint8_t>;

// the inverse of FuzzInput::Int: the two bytes that read as `value` in [lo, hi]
void PutInt(Bytes* out, int value, int lo) {
  const int raw = value - lo;
  out->push_back(uint8_t(raw & 0xff));
  out->push_back(uint8_t(raw >> 8));
}

// the inverse of FuzzInput::Value (NaN for a non-finite value)
void PutValue(Bytes* out, float value, float lo, float hi) {
  if (!std::isfinite(value)) {
    out->push_back(255);
    return;
  }
  out->push_back(uint8_t(std::clamp(std::lround((value - lo) / (hi - lo) * 250.0f), 0L, 250L)));
}

// the inverse of FuzzInput::Finite
void PutFinite(Bytes* out, double value, double lo, double hi) {
  const long raw = std::clamp(std::lround((value - lo) / (hi - lo) * 65535.0), 0L, 65535L);
  out->push_back(uint8_t(raw & 0xff));
  out->push_back(uint8_t(raw >> 8));
}

void Write(const std::filesystem::path& path, const Bytes& bytes) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

struct NamedScene {
  const char* name;
  internal::Scene scene;
};

std::vector<NamedScene> Scenes() {
  internal::Scene table;
  table.boxes = {{{1.2, -0.4, 0.30}, {1.8, 0.4, 0.34}},  // top
                 {{1.2, -0.4, 0.0}, {1.25, -0.35, 0.30}},
                 {{1.75, 0.35, 0.0}, {1.8, 0.4, 0.30}}};
  return {{"staircase", internal::Staircase(0.8, 3, 0.25, 0.05)},
          {"table", table},
          {"floor", internal::Scene{}}};
}

// segmentation_fuzz, depth mode: width, height, mode 0, a depth byte per pixel
Bytes SegmentationSeed(const DepthImage& depth) {
  Bytes out;
  PutInt(&out, depth.width, 1);
  PutInt(&out, depth.height, 1);
  out.push_back(0);
  for (const float z : depth.data) PutValue(&out, z, 0.05f, 6.0f);
  return out;
}

// stereo_fuzz: width, height, mode (left and right bytes, both checks, the 128-pixel search),
// shift 0, a grey byte per left pixel, three bytes per right pixel
Bytes StereoSeed(const RgbImage& left, const RgbImage& right) {
  Bytes out;
  PutInt(&out, left.width, 0);
  PutInt(&out, left.height, 0);
  out.push_back(1 | 4 | 8 | 32);
  PutInt(&out, 0, 0);
  for (const Rgb& p : left.data) out.push_back(p.r);
  for (const Rgb& p : right.data) {
    out.push_back(p.r);
    out.push_back(p.g);
    out.push_back(p.b);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seeds DIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  int written = 0;

  // range images and stereo pairs of the scenes from a standing camera, 96x80 and 48x40
  for (const NamedScene& s : Scenes()) {
    for (const int width : {96, 48}) {
      const int height = width * 5 / 6;
      const CameraIntrinsics K = internal::SceneIntrinsics(width, height);
      const Eigen::Isometry3d X_WC = internal::SceneCamera(0.0, 0.0, 0.5, 0.5);
      DepthImage depth = internal::RenderScene(s.scene, K, X_WC).depth;
      const std::string size = std::to_string(width) + "x" + std::to_string(height);
      Write(dir / "segmentation" / (std::string(s.name) + "_" + size), SegmentationSeed(depth));
      internal::AddDepthNoise(&depth, 0.005, 1);
      Write(dir / "segmentation" / (std::string(s.name) + "_noisy_" + size),
            SegmentationSeed(depth));
      RgbImage left, right;
      internal::RenderStereoPair(s.scene, K, X_WC, &left, &right);
      Write(dir / "stereo" / (std::string(s.name) + "_" + size), StereoSeed(left, right));
      written += 3;
    }
  }

  // map_update_fuzz: three updates of the Fig. 9 world, a camera each, 400 points at most
  const std::vector<OrientedBox> world = internal::Fig9World();
  const std::vector<Eigen::Isometry3d> cameras = internal::Fig9Cameras();
  const CameraIntrinsics K = internal::MakeIntrinsics(88, 72, 45.0);
  for (size_t first = 0; first + 3 <= cameras.size(); first += 4) {
    Bytes out;
    out.push_back(0);  // poses within 2 m
    PutInt(&out, 3, 1);
    for (size_t k = first; k < first + 3; ++k) {
      const Eigen::Isometry3d& X_WC = cameras[k];
      const Eigen::Vector3d p_WC = X_WC.translation();
      const Eigen::Vector3d forward = X_WC.linear().col(2);
      PutFinite(&out, p_WC.x(), -2, 2);
      PutFinite(&out, p_WC.y(), -2, 2);
      PutFinite(&out, std::atan2(forward.y(), forward.x()), -4 * M_PI, 4 * M_PI);
      PutFinite(&out, 0, -0.2, 0.2);
      PutFinite(&out, 0, -0.2, 0.2);
      PutFinite(&out, std::min(p_WC.z(), 0.7), 0, 0.7);
      // the robot is where FuzzInput::Finite put it, the points relative to that
      const double x = -2 + 4 * std::round((p_WC.x() + 2) / 4 * 65535) / 65535;
      const double y = -2 + 4 * std::round((p_WC.y() + 2) / 4 * 65535) / 65535;
      const PointImage points = internal::RenderBoxes(world, X_WC, K).points_C;
      std::vector<Eigen::Vector3f> valid;
      for (const Eigen::Vector3f& p_C : points.points) {
        if (p_C.allFinite()) valid.push_back((X_WC * p_C.cast<double>()).cast<float>());
      }
      const size_t n = std::min<size_t>(400, valid.size());
      PutInt(&out, int(n), 0);
      for (size_t i = 0; i < n; ++i) {
        const Eigen::Vector3f& p = valid[i * valid.size() / n];
        PutValue(&out, p.x() - float(x), -3, 3);
        PutValue(&out, p.y() - float(y), -3, 3);
        PutValue(&out, p.z(), -0.5f, 1.5f);
        // points on a level surface carry its height
        const bool level = std::abs(p.z()) < 0.005f || std::abs(p.z() - 0.03f) < 0.005f ||
                           std::abs(p.z() - 0.11f) < 0.005f;
        out.push_back(level ? 1 : 0);
        if (level) PutValue(&out, p.z(), -0.2f, 0.6f);
        PutValue(&out, 0.005f, 0, 0.1f);
      }
      PutInt(&out, 0, 0);  // no empty rays
      PutFinite(&out, 0, -0.3, 0.3);
      out.push_back(0);  // no fading
    }
    Write(dir / "map_update" / ("fig9_cameras_" + std::to_string(first)), out);
    ++written;
  }
  std::printf("make_seeds: %d seeds in %s\n", written, dir.c_str());
  return 0;
}

// libFuzzer target: stereo matching on image pairs of any size from 0x0 to 96x80 (empty, one
// row, one column), uniform, random or shifted copies of each other, with the left-right
// checks and the sub-pixel refinement on or off.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "perception/segmentation.h"
#include "tests/fuzz/fuzz_input.h"

namespace {

void Check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "stereo_fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fognav::perception;
  fognav::fuzz::FuzzInput in(data, size);
  const int width = in.Int(0, 96), height = in.Int(0, 80);
  const uint8_t mode = in.Byte();
  StereoParams params;
  params.left_right_check = mode & 4;
  params.refine_left_right_tolerance = (mode & 8) ? 0.3 : 0.0;
  params.num_disparities = (mode & 16) ? 16 : 128;

  CameraIntrinsics K;
  K.width_px = width;
  K.height_px = height;
  K.fx = K.fy = 0.5 * width / std::tan(0.5 * 45.0 * M_PI / 180.0);
  K.cx = 0.5 * (width - 1);
  K.cy = 0.5 * (height - 1);

  RgbImage left(width, height), right(width, height);
  const int shift = in.Int(0, 40);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      uint8_t grey = 0;
      switch (mode & 3) {
        case 0:
          grey = 128;
          break;  // uniform
        case 1:
          grey = in.Byte();
          break;
        default:
          grey = uint8_t((u * 37 + v * 11) ^ in.Byte());
      }
      left.at(u, v) = {grey, grey, grey};
    }
  }
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      // the right eye sees the left image shifted by `shift` pixels, or bytes of its own
      const Rgb& seen = left.at(std::min(width - 1, u + shift), v);
      right.at(u, v) = (mode & 32) ? Rgb{in.Byte(), in.Byte(), in.Byte()} : seen;
    }
  }

  Image<float> disparity;
  const PointImage points = StereoPointImage(left, right, K, params, &disparity);
  Check(points.width == width && points.height == height, "the points are not the image's size");
  Check(disparity.width == width && disparity.height == height,
        "the disparity is not the image's size");
  for (const Eigen::Vector3f& p : points.points) {
    Check(std::isnan(p.x()) || (p.allFinite() && p.z() > 0), "a point neither NaN nor in front");
  }
  const Image<uint8_t> rims = DepthEdgeRims(disparity, params);
  Check(rims.width == width && rims.height == height, "the rims are not the image's size");
  return 0;
}

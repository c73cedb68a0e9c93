// libFuzzer target: plane segmentation of point images of any size from 1x1 to 96x80 (1xN and
// Nx1 included) whose points may be NaN, infinite, zero or anything: depth images (points on
// the pixels' rays), points of any three values, and raw float bits.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "perception/segmentation.h"
#include "tests/fuzz/fuzz_input.h"

namespace {

void Check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "segmentation_fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fognav::perception;
  fognav::fuzz::FuzzInput in(data, size);
  const int width = in.Int(1, 96), height = in.Int(1, 80);
  const uint8_t mode = in.Byte();
  SegmentParams params = (mode & 4)   ? PreciseRangeParams()
                         : (mode & 8) ? RayNoiseParams()
                                      : SegmentParams();
  params.merge_coplanar = mode & 16;
  params.method = (mode & 32) ? LineMethod::kSplit : LineMethod::kRdSplit;

  PointImage points(width, height);
  // the scenes' 45-degree camera (make_seeds.cc); braced lists read their values in order
  const float f = 0.5f * float(width) / std::tan(0.5f * 45.0f * float(M_PI) / 180.0f);
  const float cx = 0.5f * float(width - 1), cy = 0.5f * float(height - 1);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      Eigen::Vector3f& p = points.at(u, v);
      switch (mode & 3) {
        case 0: {  // a depth image: the point on the pixel's ray
          const float z = in.Value(0.05f, 6.0f);
          p = {(float(u) - cx) / f * z, (float(v) - cy) / f * z, z};
          break;
        }
        case 1:
          p = {in.Value(-3, 3), in.Value(-3, 3), in.Value(-1, 6)};
          break;
        default:
          p = {in.RawFloat(), in.RawFloat(), in.RawFloat()};
      }
    }
  }

  const PlaneSet planes = SegmentPlanes(points, params);
  Check(planes.labels.width == width && planes.labels.height == height,
        "the label image is not the size of the point image");
  for (const int32_t label : planes.labels.data) {
    Check(label >= -1 && label < int32_t(planes.planes.size()), "a label names no plane");
  }
  return 0;
}

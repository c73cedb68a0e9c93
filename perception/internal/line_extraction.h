// Line segments of scan lines (paper Section 3.2): rd-split and the classic split.
#ifndef FOGNAV_PERCEPTION_INTERNAL_LINE_EXTRACTION_H_
#define FOGNAV_PERCEPTION_INTERNAL_LINE_EXTRACTION_H_

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "perception/internal/plane_moments.h"
#include "perception/segmentation.h"
#include "perception/types.h"

namespace fognav::perception::internal {

// A line record L = (s, b, e, N, b, A, sigma) of eq. (11), plus its end points (for the UB
// method's d_line test) and the plane it was grouped into (-1 none).
struct LineSegment {
  int s = 0;      // scan line (row)
  int b = 0;      // first column
  int e = 0;      // last column, inclusive
  Moments m;      // N, sum p, sum p p^T of its points
  double sigma = 0;  // RMS distance of its points to the fitted 2D line, metres
  // Unit normal of the fitted line within the scan line's plane, camera frame: sigma is the
  // spread of the points along this direction.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_first = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_last = Eigen::Vector3d::Zero();
  int plane = -1;
};

// All line segments of an image, ordered by row and, within a row, by column; and which pixels
// hold a valid point.
struct LineSet {
  int width = 0, height = 0;
  std::vector<LineSegment> lines;
  std::vector<int> row_begin;   // lines of row s are [row_begin[s], row_begin[s + 1])
  std::vector<uint8_t> valid;   // 1 where the pixel's point is finite, row-major
};

// Reusable buffers of one scan line, so that extraction allocates nothing per pixel.
struct ScanlineScratch {
  std::vector<int> u;
  std::vector<Eigen::Vector3f> q;              // the valid points, compact (a = x)
  std::vector<double> c;                       // 2D coordinate c in the scan line's plane
  std::vector<std::array<double, 9>> prefix;   // running sums x y z xx xy xz yy yz zz
  std::vector<int> cut;                        // first index of each run, then the count
};

// Reads every point of the image once and cuts each scan line into line segments with
// p.method (rd-split or split), replacing the contents of *out.
void ExtractLines(const PointImage& points, const SegmentParams& p, LineSet* out,
                  ScanlineScratch* scratch);

// max-count-consecutive-same-side: the longest run of consecutive residuals with the same sign,
// where |r| <= tolerance breaks a run.
int MaxConsecutiveSameSide(const double* residuals, int count, double tolerance);

// The same over residual(0) ... residual(count - 1), stopping as soon as a run reaches stop_at.
// Branch-free but for the stop (the sides of noisy points are random and would defeat branch
// prediction), and the loop carries only the start of the current run and the longest length,
// not a run counter whose update would chain multiply or compare-and-add latencies.
template <typename Residual>
int LongestSameSideRun(int count, Residual residual, double tolerance, int stop_at) {
  int longest = 0, start = 0, side = 0;
  for (int i = 0; i < count; ++i) {
    const double r = residual(i);
    const int sd = int(r > tolerance) - int(r < -tolerance);
    start = sd != side ? i : start;
    side = sd;
    const int run = sd != 0 ? i - start + 1 : 0;
    longest = run > longest ? run : longest;
    if (longest >= stop_at) break;
  }
  return longest;
}

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_LINE_EXTRACTION_H_

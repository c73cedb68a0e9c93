// Range data: stereo matching, depth images, sub-sampling and false-colour disparity pictures.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/segmentation.h"

namespace fognav::perception {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr int kRangeBlockSize = 3;  // block side of the half-resolution matching, pixels

cv::Mat ToMat(const RgbImage& image) {
  cv::Mat mat(image.height, image.width, CV_8UC3);
  for (int v = 0; v < image.height; ++v) {
    auto* row = mat.ptr<cv::Vec3b>(v);
    for (int u = 0; u < image.width; ++u) {
      const Rgb& c = image.at(u, v);
      row[u] = cv::Vec3b(c.b, c.g, c.r);
    }
  }
  return mat;
}

template <typename T>
Image<T> SubsampleImage(const Image<T>& in) {
  Image<T> out(in.width / 2, in.height / 2);
  for (int v = 0; v < out.height; ++v)
    for (int u = 0; u < out.width; ++u) out.at(u, v) = in.at(2 * u, 2 * v);
  return out;
}

// Grey levels of an image as floats.
cv::Mat GreyFloat(const RgbImage& image) {
  cv::Mat grey(image.height, image.width, CV_32F);
  for (int v = 0; v < image.height; ++v) {
    float* row = grey.ptr<float>(v);
    for (int u = 0; u < image.width; ++u) {
      const Rgb& c = image.at(u, v);
      row[u] = 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
    }
  }
  return grey;
}

// Sub-pixel refinement of a disparity d0 by Gauss-Newton on the sum of squared differences over
// a window around (u, v) of the reference image `ref`, sampling `other` linearly along its row
// at x + sign d: the left image as the reference has its match in the right image at x - d
// (sign -1), the right image as the reference in the left one at x + d (sign +1). Minimises
// sum (ref(x) - other(x + sign d))^2: step = sign sum e g / sum g^2 with e = ref - other and
// g = other_x at x + sign d. Returns NaN if the refinement leaves [d0 - 1, d0 + 1] or the window
// has no texture.
float RefineDisparity(const cv::Mat& ref, const cv::Mat& other, const cv::Mat& other_dx, int sign,
                      int u, int v, float d0, int half, int iterations) {
  const int w = ref.cols, h = ref.rows;
  // With x + sign d = (x + shift) + t (a whole shift, 0 <= t < 1, the same for the window),
  // e = e0 - t de and g = g0 + t dg are linear in t, so sum e g = a + t b - t^2 c and
  // sum g^2 = gg + 2 t gh + t^2 hh from window sums that depend on the shift alone.
  int sums_shift = std::numeric_limits<int>::min();
  float a = 0, b = 0, c = 0, gg = 0, gh = 0, hh = 0;
  double d = d0;
  for (int it = 0; it < iterations; ++it) {
    const int shift = int(std::floor(sign * d));
    if (shift != sums_shift) {
      sums_shift = shift;
      a = b = c = gg = gh = hh = 0;
      const int ub = std::max({u - half, 0, -shift});
      const int ue = std::min({u + half, w - 1, w - 2 - shift});
      for (int vv = std::max(v - half, 0); vv <= std::min(v + half, h - 1); ++vv) {
        const float* r = ref.ptr<float>(vv);
        const float* o = other.ptr<float>(vv) + shift;
        const float* g = other_dx.ptr<float>(vv) + shift;
        for (int uu = ub; uu <= ue; ++uu) {
          const float e0 = r[uu] - o[uu], de = o[uu + 1] - o[uu];
          const float g0 = g[uu], dg = g[uu + 1] - g[uu];
          a += e0 * g0;
          b += e0 * dg - de * g0;
          c += de * dg;
          gg += g0 * g0;
          gh += g0 * dg;
          hh += dg * dg;
        }
      }
    }
    const double t = sign * d - shift;
    const double seg = a + t * (b - t * c), sgg = gg + t * (2 * gh + t * hh);
    if (!(sgg > 1e-6)) return std::numeric_limits<float>::quiet_NaN();
    const double step = std::clamp(sign * seg / sgg, -0.5, 0.5);
    d += step;
    if (std::abs(d - d0) > 1.0) return std::numeric_limits<float>::quiet_NaN();
    if (std::abs(step) < 1e-3) break;
  }
  return float(d);
}

// Semi-global matching of a rectified pair over the disparities [lo, lo + num) (num a multiple
// of 16), as 16 x disparity, -1 where it fails. With p.pad_left both images are padded on the
// left by lo + num columns, so that every column gets the whole range.
cv::Mat Match(const cv::Mat& left, const cv::Mat& right, int lo, int num, int block_size,
              const StereoParams& p) {
  const int pad = p.pad_left ? std::max(0, lo + num) : 0;
  cv::Mat l = left, r = right;
  if (pad > 0) {
    cv::copyMakeBorder(left, l, 0, 0, pad, 0, cv::BORDER_REPLICATE);
    cv::copyMakeBorder(right, r, 0, 0, pad, 0, cv::BORDER_REPLICATE);
  }
  const int area = block_size * block_size * left.channels();
  const int mode = p.full_dp     ? cv::StereoSGBM::MODE_HH
                   : p.three_way ? cv::StereoSGBM::MODE_SGBM_3WAY
                                 : cv::StereoSGBM::MODE_SGBM;
  auto sgbm = cv::StereoSGBM::create(lo, num, block_size, p.p1 > 0 ? p.p1 : 8 * area,
                                     p.p2 > 0 ? p.p2 : 32 * area, p.disp12_max_diff,
                                     p.pre_filter_cap, p.uniqueness_ratio, p.speckle_window_size,
                                     p.speckle_range, mode);
  cv::Mat disp16;
  sgbm->compute(l, r, disp16);
  cv::Mat out = disp16(cv::Rect(pad, 0, left.cols, left.rows)).clone();
  out.setTo(-1, out < 16 * std::max(lo, 1));  // OpenCV marks failures (lo - 1) * 16
  return out;
}

// The disparities worth searching at full resolution, [*lo, *lo + *num): those that a
// matching of the pair at half resolution over the whole range finds at p.range_min_pixels
// pixels or more, widened by p.range_margin pixels. The whole range if it finds none.
void SearchRange(const cv::Mat& left, const cv::Mat& right, const StereoParams& p, int* lo,
                 int* num) {
  *lo = p.min_disparity;
  *num = p.num_disparities;
  if (p.range_margin < 0 || left.cols < 2 || left.rows < 2) return;
  cv::Mat l, r;
  const cv::Size half(left.cols / 2, left.rows / 2);
  cv::resize(left, l, half, 0, 0, cv::INTER_AREA);
  cv::resize(right, r, half, 0, 0, cv::INTER_AREA);
  const int half_lo = int(std::floor(p.min_disparity / 2.0));
  const int half_num = std::max(16, (p.num_disparities / 2 + 15) / 16 * 16);
  const cv::Mat disp16 = Match(l, r, half_lo, half_num, kRangeBlockSize, p);
  std::vector<int> count(size_t(half_num) + 1, 0);  // pixels per whole disparity - half_lo
  for (int v = 0; v < disp16.rows; ++v) {
    const int16_t* row = disp16.ptr<int16_t>(v);
    for (int u = 0; u < disp16.cols; ++u) {
      if (row[u] >= 0) ++count[size_t(std::clamp(row[u] / 16 - half_lo, 0, half_num))];
    }
  }
  int first = 0, last = half_num, sum = 0;
  while (first <= half_num && (sum += count[size_t(first)]) < p.range_min_pixels) ++first;
  sum = 0;
  while (last >= 0 && (sum += count[size_t(last)]) < p.range_min_pixels) --last;
  if (last < first) return;
  const int end = p.min_disparity + p.num_disparities;
  *lo = std::max(p.min_disparity, 2 * (first + half_lo) - p.range_margin);
  const int hi = std::min(end, 2 * (last + half_lo) + 2 + p.range_margin);
  *num = std::max(16, (hi - *lo + 15) / 16 * 16);
  if (*lo + *num > end) *lo = std::max(p.min_disparity, end - *num);
}

}  // namespace

PointImage StereoPointImage(const RgbImage& left, const RgbImage& right, const CameraIntrinsics& K,
                            const StereoParams& p, Image<float>* disparity_px) {
  const int w = left.width, h = left.height;
  PointImage points(w, h);
  if (disparity_px) *disparity_px = Image<float>(w, h, kNaN);
  if (w == 0 || h == 0 || right.width != w || right.height != h) return points;

  // semi-global matching over the range worth searching, of colours or grey levels
  cv::Mat left_mat = ToMat(left), right_mat = ToMat(right);
  if (p.grey) {
    cv::cvtColor(left_mat, left_mat, cv::COLOR_BGR2GRAY);
    cv::cvtColor(right_mat, right_mat, cv::COLOR_BGR2GRAY);
  }
  int lo = 0, num = 0;
  SearchRange(left_mat, right_mat, p, &lo, &num);
  cv::Mat disp16 = Match(left_mat, right_mat, lo, num, p.block_size, p);
  if (p.left_right_check) {
    // the right image as the reference: flipped, the right image becomes a left one and
    // disparities keep their sign; right column ur is column w - 1 - ur of the flipped pair
    cv::Mat lf, rf;
    cv::flip(right_mat, lf, 1);
    cv::flip(left_mat, rf, 1);
    const cv::Mat disp16_right = Match(lf, rf, lo, num, p.block_size, p);
    const double tolerance16 = 16.0 * p.left_right_tolerance;
    for (int v = 0; v < h; ++v) {
      int16_t* row = disp16.ptr<int16_t>(v);
      const int16_t* row_right = disp16_right.ptr<int16_t>(v);
      for (int u = 0; u < w; ++u) {
        if (row[u] <= 0) continue;
        const int ur = u - int(std::lround(row[u] / 16.0));
        const int raw_right = ur >= 0 ? row_right[w - 1 - ur] : 0;
        if (raw_right <= 0 || std::abs(raw_right - row[u]) > tolerance16) row[u] = -1;
      }
    }
  }

  // sub-pixel refinement on the grey images (SGBM's interpolation locks towards whole pixels)
  cv::Mat gl, gr, gl_dx, gr_dx;
  const bool refine = p.refine_iterations > 0;
  const bool check_refined = refine && p.refine_left_right_tolerance > 0;
  if (refine) {
    gl = GreyFloat(left);
    gr = GreyFloat(right);
    cv::Sobel(gr, gr_dx, CV_32F, 1, 0, 1, 0.5);  // central difference
    if (check_refined) cv::Sobel(gl, gl_dx, CV_32F, 1, 0, 1, 0.5);
  }

  // triangulate: z = f B / disparity, x = (u - cx) z / fx, y = (v - cy) z / fy
  const double fb = K.fx * K.baseline;
  const double min_disp = fb / p.max_depth;
  for (int v = 0; v < h; ++v) {
    const int16_t* row = disp16.ptr<int16_t>(v);
    for (int u = 0; u < w; ++u) {
      const int raw = row[u];
      if (raw <= 0) continue;
      double disp = raw / 16.0;
      if (refine) {
        disp = RefineDisparity(gl, gr, gr_dx, -1, u, v, float(disp), p.refine_window / 2,
                               p.refine_iterations);
        if (!std::isfinite(disp)) continue;
      }
      if (disp < min_disp) continue;
      // the disparity image keeps what the check below drops: DepthEdgeRims reads the edges
      // of nearer surfaces from it
      if (disparity_px) disparity_px->at(u, v) = float(disp);
      if (check_refined) {
        // the same match refined from the right image's window (StereoParams)
        const int ur = int(std::lround(u - disp));
        const float back = ur < 0 ? kNaN
                                  : RefineDisparity(gr, gl, gl_dx, +1, ur, v, float(disp),
                                                    p.refine_window / 2, p.refine_iterations);
        if (!(std::abs(back - disp) <= p.refine_left_right_tolerance)) continue;
      }
      const double z = fb / disp;
      points.at(u, v) = Eigen::Vector3f(float((u - K.cx) * z / K.fx),
                                        float((v - K.cy) * z / K.fy), float(z));
    }
  }
  return points;
}

Image<uint8_t> DepthEdgeRims(const Image<float>& disparity_px, const StereoParams& p) {
  // the smallest disparity within edge_margin along the row and 2 * edge_margin along the
  // column (after a median of three along the row, so that one stray far match marks nothing).
  // Failed pixels to the left take the disparity left of them: left of a nearer surface lies
  // background that the right eye cannot see (the left-right check fails there). Other failed
  // pixels count as near.
  const int w = disparity_px.width, h = disparity_px.height, m = p.edge_margin;
  Image<uint8_t> rims(w, h, 0);
  if (m <= 0 || w == 0 || h == 0) return rims;
  const float jump = float(p.edge_jump);
  constexpr float kNear = std::numeric_limits<float>::infinity();
  std::vector<float> from_left(static_cast<size_t>(w));
  Image<float> median(w, h, kNear);  // per row, of three; failed pixels count as near
  for (int v = 0; v < h; ++v) {
    const float* d = &disparity_px.data[size_t(v) * size_t(w)];
    auto near_at = [&](int u) { return std::isfinite(d[u]) ? d[u] : kNear; };
    for (int u = 0; u < w; ++u) {
      const float a = near_at(std::max(u - 1, 0)), b = near_at(u),
                  c = near_at(std::min(u + 1, w - 1));
      median.at(u, v) = std::max(std::min(a, b), std::min(std::max(a, b), c));
    }
  }
  const float keep_ratio = float(1.0 - p.edge_depth_ratio);
  for (int v = 0; v < h; ++v) {
    const float* d = &disparity_px.data[size_t(v) * size_t(w)];
    for (int u = 0; u < w; ++u) {
      from_left[size_t(u)] = std::isfinite(d[u]) ? median.at(u, v)
                             : u > 0             ? from_left[size_t(u) - 1]
                                                 : kNear;
    }
    for (int u = 0; u < w; ++u) {
      if (!std::isfinite(d[u])) continue;
      float far = d[u];
      for (int k = std::max(0, u - m); k <= std::min(w - 1, u + m); ++k) {
        far = std::min(far, k < u ? from_left[size_t(k)] : median.at(k, v));
      }
      float far_in_column = d[u];
      for (int k = std::max(0, v - 2 * m); k <= std::min(h - 1, v + 2 * m); ++k) {
        far_in_column = std::min(far_in_column, median.at(u, k));
      }
      rims.at(u, v) = d[u] - far >= jump ? kRowRim
                      : d[u] - far_in_column >= jump && far_in_column <= keep_ratio * d[u]
                          ? kColumnRim
                          : 0;
    }
  }
  return rims;
}

PointImage DepthPointImage(const DepthImage& depth_m, const CameraIntrinsics& K) {
  PointImage points(depth_m.width, depth_m.height);
  for (int v = 0; v < depth_m.height; ++v) {
    for (int u = 0; u < depth_m.width; ++u) {
      const double z = depth_m.at(u, v);
      if (!(z > 0) || !std::isfinite(z)) continue;
      points.at(u, v) = Eigen::Vector3f(float((u - K.cx) * z / K.fx),
                                        float((v - K.cy) * z / K.fy), float(z));
    }
  }
  return points;
}

PointImage Subsample2x(const PointImage& points) {
  PointImage out(points.width / 2, points.height / 2);
  for (int v = 0; v < out.height; ++v)
    for (int u = 0; u < out.width; ++u) out.at(u, v) = points.at(2 * u, 2 * v);
  return out;
}

LabelImage Subsample2x(const LabelImage& labels) { return SubsampleImage(labels); }

Image<uint8_t> Subsample2x(const Image<uint8_t>& mask) { return SubsampleImage(mask); }

DepthImage Subsample2x(const DepthImage& depth) { return SubsampleImage(depth); }

CameraIntrinsics Subsample2x(const CameraIntrinsics& K) {
  CameraIntrinsics out = K;
  out.width_px = K.width_px / 2;
  out.height_px = K.height_px / 2;
  out.fx = K.fx / 2;
  out.fy = K.fy / 2;
  out.cx = K.cx / 2;
  out.cy = K.cy / 2;
  return out;
}

}  // namespace fognav::perception

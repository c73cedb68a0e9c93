// Stereo range data and plane segmentation by extended scan-line grouping (paper Section 3),
// and its score against ground-truth surfaces.
#ifndef FOGNAV_PERCEPTION_SEGMENTATION_H_
#define FOGNAV_PERCEPTION_SEGMENTATION_H_

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "perception/types.h"

namespace fognav::perception {

// ---- range data ----

// OpenCV StereoSGBM settings for the 176x144, 45° hfov, 5 cm baseline head camera on textured
// renders (focal length about 212 px, so disparity 10.6 px at 1 m and 3.5 px at 3 m). How the
// values were found: docs/params.md, "Stereo".
struct StereoParams {
  int min_disparity = 0;          // smallest disparity searched, pixels
  int num_disparities = 128;      // whole search range, pixels, a multiple of 16 (nearest 0.083 m)
  int block_size = 5;             // matching block side in pixels, odd
  int p1 = 0;                     // SGM small-change penalty; 0 = 8 * channels * block_size^2
  int p2 = 0;                     // SGM large-change penalty; 0 = 32 * channels * block_size^2
  int disp12_max_diff = 1;        // OpenCV's own left-right test in pixels; < 0 disables
  int pre_filter_cap = 31;        // clip of the x-derivative prefilter
  int uniqueness_ratio = 20;      // percent margin of the best over the second-best cost
  int speckle_window_size = 40;   // largest speckle in pixels removed; 0 disables
  int speckle_range = 2;          // disparity variation (pixels) within one connected speckle
  bool full_dp = false;           // OpenCV MODE_HH (full 8-path) instead of MODE_SGBM
  bool three_way = false;         // OpenCV MODE_SGBM_3WAY instead of MODE_SGBM (unless full_dp)
  bool grey = false;              // match grey levels, not colours
  int range_margin = -1;          // search what a half-resolution matching finds +- this, pixels;
                                  // < 0 = always the whole range
  int range_min_pixels = 1;       // disparities fewer half-resolution pixels have are left out
  bool pad_left = true;           // pad both images on the left so border columns get disparities
  double max_depth = 10.0;        // metres; farther points (disparity below f B / max_depth) NaN
  int refine_iterations = 3;      // Gauss-Newton steps refining each disparity to sub-pixel on the
                                  // grey images (0 = SGBM's own interpolation)
  int refine_window = 5;          // side in pixels of the refinement window, odd
  double refine_left_right_tolerance = 0.0;  // refined from each eye, the two must agree within
                                             // this, pixels; 0 = no check
  bool left_right_check = true;       // match a second time right to left and compare
  double left_right_tolerance = 1.0;  // the two matchings must agree within this, pixels
  int edge_margin = 3;            // depth-edge rims: reach along a row, pixels; 0 marks nothing
  double edge_jump = 1.0;         // depth-edge rims: smallest disparity jump, pixels
  double edge_depth_ratio = 0.2;  // depth-edge rims in a column: the far disparity is at most
                                  // (1 - this) times the pixel's
};

// Dense stereo by semi-global matching on a rectified horizontal pair (right camera at
// +K.baseline along the camera x axis) into 3D points in the left camera frame (OpenCV
// convention, metres). With StereoParams::range_margin >= 0 the search covers only the
// disparities that a matching at half resolution over the whole range finds. Pixels where matching fails are NaN. If disparity_px is given it receives
// the disparity in pixels (NaN where invalid), the same size as the images; there the pixels
// that only p.refine_left_right_tolerance drops keep their disparity (DepthEdgeRims reads the
// edges of nearer surfaces from it).
PointImage StereoPointImage(const RgbImage& left, const RgbImage& right, const CameraIntrinsics& K,
                            const StereoParams& p = {}, Image<float>* disparity_px = nullptr);

// The rims of nearer surfaces in a disparity image (NaN = none): kRowRim where a pixel is
// within p.edge_margin pixels along its row of a disparity at least p.edge_jump smaller (or, to
// its left, of a failed match: the occluded background), else kColumnRim where it is within
// 2 * p.edge_margin rows in its column of one smaller by p.edge_jump and by the fraction
// p.edge_depth_ratio, else 0. Fattened pixels lie there; so do the true edges of nearer
// surfaces, which cannot be told apart from them.
constexpr uint8_t kRowRim = 1, kColumnRim = 2;
Image<uint8_t> DepthEdgeRims(const Image<float>& disparity_px, const StereoParams& p = {});

// 3D points from a depth image (metres along the optical axis, NaN or <= 0 = none): pixel (u, v)
// becomes z * ((u - cx) / fx, (v - cy) / fy, 1); NaN where there is no depth.
PointImage DepthPointImage(const DepthImage& depth_m, const CameraIntrinsics& K);

// 2x sub-sampling as on QRIO (176x144 -> 88x72): output pixel (u, v) is input pixel
// (2u, 2v); the output size is (width / 2, height / 2) rounded down.
PointImage Subsample2x(const PointImage& points);
// The same sub-sampling for label images (e.g. ground-truth surface ids): output (u, v) is
// input (2u, 2v).
LabelImage Subsample2x(const LabelImage& labels);
Image<uint8_t> Subsample2x(const Image<uint8_t>& mask);
// The same sub-sampling for depth images: output (u, v) is input (2u, 2v).
DepthImage Subsample2x(const DepthImage& depth);
// Intrinsics of the 2x sub-sampled image: fx / 2, fy / 2, cx / 2, cy / 2, half the size.
CameraIntrinsics Subsample2x(const CameraIntrinsics& K);

// ---- segmentation ----

// A planar region found in a point image (paper Section 3.5: P_i = (n, d, N, b, A, B)).
// Camera frame: points p on the plane satisfy p . n = d. Because n points towards the camera
// (the visible side), d = -(distance from the camera centre to the plane) < 0.
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();  // unit normal, pointing towards the camera
  double d = 0;                                  // signed distance to the origin, metres (< 0)
  int num_points = 0;                            // N
  Eigen::Vector3d b = Eigen::Vector3d::Zero();   // sum of points
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();   // sum of p p^T
  double rms = 0;                                // RMS residual of its points, metres (eq. 9)
  // Border per scan line: for each row v of the image the plane touches, the first and
  // last column (inclusive) of its pixels on that row.
  struct RowSpan {
    int v = 0, u_begin = 0, u_end = 0;
  };
  std::vector<RowSpan> border;

  // Signed distance of camera-frame point p to the plane in metres, positive on the camera side.
  double SignedDistance(const Eigen::Vector3d& p) const { return p.dot(n) - d; }
  // Mean of its points in the camera frame, metres.
  Eigen::Vector3d Centroid() const { return num_points > 0 ? Eigen::Vector3d(b / num_points) : b; }
};

// The planes of one point image and a label image of the same size: the index of the plane
// each pixel belongs to, or -1 for none. Planes are sorted by decreasing num_points.
struct PlaneSet {
  std::vector<Plane> planes;
  LabelImage labels;
};

// How scan lines are cut into line segments: the paper's rd-split (run distribution test,
// C_max) or the classic split with the chord threshold d_cord of the UB method [Jiang & Bunke],
// which also accepts lines into planes by their end points' distance d_line instead of r_sigma.
enum class LineMethod { kRdSplit, kSplit };

// Parameters of scan-line grouping; defaults are the paper's Table 1 for stereo data. The
// extensions' mechanisms and how their values were found: docs/params.md, "Segmentation".
struct SegmentParams {
  int n_min = 5;            // N_min, fewest points of a line segment
  int c_max = 15;           // C_max, consecutive same-side points that force a split
  double r_seed = 2;        // r_sigma threshold for the three lines of a seed (eq. 13)
  double r_grow = 3;        // r_sigma threshold for growing a region by a line (eq. 14)
  LineMethod method = LineMethod::kRdSplit;
  double d_cord = 0.015;    // UB split: chord distance threshold, metres
  double d_line = 0.03;     // UB: end point distance to the plane for line membership, metres
  int trade_window = 5;     // side in pixels of the window for trading points (odd)
  // Extensions that the paper does not name (set to 0 to turn off):
  double sigma_min = 0.001;        // floor on a line's sigma and a plane's rms in r_sigma, metres
  double side_tolerance = 0.0005;  // smaller residuals (metres) count as on the line, no side
  double jump_ratio = 0.1;      // a scan line is cut where neighbours' depths differ by this share
  int max_gap_px = 1;           // invalid pixels a line segment may bridge on its scan line
  int min_plane_points = 15;    // planes with fewer points after post-processing are dropped
  bool trade_lines = true;      // post-processing steps, each may be turned off
  bool trade_points = true;
  bool merge_planes = true;
  bool ray_noise = false;       // eq. (13, 14) use the spread across the plane of noise along rays
  double offset_sigmas = 0;     // a line fits a plane only within this many standard errors; 0 off
  double correlation_px = 5;    // neighbouring points that share one stereo window
  double offset_min = 0.01;     // offsets up to this always pass the offset test, metres
  bool merge_across_missing = true;  // regions separated only by missing points are neighbours
  bool merge_coplanar = false;  // also merge coplanar regions that are not neighbours in the image
};

// Table 1 settings for precise range data such as the ideal depth mode: C_max = 10 and a
// sigma floor of 0.3 mm (depth rounded to whole millimetres has sigma 0.29 mm).
inline SegmentParams PreciseRangeParams() {
  SegmentParams p;
  p.c_max = 10;
  p.sigma_min = 0.0003;
  return p;
}

// Table 1 settings plus the extensions for range noise along the viewing rays (stereo): the
// expected spread across the plane in eq. (13, 14) and the mean offset test, at 3 standard
// errors with offsets up to 5 mm passing.
inline SegmentParams RayNoiseParams() {
  SegmentParams p;
  p.ray_noise = true;
  p.offset_sigmas = 3;
  p.offset_min = 0.005;
  return p;
}

// Segments an organised point image (camera frame, NaN = no data) into planes by extended
// scan-line grouping: line extraction, seeds, region growing, line trading, point trading,
// plane merging (paper Section 3). Each point is read only in line extraction and point trading.
PlaneSet SegmentPlanes(const PointImage& points, const SegmentParams& p = {});

// ---- scoring against ground truth ----

// Which ground-truth surfaces are scored and how strictly (DESIGN.md "Ground truth").
struct ScoreParams {
  int min_surface_px = 50;      // surfaces covering fewer pixels are ignored
  double max_depth_m = 2.5;     // surfaces whose median depth is farther are ignored
  double tolerance = 0.8;       // Hoover et al.'s compare tolerance T
};

// Scores of a segmentation against ground-truth surfaces. Accuracy and coverage associate one
// to one and count only pixels whose true depth is within max_depth_m: each segment belongs to
// the surface it overlaps most, each scored surface takes the segment of its own that overlaps it
// most, and a scored surface without one is missed (it lowers coverage, not accuracy). Both are 0
// when no surface is scored. Hoover counts use all pixels: a segment enters them if at least half
// of its pixels lie on scored surfaces; a scored surface without a correct/over/under instance is
// missed, such a segment without one is noise.
struct SegmentationScore {
  double accuracy = 0;   // sum |S ∩ G| / sum |S| over scored G and their segments (Table 2)
  double coverage = 0;   // sum |S ∩ G| / sum |G| over scored G
  int correct = 0;       // Hoover: correct detections
  int over = 0;          // over-segmented surfaces
  int under = 0;         // under-segmenting segments
  int missed = 0;        // missed surfaces
  int noise = 0;         // noise segments
  int planes = 0;        // segments in the label image
  int truth_surfaces = 0;  // scored ground-truth surfaces
  int64_t overlap_px = 0;  // sum |S ∩ G|
  int64_t segment_px = 0;  // sum |S|
  int64_t surface_px = 0;  // sum |G|
};

// Scores a label image (segment ids >= 0, -1 none) against ground-truth surface ids (>= 0, -1
// none) and depth (metres, NaN none), all the same size.
SegmentationScore ScoreSegmentation(const LabelImage& labels, const LabelImage& truth_surface_ids,
                                    const DepthImage& truth_depth_m, const ScoreParams& p = {});

// The ground truth's surfaces are the world's planar surfaces, not the faces of its geoms: faces
// of different geoms that touch and lie in one plane (a table leg flush with the top's edge, two
// blocks side by side) are one surface that no range data can split. Joins every two surface
// ids that are 4-neighbours somewhere in the image and whose exact points (`exact_points`, from
// the renderer's depth, the same size) fit one plane: the RMS residual of their joint fit is at
// most `tolerance` metres and their own normals differ by at most max_angle radians. Only
// surfaces with a normal of their own take part: at least min_points points, spread by at
// least min_spread metres (standard deviation) in two directions. A joined surface takes the
// lowest of its ids.
LabelImage JoinCoplanarSurfaces(const LabelImage& truth_surface_ids, const PointImage& exact_points,
                                double tolerance = 0.001, double max_angle = 0.02,
                                int min_points = 20, double min_spread = 0.005);

// Range data against the renderer's depth, in disparity pixels (d = fx B / z), as stereo
// benchmarks score it; over pixels whose true depth is finite and at most max_depth_m.
struct StereoScore {
  int64_t pixels = 0;           // pixels with a true depth in range
  double valid = 0;             // share of them with a point
  double median_error_px = 0;   // median |d - d_true| over valid pixels
  double bad_1px = 0;           // share of valid pixels with |d - d_true| > 1 px
  double median_depth_error = 0;  // median |z - z_true|, metres
};

// Scores a point image (camera frame, NaN none) against true depth (metres along the optical
// axis, NaN none) of the same size.
StereoScore ScoreStereo(const PointImage& points, const DepthImage& truth_depth_m,
                        const CameraIntrinsics& K, double max_depth_m = 2.5);

// Pools scores of several views: counts add, accuracy and coverage are recomputed from the
// pixel sums.
SegmentationScore CombineScores(const std::vector<SegmentationScore>& scores);

// The median of a list, the mean of the middle two for an even count; 0 if empty.
double Median(std::vector<double> values);

// Pools range scores of several views: pixels add, the shares are weighted by pixels, the
// errors are the median of the views' medians (views without a valid point left out).
StereoScore CombineStereoScores(const std::vector<StereoScore>& scores);

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_SEGMENTATION_H_

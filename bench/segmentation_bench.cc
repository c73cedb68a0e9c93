// Benchmarks of stereo range data and plane segmentation on analytic scenes (a floor, a
// three-step staircase, a low box and a wall), with OpenCV's RgbdPlane beside ours when the
// rgbd module is available and PCL's OrganizedMultiPlaneSegmentation when libpcl-dev is
// installed. Counters: planes found and the Table 2 accuracy / coverage against
// the scene's surfaces (DESIGN.md "Ground truth").
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <benchmark/benchmark.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#ifdef FOGNAV_HAVE_OPENCV_RGBD
#include <opencv2/rgbd.hpp>
#endif
#ifdef FOGNAV_HAVE_PCL
#include <pcl/features/integral_image_normal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/organized_multi_plane_segmentation.h>
#endif

#include "perception/internal/scanline_scenes.h"
#include "perception/segmentation.h"

namespace fognav::perception {
namespace {

using internal::Scene;

// The bench course seen from the humanoid's head (0.55 m, pitched down 25°).
Scene BenchScene() {
  Scene scene = internal::Staircase(1.0, 3, 0.25, 0.03);
  scene.boxes.push_back({Eigen::Vector3d(0.6, 0.25, 0), Eigen::Vector3d(0.8, 0.45, 0.08)});
  scene.boxes.push_back({Eigen::Vector3d(2.6, -3, 0), Eigen::Vector3d(2.8, 3, 2)});
  return scene;
}

Eigen::Isometry3d BenchCamera() { return internal::SceneCamera(0, -0.1, 0.55, 25 * M_PI / 180); }

// A point image of the bench scene with stereo-like depth noise (2 mm at 1 m, growing with z^2)
// and its ground truth, made once per size.
struct BenchInput {
  PointImage points;
  internal::SceneView truth;
  CameraIntrinsics K;
};

const BenchInput& Input(int w, int h) {
  static std::map<std::pair<int, int>, BenchInput> cache;
  auto it = cache.find({w, h});
  if (it != cache.end()) return it->second;
  BenchInput in;
  in.K = internal::SceneIntrinsics(w, h);
  in.truth = internal::RenderScene(BenchScene(), in.K, BenchCamera());
  DepthImage noisy = in.truth.depth;
  internal::AddDepthNoise(&noisy, 0.002, 1);
  in.points = DepthPointImage(noisy, in.K);
  return cache.emplace(std::make_pair(w, h), std::move(in)).first->second;
}

void SetScoreCounters(benchmark::State& state, const LabelImage& labels, const BenchInput& in) {
  const SegmentationScore s = ScoreSegmentation(labels, in.truth.surface, in.truth.depth);
  state.counters["planes"] = s.planes;
  state.counters["accuracy"] = s.accuracy;
  state.counters["coverage"] = s.coverage;
  state.counters["correct"] = s.correct;
  state.counters["truth"] = s.truth_surfaces;
}

// Registers fn as NAME/WxH at the point-image sizes of the speed targets, in milliseconds
// (static registration, like BENCHMARK, and in the same order).
int AtTargetSizes(const std::string& name, void (*fn)(benchmark::State&)) {
  for (const auto& [w, h] : {std::pair{176, 144}, std::pair{320, 240}, std::pair{640, 480}}) {
    benchmark::RegisterBenchmark((name + "/" + std::to_string(w) + "x" + std::to_string(h)).c_str(),
                                 fn)
        ->Args({w, h})
        ->Unit(benchmark::kMillisecond);
  }
  return 0;
}

void BM_Segmentation(benchmark::State& state) {
  const BenchInput& in = Input(int(state.range(0)), int(state.range(1)));
  PlaneSet set;
  for (auto _ : state) {
    set = SegmentPlanes(in.points);
    benchmark::DoNotOptimize(set.planes.data());
  }
  SetScoreCounters(state, set.labels, in);
}
const int kSegmentationRegistered = AtTargetSizes("Segmentation", BM_Segmentation);
BENCHMARK(BM_Segmentation)
    ->Name("Segmentation/88x72")->Args({88, 72})->Unit(benchmark::kMillisecond);

// the UB method (classic split, d_cord / d_line) on the same points, for the paper's comparison
void BM_SegmentationUb(benchmark::State& state) {
  const BenchInput& in = Input(int(state.range(0)), int(state.range(1)));
  SegmentParams p;
  p.method = LineMethod::kSplit;
  PlaneSet set;
  for (auto _ : state) {
    set = SegmentPlanes(in.points, p);
    benchmark::DoNotOptimize(set.planes.data());
  }
  SetScoreCounters(state, set.labels, in);
}
BENCHMARK(BM_SegmentationUb)
    ->Name("SegmentationUB/176x144")->Args({176, 144})->Unit(benchmark::kMillisecond);

// The same scene with the head stereo's depth noise (0.13 px disparity error at f = 212 px and
// B = 5 cm: 12 mm at 1 m along the ray), segmented with Table 1 (arg 0) or with the ray noise
// extensions of RayNoiseParams (arg 1).
void BM_SegmentationHeadStereoNoise(benchmark::State& state) {
  static const BenchInput in = [] {
    BenchInput b;
    b.K = internal::SceneIntrinsics(176, 144);
    b.truth = internal::RenderScene(BenchScene(), b.K, BenchCamera());
    DepthImage noisy = b.truth.depth;
    internal::AddDepthNoise(&noisy, 0.0123, 1);
    b.points = DepthPointImage(noisy, b.K);
    return b;
  }();
  const SegmentParams p = state.range(0) ? RayNoiseParams() : SegmentParams();
  PlaneSet set;
  for (auto _ : state) {
    set = SegmentPlanes(in.points, p);
    benchmark::DoNotOptimize(set.planes.data());
  }
  SetScoreCounters(state, set.labels, in);
}
BENCHMARK(BM_SegmentationHeadStereoNoise)
    ->Name("SegmentationHeadNoise/176x144/table1")->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SegmentationHeadStereoNoise)
    ->Name("SegmentationHeadNoise/176x144/ray_noise")->Arg(1)->Unit(benchmark::kMillisecond);

// range(2): StereoParams::refine_left_right_tolerance in hundredths of a pixel
void BM_Stereo(benchmark::State& state) {
  const auto K = internal::SceneIntrinsics(int(state.range(0)), int(state.range(1)));
  RgbImage left, right;
  internal::RenderStereoPair(BenchScene(), K, BenchCamera(), &left, &right);
  StereoParams params;
  params.refine_left_right_tolerance = 0.01 * double(state.range(2));
  PointImage points;
  for (auto _ : state) {
    points = StereoPointImage(left, right, K, params);
    benchmark::DoNotOptimize(points.points.data());
  }
  // segmentation of the matched points, scored against the scene
  BenchInput in;
  in.truth = internal::RenderScene(BenchScene(), K, BenchCamera());
  SetScoreCounters(state, SegmentPlanes(points).labels, in);
}
BENCHMARK(BM_Stereo)->Name("Stereo/176x144")->Args({176, 144, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stereo)
    ->Name("Stereo/176x144/refined_check")
    ->Args({176, 144, 30})
    ->Unit(benchmark::kMillisecond);

// The stereo peer: OpenCV's StereoSGBM, one plain pass over the same pair with our search range,
// block and penalties (no padding, left-right check or refinement); the timing includes the
// conversion to OpenCV's images, as Stereo's does.
void BM_StereoPeerSgbm(benchmark::State& state) {
  const auto K = internal::SceneIntrinsics(176, 144);
  RgbImage left, right;
  internal::RenderStereoPair(BenchScene(), K, BenchCamera(), &left, &right);
  const StereoParams p;
  const int area = p.block_size * p.block_size * 3;
  auto sgbm = cv::StereoSGBM::create(p.min_disparity, p.num_disparities, p.block_size, 8 * area,
                                     32 * area);
  auto to_mat = [](const RgbImage& image) {
    cv::Mat mat(image.height, image.width, CV_8UC3);
    for (int v = 0; v < image.height; ++v)
      for (int u = 0; u < image.width; ++u) {
        const Rgb& c = image.at(u, v);
        mat.at<cv::Vec3b>(v, u) = cv::Vec3b(c.b, c.g, c.r);
      }
    return mat;
  };
  cv::Mat disp16;
  for (auto _ : state) {
    sgbm->compute(to_mat(left), to_mat(right), disp16);
    benchmark::DoNotOptimize(disp16.data);
  }
}
BENCHMARK(BM_StereoPeerSgbm)->Name("StereoPeer/SGBM_1pass")->Unit(benchmark::kMillisecond);

#ifdef FOGNAV_HAVE_OPENCV_RGBD
// OpenCV's plane finder (cv::rgbd::RgbdPlane with RgbdNormals) on the same point images; the
// timing includes the normals.
void BM_OpenCvRgbdPlane(benchmark::State& state) {
  const BenchInput& in = Input(int(state.range(0)), int(state.range(1)));
  cv::Mat points(in.points.height, in.points.width, CV_32FC3);
  for (int v = 0; v < in.points.height; ++v)
    for (int u = 0; u < in.points.width; ++u) {
      const Eigen::Vector3f& p = in.points.at(u, v);
      points.at<cv::Vec3f>(v, u) = cv::Vec3f(p.x(), p.y(), p.z());
    }
  const cv::Matx33f K(float(in.K.fx), 0, float(in.K.cx), 0, float(in.K.fy), float(in.K.cy), 0, 0,
                      1);
  cv::rgbd::RgbdNormals normals_of(in.points.height, in.points.width, CV_32F, K, 5,
                                   cv::rgbd::RgbdNormals::RGBD_NORMALS_METHOD_FALS);
  // block size scaled with the image (40 px at 640x480), sensor error quadratic in depth
  const int block = std::max(8, in.points.width / 16);
  cv::rgbd::RgbdPlane planes_of(cv::rgbd::RgbdPlane::RGBD_PLANE_METHOD_DEFAULT, block,
                                block * block, 0.01, 0, 0, 0.004);
  cv::Mat normals, mask, coefficients;
  for (auto _ : state) {
    normals_of(points, normals);
    planes_of(points, normals, mask, coefficients);
    benchmark::DoNotOptimize(mask.data);
  }
  LabelImage labels(in.points.width, in.points.height, -1);
  for (int v = 0; v < mask.rows; ++v)
    for (int u = 0; u < mask.cols; ++u) {
      const int m = mask.at<uchar>(v, u);
      if (m != 255) labels.at(u, v) = m;
    }
  SetScoreCounters(state, labels, in);
}
const int kOpenCvRgbdPlaneRegistered = AtTargetSizes("OpenCvRgbdPlane", BM_OpenCvRgbdPlane);
#endif

#ifdef FOGNAV_HAVE_PCL
// PCL's plane finder on the same point images: integral-image normals (covariance method), then
// OrganizedMultiPlaneSegmentation with refinement (segmentAndRefine); the timing includes the
// normals. Thresholds: 2 cm to the plane, 3 degrees between normals, and PCL's default of 1000
// inliers at 640x480 scaled with the image (w h / 300, at least 30).
void BM_PclOrganizedMultiPlane(benchmark::State& state) {
  const BenchInput& in = Input(int(state.range(0)), int(state.range(1)));
  const int w = in.points.width, h = in.points.height;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>(w, h));
  cloud->is_dense = false;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3f& p = in.points.at(u, v);
      (*cloud)(u, v) = pcl::PointXYZ(p.x(), p.y(), p.z());
    }
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> normals_of;
  normals_of.setNormalEstimationMethod(normals_of.COVARIANCE_MATRIX);
  normals_of.setMaxDepthChangeFactor(0.02f);
  normals_of.setNormalSmoothingSize(float(std::max(5, w / 32)));
  pcl::OrganizedMultiPlaneSegmentation<pcl::PointXYZ, pcl::Normal, pcl::Label> planes_of;
  planes_of.setMinInliers(unsigned(std::max(30, w * h / 300)));
  planes_of.setAngularThreshold(3 * M_PI / 180);
  planes_of.setDistanceThreshold(0.02);
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  std::vector<pcl::PlanarRegion<pcl::PointXYZ>,
              Eigen::aligned_allocator<pcl::PlanarRegion<pcl::PointXYZ>>>
      regions;
  std::vector<pcl::ModelCoefficients> coefficients;
  std::vector<pcl::PointIndices> inliers, label_indices, boundaries;
  pcl::PointCloud<pcl::Label>::Ptr plane_labels;
  for (auto _ : state) {
    // a fresh label cloud each time: segment() resizes the one it is given without resetting
    // it, and stale labels from the last call make its union-find loop forever
    plane_labels.reset(new pcl::PointCloud<pcl::Label>);
    regions.clear();
    coefficients.clear();
    inliers.clear();
    label_indices.clear();
    boundaries.clear();
    normals_of.setInputCloud(cloud);
    normals_of.compute(*normals);
    planes_of.setInputNormals(normals);
    planes_of.setInputCloud(cloud);
    planes_of.segmentAndRefine(regions, coefficients, inliers, plane_labels, label_indices,
                               boundaries);
    benchmark::DoNotOptimize(inliers.data());
  }
  LabelImage labels(w, h, -1);
  for (size_t k = 0; k < inliers.size(); ++k)
    for (int i : inliers[k].indices) labels.data[size_t(i)] = int(k);
  SetScoreCounters(state, labels, in);
}
const int kPclOrganizedMultiPlaneRegistered = AtTargetSizes("PclOrganizedMultiPlane", BM_PclOrganizedMultiPlane);
#endif

}  // namespace
}  // namespace fognav::perception

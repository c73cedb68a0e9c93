#include "scenarios/video.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "scenarios/scenario.h"
#include "scenarios/views.h"

namespace fognav::scenarios {

namespace {

constexpr int kTitleHeight = 20, kStatusHeight = 22;

// the image scaled into a panel, centred on a dark background (BGR for OpenCV)
cv::Mat Panel(const perception::RgbImage& image, const char* title) {
  cv::Mat panel(kTitleHeight + MissionVideo::kPanelHeight, MissionVideo::kPanelWidth, CV_8UC3,
                cv::Scalar(40, 40, 40));
  cv::putText(panel, title, {6, 15}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(230, 230, 230), 1,
              cv::LINE_AA);
  if (image.width <= 0 || image.height <= 0) return panel;
  cv::Mat bgr(image.height, image.width, CV_8UC3);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const perception::Rgb& p = image.at(x, y);
      bgr.at<cv::Vec3b>(y, x) = {p.b, p.g, p.r};
    }
  }
  const double scale = std::min(double(MissionVideo::kPanelWidth) / image.width,
                                double(MissionVideo::kPanelHeight) / image.height);
  const int w = std::max(1, int(std::lround(image.width * scale)));
  const int h = std::max(1, int(std::lround(image.height * scale)));
  cv::Mat scaled;
  cv::resize(bgr, scaled, {w, h}, 0, 0, scale >= 1 ? cv::INTER_NEAREST : cv::INTER_AREA);
  scaled.copyTo(panel(cv::Rect((MissionVideo::kPanelWidth - w) / 2,
                               kTitleHeight + (MissionVideo::kPanelHeight - h) / 2, w, h)));
  return panel;
}

}  // namespace

Eigen::Isometry3d ChaseCamera(double x, double y, double yaw, double z) {
  const Eigen::Vector3d ahead(std::cos(yaw), std::sin(yaw), 0);
  const Eigen::Vector3d robot(x, y, z + 0.3);
  return LookAt(robot - 1.1 * ahead + Eigen::Vector3d(0, 0, 0.9), robot + 0.4 * ahead);
}

MissionVideo::MissionVideo(const std::string& path, double fps)
    : writer_(std::make_unique<cv::VideoWriter>()), path_(path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  int fourcc = 0;
  if (ext == ".avi") {
    fourcc = cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
  } else if (ext == ".mp4") {
    fourcc = cv::VideoWriter::fourcc('m', 'p', '4', 'v');
  } else if (ext == ".webm") {
    fourcc = cv::VideoWriter::fourcc('V', 'P', '8', '0');  // the one a browser plays in the page
  } else {
    throw InputError(path + ": --video: the file must end in .avi, .mp4 or .webm");
  }
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  const cv::Size size(3 * kPanelWidth, kTitleHeight + kPanelHeight + kStatusHeight);
  if (!writer_->open(path, fourcc, fps, size, true)) {
    throw OutputError(path + ": --video: could not open the file for writing");
  }
}

MissionVideo::~MissionVideo() = default;

void MissionVideo::Add(const perception::RgbImage& chase, const perception::RgbImage& head,
                       const perception::RgbImage& fog, const std::string& status) {
  cv::Mat top;
  cv::hconcat(std::vector<cv::Mat>{Panel(chase, "world"), Panel(head, "head camera (left)"),
                                   Panel(fog, "FOG and plan")},
              top);
  cv::Mat frame(top.rows + kStatusHeight, top.cols, CV_8UC3, cv::Scalar(20, 20, 20));
  top.copyTo(frame(cv::Rect(0, 0, top.cols, top.rows)));
  cv::putText(frame, status, {6, top.rows + 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(230, 230, 230), 1, cv::LINE_AA);
  writer_->write(frame);
  ++frames_;
}

}  // namespace fognav::scenarios

// The mission as a video for reviewers: a chase camera on the robot beside the head camera's
// left image and the FOG with the plan, one frame every few control ticks.
#ifndef FOGNAV_SCENARIOS_VIDEO_H_
#define FOGNAV_SCENARIOS_VIDEO_H_

#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "perception/types.h"

namespace cv {
class VideoWriter;
}

namespace fognav::scenarios {

// A camera pose (OpenCV convention) behind and above a robot at (x, y, yaw) on floor height z,
// looking at it: the chase view of the video.
Eigen::Isometry3d ChaseCamera(double x, double y, double yaw, double z);

class MissionVideo {
 public:
  static constexpr int kPanelWidth = 320, kPanelHeight = 240;

  // Opens `path` for writing: .avi is Motion-JPEG, .mp4 is MPEG-4 part 2, .webm is VP8 (which
  // browsers play, so report.html shows it). Throws InputError naming the path if the
  // extension is none of these, OutputError if the file cannot be opened.
  MissionVideo(const std::string& path, double fps);
  ~MissionVideo();
  MissionVideo(const MissionVideo&) = delete;
  MissionVideo& operator=(const MissionVideo&) = delete;

  // Appends one frame of three panels (each scaled to fit 320x240, aspect kept) with their
  // titles and a status line (cycle, move, distance to the goal) across the bottom.
  void Add(const perception::RgbImage& chase, const perception::RgbImage& head,
           const perception::RgbImage& fog, const std::string& status);

  int frames() const { return frames_; }

 private:
  std::unique_ptr<cv::VideoWriter> writer_;
  std::string path_;
  int frames_ = 0;
};

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_VIDEO_H_

// The mission video: frames of three titled panels, readable back with the size and count
// written, each panel's picture where it belongs.
#include "scenarios/video.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>

#include "scenarios/scenario.h"

namespace fognav::scenarios {
namespace {

perception::RgbImage Filled(int width, int height, perception::Rgb colour) {
  perception::RgbImage image(width, height);
  for (auto& p : image.data) p = colour;
  return image;
}

// mean BGR colour of a block of a frame
cv::Vec3d Mean(const cv::Mat& frame, int x, int y) {
  const cv::Scalar m = cv::mean(frame(cv::Rect(x - 10, y - 10, 20, 20)));
  return {m[0], m[1], m[2]};
}

class MissionVideoTest : public ::testing::TestWithParam<std::string> {};

TEST_P(MissionVideoTest, WritesFramesOfThreePanels) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("fognav_video_test" + GetParam())).string();
  std::filesystem::remove(path);
  {
    MissionVideo video(path, 10);
    // panels of different shapes: each is scaled to fit 320x240
    for (int i = 0; i < 12; ++i) {
      video.Add(Filled(640, 480, {200, 30, 30}), Filled(176, 144, {30, 200, 30}),
                Filled(300, 150, {30, 30, 200}), "cycle " + std::to_string(i));
    }
    EXPECT_EQ(video.frames(), 12);
  }
  cv::VideoCapture capture(path);
  ASSERT_TRUE(capture.isOpened()) << path;
  EXPECT_EQ(int(capture.get(cv::CAP_PROP_FRAME_WIDTH)), 3 * MissionVideo::kPanelWidth);
  int frames = 0;
  cv::Mat frame, first;
  while (capture.read(frame)) {
    if (frames == 0) first = frame.clone();
    ++frames;
  }
  EXPECT_EQ(frames, 12);
  ASSERT_FALSE(first.empty());
  // the middle of each panel has its picture's colour (BGR, lossy)
  const int y = first.rows / 2;
  const cv::Vec3d red = Mean(first, 160, y), green = Mean(first, 480, y), blue = Mean(first, 800, y);
  EXPECT_GT(red[2], 150);
  EXPECT_LT(red[1], 80);
  EXPECT_GT(green[1], 150);
  EXPECT_LT(green[0], 80);
  EXPECT_GT(blue[0], 150);
  EXPECT_LT(blue[2], 80);
  // the wide FOG picture (2:1) is letterboxed: dark above and below it
  const cv::Vec3d above = Mean(first, 800, 40);
  EXPECT_LT(above[0], 80);
  std::filesystem::remove(path);
}

INSTANTIATE_TEST_SUITE_P(Formats, MissionVideoTest, ::testing::Values(".avi", ".mp4", ".webm"));

TEST(MissionVideo, RefusesOtherFormatsNamingThePath) {
  try {
    MissionVideo video("/tmp/fognav_video_test.gif", 10);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/fognav_video_test.gif"), std::string::npos);
  }
}

}  // namespace
}  // namespace fognav::scenarios

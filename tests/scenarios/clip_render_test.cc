// Clips of the controller's motions: frames from the external camera and a strip, no collisions.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "scenarios/clips.h"
#include "scenarios/scenario.h"

namespace fognav::scenarios {
namespace {

TEST(Clips, EachMotionWritesFramesAndAStripWithoutCollisions) {
  for (const std::string& motion : ClipMotions()) {
    const std::string dir = ::testing::TempDir() + "/fognav_clip_" + motion;
    std::filesystem::remove_all(dir);
    const ClipResult result = RecordClip(motion, dir, 50);
    EXPECT_GE(result.frames, 3) << motion;
    EXPECT_EQ(result.collisions, 0) << motion;
    const cv::Mat strip = cv::imread(dir + "/strip.png");
    ASSERT_FALSE(strip.empty()) << motion;
    const int shown = std::min(result.frames, 6);
    EXPECT_EQ(strip.cols, shown * 320 + (shown - 1) * 2) << motion;
    EXPECT_EQ(strip.rows, 240) << motion;
    // the frames differ: the robot moves in them
    const cv::Mat first = cv::imread(dir + "/frame_00000.png");
    char last[32];
    std::snprintf(last, sizeof(last), "/frame_%05d.png", result.frames - 1);
    EXPECT_GT(cv::norm(first, cv::imread(dir + last), cv::NORM_L1), 0.0) << motion;
  }
}

TEST(Clips, UnknownMotionOrPeriodIsAnInputError) {
  const std::string dir = ::testing::TempDir() + "/fognav_clip_bad";
  EXPECT_THROW(RecordClip("moonwalk", dir, 5), InputError);
  EXPECT_THROW(RecordClip("walk", dir, 0), InputError);
}

}  // namespace
}  // namespace fognav::scenarios

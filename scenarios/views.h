// What the program does with a scenario short of running the loop: build its world, place the
// robot at its start pose, render the head camera's views and write them out.
#ifndef FOGNAV_SCENARIOS_VIEWS_H_
#define FOGNAV_SCENARIOS_VIEWS_H_

#include <string>

#include "perception/types.h"
#include "scenarios/output.h"
#include "scenarios/scenario.h"
#include "sim/render.h"
#include "sim/world.h"

namespace fognav::scenarios {

// The world a scenario describes: its floor and solids, and the humanoid when with_robot.
sim::WorldSpec MakeWorldSpec(const Scenario& scenario, bool with_robot = true);

// The intrinsics of the scenario's head cameras (both eyes share them).
perception::CameraIntrinsics HeadIntrinsics(const SensorSettings& sensor);

// A stereo view of the head cameras: left and right colour, left depth and surface ids.
struct StereoView {
  perception::CameraIntrinsics intrinsics;
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();  // left camera in the world (OpenCV)
  perception::RgbImage left, right;
  perception::DepthImage depth;      // left camera, metres, NaN where nothing is seen
  perception::LabelImage surfaces;   // left camera, sim surface ids, -1 where nothing is seen
};

// Places the humanoid standing at `pose` (world frame, on the floor) and returns the pose of its
// left eye in the world (OpenCV convention). Throws sim::SimError if the world has no robot.
Eigen::Isometry3d PlaceRobot(sim::World* world, const perception::Pose2& pose);

// Renders the stereo pair from a left camera pose; the right camera sits `baseline` to its
// right (camera +x).
StereoView RenderStereo(sim::Renderer* renderer, const sim::World& world,
                        const Eigen::Isometry3d& X_WL, const SensorSettings& sensor);

// A camera pose (OpenCV convention) at `eye` looking at `target`, world z up in the image.
Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

// A 640x400 colour view of the whole course from behind and above the start, for people.
perception::RgbImage RenderOverview(sim::Renderer* renderer, const sim::World& world,
                                    const Scenario& scenario);

// Writes an RGB image as PNG. Throws OutputError naming the path if it cannot.
void WritePng(const perception::RgbImage& image, const std::string& path);

// Writes left.png, right.png, depth.png (16-bit millimetres, 0 = nothing seen), surfaces.png
// (each surface id a distinct colour) and intrinsics.json into dir (created if missing).
// Throws OutputError if dir cannot be written.
void WriteStereoView(const StereoView& view, const std::string& dir);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_VIEWS_H_

// One perception cycle of the loop (DESIGN.md data flow), shared by `fognav perceive` and the
// mission runner: stereo pair -> points -> planes -> labelled points -> maps, with the scores
// of each view against the renderer's ground truth.
#ifndef FOGNAV_SCENARIOS_PERCEPTION_CYCLE_H_
#define FOGNAV_SCENARIOS_PERCEPTION_CYCLE_H_

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "perception/localization.h"
#include "perception/mapping.h"
#include "perception/segmentation.h"
#include "scenarios/params.h"
#include "scenarios/scenario.h"
#include "scenarios/views.h"
#include "sim/controller.h"
#include "sim/humanoid.h"

namespace fognav::scenarios {

// What one view gave, for frames and reports.
struct ViewResult {
  perception::PointImage points;        // camera frame (sub-sampled if params.subsample)
  perception::Image<float> disparity;   // pixels, NaN where invalid; empty in ideal mode
  perception::PlaneSet planes;
  perception::SegmentationScore segmentation;
  perception::StereoScore stereo;  // range data against the renderer's depth
  perception::Pose2 robot_G;       // the pose the maps were updated with (localized if asked)
  Eigen::Isometry3d X_GC = Eigen::Isometry3d::Identity();  // the left camera it implies, grid frame
  // the labelled points the maps were updated with (grid frame, robot's own body dropped)
  std::vector<perception::LabelledPoint> labelled_G;
  perception::LocalizationReport localization;  // what localizing the view did
  double stereo_ms = 0, segmentation_ms = 0, mapping_ms = 0, localization_ms = 0;
};

// The look-around head sweep a mission starts with: the controller's near and middle rings plus
// a near-level ring, so that undersides above the eyes (a table to crawl under) are seen.
std::vector<sim::HeadAngles> StartSweep();

// The robot's own surfaces are not part of the world: their ids become -1 (none).
perception::LabelImage WorldSurfaces(const perception::LabelImage& surfaces,
                                     const sim::Humanoid& humanoid);

// Perceives one stereo view and updates the maps. The robot stands at robot_G (odometry, grid
// frame) on a floor floor_z high; X_RC is the left camera and body_R the robot's body boxes in
// the robot frame (kinematics). With `localization` the view's vertical planes first correct
// robot_G (CorrectPose), and the maps are updated with the corrected pose, which the result
// returns.
ViewResult PerceiveView(const PerceptionParams& params, DepthMode mode, const StereoView& view,
                        const sim::Humanoid& humanoid, const perception::Pose2& robot_G,
                        double floor_z, const Eigen::Isometry3d& X_RC,
                        const std::vector<sim::RobotBox>& body_R, perception::MapState* maps,
                        perception::LocalizationState* localization = nullptr);

// The ground-truth FOG of the scenario's world in the window; the grid frame is the world frame
// shifted by `X_GW` (identity while odometry has no error).
perception::Fog TruthFog(const Scenario& scenario, const perception::GridWindow& window,
                         const perception::FogParams& params,
                         const Eigen::Isometry3d& X_GW = Eigen::Isometry3d::Identity());

// Writes frames/<prefix>_left.png, _disparity.png (if any) and _segments.png into dir.
void WriteViewFrames(const StereoView& view, const ViewResult& result, const std::string& dir,
                     const std::string& prefix);

// The FOG scores as report.json and perception.json hold them under "fog" (docs/scores.md).
nlohmann::json FogScoreJson(const perception::FogScore& s);

// `fognav perceive`: keeps the robot at its start pose, runs the look-around head sweep,
// perceives every view and writes DIR/perception.json, DIR/frames/ and DIR/maps/.
// Returns the JSON text it wrote. Throws OutputError for an unwritable DIR, SimError if the
// simulator cannot run. `params` may change the perception (the UB line method, for the
// paper's comparison).
std::string RunPerceive(const Scenario& scenario, const std::string& out_dir, bool quiet,
                        const PerceptionParams& params = {});

// `fognav perceive --depth both`: RunPerceive with stereo into DIR/stereo and with the
// renderer's depth into DIR/ideal, and DIR/perception.json holding both reports under "stereo"
// and "ideal", so that the sensor's ceiling stands beside what stereo gives. Returns that text.
std::string RunPerceiveBoth(const Scenario& scenario, const std::string& out_dir, bool quiet,
                            const PerceptionParams& params = {});

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_PERCEPTION_CYCLE_H_

// Pages a reviewer opens in a browser, one per output folder: plain HTML with inline CSS and
// SVG, no scripts, fonts or anything else from elsewhere; the pictures are linked relative to the
// page, so the folder can be moved or archived whole.
#ifndef FOGNAV_VIZ_PAGES_H_
#define FOGNAV_VIZ_PAGES_H_

#include <string>

#include <Eigen/Core>

#include "navigation/planner.h"
#include "perception/mapping.h"
#include "perception/types.h"

namespace fognav::viz {

// `text` for HTML or XML text and attribute values: & < > " ' as entities, control characters
// but the newline as spaces.
std::string EscapeMarkup(const std::string& text);

// Writes out_dir/report.html and out_dir/maps/mission.png (DrawMissionMap) for a mission whose
// report.json, trajectory.csv and cycles.csv, frames/final_* and maps/ are in out_dir already.
// The page: a title with the scenario, the outcome (element #outcome: "success" or "failed")
// and the failure (#failure: its name or "none") with its detail; report.json's figures as a
// table; the whole floor (floor_truth, the ground-truth FOG of the whole floor in the world
// frame, with `optimal` on it, the true and believed ways, start_W and goal_W); a timeline over
// the cycles (distance to the goal, the plan's length, the plan and the decision, the failure
// cycle marked); for a failure the map at that cycle and the last decisions; the last frames;
// the maps at the end; the video when video_path is not empty. Throws std::runtime_error naming
// a file that cannot be read, perception::OutputError one that cannot be written.
void WriteMissionPage(const std::string& out_dir, const perception::Fog& floor_truth,
                      const navigation::PlanResult& optimal, const perception::Pose2& start_W,
                      const Eigen::Vector2d& goal_W, const std::string& video_path);

// Writes out_dir/report.html for `fognav perceive`: the scores of perception.json as tables
// (overall, FOG confusion, one row per view with its left, disparity and segment frames) and
// the maps. Throws std::runtime_error naming a file that cannot be read, perception::OutputError
// one that cannot be written.
void WritePerceivePage(const std::string& out_dir);

}  // namespace fognav::viz

#endif  // FOGNAV_VIZ_PAGES_H_

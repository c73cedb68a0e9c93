// The closed loop (DESIGN.md): look around, then each cycle render the head's stereo pair,
// perceive, update the maps with the odometry pose, plan on the FOG, execute the first moves
// with the stepping controller; until the goal is reached, no path remains, a collision occurs
// (when expected not to) or the limits are hit.
#ifndef FOGNAV_SCENARIOS_MISSION_H_
#define FOGNAV_SCENARIOS_MISSION_H_

#include <atomic>
#include <string>

#include "scenarios/scenario.h"

namespace fognav::scenarios {

struct MissionOptions {
  std::string out_dir;  // report.json, trajectory.csv, cycles.csv, frames/, maps/
  int dump_every = 0;   // write frames and maps every N cycles (0: only at the end)
  bool quiet = false;   // no progress line and no summary
  // if set, the mission as a video (.avi, .mp4 or .webm): chase camera, head camera and FOG
  // with the plan, a frame every video_period_s of simulated time, played at video_fps
  std::string video_path;
  double video_period_s = 0.1;
  double video_fps = 20;
  // if set, read at the start of every cycle: once true, the mission ends there with failure
  // "interrupted" and writes its report, logs and maps as at any other end (a signal handler
  // sets it)
  const std::atomic<bool>* stop = nullptr;
};

// What a mission ended with; the full figures are in the report.
struct MissionOutcome {
  bool success = false;        // every expectation of the scenario held
  bool reached_goal = false;   // ground truth within the goal tolerance
  std::string failure;         // "" or no_path, collision, off_floor, timeout, interrupted
  std::string report_json;     // the text written to report.json
};

// Runs the mission. report.json is written last and whole (a stale one is removed first), so
// it exists only for a mission that ended. Throws OutputError if an output file cannot be
// written, sim::SimError if the simulator cannot run.
MissionOutcome RunMission(const Scenario& scenario, const MissionOptions& options);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_MISSION_H_

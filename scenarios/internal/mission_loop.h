// The parts of the mission loop (scenarios/mission.cc) that a mission stepped from outside
// (scenarios/mission_session.h) shares with it: when a mission ends, and its report.
#ifndef FOGNAV_SCENARIOS_INTERNAL_MISSION_LOOP_H_
#define FOGNAV_SCENARIOS_INTERNAL_MISSION_LOOP_H_

#include <chrono>
#include <string>

#include "navigation/planner.h"
#include "scenarios/behaviour.h"
#include "scenarios/internal/mission_robot.h"
#include "scenarios/mission.h"
#include "scenarios/params.h"
#include "scenarios/scenario.h"

namespace fognav::scenarios::internal {

// How a mission ended, for its report.
struct MissionEnd {
  std::string failure, failure_detail;
  int cycles = 0;
  navigation::PlanResult plan;  // the last cycle's
  std::chrono::steady_clock::time_point wall_start;
};

// Whether the mission ends before cycle `cycle` + 1: with the goal reached (no failure), or with
// the failure and what caused it.
bool MissionEnds(const Scenario& scenario, const MissionOptions& options, const MissionRobot& robot,
                 int cycle, std::string* failure, std::string* detail);

// Scores the end state against the ground truth, writes the pictures, report.json and
// report.html.
MissionOutcome Report(const Scenario& scenario, const MissionOptions& options,
                      const RunParams& run_params, const navigation::PlannerParams& planner,
                      MissionRobot& robot, const MissionEnd& end);

// What one cycle did: moved (a decision to follow), only looked (or nothing), or gave up (the
// mission ends in no_path).
enum class CycleEnd { kMoved, kLooked, kGaveUp };

// One cycle of the loop with the built-in behaviour: plan and decide on the FOG, log the
// cycles.csv row, then look around, or execute the decision's moves and look after them.
CycleEnd RunCycle(const MissionOptions& options, const RunParams& run_params, MissionRobot& robot,
                  Behaviour& behaviour, MissionEnd* end);

}  // namespace fognav::scenarios::internal

#endif  // FOGNAV_SCENARIOS_INTERNAL_MISSION_LOOP_H_

// The Slurm backend of `fognav sweep`: the runs still to do as a job array, followed to its end.
#ifndef FOGNAV_SCENARIOS_INTERNAL_SWEEP_SLURM_H_
#define FOGNAV_SCENARIOS_INTERNAL_SWEEP_SLURM_H_

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "scenarios/sweep.h"

namespace fognav::scenarios::internal {

// The sbatch script of a job array whose task t does the runs tasks[t] (indices into rows) one
// after another, each writing runs/NAME/ and runs/NAME/exit_code; paths are made absolute.
std::string SbatchScript(const SweepOptions& options, const std::vector<SweepRow>& rows,
                         const std::vector<std::vector<size_t>>& tasks);

// The array tasks' states from the text of `squeue -h -r -t all -o "%K|%T"` or of
// `sacct -n -P -X -o JobID,State` (JobID "123_4"): {task id: state}; other lines are skipped.
std::map<int, std::string> ParseTaskStates(const std::string& text);

// Submits the runs todo (indices into rows) with sbatch, follows the job with squeue and sacct
// until every task ended, and fills their rows; a run that did not end by itself (no exit code
// written: its task was cancelled, timed out, failed) is an error naming the task's Slurm state. Returns false if
// options.stop ended the sweep first (the job is cancelled then). Throws std::runtime_error if
// sbatch fails.
bool RunSlurm(const SweepOptions& options, const std::vector<size_t>& todo,
              std::vector<SweepRow>* rows);

}  // namespace fognav::scenarios::internal

#endif  // FOGNAV_SCENARIOS_INTERNAL_SWEEP_SLURM_H_

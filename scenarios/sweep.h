// `fognav sweep`: many runs of the program (missions, or start views with --perceive), each a
// process of its own on this machine or a task of a Slurm job array, gathered into one table
// (results.tsv, results.json), a JUnit file, a summary and an index page. A run is finished
// when its report and, written last, its report.html are there; a rerun of the same sweep keeps
// the finished runs and redoes the others.
#ifndef FOGNAV_SCENARIOS_SWEEP_H_
#define FOGNAV_SCENARIOS_SWEEP_H_

#include <atomic>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace fognav::scenarios {

// One run of a sweep: a scenario file, with a seed when the sweep has --seeds and a point of
// the grid of parameter overrides when it has --set.
struct SweepRun {
  std::string name;      // its folder under DIR/runs/: the file's stem, "_s<seed>", "_key=value"
  std::string scenario;  // the scenario file as given (or found in a given folder)
  int seed = -1;         // passed as `run --seed`; -1: the scenario's own
  std::vector<std::string> params;  // "section.key=value", each passed as `--set`
};

// Which cluster runs the sweep's runs, and how.
struct SlurmOptions {
  std::string partition;  // sbatch --partition; "" the cluster's default
  std::string time;       // sbatch --time per task, e.g. "00:30:00"; "" the partition's
  std::string mem;        // sbatch --mem per task, e.g. "2G"; "" the partition's
  int per_task = 1;       // runs done one after another by each array task
  double poll_s = 2;      // seconds between looks at squeue (the runs' files: every 0.2 s)
};

struct SweepOptions {
  std::vector<std::string> scenarios;  // files, folders (their *.yaml) or glob patterns
  std::string out_dir;                 // DIR: runs/, results.*, junit.xml, index.html
  int seeds = 0;                       // N > 0: every scenario with seeds 1..N
  std::vector<std::string> sets;       // "section.key=v1,v2,...": a run per combination
  int jobs = 0;                        // local workers; 0: the number of cores
  bool perceive = false;               // `fognav perceive` (scored start views), not missions
  std::string compare_dir;             // an earlier sweep's DIR: list the changed outcomes
  std::string program;                 // the fognav binary the runs use
  std::string backend = "local";       // local or slurm
  SlurmOptions slurm;
  const std::atomic<bool>* stop = nullptr;  // once true, no run starts and the sweep ends
};

// One row of the results: a run and what it ended with.
struct SweepRow {
  SweepRun run;
  bool finished = false;  // its report and page are there (and the run was not interrupted)
  int exit_code = -1;     // the program's: 0 or 1 from a report; else as it ended
  std::string outcome;    // success, a failure class, "error" or "not run"
  std::string failure;    // the report's failure ("" none), or the error
  std::string detail;     // the report's failure detail, or the error's last line
  bool reached_goal = false;
  int cycles = 0;
  int collisions = 0;
  double spl = 0;
  double optimal_path_length = 0;  // 0: no way on the ground truth (NaN: unknown)
  double wall_time_s = 0;          // NaN: unknown
  double traversability = 0;       // FOG score (docs/scores.md), NaN: none
  int unsafe_cells = 0;
  // --perceive: the start views' scores
  double accuracy = 0, coverage = 0, fog_accuracy = 0;
  int correct = 0, surfaces = 0, fog_cells = 0;
};

// The runs of a sweep in name order. Throws InputError naming a scenario argument that matches
// nothing, or two files whose runs would share a folder.
std::vector<SweepRun> PlanSweep(const SweepOptions& options);

// The program's arguments for one run (without the program itself), writing into run_dir.
std::vector<std::string> RunArguments(const SweepOptions& options, const SweepRun& run,
                                      const std::string& run_dir);

// A run's row from its folder: its report when there is one, otherwise the exit code given
// (-1: not run) and the first line of run_dir/stderr.log as the detail.
SweepRow ReadRow(const SweepRun& run, const std::string& run_dir, bool perceive, int exit_code);

// The Wilson score interval of successes out of n at 95 %: {lo, hi}; {0, 1} when n is 0.
std::pair<double, double> Wilson(int successes, int n);

// The summary printed at the end and kept in results.json: success rate with its interval over
// the runs with a way on the ground truth, collisions, failures by class, the runs without a
// way apart (missions); the scores' means (perceive).
std::string FormatSummary(const std::vector<SweepRow>& rows, bool perceive);

// Writes results.tsv, results.json, junit.xml and index.html into out_dir. Throws OutputError.
void WriteSweepFiles(const std::string& out_dir, const std::vector<SweepRow>& rows, bool perceive);

// The outcome of each run in old_dir/results.tsv, by run name. Throws InputError if it cannot be
// read or has no name and outcome columns.
std::map<std::string, std::string> ReadOutcomes(const std::string& old_dir);
// "name: old -> new" for each run in rows whose outcome differs from `old`'s.
std::vector<std::string> CompareOutcomes(const std::vector<SweepRow>& rows,
                                         const std::map<std::string, std::string>& old);

// Runs the sweep, prints its progress to stderr and its summary to stdout, writes its files.
// Returns the exit code: 0 every run passed, 1 some run failed or could not run, 4 stopped
// (options.stop) before every run ended. Throws InputError for bad options.
int RunSweep(const SweepOptions& options);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_SWEEP_H_

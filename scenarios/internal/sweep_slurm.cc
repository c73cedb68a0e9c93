#include "scenarios/internal/sweep_slurm.h"

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "scenarios/output.h"

namespace fognav::scenarios::internal {
namespace {

namespace fs = std::filesystem;

// the text in single quotes for sh: ' becomes '\''
std::string Quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string Absolute(const std::string& path) { return fs::absolute(path).lexically_normal(); }

// runs a command with sh and returns its exit code (-1 if it could not run) and its stdout
int Capture(const std::string& command, std::string* output) {
  output->clear();
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return -1;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) output->append(buffer, n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool Ended(const std::string& state) {
  static const std::set<std::string> kEnded = {"COMPLETED", "FAILED",        "CANCELLED",
                                               "TIMEOUT",   "OUT_OF_MEMORY", "NODE_FAIL",
                                               "PREEMPTED", "BOOT_FAIL",     "DEADLINE"};
  return kEnded.count(state) > 0;
}

int ExitCodeFile(const std::string& path) {
  std::ifstream in(path);
  int code = -1;
  return in >> code ? code : -1;
}

}  // namespace

std::string SbatchScript(const SweepOptions& options, const std::vector<SweepRow>& rows,
                         const std::vector<std::vector<size_t>>& tasks) {
  const std::string out = Absolute(options.out_dir);
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "# fognav sweep: task t of this job array does the runs of its case below\n"
    << "#SBATCH --job-name=fognav-sweep\n"
    << "#SBATCH --array=0-" << tasks.size() - 1 << "\n"
    << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n"
    << "#SBATCH --chdir=" << Quote(out) << "\n"
    << "#SBATCH --output=" << Quote(out + "/slurm/task_%a.log") << "\n";
  if (!options.slurm.partition.empty())
    s << "#SBATCH --partition=" << options.slurm.partition << "\n";
  if (!options.slurm.time.empty()) s << "#SBATCH --time=" << options.slurm.time << "\n";
  if (!options.slurm.mem.empty()) s << "#SBATCH --mem=" << options.slurm.mem << "\n";
  s << "\n# a run starts afresh in its folder; its exit code is written when it ends\n"
    << "run() {\n  dir=\"$1\"; shift\n  rm -rf \"$dir\" && mkdir -p \"$dir\" || return\n"
    << "  \"$@\" > /dev/null 2> \"$dir/stderr.log\"\n"
    << "  echo $? > \"$dir/exit_code.tmp\" && mv \"$dir/exit_code.tmp\" \"$dir/exit_code\"\n}\n\n"
    << "case \"$SLURM_ARRAY_TASK_ID\" in\n";
  for (size_t t = 0; t < tasks.size(); ++t) {
    s << "  " << t << ")\n";
    for (size_t i : tasks[t]) {
      SweepRun run = rows[i].run;
      run.scenario = Absolute(run.scenario);
      const std::string dir = out + "/runs/" + run.name;
      s << "    run " << Quote(dir) << " " << Quote(Absolute(options.program));
      for (const auto& a : RunArguments(options, run, dir)) s << " " << Quote(a);
      s << "\n";
    }
    s << "    ;;\n";
  }
  s << "esac\n";
  return s.str();
}

std::map<int, std::string> ParseTaskStates(const std::string& text) {
  std::map<int, std::string> states;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const size_t bar = line.find('|');
    if (bar == std::string::npos) continue;
    std::string id = line.substr(0, bar);
    if (const size_t underscore = id.find('_'); underscore != std::string::npos) {
      id = id.substr(underscore + 1);
    }
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string state = line.substr(bar + 1);
    state = state.substr(0, state.find(' '));  // "CANCELLED by 0"
    states[std::stoi(id)] = state;
  }
  return states;
}

bool RunSlurm(const SweepOptions& options, const std::vector<size_t>& todo,
              std::vector<SweepRow>* rows) {
  if (todo.empty()) return true;
  const int per_task = std::max(1, options.slurm.per_task);
  std::vector<std::vector<size_t>> tasks;
  for (size_t k = 0; k < todo.size(); k += size_t(per_task)) {
    tasks.emplace_back(todo.begin() + long(k),
                       todo.begin() + long(std::min(todo.size(), k + size_t(per_task))));
  }
  MakeOutputFolder(options.out_dir + "/slurm");
  // the runs to do start from empty folders: an exit_code there is this job's
  for (size_t i : todo) {
    std::error_code error;
    fs::remove_all(options.out_dir + "/runs/" + (*rows)[i].run.name, error);
  }
  const std::string script = Absolute(options.out_dir) + "/slurm/sweep.sbatch";
  WriteFileAtomically(script, SbatchScript(options, *rows, tasks));

  // submit
  std::string output;
  if (Capture("sbatch --parsable " + Quote(script), &output) != 0) {
    throw std::runtime_error("sbatch " + script + " failed: " + output);
  }
  // --parsable prints "jobid[;cluster]" as its last line
  std::string job;
  std::istringstream submitted(output);
  for (std::string line; std::getline(submitted, line);) {
    if (!line.empty()) job = line.substr(0, line.find(';'));
  }
  if (job.empty() || job.find_first_not_of("0123456789") != std::string::npos) {
    throw std::runtime_error("sbatch " + script + ": no job id in its output: " + output);
  }
  std::cerr << "sweep: submitted Slurm job " << job << ", " << tasks.size() << " tasks of up to "
            << per_task << " runs (" << script << ")\n";

  // follow: squeue lists the tasks, ended ones too, for MinJobAge after they end
  std::map<int, std::string> states;
  constexpr int kMaxFailedLooks = 5;
  int failed_looks = 0;
  bool stopped = false;
  std::string last_line;
  bool all_written = false;
  for (;;) {
    if (options.stop != nullptr && *options.stop) {
      Capture("scancel " + job + " 2>&1", &output);
      stopped = true;
      break;
    }
    bool listed = false;
    const int squeue =
        Capture("squeue -h -r -t all -j " + job + " -o '%K|%T' 2>/dev/null", &output);
    // Ctrl-C reaches squeue too: the stop is the sweep's, not the job's end
    if (options.stop != nullptr && *options.stop) continue;
    // the controller may be busy: only a few failures in a row end the following
    failed_looks = squeue == 0 ? 0 : failed_looks + 1;
    if (squeue != 0 && failed_looks < kMaxFailedLooks) listed = true;
    if (squeue == 0) {
      const auto now = ParseTaskStates(output);
      listed = !now.empty();
      // squeue lists every task of the array from its submission until MinJobAge after it
      // ended, but for one cancelled while pending: that one is gone at once
      for (const auto& [task, state] : now) states[task] = state;
      for (size_t t = 0; listed && t < tasks.size(); ++t) {
        if (!now.count(int(t)) && !Ended(states[int(t)])) states[int(t)] = "CANCELLED";
      }
    }
    std::map<std::string, int> counts;
    size_t ended = 0;
    for (size_t t = 0; t < tasks.size(); ++t) {
      const auto it = states.find(int(t));
      const std::string state = it == states.end() ? "PENDING" : it->second;
      ++counts[state];
      ended += Ended(state);
    }
    std::string line = "sweep: job " + job;
    for (const auto& [state, n] : counts) line += ", " + std::to_string(n) + " " + state;
    if (line != last_line) std::cerr << line << "\n";
    last_line = line;
    // done when every task ended, squeue no longer knows the job, or every run wrote its exit
    // code (a task's last act)
    if (ended == tasks.size() || !listed || all_written) break;
    // until the next look at squeue, a look at the runs' exit codes every 0.2 s
    for (double waited = 0; waited < options.slurm.poll_s && !all_written; waited += 0.2) {
      if (options.stop != nullptr && *options.stop) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      all_written = std::all_of(todo.begin(), todo.end(), [&](size_t i) {
        std::error_code error;
        return fs::exists(options.out_dir + "/runs/" + (*rows)[i].run.name + "/exit_code", error);
      });
    }
  }
  // sacct has the states of tasks squeue has forgotten
  if (Capture("sacct -n -P -X -j " + job + " -o JobID,State 2>/dev/null", &output) == 0) {
    for (const auto& [task, state] : ParseTaskStates(output)) {
      if (Ended(state) && !Ended(states[task])) states[task] = state;
    }
  }

  // gather
  for (size_t t = 0; t < tasks.size(); ++t) {
    const std::string state = states.count(int(t)) ? states[int(t)] : "UNKNOWN";
    for (size_t i : tasks[t]) {
      SweepRow& row = (*rows)[i];
      const std::string dir = options.out_dir + "/runs/" + row.run.name;
      row = ReadRow(row.run, dir, options.perceive, ExitCodeFile(dir + "/exit_code"));
      // a run that ended by itself keeps its error; one stopped from outside (no exit code, or
      // interrupted by the task's end) is the task's
      if (row.finished || (row.exit_code >= 0 && row.outcome == "error")) continue;
      row.outcome = "error";
      row.detail = "Slurm task " + job + "_" + std::to_string(t) + " " + state +
                   (row.detail.empty() ? "" : "; " + row.detail);
    }
  }
  return !stopped;
}

}  // namespace fognav::scenarios::internal

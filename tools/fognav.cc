// fognav: the command-line program. Parses flags and calls scenarios/; exit codes as DESIGN.md:
// 0 ran and every expectation held, 1 an expectation failed, 2 bad input, 3 simulator failure;
// and since: 4 a run (or a sweep) interrupted by SIGINT or SIGTERM (its outputs written), 5 an
// output that could not be written. `sweep` returns 1 when any of its runs did not pass.
#include <signal.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "scenarios/clips.h"
#include "scenarios/mission.h"
#include "scenarios/output.h"
#include "scenarios/params.h"
#include "scenarios/perception_cycle.h"
#include "scenarios/scenario.h"
#include "scenarios/sweep.h"
#include "scenarios/views.h"
#include "sim/model.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitExpectationFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitSimFailure = 3;
constexpr int kExitInterrupted = 4;
constexpr int kExitOutputError = 5;

using fognav::scenarios::InputError;
using fognav::scenarios::OutputError;
using fognav::sim::SimError;

// set by SIGINT and SIGTERM during a run; the mission reads it at the start of each cycle
std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

void RequestStop(int) { stop_requested = true; }

// SIGINT and SIGTERM end the run after its cycle; a second one of the same kind ends the
// process at once (SA_RESETHAND restores the default action). SA_RESTART: a write under way
// goes on rather than failing as interrupted.
// A sweep is stopped the same way, but without SA_RESTART: its wait for a run returns at once.
void StopOnSignals(bool restart = true) {
  struct sigaction action = {};
  action.sa_handler = RequestStop;
  action.sa_flags = SA_RESETHAND | (restart ? SA_RESTART : 0);
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int Validate(const std::string& path) {
  auto scenario = fognav::scenarios::LoadScenario(path);
  std::cout << fognav::scenarios::Summary(scenario) << "\n";
  return kExitOk;
}

int Render(const std::string& path, const std::string& out) {
  auto scenario = fognav::scenarios::LoadScenario(path);
  fognav::sim::World world(fognav::scenarios::MakeWorldSpec(scenario));
  Eigen::Isometry3d X_WL = fognav::scenarios::PlaceRobot(&world, scenario.start);
  fognav::sim::Renderer renderer(world.model());
  auto view = fognav::scenarios::RenderStereo(&renderer, world, X_WL, scenario.sensor);
  fognav::scenarios::WriteStereoView(view, out);
  fognav::scenarios::WritePng(fognav::scenarios::RenderOverview(&renderer, world, scenario),
                              out + "/overview.png");
  std::cout << "wrote left.png, right.png, depth.png, surfaces.png, intrinsics.json and "
               "overview.png to "
            << out << "\n";
  return kExitOk;
}

// Loads the scenario; each --set overrides a parameter after the file's `params:`, --depth,
// when given, replaces its sensor's depth mode.
fognav::scenarios::Scenario LoadWithDepth(const std::string& path, const std::string& depth,
                                          const std::vector<std::string>& sets) {
  auto scenario = fognav::scenarios::LoadScenario(path);
  for (const std::string& set : sets) fognav::scenarios::ApplySetFlag(set, &scenario.params);
  if (depth == "ideal") scenario.sensor.depth = fognav::scenarios::DepthMode::kIdeal;
  if (depth == "stereo") scenario.sensor.depth = fognav::scenarios::DepthMode::kStereo;
  return scenario;
}

int Perceive(const std::string& path, const std::string& out, const std::string& depth,
             const std::vector<std::string>& sets, bool quiet) {
  if (depth == "both") {
    auto scenario = LoadWithDepth(path, "", sets);
    fognav::scenarios::RunPerceiveBoth(
        scenario, out, quiet, fognav::scenarios::ResolveParams(scenario.params).perception);
    if (!quiet) std::cout << "wrote perception.json, stereo/ and ideal/ to " << out << "\n";
    return kExitOk;
  }
  auto scenario = LoadWithDepth(path, depth, sets);
  fognav::scenarios::RunPerceive(scenario, out, quiet,
                                 fognav::scenarios::ResolveParams(scenario.params).perception);
  if (!quiet) {
    std::cout << "wrote report.html, perception.json, frames/ and maps/ to " << out << "\n";
  }
  return kExitOk;
}

// seed >= 0 replaces the scenario's seed (of the odometry noise)
int Run(const std::string& path, const std::string& out, const std::string& depth,
        const std::vector<std::string>& sets, int dump_every, const std::string& video,
        bool quiet, int64_t seed) {
  auto scenario = LoadWithDepth(path, depth, sets);
  if (seed >= 0) scenario.seed = uint64_t(seed);
  fognav::scenarios::MissionOptions options;
  options.out_dir = out;
  options.video_path = video;
  options.dump_every = dump_every;
  options.quiet = quiet;
  options.stop = &stop_requested;
  StopOnSignals();
  auto outcome = fognav::scenarios::RunMission(scenario, options);
  if (outcome.failure == "interrupted") {
    std::cerr << "fognav: interrupted; report.json, trajectory.csv, cycles.csv and maps/ up to "
                 "the last cycle are in "
              << out << "\n";
    return kExitInterrupted;
  }
  if (!quiet) {
    // "out/" and "out" name the same directory: print it without the trailing slash
    std::string dir = out;
    while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
    std::cout << scenario.name << ": " << (outcome.success ? "success" : "FAILED")
              << (outcome.reached_goal ? ", goal reached" : ", goal not reached")
              << (outcome.failure.empty() ? "" : ", failure " + outcome.failure) << "\n"
              << "page: " << dir << "/report.html\n"
              << "report: " << dir << "/report.json, trajectory: " << dir
              << "/trajectory.csv, decisions: " << dir << "/cycles.csv, frames: " << dir
              << "/frames/, maps: " << dir << "/maps/\n";
    if (!video.empty()) std::cout << "video: " << video << "\n";
  }
  return outcome.success ? kExitOk : kExitExpectationFailed;
}

int Clip(const std::string& motion, const std::string& out, int every, bool quiet) {
  const auto result = fognav::scenarios::RecordClip(motion, out, every);
  if (!quiet) {
    std::cout << motion << ": " << result.frames << " frames and strip.png in " << out << ", "
              << result.collisions << " collisions\n";
  }
  return result.collisions == 0 ? kExitOk : kExitExpectationFailed;
}

int Sweep(fognav::scenarios::SweepOptions options) {
  std::error_code error;
  options.program = std::filesystem::read_symlink("/proc/self/exe", error).string();
  if (error) throw std::runtime_error("cannot find the program's own file: " + error.message());
  options.stop = &stop_requested;
  StopOnSignals(/*restart=*/false);
  return fognav::scenarios::RunSweep(options);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fognav: closed-loop humanoid navigation simulator (headless)"};
  app.require_subcommand(1);

  std::string scenario_path, out_dir;
  auto* validate = app.add_subcommand("validate", "check a scenario file without running it");
  validate->add_option("scenario", scenario_path, "scenario YAML file")->required();

  auto* render = app.add_subcommand("render", "write the head camera's views from the start pose");
  render->add_option("scenario", scenario_path, "scenario YAML file")->required();
  render->add_option("--out", out_dir, "output directory")->required();

  std::string depth, video;
  std::vector<std::string> sets;
  const char* set_help = "override a parameter, section.key=value (repeatable; wins over the "
                         "scenario's params; `fognav params` lists them)";
  bool quiet = false;
  int dump_every = 0;
  auto* run = app.add_subcommand("run", "run a mission headless");
  run->add_option("scenario", scenario_path, "scenario YAML file")->required();
  run->add_option("--out", out_dir, "output directory")->required();
  run->add_option("--dump-every", dump_every, "write frames and maps every N cycles")
      ->check(CLI::Range(0, 1000000000));
  run->add_option("--depth", depth, "range data: stereo or ideal (default: the scenario's)")
      ->check(CLI::IsMember({"stereo", "ideal"}));
  run->add_option("--video", video,
                  "write the mission as a video, FILE.avi, FILE.mp4 or FILE.webm (chase camera, "
                  "head camera, FOG with the plan; twice real time; report.html plays .webm)");
  run->add_option("--set", sets, set_help)->allow_extra_args(false);
  run->add_flag("--quiet", quiet, "print nothing but errors");
  int64_t seed = -1;
  run->add_option("--seed", seed, "seed of the odometry noise, instead of the scenario's")
      ->check(CLI::Range(int64_t(0), int64_t(std::numeric_limits<uint32_t>::max())));

  auto* perceive = app.add_subcommand(
      "perceive", "look around from the start pose, perceive every view, score against truth");
  perceive->add_option("scenario", scenario_path, "scenario YAML file")->required();
  perceive->add_option("--out", out_dir, "output directory")->required();
  perceive->add_option("--depth", depth,
                       "range data: stereo, ideal, or both side by side (default: the scenario's)")
      ->check(CLI::IsMember({"stereo", "ideal", "both"}));
  perceive->add_option("--set", sets, set_help)->allow_extra_args(false);
  perceive->add_flag("--quiet", quiet, "print nothing but errors");

  auto* params = app.add_subcommand(
      "params", "list every parameter a scenario's params: or --set may change: name, type, "
                "default, range, meaning");

  std::string motion;
  int every = 5;
  auto* clip = app.add_subcommand(
      "clip", "dump frames of one motion of the stepping controller from an external camera");
  clip->add_option("motion", motion, "walk, sidestep, turn, stairs or crawl")
      ->required()
      ->check(CLI::IsMember(fognav::scenarios::ClipMotions()));
  clip->add_option("--out", out_dir, "output directory")->required();
  clip->add_option("--every", every, "control ticks between frames (default 5)")
      ->check(CLI::Range(1, 1000000));
  clip->add_flag("--quiet", quiet, "print nothing but errors");

  fognav::scenarios::SweepOptions sweep_options;
  auto* sweep = app.add_subcommand(
      "sweep", "run many missions (or start views), N at a time or as a Slurm job array");
  sweep->add_option("scenarios", sweep_options.scenarios, "scenario files, folders or globs")
      ->required();
  sweep->add_option("--out", sweep_options.out_dir,
                    "output folder: runs/, results.tsv, results.json, junit.xml, index.html; a "
                    "rerun keeps its finished runs")
      ->required();
  sweep->add_option("--seeds", sweep_options.seeds, "each scenario with the seeds 1..N")
      ->check(CLI::Range(1, 100000));
  sweep->add_option("--set", sweep_options.sets,
                    "section.key=v1,v2,...: a run per value (per combination if repeated), "
                    "passed to each as `--set section.key=v`")
      ->allow_extra_args(false);
  sweep->add_option("--jobs", sweep_options.jobs, "local runs at a time (default: the cores)")
      ->check(CLI::Range(1, 100000));
  sweep->add_flag("--perceive", sweep_options.perceive,
                  "the start views, scored, as `fognav perceive` (not missions)");
  sweep->add_option("--compare", sweep_options.compare_dir,
                    "an earlier sweep's output folder: list the runs whose outcome changed");
  sweep->add_option("--backend", sweep_options.backend, "local (default) or slurm")
      ->check(CLI::IsMember({"local", "slurm"}));
  sweep->add_option("--partition", sweep_options.slurm.partition, "slurm: the partition");
  sweep->add_option("--time", sweep_options.slurm.time, "slurm: time limit of a task");
  sweep->add_option("--mem", sweep_options.slurm.mem, "slurm: memory of a task, e.g. 2G");
  sweep->add_option("--per-task", sweep_options.slurm.per_task,
                    "slurm: runs one after another in each array task (default 1)")
      ->check(CLI::Range(1, 100000));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    if (*validate) return Validate(scenario_path);
    if (*run) return Run(scenario_path, out_dir, depth, sets, dump_every, video, quiet, seed);
    if (*sweep) return Sweep(sweep_options);
    if (*render) return Render(scenario_path, out_dir);
    if (*perceive) return Perceive(scenario_path, out_dir, depth, sets, quiet);
    if (*params) {
      fognav::scenarios::PrintParamTable(std::cout);
      return kExitOk;
    }
    if (*clip) return Clip(motion, out_dir, every, quiet);
  } catch (const InputError& e) {
    std::cerr << "fognav: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const OutputError& e) {
    std::cerr << "fognav: output: " << e.what() << "\n";
    return kExitOutputError;
  } catch (const SimError& e) {
    std::cerr << "fognav: simulator: " << e.what() << "\n";
    return kExitSimFailure;
  } catch (const std::exception& e) {
    // anything else stops the run
    std::cerr << "fognav: could not run: " << e.what() << "\n";
    return kExitSimFailure;
  }
  return kExitBadInput;
}

// The sweep's plan, its rows from reports, its summary, files and comparison; the Slurm
// backend's job script and the parsing of task states. No runs: reports are written here.
#include "scenarios/sweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "scenarios/internal/sweep_slurm.h"
#include "scenarios/scenario.h"

namespace fognav::scenarios {
namespace {

namespace fs = std::filesystem;

std::string Folder(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/fognav_sweep_" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void Write(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
}

std::string Read(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

SweepRow Row(const std::string& name, int exit_code, const std::string& outcome,
             double optimal = 2.0, int collisions = 0) {
  SweepRow r;
  r.run = {name, name + ".yaml", -1, {}};
  r.finished = outcome != "error" && outcome != "not run";
  r.exit_code = exit_code;
  r.outcome = outcome;
  r.failure = exit_code == 1 ? outcome : "";
  r.reached_goal = exit_code == 0;
  r.spl = exit_code == 0 ? 0.8 : 0;
  r.optimal_path_length = optimal;
  r.collisions = collisions;
  r.traversability = 0.9;
  r.wall_time_s = 1.5;
  return r;
}

TEST(SweepPlan, FilesFoldersAndGlobsGiveRunsInNameOrderWithSeeds) {
  const std::string dir = Folder("plan");
  Write(dir + "/a/b_world.yaml", "");
  Write(dir + "/a/a_world.yaml", "");
  Write(dir + "/a/notes.txt", "");
  Write(dir + "/c/c_world.yaml", "");
  SweepOptions options;
  options.scenarios = {dir + "/a", dir + "/c/*.yaml", dir + "/a/a_world.yaml"};
  const auto once = PlanSweep(options);
  ASSERT_EQ(once.size(), 3u);  // a_world given twice runs once; notes.txt is no scenario
  EXPECT_EQ(once[0].name, "a_world");
  EXPECT_EQ(once[2].name, "c_world");
  EXPECT_EQ(once[2].scenario, dir + "/c/c_world.yaml");
  EXPECT_EQ(once[0].seed, -1);
  options.seeds = 2;
  const auto seeded = PlanSweep(options);
  ASSERT_EQ(seeded.size(), 6u);
  EXPECT_EQ(seeded[1].name, "a_world_s2");
  EXPECT_EQ(seeded[1].seed, 2);
  EXPECT_EQ(RunArguments(options, seeded[1], "out/runs/a_world_s2"),
            (std::vector<std::string>{"run", dir + "/a/a_world.yaml", "--out",
                                      "out/runs/a_world_s2", "--quiet", "--seed", "2"}));
}

TEST(SweepPlan, EachSetIsAnAxisOfAGridOfOverridesPassedToTheRuns) {
  const std::string dir = Folder("grid");
  Write(dir + "/w.yaml", "");
  SweepOptions options;
  options.scenarios = {dir + "/w.yaml"};
  options.seeds = 1;
  options.sets = {"planner.sidestep_factor=1.2,1.6", "fog.h_floor=0.02"};
  const auto runs = PlanSweep(options);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].name, "w_s1_planner.sidestep_factor=1.2_fog.h_floor=0.02");
  EXPECT_EQ(runs[1].params,
            (std::vector<std::string>{"planner.sidestep_factor=1.6", "fog.h_floor=0.02"}));
  EXPECT_EQ(RunArguments(options, runs[1], "d"),
            (std::vector<std::string>{"run", dir + "/w.yaml", "--out", "d", "--quiet", "--seed",
                                      "1", "--set", "planner.sidestep_factor=1.6", "--set",
                                      "fog.h_floor=0.02"}));
  // each key and value as fognav run --set takes them, each value once, none empty
  for (const std::string bad :
       {"planner.x", "=1", "Planner.x=1", "planner.sidestep_factor=1,,2",
        "planner.sidestep_factor=../x", "planner.nope=1", "planner.sidestep_factor=fast",
        "planner.sidestep_factor=1,1", "planner.sidestep_factor=1,2,"}) {
    options.sets = {bad};
    EXPECT_THROW(PlanSweep(options), InputError) << bad;
  }
  options.sets = {"planner.walk_factor=1", "planner.walk_factor=2"};
  EXPECT_THROW(PlanSweep(options), InputError);
}

TEST(SweepPlan, ArgumentsThatMatchNothingOrShareANameAreErrorsNamingThem) {
  const std::string dir = Folder("plan_errors");
  Write(dir + "/x/world.yaml", "");
  Write(dir + "/y/world.yaml", "");
  SweepOptions options;
  options.scenarios = {dir + "/nothing_*.yaml"};
  EXPECT_THROW(
      {
        try {
          PlanSweep(options);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find(dir + "/nothing_*.yaml"), std::string::npos);
          throw;
        }
      },
      InputError);
  options.scenarios = {dir + "/x", dir + "/y"};
  try {
    PlanSweep(options);
    FAIL() << "two files named world.yaml";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the same file name"), std::string::npos) << e.what();
  }
}

TEST(SweepRows, AReportAndItsPageMakeARowAndAnInterruptedOrMissingOneDoesNot) {
  const std::string dir = Folder("rows");
  const SweepRun run{"w", "w.yaml", 3, {}};
  Write(dir + "/done/report.json",
        R"({"success": false, "reached_goal": false, "failure": "collision",
            "failure_detail": "hit box", "cycles": 12, "collisions": 2, "spl": null,
            "optimal_path_length": 2.5, "wall_time_s": 4.25,
            "fog": {"traversability": 0.75, "unsafe_cells": 7}})");
  // the page comes last: a report without it is from a run killed just after writing it
  EXPECT_FALSE(ReadRow(run, dir + "/done", false, -1).finished);
  Write(dir + "/done/report.html", "<!DOCTYPE html>");
  const SweepRow done = ReadRow(run, dir + "/done", false, -1);
  EXPECT_TRUE(done.finished);
  EXPECT_EQ(done.exit_code, 1);
  EXPECT_EQ(done.outcome, "collision");
  EXPECT_EQ(done.detail, "hit box");
  EXPECT_EQ(done.cycles, 12);
  EXPECT_EQ(done.collisions, 2);
  EXPECT_EQ(done.spl, 0.0);  // null: no SPL
  EXPECT_DOUBLE_EQ(done.optimal_path_length, 2.5);
  EXPECT_DOUBLE_EQ(done.traversability, 0.75);
  EXPECT_EQ(done.unsafe_cells, 7);

  Write(dir + "/stopped/report.json", R"({"success": false, "failure": "interrupted"})");
  EXPECT_FALSE(ReadRow(run, dir + "/stopped", false, -1).finished);
  EXPECT_EQ(ReadRow(run, dir + "/stopped", false, -1).outcome, "not run");

  Write(dir + "/bad/report.json", R"({"success": tr)");  // cut short
  Write(dir + "/bad/stderr.log", "fognav: w.yaml:3: key 'goal': expected a map\n\n");
  const SweepRow bad = ReadRow(run, dir + "/bad", false, 2);
  EXPECT_FALSE(bad.finished);
  EXPECT_EQ(bad.outcome, "error");
  EXPECT_EQ(bad.detail, "exit 2: fognav: w.yaml:3: key 'goal': expected a map");
}

TEST(SweepSummary, CountsRunsWithAWayApartWithAWilsonInterval) {
  const auto [lo, hi] = Wilson(2, 4);
  EXPECT_NEAR(lo, 0.1500, 1e-4);
  EXPECT_NEAR(hi, 0.8500, 1e-4);
  EXPECT_EQ(Wilson(0, 0), std::make_pair(0.0, 1.0));
  const std::vector<SweepRow> rows = {Row("a", 0, "success"),      Row("b", 1, "collision", 2, 1),
                                      Row("c", 0, "success"),      Row("d", 1, "timeout"),
                                      Row("e", 1, "no_path", 0.0), Row("f", 3, "error")};
  const std::string text = FormatSummary(rows, false);
  EXPECT_NE(text.find("sweep: 6 runs, 1 could not run; 4 with a way on the ground truth"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("success     2/4 = 50.0 % (95 % interval 15.0 % - 85.0 %)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("collisions  1 runs"), std::string::npos) << text;
  EXPECT_NE(text.find("failures    collision 1, timeout 1"), std::string::npos) << text;
  EXPECT_NE(text.find("no way      1 runs, ended: no_path 1"), std::string::npos) << text;
  EXPECT_NE(text.find("mean SPL    0.400"), std::string::npos) << text;
}

TEST(SweepFiles, TableJunitIndexAndComparison) {
  const std::string dir = Folder("files");
  std::vector<SweepRow> rows = {Row("a", 0, "success"), Row("b", 1, "timeout"),
                                Row("c", 2, "error"), Row("d", -1, "not run")};
  rows[1].detail = "ran out of <cycles> & time";
  rows[2].detail = "exit 2: bad";
  WriteSweepFiles(dir, rows, false);
  const std::string tsv = Read(dir + "/results.tsv");
  EXPECT_EQ(tsv.substr(0, tsv.find('\n')),
            "name\tscenario\tseed\tparams\texit\toutcome\treached_"
            "goal\tfailure\tcycles\tcollisions\tspl\t"
            "optimal_path_length\ttraversability\tunsafe_cells\twall_time_s\tdetail");
  EXPECT_NE(tsv.find("\nb\tb.yaml\t\t\t1\ttimeout\t0\ttimeout\t"), std::string::npos) << tsv;
  const std::string junit = Read(dir + "/junit.xml");
  EXPECT_NE(junit.find("tests=\"4\" failures=\"1\" errors=\"1\" skipped=\"1\""), std::string::npos)
      << junit;
  EXPECT_NE(junit.find("<testcase classname=\"fognav.sweep\" name=\"a\" file=\"a.yaml\" "
                       "time=\"1.50\"/>"),
            std::string::npos)
      << junit;
  EXPECT_NE(junit.find("<failure type=\"timeout\" message=\"timeout: ran out of &lt;cycles&gt; "
                       "&amp; time\"/>"),
            std::string::npos)
      << junit;
  EXPECT_NE(junit.find("<error type=\"exit 2\" message=\"error: exit 2: bad\"/>"),
            std::string::npos)
      << junit;
  const std::string index = Read(dir + "/index.html");
  EXPECT_NE(index.find("<td><a href=\"runs/b/report.html\">b</a></td><td class=\"bad\">timeout"),
            std::string::npos);
  EXPECT_NE(index.find("<pre id=\"summary\">sweep: 4 runs"), std::string::npos);

  // the same runs later: a now succeeds no more, b does
  std::vector<SweepRow> later = rows;
  later[0] = Row("a", 1, "collision");
  later[1] = Row("b", 0, "success");
  EXPECT_EQ(CompareOutcomes(later, ReadOutcomes(dir)),
            (std::vector<std::string>{"a: success -> collision", "b: timeout -> success"}));
  Write(dir + "/old/results.tsv", "world\tresult\n");
  try {
    ReadOutcomes(dir + "/old");
    FAIL() << "a results file without name and outcome";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/old/results.tsv:1: expected"), std::string::npos)
        << e.what();
  }
}

TEST(SweepSlurm, JobScriptHasATaskPerGroupOfRunsAndTheOptions) {
  SweepOptions options;
  options.out_dir = "/data/sweep";
  options.program = "/opt/fognav/bin/fognav";
  options.slurm.partition = "cpu";
  options.slurm.time = "00:20:00";
  options.slurm.mem = "2G";
  std::vector<SweepRow> rows(3);
  rows[0].run = {"a_s1", "/w/a.yaml", 1, {}};
  rows[1].run = {"a_s2", "/w/a.yaml", 2, {}};
  rows[2].run = {"it's", "/w/it's.yaml", -1, {}};
  const std::string script = internal::SbatchScript(options, rows, {{0, 1}, {2}});
  EXPECT_NE(script.find("#SBATCH --array=0-1\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --partition=cpu\n#SBATCH --time=00:20:00\n#SBATCH --mem=2G\n"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("  0)\n    run '/data/sweep/runs/a_s1' '/opt/fognav/bin/fognav' 'run' "
                        "'/w/a.yaml' '--out' '/data/sweep/runs/a_s1' '--quiet' '--seed' '1'\n"
                        "    run '/data/sweep/runs/a_s2'"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("  1)\n    run '/data/sweep/runs/it'\\''s'"), std::string::npos) << script;
}

TEST(SweepSlurm, TaskStatesFromSqueueAndSacct) {
  EXPECT_EQ(internal::ParseTaskStates("0|COMPLETED\n3|RUNNING\n1-2|PENDING\n"),
            (std::map<int, std::string>{{0, "COMPLETED"}, {3, "RUNNING"}}));
  EXPECT_EQ(internal::ParseTaskStates("57_0|COMPLETED\n57_1|CANCELLED by 0\nx\n"),
            (std::map<int, std::string>{{0, "COMPLETED"}, {1, "CANCELLED"}}));
}

}  // namespace
}  // namespace fognav::scenarios

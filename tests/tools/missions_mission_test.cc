// Whole missions through the fognav program (ctest label "mission"): every scenario file with
// an `expect` meets its expectations, the same scenario and seed give the same report, and a
// failed expectation is exit code 1.
#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

namespace {

std::string TempDir(const std::string& name) {
  std::string dir = (std::filesystem::temp_directory_path() / ("fognav_mission_" + name)).string();
  std::filesystem::remove_all(dir);
  return dir;
}

int RunMission(const std::string& scenario, const std::string& out, std::string* output) {
  std::string command = std::string(FOGNAV_BINARY) + " run " + scenario + " --out " + out +
                        " --quiet 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) output->append(buffer, n);
  int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

nlohmann::json ReadReport(const std::string& dir) {
  std::ifstream file(dir + "/report.json");
  return nlohmann::json::parse(file);
}

// cycles.csv: the header's fields, then one row of fields per cycle.
std::vector<std::vector<std::string>> ReadCycles(const std::string& dir) {
  std::ifstream file(dir + "/cycles.csv");
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(file, line)) {
    std::vector<std::string> fields;
    std::stringstream fields_of(line);
    std::string field;
    while (std::getline(fields_of, field, ',')) fields.push_back(field);
    rows.push_back(fields);
  }
  return rows;
}

// The decision log against the report: a row per cycle, in order, each decision one the log
// names, and a mission that found no way gave up in its last cycle (and no other).
void ExpectCyclesMatchReport(const std::string& dir, const nlohmann::json& report) {
  const auto rows = ReadCycles(dir);
  ASSERT_FALSE(rows.empty());
  const std::vector<std::string> header = {
      "cycle", "step", "odom_x", "odom_y", "odom_yaw", "posture", "plan", "plan_cost",
      "plan_length", "decision", "target_x", "target_y", "explorations", "thrashes"};
  EXPECT_EQ(rows[0], header);
  const int cycles = report["cycles"].get<int>();
  ASSERT_EQ(int(rows.size()), cycles + 1);
  const std::vector<std::string> decisions = {
      "follow", "look_around", "look_on_arrival", "circling_look", "fresh_look", "toward_goal",
      "get_up", "explore", "explore_ends", "inspect", "peek", "explore_edge", "back_off",
      "give_up"};
  int previous_step = 0, previous_explorations = 0;
  for (int c = 1; c <= cycles; ++c) {
    const auto& row = rows[size_t(c)];
    ASSERT_EQ(row.size(), header.size()) << "cycle " << c;
    EXPECT_EQ(std::stoi(row[0]), c);
    EXPECT_GE(std::stoi(row[1]), previous_step);
    previous_step = std::stoi(row[1]);
    EXPECT_NE(std::find(decisions.begin(), decisions.end(), row[9]), decisions.end()) << row[9];
    // a mission explores at most four times; starting to is counted in its row
    const int explorations = std::stoi(row[12]);
    EXPECT_LE(explorations, 4);
    const bool starts = row[9] == "inspect" || row[9] == "peek" || row[9] == "explore_edge" ||
                        row[9] == "back_off";
    EXPECT_EQ(explorations, previous_explorations + (starts ? 1 : 0)) << "cycle " << c;
    previous_explorations = explorations;
    // exploring and looking from afar name where to; the rest name no target
    const bool targeted = row[9] == "explore" || row[9] == "inspect" || row[9] == "peek" ||
                          row[9] == "explore_edge" || row[9] == "explore_ends" ||
                          row[9] == "look_on_arrival" || row[9] == "back_off";
    EXPECT_EQ(!row[10].empty(), targeted) << "cycle " << c << " " << row[9];
    const bool last = c == cycles;
    EXPECT_EQ(row[9] == "give_up", last && report["failure"] == "no_path") << "cycle " << c;
  }
  EXPECT_LE(previous_step, report["steps"].get<int>());
  // no way: it looked around again before it gave up
  if (report["failure"] == "no_path") {
    EXPECT_TRUE(std::any_of(rows.begin() + 1, rows.end(), [](const auto& row) {
      return row[9] == "look_around" || row[9] == "fresh_look";
    }));
  }
}

class Suite : public ::testing::TestWithParam<std::string> {};

TEST_P(Suite, MeetsItsExpectations) {
  const std::string name = GetParam();
  const std::string out = TempDir(name);
  std::string output;
  int code = RunMission("scenarios/" + name + ".yaml", out, &output);
  ASSERT_TRUE(std::filesystem::exists(out + "/report.json")) << output;
  nlohmann::json report = ReadReport(out);
  EXPECT_EQ(code, 0) << report.dump(2);
  EXPECT_TRUE(report["success"].get<bool>());
  EXPECT_EQ(report["collisions"].get<int>(), 0);
  // the outputs a reviewer looks at
  EXPECT_TRUE(std::filesystem::exists(out + "/trajectory.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/maps/final_plan.png"));
  EXPECT_TRUE(std::filesystem::exists(out + "/frames/final_left.png"));
  EXPECT_TRUE(std::filesystem::exists(out + "/maps/mission.png"));
  EXPECT_TRUE(std::filesystem::exists(out + "/report.html"));
  ExpectCyclesMatchReport(out, report);
  if (name == "stairs_and_table") {
    // issue 7's target: at most 1.3 times the planner's path on the ground-truth FOG
    EXPECT_LE(report["path_length"].get<double>(),
              1.3 * report["optimal_path_length"].get<double>());
    // the table's underside seen from below before and while crawling under it: 0.744 measured
    // (0.632 when the eyes did not look up at it; issue 7's target of 0.95 is not met)
    EXPECT_GE(report["fog_accuracy"].get<double>(), 0.70);
  }
  for (const char* key : {"scenario", "success", "reached_goal", "goal_distance", "failure",
                          "cycles", "steps", "actions", "collisions", "path_length", "spl",
                          "wall_time_s", "timing_ms", "fog_accuracy"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  // the slow plans beside the median plan: median <= 95th percentile <= maximum
  const nlohmann::json& timing = report["timing_ms"];
  ASSERT_TRUE(timing.contains("planning_p95") && timing.contains("planning_max")) << timing;
  EXPECT_LE(timing["planning"].get<double>(), timing["planning_p95"].get<double>());
  EXPECT_LE(timing["planning_p95"].get<double>(), timing["planning_max"].get<double>());
  EXPECT_GT(timing["planning_max"].get<double>(), 0.0);
}

// The suite: every scenario file in `dir` (*.yaml) with a top-level `expect`, by name, sorted.
// A file that does not parse joins too, so its mission fails with the loader's message.
std::vector<std::string> ScenariosWithExpectations(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    bool expects = true;
    try {
      const YAML::Node root = YAML::LoadFile(entry.path().string());
      expects = !root.IsMap() || root["expect"];
    } catch (const YAML::Exception&) {
    }
    if (expects) names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// ctest names each mission after its file (Missions/Suite.MeetsItsExpectations/"doorway"); the
// build recompiles this test when a scenario file comes or changes, so a new one joins by itself
INSTANTIATE_TEST_SUITE_P(Missions, Suite,
                         ::testing::ValuesIn(ScenariosWithExpectations("scenarios")));

TEST(Mission, TheSuiteIsEveryScenarioFileWithAnExpectation) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "fognav_suite_listing";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "b_expects.yaml") << "name: b_expects\nexpect: {reach_goal: true}\n";
  std::ofstream(dir / "a_expects.yaml") << "name: a_expects\nexpect:\n  no_collision: true\n";
  std::ofstream(dir / "no_expect.yaml") << "name: no_expect\n# expect: {reach_goal: true}\n";
  std::ofstream(dir / "nested.yaml") << "name: nested\nworld:\n  expect: 1\n";
  std::ofstream(dir / "broken.yaml") << "name: [broken\n";
  std::ofstream(dir / "notes.txt") << "expect: {reach_goal: true}\n";
  const std::vector<std::string> expected = {"a_expects", "b_expects", "broken"};
  EXPECT_EQ(ScenariosWithExpectations(dir.string()), expected);
  // the repository's own suite: the course and every other file that expects something
  const auto suite = ScenariosWithExpectations("scenarios");
  EXPECT_NE(std::find(suite.begin(), suite.end(), "stairs_and_table"), suite.end());
  EXPECT_GE(suite.size(), 36u);
  std::filesystem::remove_all(dir);
}

TEST(Mission, SameScenarioAndSeedGiveTheSameReport) {
  std::string first_out = TempDir("det1"), second_out = TempDir("det2"), output;
  // the mission with seeded odometry noise: randomness too must repeat
  RunMission("scenarios/noisy_odometry.yaml", first_out, &output);
  RunMission("scenarios/noisy_odometry.yaml", second_out, &output);
  nlohmann::json first = ReadReport(first_out), second = ReadReport(second_out);
  for (auto* report : {&first, &second}) {
    report->erase("wall_time_s");
    report->erase("timing_ms");
  }
  EXPECT_EQ(first.dump(2), second.dump(2));
  for (const char* log : {"/trajectory.csv", "/cycles.csv"}) {
    std::ifstream a(first_out + log), b(second_out + log);
    std::stringstream ta, tb;
    ta << a.rdbuf();
    tb << b.rdbuf();
    EXPECT_FALSE(ta.str().empty()) << log;
    EXPECT_EQ(ta.str(), tb.str()) << log;
  }
}

// The stair-climbing module places the feet from the measured tread edges, wherever the
// risers lie within a 4 cm cell: after every step up or down both soles (0.055 m from the
// origin to the heel) land with the heel at least 5 mm past the edge it crossed. Placed from the
// map's cells alone, heels overhung step-up edges by up to 2.5 cm here.
TEST(Mission, FeetLandPastTheTreadEdges) {
  std::ifstream in("scenarios/stairs.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const std::string original = text.str();
  const std::string key = "start: [0.7, 0.0]";
  ASSERT_NE(original.find(key), std::string::npos);
  for (const double shift : {0.013, 0.027, 0.039}) {
    std::string yaml = original;
    const double start = 0.7 + shift;
    yaml.replace(yaml.find(key), key.size(), "start: [" + std::to_string(start) + ", 0.0]");
    const std::string path =
        (std::filesystem::temp_directory_path() / "fognav_stairs_shifted.yaml").string();
    std::ofstream(path) << yaml;
    const std::string out = TempDir("stairs_shifted");
    std::string output;
    ASSERT_EQ(RunMission(path, out, &output), 0) << output;
    // the treads of scenarios/stairs.yaml: 0.25, 0.35 and 0.25 m deep, up, up, down, down
    const std::vector<double> up = {start, start + 0.25}, down = {start + 0.6, start + 0.85};
    std::ifstream csv(out + "/trajectory.csv");
    std::string line;
    std::getline(csv, line);  // header
    struct Row {
      int step, tick;
      double x;
      std::string action;
    };
    std::vector<Row> rows;
    while (std::getline(csv, line)) {
      std::stringstream fields(line);
      std::string f[9];
      for (std::string& field : f) std::getline(fields, field, ',');
      rows.push_back({std::stoi(f[0]), std::stoi(f[1]), std::stod(f[2]), f[8]});
    }
    int checked = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      const bool is_up = rows[i].action == "stairs_up", is_down = rows[i].action == "stairs_down";
      if (!is_up && !is_down) continue;
      // a stride's footsteps follow each other at once (0.5 s, 50 ticks); its last one ends it
      if (i + 1 < rows.size() && rows[i + 1].action == rows[i].action &&
          rows[i + 1].tick - rows[i].tick <= 60) {
        continue;
      }
      // the edge it crossed: the last one of that kind behind the origin
      double crossed = -1e9;
      for (double edge : is_up ? up : down) {
        if (edge < rows[i].x) crossed = std::max(crossed, edge);
      }
      EXPECT_GE(rows[i].x - 0.055 - crossed, 0.005)
          << "shift " << shift << ", step " << rows[i].step << " " << rows[i].action;
      ++checked;
    }
    EXPECT_EQ(checked, 4) << "shift " << shift;
  }
}

TEST(Mission, AFailedExpectationIsExitCode1) {
  // the low table is walked around, so a mission that expects a crawl fails
  std::ifstream in("scenarios/low_table.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  yaml.replace(yaml.find("actions_used: [walk]"), 20, "actions_used: [crawl]");
  std::string path = (std::filesystem::temp_directory_path() / "fognav_expects_crawl.yaml").string();
  std::ofstream(path) << yaml;
  std::string out = TempDir("exit1"), output;
  EXPECT_EQ(RunMission(path, out, &output), 1) << output;
  nlohmann::json report = ReadReport(out);
  EXPECT_FALSE(report["success"].get<bool>());
  EXPECT_TRUE(report["reached_goal"].get<bool>());
  EXPECT_EQ(report["actions"]["crawl"].get<int>(), 0);
}

// `expect: {reach_goal: false}` without a `failure` expects the mission to end short of the goal,
// whatever it ends with (it was exit code 1 for every ending before: no mission could pass it);
// a `failure` named must be the one. Missions of one cycle: the look-around and a first move.
TEST(Mission, ReachGoalFalseAloneExpectsAnyEndShortOfTheGoal) {
  std::ifstream in("scenarios/obstacles.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const std::string original = text.str();
  auto run = [&](const std::string& goal, const std::string& expect, nlohmann::json* report) {
    std::string yaml = original;
    const std::string goal_line = "goal: {position: [2.6, 0.0], tolerance: 0.2}";
    yaml.replace(yaml.find(goal_line), goal_line.size(), "goal: " + goal);
    const std::string tail = "limits: {max_cycles: 200, max_steps: 600}\n"
                             "expect: {reach_goal: true, actions_used: [walk], no_collision: true}";
    yaml.replace(yaml.find(tail), tail.size(), "limits: {max_cycles: 1}\nexpect: " + expect);
    const std::string path =
        (std::filesystem::temp_directory_path() / "fognav_expect_one_cycle.yaml").string();
    std::ofstream(path) << yaml;
    const std::string out = TempDir("expect_one_cycle");
    std::string output;
    const int code = RunMission(path, out, &output);
    *report = ReadReport(out);
    return code;
  };
  const std::string far = "{position: [2.6, 0.0], tolerance: 0.2}";
  nlohmann::json report;
  EXPECT_EQ(run(far, "{reach_goal: false}", &report), 0) << report.dump(2);
  EXPECT_EQ(report["failure"], "timeout");
  EXPECT_TRUE(report["success"].get<bool>());
  EXPECT_EQ(run(far, "{reach_goal: false, failure: no_path}", &report), 1) << report.dump(2);
  EXPECT_EQ(report["failure"], "timeout");
  EXPECT_EQ(run(far, "{reach_goal: true}", &report), 1) << report.dump(2);
  EXPECT_EQ(run(far, "{}", &report), 1) << report.dump(2);
  // a goal within the tolerance of the start is reached at once
  EXPECT_EQ(run("{position: [0.1, 0.0], tolerance: 0.2}", "{reach_goal: false}", &report), 1)
      << report.dump(2);
  EXPECT_TRUE(report["reached_goal"].get<bool>());
  EXPECT_EQ(report["failure"], nullptr);
}

}  // namespace

#include "scenarios/params.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "navigation/internal/test_worlds.h"
#include "scenarios/scenario.h"

namespace fognav::scenarios {
namespace {

// a valid scenario; the tests append a `params:` block to it
const std::string kScenario = R"(name: unit
robot:
  start: [0.0, 0.0, 0.0]
goal:
  position: [3.0, 0.0]
world:
  floor: [6.0, 2.0]
  floor_center: [2.0, 0.0]
)";

// the message of the InputError that parsing `text` throws, or "" if none
std::string ErrorOf(const std::string& text) {
  try {
    ParseScenario(text, "course.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string SetErrorOf(const std::string& assignment) {
  ParamOverrides overrides;
  try {
    ApplySetFlag(assignment, &overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Params, TableNamesEachParameterOnceWithItsDefaultInRange) {
  const RunParams defaults;
  std::set<std::string> names;
  for (const ParamInfo& info : ParamTable()) {
    EXPECT_TRUE(names.insert(info.name).second) << info.name;
    EXPECT_EQ(std::count(info.name.begin(), info.name.end(), '.'), 1) << info.name;
    EXPECT_FALSE(info.meaning.empty()) << info.name;
    EXPECT_LE(info.min, info.max) << info.name;
    // the default is a value the table itself accepts
    const double value = info.get(defaults);
    double parsed = -1;
    EXPECT_EQ(ParseParamValue(info, FormatParamValue(info, value), &parsed), "") << info.name;
    EXPECT_EQ(parsed, value) << info.name;
  }
  EXPECT_GE(names.size(), 200u);
  EXPECT_EQ(ParamSections(),
            (std::vector<std::string>{"stereo", "segmentation", "segmentation_ideal", "perception",
                                      "label", "grid", "floor", "fog", "void", "localization",
                                      "visual_odometry",
                                      "planner", "mission", "step_edge"}));
}

// each row writes the field it names and no other: set every one in turn to a value of its
// range other than its default and compare the changed list
TEST(Params, EachRowWritesItsOwnField) {
  for (const ParamInfo& info : ParamTable()) {
    RunParams params;
    const double old = info.get(params);
    // the first value the table accepts that is not the default
    double other = old;
    for (double candidate : {1 - old, info.min, info.max, old + 2, old + 16}) {
      double parsed = 0;
      if (candidate != old && std::isfinite(candidate) &&
          ParseParamValue(info, FormatParamValue(info, candidate), &parsed).empty()) {
        other = parsed;
        break;
      }
    }
    ASSERT_NE(other, old) << info.name;
    info.set(&params, other);
    const auto changed = ChangedParams(params);
    ASSERT_EQ(changed.size(), 1u) << info.name;
    EXPECT_EQ(changed[0].first, info.name);
    EXPECT_EQ(changed[0].second, other) << info.name;
  }
}

TEST(Params, ResolvedStructsHoldTheOverrides) {
  const RunParams p = ResolveParams({{"planner.sidestep_factor", 1.4},
                                     {"stereo.block_size", 7},
                                     {"grid.min_hits_per_frame", 3},
                                     {"fog.infer_tops", 0},
                                     {"segmentation_ideal.c_max", 12},
                                     {"mission.max_explorations", 6},
                                     {"step_edge.reach", 0.6}});
  EXPECT_EQ(p.planner.sidestep_factor, 1.4);
  EXPECT_EQ(p.perception.stereo.block_size, 7);
  EXPECT_EQ(p.perception.map.grid.min_hits_per_frame, 3);
  EXPECT_FALSE(p.perception.map.fog.infer_tops);
  EXPECT_EQ(p.perception.segment_ideal.c_max, 12);
  EXPECT_EQ(p.perception.segment.c_max, 15);  // stereo's own stays
  EXPECT_EQ(p.mission.max_explorations, 6);
  EXPECT_EQ(p.step_edge.reach, 0.6);
  // untouched parameters keep the loop's defaults (MapDefaults, RayNoiseParams)
  EXPECT_EQ(p.perception.map.grid.overrule_ratio, 2.0);
  EXPECT_TRUE(p.perception.segment.ray_noise);
}

// a scenario's params reach the planner: a goal 0.4 m to the left, side-stepped when that is
// cheap, turned to and walked when the file makes side-steps dear
TEST(Params, FileOverrideChangesThePlan) {
  const perception::Fog fog = navigation::internal::FlatFog(50, 50, 0.04);
  const perception::Pose2 start{1.0, 0.8, 0.0};
  const Eigen::Vector2d goal(1.0, 1.2);
  auto sidesteps = [&](const std::string& factor) {
    const Scenario s = ParseScenario(
        kScenario + "params:\n  planner: {sidestep_factor: " + factor + "}\n", "unit.yaml");
    const navigation::PlanResult r =
        navigation::Plan(fog, start, goal, ResolveParams(s.params).planner);
    EXPECT_EQ(r.status, navigation::PlanStatus::kOk);
    return std::count_if(r.path.begin(), r.path.end(), [](const navigation::PathPose& q) {
      return q.move == navigation::Move::kSidestep;
    });
  };
  EXPECT_GT(sidesteps("1.0"), 0);
  EXPECT_EQ(sidesteps("5.0"), 0);
}

TEST(Params, ScenarioReadsEverySectionAndType) {
  const Scenario s = ParseScenario(kScenario + R"(params:
  planner: {sidestep_factor: 1.4, blind_moves_stay_known: false}
  grid:
    size_z: 20
  label: {max_range: .inf}
  mission: {max_explorations: 6}
)",
                                   "unit.yaml");
  EXPECT_EQ(s.params, (ParamOverrides{{"planner.sidestep_factor", 1.4},
                                      {"planner.blind_moves_stay_known", 0},
                                      {"grid.size_z", 20},
                                      {"label.max_range", INFINITY},
                                      {"mission.max_explorations", 6}}));
  // `fognav validate` says what they are
  EXPECT_NE(
      Summary(s).find(", params grid.size_z=20 label.max_range=inf mission.max_explorations=6 "
                      "planner.blind_moves_stay_known=false planner.sidestep_factor=1.4"),
      std::string::npos)
      << Summary(s);
  // no params: none
  EXPECT_TRUE(ParseScenario(kScenario, "unit.yaml").params.empty());
}

TEST(Params, SetWinsOverTheFile) {
  Scenario s = ParseScenario(
      kScenario + "params: {planner: {sidestep_factor: 1.4, walk_factor: 1.1}}\n", "unit.yaml");
  ApplySetFlag("planner.sidestep_factor=2.5", &s.params);
  ApplySetFlag("mission.level_views=false", &s.params);
  const RunParams p = ResolveParams(s.params);
  EXPECT_EQ(p.planner.sidestep_factor, 2.5);
  EXPECT_EQ(p.planner.walk_factor, 1.1);
  EXPECT_FALSE(p.mission.level_views);
}

TEST(Params, ChangedListsOnlyValuesOtherThanTheDefaults) {
  // a default given explicitly is no change
  RunParams p = ResolveParams({{"planner.sidestep_factor", 1.6}, {"stereo.block_size", 7}});
  p.perception.map.fog.max_height_sigma = INFINITY;
  p.mission.level_views = false;
  const auto changed = ChangedParams(p);
  ASSERT_EQ(changed.size(), 3u);
  EXPECT_EQ(changed[0], (std::pair<std::string, double>{"stereo.block_size", 7}));
  EXPECT_EQ(changed[1].first, "fog.max_height_sigma");
  EXPECT_EQ(changed[2], (std::pair<std::string, double>{"mission.level_views", 0}));
  EXPECT_EQ(ParamsJson(p).dump(),
            R"({"fog.max_height_sigma":"inf","mission.level_views":false,"stereo.block_size":7})");
  EXPECT_EQ(ParamsJson(RunParams{}).dump(), "{}");
}

struct BadParams {
  std::string params;    // the params block appended to kScenario (line 9 on)
  std::string expected;  // a part of the message: file:line: key: what
};

void PrintTo(const BadParams& bad, std::ostream* out) { *out << "'" << bad.expected << "'"; }

class ParamErrors : public ::testing::TestWithParam<BadParams> {};

TEST_P(ParamErrors, NameFileLineAndKey) {
  const BadParams& bad = GetParam();
  const std::string message = ErrorOf(kScenario + bad.params);
  EXPECT_NE(message.find(bad.expected), std::string::npos)
      << "message: '" << message << "'\nexpected to contain: '" << bad.expected << "'";
}

INSTANTIATE_TEST_SUITE_P(
    AllKinds, ParamErrors,
    ::testing::Values(
        // unknown section and key
        BadParams{
            "params:\n  planer: {sidestep_factor: 1.4}\n",
            "course.yaml:10: params.planer: unknown key (expected one of: floor, fog, grid, "},
        BadParams{"params:\n  planner:\n    walk_factor: 1.1\n    sidestep: 1.4\n",
                  "course.yaml:12: params.planner.sidestep: unknown key (expected one of: "},
        // a derived parameter is not in the table
        BadParams{"params: {planner: {goal_tolerance: 0.1}}\n",
                  "course.yaml:9: params.planner.goal_tolerance: unknown key"},
        // wrong types
        BadParams{"params: {planner: {sidestep_factor: fast}}\n",
                  "course.yaml:9: params.planner.sidestep_factor: expected a number, got 'fast'"},
        BadParams{"params: {planner: {sidestep_factor: \"1.4\"}}\n",
                  "course.yaml:9: params.planner.sidestep_factor: expected a number, got the "
                  "string \"1.4\""},
        BadParams{"params: {planner: {sidestep_factor: [1, 2]}}\n",
                  "course.yaml:9: params.planner.sidestep_factor: expected a number, got a list"},
        BadParams{"params: {planner: {sidestep_factor: }}\n",
                  "course.yaml:9: params.planner.sidestep_factor: expected a number, got nothing"},
        BadParams{"params:\n  mission: {max_explorations: 2.5}\n",
                  "course.yaml:10: params.mission.max_explorations: expected an integer, got "
                  "'2.5'"},
        BadParams{"params:\n  fog: {infer_tops: 1}\n",
                  "course.yaml:10: params.fog.infer_tops: expected true or false, got '1'"},
        BadParams{"params:\n  planner: 1.4\n",
                  "course.yaml:10: params.planner: expected a mapping"},
        BadParams{"params: [planner]\n", "course.yaml:9: params: expected a mapping"},
        // out of the sane range, and rules beyond it
        BadParams{"params: {grid: {size_z: 65}}\n",
                  "course.yaml:9: params.grid.size_z: expected an integer from 4 to 64, got '65'"},
        BadParams{"params: {grid: {p_hit: 1.5}}\n",
                  "course.yaml:9: params.grid.p_hit: expected a number from 1e-06 to 0.999999, "
                  "got '1.5'"},
        // a certain hit would make infinite log-odds
        BadParams{"params: {grid: {p_hit: 1}}\n",
                  "course.yaml:9: params.grid.p_hit: expected a number from 1e-06 to 0.999999, "
                  "got '1'"},
        BadParams{"params: {planner: {sidestep_factor: -1}}\n",
                  "course.yaml:9: params.planner.sidestep_factor: expected a number from 0 to "
                  "100, got '-1'"},
        BadParams{"params: {planner: {sidestep_factor: .inf}}\n",
                  "course.yaml:9: params.planner.sidestep_factor: expected a number from 0 to "
                  "100, got '.inf'"},
        BadParams{"params: {planner: {sidestep_factor: .nan}}\n",
                  "course.yaml:9: params.planner.sidestep_factor: expected a number, got '.nan'"},
        BadParams{"params: {stereo: {num_disparities: 100}}\n",
                  "course.yaml:9: params.stereo.num_disparities: expected a multiple of 16, got "
                  "'100'"},
        BadParams{"params: {stereo: {block_size: 4}}\n",
                  "course.yaml:9: params.stereo.block_size: expected an odd number, got '4'"}));

TEST(Params, BadSetNamesTheFlagTheKeyAndWhatIsWrong) {
  EXPECT_EQ(SetErrorOf("planner.sidestep_factor"),
            "--set planner.sidestep_factor: expected section.key=value");
  EXPECT_EQ(SetErrorOf("planner.sidestep=1.4")
                .rfind("--set planner.sidestep=1.4: planner.sidestep: unknown parameter (sections: "
                       "stereo, ",
                       0),
            0u);
  EXPECT_EQ(SetErrorOf("planner.sidestep_factor=fast"),
            "--set planner.sidestep_factor=fast: planner.sidestep_factor: expected a number, got "
            "'fast'");
  EXPECT_EQ(SetErrorOf("planner.sidestep_factor="),
            "--set planner.sidestep_factor=: planner.sidestep_factor: expected a number, got ''");
  EXPECT_EQ(SetErrorOf("planner.sidestep_factor=1.4x"),
            "--set planner.sidestep_factor=1.4x: planner.sidestep_factor: expected a number, got "
            "'1.4x'");
  EXPECT_EQ(SetErrorOf("mission.max_explorations=3.0"),
            "--set mission.max_explorations=3.0: mission.max_explorations: expected an integer, "
            "got '3.0'");
  EXPECT_EQ(SetErrorOf("mission.max_explorations=99999999999999999999"),
            "--set mission.max_explorations=99999999999999999999: mission.max_explorations: "
            "expected an integer, got '99999999999999999999'");
  EXPECT_EQ(SetErrorOf("fog.infer_tops=yes"),
            "--set fog.infer_tops=yes: fog.infer_tops: expected true or false, got 'yes'");
  EXPECT_EQ(SetErrorOf("grid.p_hit=2"),
            "--set grid.p_hit=2: grid.p_hit: expected a number from 1e-06 to 0.999999, got '2'");
  EXPECT_EQ(SetErrorOf("planner.sidestep_factor=1.4"), "");
}

TEST(Params, ListingHasALinePerParameterWithItsDefault) {
  std::ostringstream out;
  PrintParamTable(out);
  const std::string text = out.str();
  EXPECT_EQ(size_t(std::count(text.begin(), text.end(), '\n')), ParamTable().size());
  EXPECT_NE(text.find("planner.sidestep_factor\tnumber\t1.6\t0..100\tcost per metre "
                      "side-stepping\n"),
            std::string::npos);
  EXPECT_NE(text.find("grid.min_hits_per_frame\tinteger\t2\t1..1000\t"), std::string::npos);
  EXPECT_NE(text.find("fog.infer_tops\tbool\ttrue\ttrue/false\t"), std::string::npos);
  EXPECT_NE(text.find("label.max_range\tnumber\tinf\t0..inf\t"), std::string::npos);
}

// An enumeration is named in files, flags and reports, and a wrong name lists the right ones.
TEST(Params, AChoiceIsReadAndWrittenByName) {
  const ParamInfo& mode = *FindParam("localization.mode");
  EXPECT_EQ(mode.type, ParamType::kChoice);
  double value = -1;
  EXPECT_EQ(ParseParamValue(mode, "truth", &value), "");
  RunParams params;
  mode.set(&params, value);
  EXPECT_EQ(params.perception.localization.mode, perception::LocalizationMode::kTruth);
  EXPECT_EQ(ParamsJson(params)["localization.mode"], "truth");
  EXPECT_EQ(ParseParamValue(mode, "gps", &value),
            "expected one of odometry, walls, visual, truth, got 'gps'");
  EXPECT_EQ(FormatParamValue(mode, mode.get(RunParams{})), "visual");
}

}  // namespace
}  // namespace fognav::scenarios

#include "viz/pages.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "navigation/internal/test_worlds.h"

namespace fognav::viz {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// every src="..." of the page names a file in dir, and nothing comes from elsewhere
void ExpectLocalSources(const fs::path& dir, const std::string& html) {
  const std::regex src("(src|href)=\"([^\"]*)\"");
  int sources = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator();
       ++it) {
    const std::string target = (*it)[2];
    EXPECT_EQ(target.find("://"), std::string::npos) << target;
    if ((*it)[1] == "src") {
      ++sources;
      EXPECT_TRUE(fs::exists(dir / target)) << target;
    }
  }
  EXPECT_GT(sources, 0);
  EXPECT_EQ(html.find("<script"), std::string::npos);
}

// an output folder of a mission that failed with no_path at cycle 3
fs::path FailedMissionFolder() {
  const fs::path dir = fs::path(::testing::TempDir()) / "fognav_pages_mission";
  fs::remove_all(dir);
  fs::create_directories(dir / "maps");
  std::ofstream(dir / "report.json") << R"({"scenario": "little_course", "success": false,
    "reached_goal": false, "goal_distance": 1.5, "failure": "no_path",
    "failure_detail": "goal_blocked", "cycles": 3, "spl": 0.0,
    "actions": {"walk": 2, "crawl": 1}, "timing_ms": {"render": 1.25}})";
  std::ofstream(dir / "trajectory.csv")
      << "step,tick,true_x,true_y,true_yaw,odom_x,odom_y,odom_yaw,action\n"
      << "1,10,0.70000,1.00000,0.00000,0.70000,1.00000,0.00000,walk\n"
      << "2,20,0.90000,1.00000,0.00000,0.90000,0.98000,0.00000,walk\n"
      << "3,30,1.10000,1.00000,0.00000,1.10000,0.96000,0.00000,crawl\n";
  std::ofstream(dir / "cycles.csv")
      << "cycle,step,odom_x,odom_y,odom_yaw,posture,plan,plan_cost,plan_length,decision,"
         "target_x,target_y,explorations,thrashes\n"
      << "1,0,0.50000,1.00000,0.00000,upright,goal,3.0,2.5,follow,,,0,0\n"
      << "2,2,0.90000,0.98000,0.00000,upright,toward,2.0,1.8,follow,,,0,0\n"
      << "3,3,1.10000,0.96000,0.00000,crawling,goal_blocked,0,0,give_up,,,0,0\n";
  return dir;
}

TEST(MissionPage, NamesTheOutcomeAndShowsTheFailure) {
  const fs::path dir = FailedMissionFolder();
  const perception::Fog floor = navigation::internal::FlatFog(75, 50, 0.04);
  navigation::PlanResult optimal;
  WriteMissionPage(dir.string(), floor, optimal, {0.5, 1.0, 0.0}, {2.6, 1.0}, "");
  ASSERT_TRUE(fs::exists(dir / "maps" / "mission.png"));
  const std::string html = Read(dir / "report.html");
  EXPECT_NE(html.find("<span id=\"outcome\" class=\"bad\">failed</span>"), std::string::npos);
  EXPECT_NE(html.find("<span id=\"failure\">no_path</span> (goal_blocked)"), std::string::npos);
  // the figures of report.json, nested keys dotted
  EXPECT_NE(html.find("<th>actions.crawl</th><td>1</td>"), std::string::npos);
  EXPECT_NE(html.find("<th>timing_ms.render</th><td>1.25</td>"), std::string::npos);
  // the timeline marks the failure's cycle and holds a strip cell per cycle and decision
  EXPECT_NE(html.find("no_path at cycle 3"), std::string::npos);
  EXPECT_NE(html.find("<title>cycle 3: give_up</title>"), std::string::npos);
  // the last decisions
  EXPECT_NE(html.find("<td>crawling</td><td>goal_blocked</td>"), std::string::npos);
  EXPECT_EQ(html.find("<video"), std::string::npos);
  ExpectLocalSources(dir, html);
}

TEST(MissionPage, EmbedsTheVideoByARelativePath) {
  const fs::path dir = FailedMissionFolder();
  const perception::Fog floor = navigation::internal::FlatFog(75, 50, 0.04);
  std::ofstream(dir.parent_path() / "fognav_pages_video.webm") << "not really a video";
  WriteMissionPage(dir.string(), floor, {}, {0.5, 1.0, 0.0}, {2.6, 1.0},
                   (dir.parent_path() / "fognav_pages_video.webm").string());
  const std::string html = Read(dir / "report.html");
  EXPECT_NE(html.find("<video controls width=\"960\" src=\"../fognav_pages_video.webm\">"),
            std::string::npos);
}

TEST(MissionPage, SkipsRowsFognavDidNotWrite) {
  const fs::path dir = FailedMissionFolder();
  std::ofstream(dir / "cycles.csv", std::ios::app) << "x,-3,oops\n,,\n";
  std::ofstream(dir / "trajectory.csv", std::ios::app) << "-1,0,1,1,0,1,1,0,walk\n4,40,x\n";
  WriteMissionPage(dir.string(), navigation::internal::FlatFog(75, 50, 0.04), {}, {0.5, 1.0, 0.0},
                   {2.6, 1.0}, "");
  const std::string html = Read(dir / "report.html");
  EXPECT_NE(html.find("<title>cycle 3: give_up</title>"), std::string::npos);
  EXPECT_EQ(html.find("<title>cycle 0"), std::string::npos);
}

// The believed pose's error is plotted over the settled rows only: here 2 and 4 cm.
TEST(MissionPage, PlotsThePoseErrorAtSettledFootsteps) {
  const fs::path dir = FailedMissionFolder();
  WriteMissionPage(dir.string(), navigation::internal::FlatFog(75, 50, 0.04), {}, {0.5, 1.0, 0.0},
                   {2.6, 1.0}, "");
  EXPECT_NE(Read(dir / "report.html").find("No settled footsteps were logged."), std::string::npos);
  std::ofstream(dir / "trajectory.csv")
      << "step,tick,true_x,true_y,true_yaw,odom_x,odom_y,odom_yaw,action,settled\n"
      << "1,10,0.70000,1.00000,0.00000,0.60000,1.00000,0.00000,walk,0\n"
      << "2,20,0.90000,1.00000,0.00000,0.90000,0.98000,0.00000,walk,1\n"
      << "4,40,1.10000,1.00000,0.00000,1.10000,0.96000,0.00000,walk,1\n";
  WriteMissionPage(dir.string(), navigation::internal::FlatFog(75, 50, 0.04), {}, {0.5, 1.0, 0.0},
                   {2.6, 1.0}, "");
  const std::string html = Read(dir / "report.html");
  const size_t svg = html.find("<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"pose_error\"");
  ASSERT_NE(svg, std::string::npos);
  // two points (the unsettled 10 cm row left out), the axis up to 4 cm, the last footstep 4
  const std::string plot = html.substr(svg, html.find("</svg>", svg) - svg);
  const size_t line = plot.find("points=\"");
  ASSERT_NE(line, std::string::npos);
  const std::string coordinates = plot.substr(line + 8, plot.find('"', line + 8) - line - 8);
  EXPECT_EQ(std::count(coordinates.begin(), coordinates.end(), ','), 2) << coordinates;
  EXPECT_NE(plot.find(">4</text>"), std::string::npos);
  EXPECT_NE(plot.find("footstep 4"), std::string::npos);
}

TEST(MissionPage, AMissingReportIsAnErrorNamingTheFile) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fognav_pages_empty";
  fs::remove_all(dir);
  fs::create_directories(dir);
  try {
    WriteMissionPage(dir.string(), navigation::internal::FlatFog(10, 10, 0.04), {}, {}, {1, 1}, "");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("report.json"), std::string::npos) << e.what();
  }
}

TEST(PerceivePage, TabulatesTheViewsAndTheConfusion) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fognav_pages_perceive";
  fs::remove_all(dir);
  fs::create_directories(dir / "frames");
  std::ofstream(dir / "frames" / "view00_left.png") << "png";
  std::ofstream(dir / "perception.json") << R"({"scenario": "little_course", "depth": "ideal",
    "views": [{"pan": 0.5, "tilt": -0.6, "segmentation": {"accuracy": 0.875, "coverage": 0.5}}],
    "segmentation": {"accuracy": 0.9, "coverage": 0.8}, "fog_accuracy": 0.95,
    "fog_confusion": {"floor": {"floor": 10, "border": 2}, "border": {"floor": 1, "border": 7}}})";
  WritePerceivePage(dir.string());
  const std::string html = Read(dir / "report.html");
  EXPECT_NE(html.find("<td>0</td><td>0.5</td><td>-0.6</td><td>0.875</td><td>0.5</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<tr><th>floor</th><td>10</td><td>2</td></tr>"), std::string::npos);
  EXPECT_NE(html.find("<th>fog_accuracy</th><td>0.95</td>"), std::string::npos);
  EXPECT_EQ(html.find("<th>views"), std::string::npos);  // views have their own table
  ExpectLocalSources(dir, html);
}

}  // namespace
}  // namespace fognav::viz

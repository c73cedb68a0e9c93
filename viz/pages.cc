// report.html for a mission and for `fognav perceive`.
#include "viz/pages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "viz/pictures.h"

namespace fognav::viz {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;  // the files' order of keys

std::string Format(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

json ReadJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  }
}

// A CSV file with a header line, as rows of named fields.
using CsvRow = std::map<std::string, std::string>;
std::vector<CsvRow> ReadCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  auto split = [](const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, ',')) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.push_back("");
    return fields;
  };
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = split(line);
    CsvRow row;
    for (size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

double Number(const CsvRow& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end() || it->second.empty()) return std::nan("");
  try {
    return std::stod(it->second);
  } catch (const std::exception&) {
    return std::nan("");
  }
}

std::string Field(const CsvRow& row, const std::string& key) {
  const auto it = row.find(key);
  return it == row.end() ? "" : it->second;
}

// a JSON value as table text: numbers with 4 significant digits, null as "none"
std::string ValueText(const json& v) {
  if (v.is_null()) return "none";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  if (v.is_number_float()) return Format("%.4g", v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

// the leaves of a JSON object as (dotted key, value) rows; arrays of objects stay one row
void Flatten(const json& v, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>* rows) {
  if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it) {
      Flatten(it.value(), prefix.empty() ? it.key() : prefix + "." + it.key(), rows);
    }
    return;
  }
  rows->push_back({prefix, ValueText(v)});
}

std::string FiguresTable(const json& report, const std::vector<std::string>& skip = {}) {
  std::vector<std::pair<std::string, std::string>> rows;
  for (auto it = report.begin(); it != report.end(); ++it) {
    if (std::find(skip.begin(), skip.end(), it.key()) != skip.end()) continue;
    Flatten(it.value(), it.key(), &rows);
  }
  std::string html = "<table class=\"figures\">\n";
  for (const auto& [key, value] : rows) {
    html += "<tr><th>" + EscapeMarkup(key) + "</th><td>" + EscapeMarkup(value) + "</td></tr>\n";
  }
  return html + "</table>\n";
}

const char* kStyle = R"(body{font-family:sans-serif;margin:1.5em;color:#222;max-width:1100px}
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}
.ok{color:#1a7f37}.bad{color:#c62828}
table{border-collapse:collapse;font-size:.9em}td,th{border:1px solid #ddd;padding:2px 8px;text-align:left}
table.figures{columns:2}th{background:#f4f4f4;font-weight:normal}
figure{display:inline-block;margin:.4em;vertical-align:top}figcaption{font-size:.85em;color:#555}
img{image-rendering:pixelated;max-width:100%}img.frame{width:330px}img.window{width:520px}
.note{color:#555;font-size:.9em})";

std::string PageStart(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" +
         EscapeMarkup(title) + "</title>\n<style>" + kStyle + "</style></head><body>\n";
}

// an image figure if the file exists in out_dir (the page must not hold broken images)
std::string Figure(const std::string& out_dir, const std::string& file, const std::string& caption,
                   const std::string& img_class = "") {
  if (!fs::exists(fs::path(out_dir) / file)) return "";
  return "<figure><a href=\"" + EscapeMarkup(file) + "\"><img src=\"" + EscapeMarkup(file) +
         "\" alt=\"" + EscapeMarkup(caption) + "\"" +
         (img_class.empty() ? "" : " class=\"" + img_class + "\"") + "></a><figcaption>" +
         EscapeMarkup(caption) + "</figcaption></figure>\n";
}

// The window's maps both pages show beside their plan: the ground truth, the FOG against it,
// the floor map and the 3D grid.
std::string WindowMapFigures(const std::string& out_dir) {
  return Figure(out_dir, "maps/fog_truth.png", "ground-truth FOG of the same window", "window") +
         Figure(out_dir, "maps/fog_errors.png",
                "the FOG against the truth (docs/scores.md); red: standable where it is not",
                "window") +
         Figure(out_dir, "maps/floor.png", "floor height map", "window") +
         Figure(out_dir, "maps/grid_side.png", "3D occupancy grid from the side", "window");
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw perception::OutputError(path + ": cannot write");
}

// distinct colours for the categories of a strip, in order of first appearance
const char* kPalette[] = {"#4c78a8", "#f58518", "#54a24b", "#b279a2", "#e45756", "#72b7b2",
                          "#eeca3b", "#9d755d", "#bab0ac", "#ff9da6", "#17becf", "#8c564b"};

// The timeline of a mission over its cycles as inline SVG: distance to the goal (true, from the
// trajectory at the cycle's step) and the plan's length, then strips of the plan and the
// decision of each cycle; the failure's cycle marked.
std::string TimelineSvg(const std::vector<CsvRow>& cycles, const std::vector<CsvRow>& trajectory,
                        const perception::Pose2& start_W, const Eigen::Vector2d& goal_W,
                        const std::string& failure, int last_cycle) {
  if (cycles.empty()) return "<p class=\"note\">No cycles were logged.</p>\n";
  std::map<int, perception::Pose2> true_at_step;
  true_at_step[0] = start_W;
  for (const CsvRow& r : trajectory) {
    const double step = Number(r, "step");
    if (!(step >= 1)) continue;  // not a row fognav wrote
    true_at_step[int(step)] = {Number(r, "true_x"), Number(r, "true_y"), 0.0};
  }
  struct Point {
    int cycle;
    double distance, plan_length;
    std::string plan, decision;
  };
  std::vector<Point> points;
  double top = 0.5;
  for (const CsvRow& r : cycles) {
    const double cycle = Number(r, "cycle"), step = Number(r, "step");
    if (!(cycle >= 1) || !(step >= 0)) continue;  // not a row fognav wrote
    Point p;
    p.cycle = int(cycle);
    auto it = true_at_step.upper_bound(int(step));
    const perception::Pose2 at = std::prev(it)->second;  // the last logged step at or before
    p.distance = std::hypot(at.x - goal_W.x(), at.y - goal_W.y());
    p.plan_length = Number(r, "plan_length");
    p.plan = Field(r, "plan");
    p.decision = Field(r, "decision");
    top = std::max({top, p.distance, std::isfinite(p.plan_length) ? p.plan_length : 0.0});
    points.push_back(p);
  }
  if (points.empty()) return "<p class=\"note\">No cycles were logged.</p>\n";
  top = std::ceil(top * 2) / 2;
  const int n = std::max(last_cycle, points.back().cycle);
  const double left = 54, width = 860, plot_h = 170, strip_h = 16;
  const double plot_top = 10, plan_y = plot_top + plot_h + 26, decision_y = plan_y + strip_h + 8;
  auto x_of = [&](double cycle) { return left + width * (cycle - 0.5) / std::max(n, 1); };
  auto y_of = [&](double metres) { return plot_top + plot_h * (1 - metres / top); };
  const double cell = width / std::max(n, 1);

  // category colours, in order of first appearance
  std::map<std::string, std::string> colours;
  std::vector<std::string> order;
  for (const Point& p : points) {
    for (const std::string* name : {&p.plan, &p.decision}) {
      if (colours.count(*name)) continue;
      colours[*name] = kPalette[colours.size() % (sizeof(kPalette) / sizeof(kPalette[0]))];
      order.push_back(*name);
    }
  }
  const double legend_y = decision_y + strip_h + 40;
  const int legend_rows = int(order.size() + 5) / 6 + 1;
  const double height = legend_y + 18 * legend_rows;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << left + width + 30 << "\" height=\""
      << height << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  // axes and grid
  for (double m = 0; m <= top + 1e-9; m += top > 3 ? 1.0 : 0.5) {
    svg << "<line x1=\"" << left << "\" x2=\"" << left + width << "\" y1=\"" << y_of(m)
        << "\" y2=\"" << y_of(m) << "\" stroke=\"#e4e4e4\"/><text x=\"" << left - 6 << "\" y=\""
        << y_of(m) + 4 << "\" text-anchor=\"end\">" << Format("%.1f", m) << "</text>\n";
  }
  svg << "<text x=\"4\" y=\"" << plot_top + 10 << "\">m</text>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << plot_top << "\" width=\"" << width << "\" height=\""
      << plot_h << "\" fill=\"none\" stroke=\"#888\"/>\n";
  const int tick = std::max(1, int(std::pow(10, std::floor(std::log10(std::max(n, 1) / 2.0)))));
  for (int c = tick; c <= n; c += tick) {
    if (n / tick > 12 && c % (2 * tick) != 0) continue;
    svg << "<text x=\"" << x_of(c) << "\" y=\"" << plot_top + plot_h + 14
        << "\" text-anchor=\"middle\">" << c << "</text>\n";
  }
  svg << "<text x=\"" << left + width << "\" y=\"" << plot_top + plot_h + 14
      << "\" text-anchor=\"end\" dx=\"26\">cycle</text>\n";
  // the two curves
  auto polyline = [&](auto value, const char* colour, const char* dash) {
    svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\""
        << (dash[0] ? std::string(" stroke-dasharray=\"") + dash + "\"" : "") << " points=\"";
    for (const Point& p : points) {
      const double v = value(p);
      if (std::isfinite(v)) svg << x_of(p.cycle) << "," << y_of(v) << " ";
    }
    svg << "\"/>\n";
  };
  polyline([](const Point& p) { return p.distance; }, "#1f5fbf", "");
  polyline([](const Point& p) { return p.plan_length; }, "#e07b00", "5,3");
  // the strips
  svg << "<text x=\"" << left - 6 << "\" y=\"" << plan_y + 12
      << "\" text-anchor=\"end\">plan</text>\n<text x=\"" << left - 6 << "\" y=\""
      << decision_y + 12 << "\" text-anchor=\"end\">decision</text>\n";
  for (const Point& p : points) {
    for (const auto& [y, name] : {std::pair{plan_y, &p.plan}, std::pair{decision_y, &p.decision}}) {
      svg << "<rect x=\"" << x_of(p.cycle) - cell / 2 << "\" y=\"" << y << "\" width=\""
          << std::max(cell, 0.5) << "\" height=\"" << strip_h << "\" fill=\"" << colours[*name]
          << "\"><title>cycle " << p.cycle << ": " << EscapeMarkup(*name) << "</title></rect>\n";
    }
  }
  // the failure's cycle
  if (!failure.empty()) {
    const double x = x_of(n);
    svg << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << plot_top << "\" y2=\""
        << decision_y + strip_h + 4 << "\" stroke=\"#c62828\" stroke-width=\"2\" "
        << "stroke-dasharray=\"4,2\"/><text x=\"" << x - 4 << "\" y=\"" << decision_y + strip_h + 18
        << "\" text-anchor=\"end\" fill=\"#c62828\">" << EscapeMarkup(failure) << " at cycle " << n
        << "</text>\n";
  }
  // legend
  double lx = left, ly = legend_y;
  auto legend_line = [&](const char* colour, const char* dash, const char* label) {
    svg << "<line x1=\"" << lx << "\" x2=\"" << lx + 22 << "\" y1=\"" << ly - 4 << "\" y2=\""
        << ly - 4 << "\" stroke=\"" << colour << "\" stroke-width=\"2\""
        << (dash[0] ? std::string(" stroke-dasharray=\"") + dash + "\"" : "") << "/><text x=\""
        << lx + 26 << "\" y=\"" << ly << "\">" << label << "</text>\n";
    lx += 200;
  };
  legend_line("#1f5fbf", "", "distance to the goal (true)");
  legend_line("#e07b00", "5,3", "length of the plan");
  for (size_t i = 0; i < order.size(); ++i) {
    if (i % 6 == 0) {
      lx = left;
      ly += 18;
    }
    svg << "<rect x=\"" << lx << "\" y=\"" << ly - 10 << "\" width=\"12\" height=\"12\" fill=\""
        << colours[order[i]] << "\"/><text x=\"" << lx + 16 << "\" y=\"" << ly << "\">"
        << EscapeMarkup(order[i]) << "</text>\n";
    lx += 140;
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string LastDecisionsTable(const std::vector<CsvRow>& cycles, size_t count) {
  const char* columns[] = {"cycle",    "step",         "odom_x",      "odom_y",   "odom_yaw",
                           "posture",  "plan",         "plan_length", "decision", "target_x",
                           "target_y", "explorations", "thrashes"};
  std::string html = "<table>\n<tr>";
  for (const char* c : columns) html += std::string("<th>") + c + "</th>";
  html += "</tr>\n";
  const size_t first = cycles.size() > count ? cycles.size() - count : 0;
  for (size_t i = first; i < cycles.size(); ++i) {
    html += "<tr>";
    for (const char* c : columns) html += "<td>" + EscapeMarkup(Field(cycles[i], c)) + "</td>";
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

}  // namespace

// The believed pose's position error at the settled footsteps (trajectory.csv's settled rows)
// as inline SVG over the steps, with its largest value; a note where the run logged none.
std::string PoseErrorSvg(const std::vector<CsvRow>& trajectory) {
  std::vector<std::pair<double, double>> points;  // step, error in metres
  double top = 0.01;
  for (const CsvRow& r : trajectory) {
    if (Number(r, "settled") != 1) continue;
    const double step = Number(r, "step");
    const double e = std::hypot(Number(r, "odom_x") - Number(r, "true_x"),
                                Number(r, "odom_y") - Number(r, "true_y"));
    if (!(step >= 1) || !std::isfinite(e)) continue;
    points.emplace_back(step, e);
    top = std::max(top, e);
  }
  if (points.empty()) return "<p class=\"note\">No settled footsteps were logged.</p>\n";
  top = std::ceil(top * 100) / 100;  // whole centimetres
  const double left = 54, width = 860, height = 120, last = points.back().first;
  auto x_of = [&](double step) { return left + width * step / std::max(last, 1.0); };
  auto y_of = [&](double e) { return 10 + height * (1 - e / top); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"pose_error\" width=\"" << left + width + 30
      << "\" height=\"" << height + 40 << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  for (int cm = 0; cm <= int(std::lround(top * 100)); cm += std::max(1, int(top * 100) / 4)) {
    svg << "<line x1=\"" << left << "\" x2=\"" << left + width << "\" y1=\"" << y_of(cm / 100.0)
        << "\" y2=\"" << y_of(cm / 100.0) << "\" stroke=\"#e4e4e4\"/><text x=\"" << left - 6
        << "\" y=\"" << y_of(cm / 100.0) + 4 << "\" text-anchor=\"end\">" << cm << "</text>\n";
  }
  svg << "<text x=\"4\" y=\"20\">cm</text><text x=\"" << left + width << "\" y=\""
      << height + 34 << "\" text-anchor=\"end\">footstep " << Format("%.0f", last) << "</text>\n";
  svg << "<polyline fill=\"none\" stroke=\"#e45756\" stroke-width=\"1.5\" points=\"";
  for (const auto& [step, e] : points) svg << x_of(step) << "," << y_of(e) << " ";
  svg << "\"/>\n<rect x=\"" << left << "\" y=\"10\" width=\"" << width << "\" height=\"" << height
      << "\" fill=\"none\" stroke=\"#888\"/>\n</svg>\n";
  return svg.str();
}

void WriteMissionPage(const std::string& out_dir, const perception::Fog& floor_truth,
                      const navigation::PlanResult& optimal, const perception::Pose2& start_W,
                      const Eigen::Vector2d& goal_W, const std::string& video_path) {
  const fs::path dir(out_dir);
  const json report = ReadJson((dir / "report.json").string());
  const std::vector<CsvRow> trajectory = ReadCsv((dir / "trajectory.csv").string());
  const std::vector<CsvRow> cycles = ReadCsv((dir / "cycles.csv").string());

  // the whole floor with the ways
  std::vector<TrackPoint> track;
  for (const CsvRow& r : trajectory) {
    TrackPoint t{{Number(r, "true_x"), Number(r, "true_y"), Number(r, "true_yaw")},
                 {Number(r, "odom_x"), Number(r, "odom_y"), Number(r, "odom_yaw")},
                 Field(r, "action")};
    auto finite = [](const perception::Pose2& p) {
      return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.yaw);
    };
    if (finite(t.true_W) && finite(t.believed_W)) track.push_back(t);  // else not fognav's row
  }
  fs::create_directories(dir / "maps");
  WritePng(DrawMissionMap(floor_truth, optimal, start_W, goal_W, track),
           (dir / "maps" / "mission.png").string());

  const std::string scenario = report.value("scenario", "");
  const bool success = report.value("success", false);
  const std::string failure =
      report["failure"].is_string() ? report["failure"].get<std::string>() : "";
  const std::string detail =
      report["failure_detail"].is_string() ? report["failure_detail"].get<std::string>() : "";
  const int last_cycle = report.value("cycles", 0);
  const std::string outcome = success ? "success" : "failed";

  std::string html = PageStart("fognav: " + scenario + " " + outcome);
  html += "<h1>" + EscapeMarkup(scenario) + ": <span id=\"outcome\" class=\"" +
          (success ? "ok" : "bad") + "\">" + outcome + "</span></h1>\n";
  html += "<p>" +
          std::string(report.value("reached_goal", false) ? "Goal reached" : "Goal not reached") +
          Format(" (%.2f m from it at the end)", report.value("goal_distance", 0.0)) +
          "; failure: <span id=\"failure\">" + EscapeMarkup(failure.empty() ? "none" : failure) +
          "</span>" + (detail.empty() ? "" : " (" + EscapeMarkup(detail) + ")") +
          Format("; %.0f cycles", last_cycle) + Format(", SPL %.3f. ", report.value("spl", 0.0)) +
          (success ? "Every expectation of the scenario held."
                   : "An expectation of the scenario failed.") +
          "</p>\n";
  html +=
      "<p class=\"note\">Files: <a href=\"report.json\">report.json</a>, "
      "<a href=\"trajectory.csv\">trajectory.csv</a> (a row per step), "
      "<a href=\"cycles.csv\">cycles.csv</a> (a row per cycle), <a href=\"maps/\">maps/</a>, "
      "<a href=\"frames/\">frames/</a>.</p>\n";

  html +=
      "<h2>The whole floor</h2>\n<p class=\"note\">The ground-truth FOG of the whole floor "
      "(world frame, +x right, +y up) with the way the robot took (coloured by move), the "
      "way it believed it took (odometry, dashed) and the optimal path on the ground "
      "truth.</p>\n";
  html += Figure(out_dir, "maps/mission.png", "the mission on the whole floor");

  html +=
      "<h2>Timeline</h2>\n" + TimelineSvg(cycles, trajectory, start_W, goal_W, failure, last_cycle);
  html +=
      "<h2>Where the robot believed it was</h2>\n<p class=\"note\">The believed position's "
      "distance from the true one at each footstep that ended a stride (trajectory.csv's settled "
      "rows; localization: " +
      EscapeMarkup(report.contains("localization") ? report["localization"].value("mode", "")
                                                   : std::string()) +
      ").</p>\n" + PoseErrorSvg(trajectory);

  if (!failure.empty()) {
    html += "<h2>The failure: " + EscapeMarkup(failure) +
            (detail.empty() ? "" : " (" + EscapeMarkup(detail) + ")") + "</h2>\n";
    html += Figure(out_dir, "maps/final_plan.png",
                   "the believed FOG and the plan at cycle " + std::to_string(last_cycle) +
                       ", where the mission ended",
                   "window");
    html += "<p>The last decisions (cycles.csv):</p>\n" + LastDecisionsTable(cycles, 12);
  }

  html += "<h2>Figures (report.json)</h2>\n" + FiguresTable(report);

  html += "<h2>The last frames</h2>\n";
  html += Figure(out_dir, "frames/final_left.png", "left camera image", "frame");
  html += Figure(out_dir, "frames/final_disparity.png", "disparity (near red, far blue)", "frame");
  html += Figure(out_dir, "frames/final_segments.png", "plane segments", "frame");

  html +=
      "<h2>The maps at the end</h2>\n<p class=\"note\">The robot's 4 m window in the grid "
      "(odometry) frame.</p>\n";
  html += Figure(out_dir, "maps/final_plan.png", "believed FOG with the last plan", "window");
  html += WindowMapFigures(out_dir);
  html += Figure(out_dir, "maps/optimal_plan.png", "optimal plan on the ground truth", "window");

  if (!video_path.empty()) {
    std::error_code error;
    fs::path video = fs::relative(fs::absolute(video_path), fs::absolute(dir), error);
    if (error || video.empty()) video = fs::absolute(video_path);
    html += "<h2>Video</h2>\n<video controls width=\"960\" src=\"" + EscapeMarkup(video.string()) +
            "\"></video>\n<p class=\"note\"><a href=\"" + EscapeMarkup(video.string()) +
            "\">the video file</a> (browsers play .webm; open .avi or .mp4 in a video player if "
            "the browser cannot)</p>\n";
  }
  html += "</body></html>\n";
  WriteText((dir / "report.html").string(), html);
}

void WritePerceivePage(const std::string& out_dir) {
  const fs::path dir(out_dir);
  const json report = ReadJson((dir / "perception.json").string());
  const std::string scenario = report.value("scenario", "");
  std::string html = PageStart("fognav perceive: " + scenario);
  html += "<h1>" + EscapeMarkup(scenario) + ": perception from the start pose</h1>\n";
  html += "<p>Depth: " + EscapeMarkup(report.value("depth", "")) +
          Format("; segmentation accuracy %.3f", report["segmentation"].value("accuracy", 0.0)) +
          Format(", coverage %.3f", report["segmentation"].value("coverage", 0.0)) +
          Format("; FOG traversability %.3f",
                 report.value("fog", json::object()).value("traversability", 0.0)) +
          Format(", unsafe cells %.0f",
                 report.value("fog", json::object()).value("unsafe_cells", 0.0)) +
          Format(", six-type accuracy %.3f.", report.value("fog_accuracy", 0.0)) + "</p>\n";
  html +=
      "<p class=\"note\">Files: <a href=\"perception.json\">perception.json</a>, "
      "<a href=\"maps/\">maps/</a>, <a href=\"frames/\">frames/</a>.</p>\n";

  html += "<h2>The maps after the look-around</h2>\n";
  html += Figure(out_dir, "maps/plan.png", "perceived FOG with the plan a mission would start with",
                 "window");
  html += WindowMapFigures(out_dir);

  html += "<h2>Scores (perception.json)</h2>\n" + FiguresTable(report, {"views", "fog_confusion"});

  if (report.contains("fog_confusion") && report["fog_confusion"].is_object()) {
    const json& confusion = report["fog_confusion"];
    html +=
        "<h2>FOG confusion</h2>\n<p class=\"note\">Rows: the ground truth; columns: the "
        "estimate; observed cells.</p>\n<table>\n<tr><th></th>";
    for (auto it = confusion.begin(); it != confusion.end(); ++it)
      html += "<th>" + EscapeMarkup(it.key()) + "</th>";
    html += "</tr>\n";
    for (auto row = confusion.begin(); row != confusion.end(); ++row) {
      html += "<tr><th>" + EscapeMarkup(row.key()) + "</th>";
      for (auto col = confusion.begin(); col != confusion.end(); ++col) {
        html += "<td>" + ValueText(row.value().value(col.key(), json(0))) + "</td>";
      }
      html += "</tr>\n";
    }
    html += "</table>\n";
  }

  html +=
      "<h2>Views</h2>\n<table>\n<tr><th>view</th><th>pan</th><th>tilt</th><th>accuracy</th>"
      "<th>coverage</th><th>left</th><th>disparity</th><th>segments</th></tr>\n";
  const json views = report.value("views", json::array());
  for (size_t i = 0; i < views.size(); ++i) {
    char prefix[32];
    std::snprintf(prefix, sizeof(prefix), "frames/view%02zu", i);
    const json& v = views[i];
    const json seg = v.value("segmentation", json::object());
    html += "<tr><td>" + std::to_string(i) + "</td><td>" + ValueText(v.value("pan", json())) +
            "</td><td>" + ValueText(v.value("tilt", json())) + "</td><td>" +
            ValueText(seg.value("accuracy", json())) + "</td><td>" +
            ValueText(seg.value("coverage", json())) + "</td>";
    for (const char* kind : {"_left.png", "_disparity.png", "_segments.png"}) {
      const std::string file = std::string(prefix) + kind;
      html += "<td>";
      if (fs::exists(dir / file)) {
        html += "<a href=\"" + file + "\"><img src=\"" + file + "\" alt=\"" + file +
                "\" width=\"176\"></a>";
      }
      html += "</td>";
    }
    html += "</tr>\n";
  }
  html += "</table>\n</body></html>\n";
  WriteText((dir / "report.html").string(), html);
}

std::string EscapeMarkup(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\n') ? ' ' : c;
    }
  }
  return out;
}

}  // namespace fognav::viz

#include "scenarios/sweep.h"

#include <fcntl.h>
#include <glob.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "scenarios/internal/sweep_slurm.h"
#include "scenarios/output.h"
#include "scenarios/params.h"
#include "scenarios/scenario.h"
#include "viz/pages.h"

extern char** environ;

namespace fognav::scenarios {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// the scenario files an argument names: the file itself, a folder's *.yaml, or a glob's matches
std::vector<std::string> Expand(const std::string& argument) {
  std::error_code error;
  if (fs::is_regular_file(argument, error)) return {argument};
  std::vector<std::string> files;
  if (fs::is_directory(argument, error)) {
    for (const auto& entry : fs::directory_iterator(argument, error)) {
      if (entry.is_regular_file() && entry.path().extension() == ".yaml") {
        files.push_back(entry.path().string());
      }
    }
    if (files.empty()) throw InputError("scenario folder '" + argument + "': no *.yaml in it");
  } else {
    glob_t matches;
    const int status = glob(argument.c_str(), 0, nullptr, &matches);
    if (status == 0) {
      for (size_t i = 0; i < matches.gl_pathc; ++i) {
        if (fs::is_regular_file(matches.gl_pathv[i], error)) files.push_back(matches.gl_pathv[i]);
      }
    }
    globfree(&matches);
    if (files.empty()) {
      throw InputError("scenario '" + argument + "': no such file or folder, and no file matches");
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// a report's number; null (a NaN written by fognav) or missing gives `missing`
double Number(const nlohmann::json& j, const char* key, double missing = kNaN) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return missing;
  return j[key].get<double>();
}

int Integer(const nlohmann::json& j, const char* key) {
  const double v = Number(j, key, 0);
  return std::isfinite(v) ? int(v) : 0;
}

std::string String(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
}

// the first line that is not empty: the program's error is one line (CLI11 adds a hint after)
std::string FirstLine(const std::string& path) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) return line;
  }
  return "";
}

std::string Fixed(double v, int digits) {
  if (std::isnan(v)) return "nan";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, v);
  return buffer;
}

std::string Percent(double x) { return std::isnan(x) ? "n/a" : Fixed(100 * x, 1) + " %"; }

double Mean(const std::vector<double>& values) {
  double sum = 0;
  int n = 0;
  for (double v : values) {
    if (!std::isnan(v)) sum += v, ++n;
  }
  return n > 0 ? sum / n : kNaN;
}

// "class n, class n" in name order, or "none"
std::string Classes(const std::vector<std::string>& names) {
  std::map<std::string, int> counts;
  for (const auto& n : names) ++counts[n];
  std::string text;
  for (const auto& [name, count] : counts) {
    text += (text.empty() ? "" : ", ") + name + " " + std::to_string(count);
  }
  return text.empty() ? "none" : text;
}

bool Ran(const SweepRow& r) { return r.finished; }
bool HasWay(const SweepRow& r) { return r.finished && r.optimal_path_length > 0; }

std::string Cell(std::string text) {
  std::replace(text.begin(), text.end(), '\t', ' ');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

nlohmann::json JsonNumber(double v) {
  return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v);
}

// the run's parameter overrides, "key=value key=value"
std::string Params(const SweepRun& run) {
  std::string text;
  for (const auto& p : run.params) text += (text.empty() ? "" : " ") + p;
  return text;
}

struct Column {
  const char* name;
  std::string (*value)(const SweepRow&);
};

// the columns of every run, then those of `more`
std::vector<Column> WithRunColumns(std::vector<Column> more) {
  std::vector<Column> columns = {
      {"name", [](const SweepRow& r) { return r.run.name; }},
      {"scenario", [](const SweepRow& r) { return r.run.scenario; }},
      {"seed", [](const SweepRow& r) { return r.run.seed < 0 ? "" : std::to_string(r.run.seed); }},
      {"params", [](const SweepRow& r) { return Params(r.run); }},
      {"exit", [](const SweepRow& r) { return std::to_string(r.exit_code); }},
      {"outcome", [](const SweepRow& r) { return r.outcome; }}};
  columns.insert(columns.end(), more.begin(), more.end());
  return columns;
}

const std::vector<Column>& Columns(bool perceive) {
  static const std::vector<Column> kMission = WithRunColumns(
      {{"reached_goal", [](const SweepRow& r) { return std::string(r.reached_goal ? "1" : "0"); }},
       {"failure", [](const SweepRow& r) { return r.failure; }},
       {"cycles", [](const SweepRow& r) { return std::to_string(r.cycles); }},
       {"collisions", [](const SweepRow& r) { return std::to_string(r.collisions); }},
       {"spl", [](const SweepRow& r) { return Fixed(r.spl, 4); }},
       {"optimal_path_length", [](const SweepRow& r) { return Fixed(r.optimal_path_length, 4); }},
       {"traversability", [](const SweepRow& r) { return Fixed(r.traversability, 4); }},
       {"unsafe_cells", [](const SweepRow& r) { return std::to_string(r.unsafe_cells); }},
       {"wall_time_s", [](const SweepRow& r) { return Fixed(r.wall_time_s, 2); }},
       {"detail", [](const SweepRow& r) { return r.detail; }}});
  static const std::vector<Column> kPerceive = WithRunColumns(
      {{"accuracy", [](const SweepRow& r) { return Fixed(r.accuracy, 4); }},
       {"coverage", [](const SweepRow& r) { return Fixed(r.coverage, 4); }},
       {"correct", [](const SweepRow& r) { return std::to_string(r.correct); }},
       {"surfaces", [](const SweepRow& r) { return std::to_string(r.surfaces); }},
       {"fog_accuracy", [](const SweepRow& r) { return Fixed(r.fog_accuracy, 4); }},
       {"fog_cells", [](const SweepRow& r) { return std::to_string(r.fog_cells); }},
       {"traversability", [](const SweepRow& r) { return Fixed(r.traversability, 4); }},
       {"unsafe_cells", [](const SweepRow& r) { return std::to_string(r.unsafe_cells); }},
       {"detail", [](const SweepRow& r) { return r.detail; }}});
  return perceive ? kPerceive : kMission;
}

// sorts the table by the clicked column, numbers as numbers; a second click reverses
constexpr const char* kSortScript = R"(
document.querySelectorAll('th').forEach((th, column) => th.addEventListener('click', () => {
  const body = th.closest('table').tBodies[0];
  const up = th.dataset.order !== 'up';
  th.dataset.order = up ? 'up' : 'down';
  const key = row => row.cells[column].textContent;
  const rows = Array.from(body.rows).sort((a, b) => {
    const x = key(a), y = key(b), nx = parseFloat(x), ny = parseFloat(y);
    const order = !isNaN(nx) && !isNaN(ny) ? nx - ny : x.localeCompare(y);
    return up ? order : -order;
  });
  rows.forEach(row => body.appendChild(row));
}));
)";

// index.html: the summary, then a sortable table of the runs, each linking its report.html with
// its map as a thumbnail where there is one
std::string IndexPage(const std::string& out_dir, const std::vector<SweepRow>& rows,
                      const std::string& summary, bool perceive) {
  struct Shown {
    const char* head;
    std::string (*value)(const SweepRow&);
  };
  static const std::vector<Shown> kMission = {
      {"outcome", [](const SweepRow& r) { return r.outcome; }},
      {"failure", [](const SweepRow& r) { return r.failure; }},
      {"detail", [](const SweepRow& r) { return r.detail; }},
      {"SPL", [](const SweepRow& r) { return r.finished ? Fixed(r.spl, 3) : ""; }},
      {"cycles", [](const SweepRow& r) { return r.finished ? std::to_string(r.cycles) : ""; }},
      {"wall time [s]", [](const SweepRow& r) { return Fixed(r.wall_time_s, 1); }},
      {"FOG traversability", [](const SweepRow& r) { return Fixed(r.traversability, 4); }},
      {"unsafe cells",
       [](const SweepRow& r) { return r.finished ? std::to_string(r.unsafe_cells) : ""; }}};
  static const std::vector<Shown> kPerceive = {
      {"outcome", [](const SweepRow& r) { return r.outcome; }},
      {"segmentation accuracy", [](const SweepRow& r) { return Fixed(r.accuracy, 4); }},
      {"coverage", [](const SweepRow& r) { return Fixed(r.coverage, 4); }},
      {"FOG traversability", [](const SweepRow& r) { return Fixed(r.traversability, 4); }},
      {"unsafe cells", [](const SweepRow& r) { return std::to_string(r.unsafe_cells); }},
      {"FOG six-type accuracy", [](const SweepRow& r) { return Fixed(r.fog_accuracy, 4); }}};
  const auto& shown = perceive ? kPerceive : kMission;
  const std::string thumbnail = perceive ? "maps/plan.png" : "maps/mission.png";
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
       << "<title>fognav sweep</title>\n"
       << "<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
          "td,th{border:1px solid #ddd;padding:2px 8px;text-align:left}"
          "th{background:#f4f4f4;cursor:pointer}.bad{color:#c62828}.ok{color:#1a7f37}"
          "img{max-width:240px;max-height:120px}</style></head><body>\n"
       << "<h1>fognav sweep</h1>\n<pre id=\"summary\">" << viz::EscapeMarkup(summary) << "</pre>\n"
       << "<p>Click a column's head to sort by it.</p>\n<table><thead><tr><th>run</th>";
  for (const auto& s : shown) page << "<th>" << viz::EscapeMarkup(s.head) << "</th>";
  page << "<th>map</th></tr></thead><tbody>\n";
  for (const auto& r : rows) {
    const std::string link = "runs/" + r.run.name + "/report.html";
    page << "<tr><td><a href=\"" << viz::EscapeMarkup(link) << "\">"
         << viz::EscapeMarkup(r.run.name) << "</a></td>";
    for (const auto& s : shown) {
      const std::string value = s.value(r) == "nan" ? "" : s.value(r);
      if (std::string(s.head) == "outcome") {
        const bool ok = value == "success" || value == "perceived";
        page << "<td class=\"" << (ok ? "ok" : "bad") << "\">" << viz::EscapeMarkup(value)
             << "</td>";
      } else {
        page << "<td>" << viz::EscapeMarkup(value) << "</td>";
      }
    }
    const std::string image = "runs/" + r.run.name + "/" + thumbnail;
    std::error_code error;
    if (fs::exists(fs::path(out_dir) / image, error)) {
      page << "<td><a href=\"" << viz::EscapeMarkup(link) << "\"><img src=\""
           << viz::EscapeMarkup(image) << "\" alt=\"map of " << viz::EscapeMarkup(r.run.name)
           << "\"></a></td>";
    } else {
      page << "<td></td>";
    }
    page << "</tr>\n";
  }
  page << "</tbody></table>\n<script>" << kSortScript << "</script>\n</body></html>\n";
  return page.str();
}

std::string JunitXml(const std::vector<SweepRow>& rows) {
  int failures = 0, errors = 0, skipped = 0;
  double time_s = 0;
  for (const auto& r : rows) {
    if (!r.finished)
      (r.outcome == "not run" ? skipped : errors)++;
    else if (r.exit_code != 0)
      ++failures;
    if (std::isfinite(r.wall_time_s)) time_s += r.wall_time_s;
  }
  std::ostringstream xml;
  const std::string counts = "tests=\"" + std::to_string(rows.size()) + "\" failures=\"" +
                             std::to_string(failures) + "\" errors=\"" + std::to_string(errors) +
                             "\" skipped=\"" + std::to_string(skipped) + "\"";
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"fognav sweep\" " << counts << " time=\"" << Fixed(time_s, 2)
      << "\">\n  <testsuite name=\"fognav sweep\" " << counts << " time=\"" << Fixed(time_s, 2)
      << "\">\n";
  for (const auto& r : rows) {
    xml << "    <testcase classname=\"fognav.sweep\" name=\"" << viz::EscapeMarkup(r.run.name)
        << "\" file=\"" << viz::EscapeMarkup(r.run.scenario) << "\" time=\""
        << (std::isfinite(r.wall_time_s) ? Fixed(r.wall_time_s, 2) : "0") << "\"";
    const std::string message = r.failure.empty() ? r.outcome : r.failure;
    const std::string text = message + (r.detail.empty() ? "" : ": " + r.detail);
    if (r.finished && r.exit_code == 0) {
      xml << "/>\n";
    } else if (r.finished) {
      xml << ">\n      <failure type=\"" << viz::EscapeMarkup(r.outcome) << "\" message=\""
          << viz::EscapeMarkup(text) << "\"/>\n    </testcase>\n";
    } else if (r.outcome == "not run") {
      xml << ">\n      <skipped message=\"" << viz::EscapeMarkup(text) << "\"/>\n    </testcase>\n";
    } else {
      xml << ">\n      <error type=\"exit " << r.exit_code << "\" message=\""
          << viz::EscapeMarkup(text) << "\"/>\n    </testcase>\n";
    }
  }
  xml << "  </testsuite>\n</testsuites>\n";
  return xml.str();
}

nlohmann::json RowJson(const SweepRow& r, bool perceive) {
  nlohmann::json j = {
      {"name", r.run.name},
      {"scenario", r.run.scenario},
      {"seed", r.run.seed < 0 ? nlohmann::json(nullptr) : nlohmann::json(r.run.seed)},
      {"params", r.run.params},
      {"exit", r.exit_code},
      {"outcome", r.outcome},
      {"failure", r.failure},
      {"detail", r.detail},
      {"traversability", JsonNumber(r.traversability)},
      {"unsafe_cells", r.unsafe_cells},
      {"wall_time_s", JsonNumber(r.wall_time_s)}};
  if (perceive) {
    j.update({{"accuracy", JsonNumber(r.accuracy)},
              {"coverage", JsonNumber(r.coverage)},
              {"correct", r.correct},
              {"surfaces", r.surfaces},
              {"fog_accuracy", JsonNumber(r.fog_accuracy)},
              {"fog_cells", r.fog_cells}});
  } else {
    j.update({{"reached_goal", r.reached_goal},
              {"cycles", r.cycles},
              {"collisions", r.collisions},
              {"spl", JsonNumber(r.spl)},
              {"optimal_path_length", JsonNumber(r.optimal_path_length)}});
  }
  return j;
}

// What to show on a terminal while runs go on; the progress line is redrawn in place there.
class Progress {
 public:
  explicit Progress(size_t total) : total_(total), terminal_(::isatty(STDERR_FILENO) == 1) {}
  void Finished(const SweepRow& row, size_t running) {
    ++done_;
    if (!(row.finished && row.exit_code == 0)) ++failed_;
    if (terminal_) {
      std::cerr << "\r[" << done_ << "/" << total_ << "] " << running << " running, " << failed_
                << " not passed; last " << row.run.name << ": " << row.outcome << "\033[K"
                << std::flush;
    } else {
      std::cerr << "[" << done_ << "/" << total_ << "] " << row.run.name << ": " << row.outcome
                << (row.detail.empty() ? "" : " (" + row.detail + ")") << "\n";
    }
  }
  ~Progress() {
    if (terminal_ && done_ > 0) std::cerr << "\n";
  }

 private:
  size_t total_, done_ = 0, failed_ = 0;
  bool terminal_;
};

bool Stopped(const SweepOptions& options) { return options.stop != nullptr && *options.stop; }

// Runs the rows still to do as child processes, `jobs` at a time; returns false if stopped.
bool RunLocal(const SweepOptions& options, const std::vector<size_t>& todo,
              std::vector<SweepRow>* rows) {
  const int jobs =
      options.jobs > 0 ? options.jobs : std::max(1, int(sysconf(_SC_NPROCESSORS_ONLN)));
  std::map<pid_t, size_t> running;
  Progress progress(todo.size());
  size_t next = 0;
  bool signalled = false;
  while (next < todo.size() || !running.empty()) {
    // start runs while workers are free
    while (!Stopped(options) && int(running.size()) < jobs && next < todo.size()) {
      const size_t i = todo[next++];
      const SweepRun& run = (*rows)[i].run;
      const std::string dir = options.out_dir + "/runs/" + run.name;
      std::error_code error;
      fs::remove_all(dir, error);  // a half-done run starts afresh
      MakeOutputFolder(dir);
      std::vector<std::string> arguments = RunArguments(options, run, dir);
      arguments.insert(arguments.begin(), options.program);
      std::vector<char*> argv;
      for (auto& a : arguments) argv.push_back(a.data());
      argv.push_back(nullptr);
      posix_spawn_file_actions_t files;
      posix_spawn_file_actions_init(&files);
      posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
      const std::string log = dir + "/stderr.log";
      posix_spawn_file_actions_addopen(&files, STDERR_FILENO, log.c_str(),
                                       O_WRONLY | O_CREAT | O_TRUNC, 0644);
      pid_t pid = 0;
      const int status =
          posix_spawn(&pid, options.program.c_str(), &files, nullptr, argv.data(), environ);
      posix_spawn_file_actions_destroy(&files);
      if (status != 0) {
        (*rows)[i] = ReadRow(run, dir, options.perceive, 127);
        (*rows)[i].detail = options.program + ": cannot start: " + std::strerror(status);
        progress.Finished((*rows)[i], running.size());
        continue;
      }
      running[pid] = i;
    }
    if (running.empty()) break;
    // a stop reaches the runs too (a Ctrl-C on the terminal does by itself): each ends after
    // its cycle and reports itself interrupted, so a rerun redoes it
    if (Stopped(options) && !signalled) {
      for (const auto& [pid, i] : running) kill(pid, SIGTERM);
      signalled = true;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("sweep: waiting for a run: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const size_t i = it->second;
    running.erase(it);
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    (*rows)[i] = ReadRow((*rows)[i].run, options.out_dir + "/runs/" + (*rows)[i].run.name,
                         options.perceive, code);
    progress.Finished((*rows)[i], running.size());
  }
  return !Stopped(options);
}

}  // namespace

std::vector<SweepRun> PlanSweep(const SweepOptions& options) {
  std::map<std::string, std::string> files;  // stem -> file
  for (const auto& argument : options.scenarios) {
    for (const auto& file : Expand(argument)) {
      const std::string stem = fs::path(file).stem().string();
      const auto [it, added] = files.emplace(stem, file);
      if (!added && fs::weakly_canonical(it->second) != fs::weakly_canonical(file)) {
        throw InputError("scenarios '" + it->second + "' and '" + file +
                         "': the same file name, so their runs would share a folder");
      }
    }
  }
  // the grid of parameter overrides: every combination of one value per --set
  std::vector<std::vector<std::string>> grid = {{}};
  std::set<std::string> keys;
  for (const auto& set : options.sets) {
    const size_t equals = set.find('=');
    const std::string key = set.substr(0, equals);
    if (equals == std::string::npos || key.empty() ||
        key.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_.") != std::string::npos) {
      throw InputError("--set '" + set + "': expected section.key=value[,value...]");
    }
    if (!keys.insert(key).second) throw InputError("--set '" + set + "': " + key + " set twice");
    std::vector<std::string> values;
    const std::string list = set.substr(equals + 1);
    for (size_t begin = 0;;) {
      const size_t comma = list.find(',', begin);
      const std::string value = list.substr(begin, comma - begin);
      if (value.empty() || value.find_first_of("/ \t\n") != std::string::npos) {
        throw InputError("--set '" + set + "': a value is empty or has a '/' or a space");
      }
      if (std::find(values.begin(), values.end(), value) != values.end()) {
        throw InputError("--set '" + set + "': " + value + " given twice");
      }
      // the key and each value as fognav run --set takes them: a bad one fails here, not in
      // every run
      ParamOverrides checked;
      ApplySetFlag(key + "=" + value, &checked);
      values.push_back(value);
      if (comma == std::string::npos) break;
      begin = comma + 1;
    }
    std::vector<std::vector<std::string>> wider;
    for (const auto& point : grid) {
      for (const auto& value : values) {
        wider.push_back(point);
        wider.back().push_back(key + "=" + value);
      }
    }
    grid = std::move(wider);
  }
  std::vector<int> seeds = {-1};  // the scenario's own
  if (options.seeds > 0) seeds.clear();
  for (int seed = 1; seed <= options.seeds; ++seed) seeds.push_back(seed);
  std::vector<SweepRun> runs;
  for (const auto& [stem, file] : files) {
    for (const int seed : seeds) {
      for (const auto& params : grid) {
        std::string name = stem + (seed > 0 ? "_s" + std::to_string(seed) : "");
        for (const auto& p : params) name += "_" + p;
        runs.push_back({name, file, seed, params});
      }
    }
  }
  std::sort(runs.begin(), runs.end(),
            [](const SweepRun& a, const SweepRun& b) { return a.name < b.name; });
  return runs;
}

std::vector<std::string> RunArguments(const SweepOptions& options, const SweepRun& run,
                                      const std::string& run_dir) {
  std::vector<std::string> arguments = {options.perceive ? "perceive" : "run", run.scenario,
                                        "--out", run_dir, "--quiet"};
  if (run.seed >= 0) arguments.insert(arguments.end(), {"--seed", std::to_string(run.seed)});
  for (const auto& p : run.params) arguments.insert(arguments.end(), {"--set", p});
  return arguments;
}

SweepRow ReadRow(const SweepRun& run, const std::string& run_dir, bool perceive, int exit_code) {
  SweepRow row;
  row.run = run;
  row.exit_code = exit_code;
  row.optimal_path_length = row.wall_time_s = row.traversability = kNaN;
  nlohmann::json report;
  std::ifstream in(run_dir + (perceive ? "/perception.json" : "/report.json"));
  if (in) report = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  const bool interrupted = String(report, "failure") == "interrupted";
  if (interrupted) {  // stopped with the sweep: to do again
    row.outcome = "not run";
    row.detail = "interrupted";
    return row;
  }
  // the page is the run's last file: a report without it is from a run killed just after it
  std::error_code error;
  if (!report.is_object() || !fs::exists(run_dir + "/report.html", error)) {
    row.outcome = exit_code < 0 ? "not run" : "error";
    if (exit_code >= 0) {
      const std::string last = FirstLine(run_dir + "/stderr.log");
      row.detail = "exit " + std::to_string(exit_code) + (last.empty() ? "" : ": " + last);
    }
    return row;
  }
  row.finished = true;
  const nlohmann::json fog = report.contains("fog") ? report["fog"] : nlohmann::json::object();
  row.traversability = Number(fog, "traversability");
  row.unsafe_cells = Integer(fog, "unsafe_cells");
  if (perceive) {
    const nlohmann::json seg =
        report.contains("segmentation") ? report["segmentation"] : nlohmann::json::object();
    row.exit_code = 0;
    row.outcome = "perceived";
    row.accuracy = Number(seg, "accuracy");
    row.coverage = Number(seg, "coverage");
    row.correct = Integer(seg, "correct");
    row.surfaces = Integer(seg, "truth_surfaces");
    row.fog_accuracy = Number(report, "fog_accuracy");
    row.fog_cells = Integer(report, "fog_observed_cells");
    return row;
  }
  const bool success = report.value("success", false);
  row.reached_goal = report.value("reached_goal", false);
  row.failure = String(report, "failure");
  row.detail = String(report, "failure_detail");
  row.exit_code = success ? 0 : 1;
  row.outcome = success                ? "success"
                : !row.failure.empty() ? row.failure
                : row.reached_goal     ? "unmet_expectation"
                                       : "goal_not_reached";
  row.cycles = Integer(report, "cycles");
  row.collisions = Integer(report, "collisions");
  row.spl = Number(report, "spl", 0);
  row.optimal_path_length = Number(report, "optimal_path_length");
  row.wall_time_s = Number(report, "wall_time_s");
  return row;
}

std::pair<double, double> Wilson(int successes, int n) {
  if (n == 0) return {0, 1};
  const double z = 1.959964, p = double(successes) / n;
  const double centre = (p + z * z / (2 * n)) / (1 + z * z / n);
  const double half = z * std::sqrt(p * (1 - p) / n + z * z / (4.0 * n * n)) / (1 + z * z / n);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

std::string FormatSummary(const std::vector<SweepRow>& rows, bool perceive) {
  int ran = 0, with_way = 0, successes = 0, reached = 0, collided = 0;
  std::vector<double> spl, traversability, unsafe, accuracy, coverage, fog_accuracy;
  std::vector<std::string> failures, no_way_ends;
  for (const auto& r : rows) {
    if (!Ran(r)) continue;
    ++ran;
    traversability.push_back(r.traversability);
    unsafe.push_back(r.unsafe_cells);
    accuracy.push_back(r.accuracy);
    coverage.push_back(r.coverage);
    fog_accuracy.push_back(r.fog_accuracy);
    collided += r.collisions > 0;
    if (!HasWay(r)) {
      no_way_ends.push_back(r.failure.empty() ? "reached_goal" : r.failure);
      continue;
    }
    ++with_way;
    successes += r.exit_code == 0;
    reached += r.reached_goal;
    spl.push_back(r.spl);
    if (r.exit_code != 0) failures.push_back(r.outcome);
  }
  const int errors = int(std::count_if(rows.begin(), rows.end(),
                                       [](const SweepRow& r) { return r.outcome == "error"; }));
  const int not_run = int(rows.size()) - ran - errors;
  std::ostringstream text;
  text << "sweep: " << rows.size() << " runs";
  if (errors > 0) text << ", " << errors << " could not run";
  if (not_run > 0) text << ", " << not_run << " not run";
  if (perceive) {
    text << "; " << ran << " perceived\n"
         << "  mean        segmentation accuracy " << Fixed(Mean(accuracy), 4) << ", coverage "
         << Fixed(Mean(coverage), 4) << ", FOG six-type accuracy " << Fixed(Mean(fog_accuracy), 4)
         << "\n";
  } else {
    const auto [lo, hi] = Wilson(successes, with_way);
    const double rate = with_way > 0 ? double(successes) / with_way : kNaN;
    text << "; " << with_way << " with a way on the ground truth\n"
         << "  success     " << successes << "/" << with_way << " = " << Percent(rate)
         << " (95 % interval " << Percent(lo) << " - " << Percent(hi) << "), reached the goal "
         << reached << "\n"
         << "  collisions  " << collided << " runs\n"
         << "  mean SPL    " << (spl.empty() ? "n/a" : Fixed(Mean(spl), 3)) << "\n"
         << "  failures    " << Classes(failures) << "\n"
         << "  no way      " << no_way_ends.size() << " runs, ended: " << Classes(no_way_ends)
         << "\n";
  }
  text << "  FOG         mean traversability " << (ran > 0 ? Fixed(Mean(traversability), 3) : "n/a")
       << ", mean unsafe cells " << (ran > 0 ? Fixed(Mean(unsafe), 1) : "n/a") << "\n";
  return text.str();
}

void WriteSweepFiles(const std::string& out_dir, const std::vector<SweepRow>& rows, bool perceive) {
  const auto& columns = Columns(perceive);
  std::string tsv;
  for (const auto& c : columns) tsv += std::string(tsv.empty() ? "" : "\t") + c.name;
  tsv += "\n";
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& r : rows) {
    std::string line;
    for (const auto& c : columns) line += (line.empty() ? "" : "\t") + Cell(c.value(r));
    tsv += line + "\n";
    runs.push_back(RowJson(r, perceive));
  }
  const std::string summary = FormatSummary(rows, perceive);
  const nlohmann::json results = {
      {"kind", perceive ? "perceive" : "mission"}, {"summary", summary}, {"runs", runs}};
  WriteFileAtomically(out_dir + "/results.tsv", tsv);
  WriteFileAtomically(out_dir + "/results.json", results.dump(2) + "\n");
  WriteFileAtomically(out_dir + "/junit.xml", JunitXml(rows));
  WriteFileAtomically(out_dir + "/index.html", IndexPage(out_dir, rows, summary, perceive));
}

std::map<std::string, std::string> ReadOutcomes(const std::string& old_dir) {
  const std::string path = old_dir + "/results.tsv";
  std::ifstream in(path);
  if (!in) throw InputError("--compare: cannot read " + path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::istringstream fields(line);
  for (std::string field; std::getline(fields, field, '\t');) header.push_back(field);
  const auto column = [&](const char* name) {
    return size_t(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const size_t name_at = column("name"), outcome_at = column("outcome");
  if (name_at >= header.size() || outcome_at >= header.size()) {
    throw InputError(path + ":1: expected a results.tsv header with the columns name and outcome");
  }
  std::map<std::string, std::string> old;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream split(line);
    for (std::string cell; std::getline(split, cell, '\t');) cells.push_back(cell);
    if (cells.size() > std::max(name_at, outcome_at)) old[cells[name_at]] = cells[outcome_at];
  }
  return old;
}

std::vector<std::string> CompareOutcomes(const std::vector<SweepRow>& rows,
                                         const std::map<std::string, std::string>& old) {
  std::vector<std::string> changes;
  for (const auto& r : rows) {
    const auto it = old.find(r.run.name);
    if (it != old.end() && it->second != r.outcome) {
      changes.push_back(r.run.name + ": " + it->second + " -> " + r.outcome);
    }
  }
  return changes;
}

int RunSweep(const SweepOptions& options) {
  if (options.perceive && options.seeds > 0) {
    throw InputError("--seeds: the start views (--perceive) have no noise for a seed to drive");
  }
  if (options.backend != "local" && options.backend != "slurm") {
    throw InputError("--backend: expected local or slurm, not '" + options.backend + "'");
  }
  for (const auto& [flag, value] :
       {std::pair<const char*, std::string>{"--partition", options.slurm.partition},
        {"--time", options.slurm.time},
        {"--mem", options.slurm.mem}}) {
    if (value.find_first_of(" \t\n\r'\"") != std::string::npos) {
      throw InputError(std::string(flag) + " '" + value +
                       "': expected a value without spaces or quotes");
    }
  }
  const std::vector<SweepRun> plan = PlanSweep(options);
  // the old results first: a bad --compare stops the sweep before it runs, and an old folder
  // that is the output folder too is read before it is written
  std::map<std::string, std::string> old;
  if (!options.compare_dir.empty()) old = ReadOutcomes(options.compare_dir);
  std::vector<SweepRow> rows;
  MakeOutputFolder(options.out_dir + "/runs");

  // finished runs are kept; the others are to do
  std::vector<size_t> todo;
  for (const auto& run : plan) {
    rows.push_back(ReadRow(run, options.out_dir + "/runs/" + run.name, options.perceive, -1));
    if (!rows.back().finished) todo.push_back(rows.size() - 1);
  }
  std::cerr << "sweep: " << plan.size() << " runs, " << plan.size() - todo.size()
            << " finished before, " << todo.size() << " to run (" << options.backend << ")\n";
  const bool complete = options.backend == "slurm" ? internal::RunSlurm(options, todo, &rows)
                                                   : RunLocal(options, todo, &rows);

  WriteSweepFiles(options.out_dir, rows, options.perceive);
  bool all_passed = true;
  for (const auto& r : rows) {
    if (r.finished && r.exit_code == 0) continue;
    all_passed = false;
    std::cout << "NOT PASSED " << r.run.name << ": " << r.outcome
              << (r.detail.empty() ? "" : " (" + r.detail + ")") << "\n";
  }
  std::cout << FormatSummary(rows, options.perceive);
  if (!options.compare_dir.empty()) {
    const auto changes = CompareOutcomes(rows, old);
    std::cout << "changed outcome: " << changes.size() << " runs\n";
    for (const auto& c : changes) std::cout << "  " << c << "\n";
  }
  std::cout << "results: " << options.out_dir << "/results.tsv, junit.xml, index.html\n";
  if (!complete) return 4;
  return all_passed ? 0 : 1;
}

}  // namespace fognav::scenarios

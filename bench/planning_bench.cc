// Planning on a 100x100 FOG like the paper's course (walls, an 8 and a 20 cm block, stairs of
// 3/6/3 cm, a 0.22 m gap, a table): A* over 16 headings and two postures.
#include <algorithm>
#include <chrono>
#include <vector>

#include <benchmark/benchmark.h>

#include "navigation/internal/test_worlds.h"
#include "navigation/planner.h"

namespace fognav::navigation {
namespace {

// the whole course from its start to the goal behind the table
void BM_PlanningCourse(benchmark::State& bench) {
  const internal::Course course = internal::PaperCourse();
  const PlannerParams params;
  int64_t expanded = 0;
  size_t poses = 0;
  for (auto _ : bench) {
    const PlanResult r = Plan(course.fog, course.start_G, course.goal_G, params);
    if (r.status != PlanStatus::kOk) bench.SkipWithError("no path on the course");
    expanded += r.expanded;
    poses = r.path.size();
    benchmark::DoNotOptimize(r.path.data());
  }
  bench.counters["expanded"] = double(expanded) / double(std::max<int64_t>(1, bench.iterations()));
  bench.counters["poses"] = double(poses);
}
BENCHMARK(BM_PlanningCourse)->Name("Planning/course")->Unit(benchmark::kMillisecond);

// re-planning as a mission does, from poses along the course (one per iteration, in turn), with
// the slowest single plan as a counter
void BM_PlanningCourseReplan(benchmark::State& bench) {
  const internal::Course course = internal::PaperCourse();
  const PlannerParams params;
  struct Start {
    perception::Pose2 pose;
    Posture posture;
  };
  const std::vector<Start> starts = {
      {{0.0, 0.0, 0.0}, Posture::kUpright},    {{0.3, 0.4, 0.8}, Posture::kUpright},
      {{0.8, 0.0, 0.0}, Posture::kUpright},    {{1.1, -0.3, 0.0}, Posture::kUpright},
      {{1.4, 0.2, 0.0}, Posture::kUpright},    {{1.9, 0.0, -0.5}, Posture::kUpright},
      {{2.05, 0.0, 1.57}, Posture::kUpright},  {{2.5, 0.0, 0.0}, Posture::kUpright},
      {{2.7, 0.0, 0.0}, Posture::kCrawling},   {{3.1, 0.0, 0.0}, Posture::kCrawling},
      {{0.0, 0.0, 3.14}, Posture::kUpright},   {{3.6, 0.3, 3.14}, Posture::kUpright},
  };
  // the last start plans back to the course start; every third query has its goal 2 m beyond
  // the window, as in a mission before the goal comes into view
  size_t k = 0, query = 0;
  double worst_ms = 0;
  for (auto _ : bench) {
    const Start& s = starts[k];
    Eigen::Vector2d goal = k + 1 == starts.size() ? Eigen::Vector2d(0.0, 0.0) : course.goal_G;
    if (query++ % 3 == 2 && k + 1 != starts.size()) goal = Eigen::Vector2d(5.9, 0.3);
    k = (k + 1) % starts.size();
    const auto t0 = std::chrono::steady_clock::now();
    const PlanResult r = Plan(course.fog, s.pose, goal, params, s.posture);
    const auto t1 = std::chrono::steady_clock::now();
    if (r.status != PlanStatus::kOk) bench.SkipWithError("no path from a course pose");
    worst_ms = std::max(worst_ms, std::chrono::duration<double, std::milli>(t1 - t0).count());
    benchmark::DoNotOptimize(r.path.data());
  }
  bench.counters["worst_ms"] = worst_ms;
}
BENCHMARK(BM_PlanningCourseReplan)->Name("Planning/course_replan")->Unit(benchmark::kMillisecond);

// the slowest kind of query: a goal that only the full search shows to be enclosed (a wall with
// an L-shaped slot too narrow to turn the corner in), so every reachable state is expanded
void BM_PlanningExhaustive(benchmark::State& bench) {
  using perception::CellType;
  perception::Fog fog = internal::FlatFog(100, 100, 0.04);
  internal::FillBox(&fog, 2.0, 0.0, 2.4, 4.0, CellType::kObstacle, 0.3f);
  internal::FillBox(&fog, 1.96, 1.0, 2.26, 1.16, CellType::kFloor, 0.0f);
  internal::FillBox(&fog, 2.1, 1.0, 2.26, 1.8, CellType::kFloor, 0.0f);
  internal::FillBox(&fog, 2.1, 1.64, 2.44, 1.8, CellType::kFloor, 0.0f);
  const PlannerParams params;
  int64_t expanded = 0;
  for (auto _ : bench) {
    const PlanResult r = Plan(fog, {0.5, 2.02, 0.0}, {3.2, 2.02}, params);
    if (r.reason != NoPathReason::kGoalEnclosed) bench.SkipWithError("expected an enclosed goal");
    expanded += r.expanded;
  }
  bench.counters["expanded"] = double(expanded) / double(std::max<int64_t>(1, bench.iterations()));
}
BENCHMARK(BM_PlanningExhaustive)->Name("Planning/exhaustive")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fognav::navigation

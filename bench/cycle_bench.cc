// Cycle/course: one perception-action cycle of the course mission (stairs_and_table.yaml)
// from the robot's pose at cycle 14 of its run (1.26, -0.06, heading along the course, before
// the stairs), with the maps of the look-around sweep there: render the pair, stereo,
// segmentation, mapping, the FOG and a plan to the goal.
#include <benchmark/benchmark.h>

#include "navigation/planner.h"
#include "scenarios/params.h"
#include "scenarios/perception_cycle.h"
#include "scenarios/views.h"
#include "sim/controller.h"

namespace fognav::scenarios {
namespace {

void BM_CycleCourse(benchmark::State& state) {
  const Scenario scenario = LoadScenario(FOGNAV_SOURCE_DIR "/scenarios/stairs_and_table.yaml");
  const RunParams run_params = ResolveParams(scenario.params);
  sim::World world(MakeWorldSpec(scenario));
  const mjModel* m = world.model();
  mjData* d = world.data();
  sim::Controller controller(m);
  const sim::Humanoid& humanoid = controller.humanoid();
  const sim::Pose2 at{1.26, -0.06, 0.0};
  controller.Reset(at, 0.0, m, d);
  sim::Renderer renderer(m);
  const perception::Pose2 robot_G{at.x, at.y, at.yaw};
  navigation::PlannerParams planner_params = run_params.planner;
  planner_params.goal_tolerance = 0.5 * scenario.goal_tolerance;
  planner_params.kneel_offset = controller.KneelOffset();
  const sim::ControllerParams controller_params;
  planner_params.max_step_length = controller_params.limits.max_climb_forward;
  planner_params.max_step_sideways = controller_params.limits.max_climb_sideways;

  // the recorded state: the maps of the look-around sweep at that pose, head looking ahead
  perception::MapState maps;
  auto perceive = [&]() {
    const Eigen::Isometry3d X_WL = sim::HeadCameraPoseInWorld(humanoid, d, sim::Eye::kLeft);
    const StereoView view = RenderStereo(&renderer, world, X_WL, scenario.sensor);
    return PerceiveView(run_params.perception, scenario.sensor.depth, view, humanoid, robot_G, 0.0,
                        sim::HeadCameraPose(humanoid, d, sim::Eye::kLeft),
                        sim::RobotBodyBoxes(humanoid, m, d), &maps);
  };
  for (const sim::HeadAngles& view : StartSweep()) {
    controller.MoveHead(view);
    controller.RunUntilIdle(m, d);
    perceive();
  }

  size_t path_poses = 0;
  for (auto _ : state) {
    const ViewResult view = perceive();
    const perception::Fog fog = perception::ComputeFog(run_params.perception.map, maps);
    const navigation::PlanResult plan =
        navigation::Plan(fog, robot_G, scenario.goal, planner_params);
    if (plan.status != navigation::PlanStatus::kOk) state.SkipWithError("no plan on the course");
    path_poses = plan.path.size();
    benchmark::DoNotOptimize(plan.path.data());
  }
  state.counters["poses"] = double(path_poses);
}
// real time, as StereoRender: llvmpipe renders on worker threads
BENCHMARK(BM_CycleCourse)->Name("Cycle/course")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace fognav::scenarios

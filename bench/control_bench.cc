// ControlTick: one tick of the stepping controller (IK + forward kinematics + contact check)
// while walking back and forth in a small world of floor, blocks, treads and a table.
#include <algorithm>
#include <chrono>
#include <vector>

#include <benchmark/benchmark.h>

#include "sim/controller.h"
#include "sim/model.h"

namespace {

const char* kWorld = R"(
<mujoco model="control_bench">
  <include file="humanoid.xml"/>
  <worldbody>
    <geom name="floor" type="plane" size="4 4 0.1"/>
    <geom name="block" type="box" pos="0.5 0.35 0.1" size="0.1 0.1 0.1"/>
    <geom name="tread_1" type="box" pos="1.2 0 0.015" size="0.125 0.5 0.015"/>
    <geom name="tread_2" type="box" pos="1.5 0 0.03" size="0.175 0.5 0.03"/>
    <geom name="desk_top" type="box" pos="-0.8 0 0.365" size="0.3 0.5 0.015"/>
    <geom name="desk_leg" type="box" pos="-0.5 0.47 0.175" size="0.02 0.02 0.175"/>
  </worldbody>
</mujoco>)";

void BM_ControlTick(benchmark::State& state) {
  auto m = fognav::sim::LoadModelFromXml(kWorld);
  auto d = fognav::sim::MakeData(m.get());
  fognav::sim::Controller controller(m.get());
  controller.Reset({0, 0, 0}, 0.0, m.get(), d.get());
  std::vector<double> tick_us;
  tick_us.reserve(1 << 16);
  bool forward = true;
  for (auto _ : state) {
    if (controller.Idle()) {
      controller.Walk(forward ? 0.4 : -0.4, 0, forward ? 0.3 : -0.3);
      forward = !forward;
    }
    const auto t0 = std::chrono::steady_clock::now();
    controller.Tick(m.get(), d.get());
    const auto t1 = std::chrono::steady_clock::now();
    if (tick_us.size() < tick_us.capacity()) {
      tick_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
  }
  if (!tick_us.empty()) {
    std::nth_element(tick_us.begin(), tick_us.begin() + tick_us.size() / 2, tick_us.end());
    state.counters["median_us"] = tick_us[tick_us.size() / 2];
  }
}
BENCHMARK(BM_ControlTick)->Name("ControlTick")->Unit(benchmark::kMicrosecond);

}  // namespace

#!/usr/bin/env python3
"""What calling fognav from Python costs, measured beside the C++ programs in the same run.

1. A whole mission: `fognav run SCENARIO` (the process) against a fresh python3 process that
   imports fognav and calls fognav.run(), and in this process (warm) fognav.run() and a Mission
   stepped with the built-in decisions (Mission.step): wall and CPU time of each, and the
   report's wall_time_s (the mission itself, from the robot's start to the report).
2. Plane segmentation of a 640 x 480 point image: fognav.perception.segment() on the scene of
   fognav_bench's Segmentation/640x480 (ray-cast here the same way: staircase, low box, wall,
   2 mm depth noise at 1 m) against that benchmark.

Rounds alternate the two sides so that a slow neighbour on the machine hits both; medians are
printed with their ratio. Pin it to one core as the benchmarks are: `taskset -c 1 python3
scripts/python_bench.py` (PYTHONPATH=build/python).
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def bench_points(w, h, seed=1):
    """The point image of fognav_bench's segmentation scenes (BenchScene, BenchCamera)."""
    f = 0.5 * w / np.tan(np.radians(22.5))
    cx, cy = 0.5 * (w - 1), 0.5 * (h - 1)
    pitch = np.radians(25)
    z_c = np.array([np.cos(pitch), 0, -np.sin(pitch)])
    x_c = np.array([0.0, -1.0, 0.0])
    R = np.column_stack([x_c, np.cross(z_c, x_c), z_c])
    o = np.array([0.0, -0.1, 0.55])
    boxes = [((1.0 + 0.25 * i, -0.6, 0), (1.75, 0.6, 0.03 * (i + 1))) for i in range(3)]
    boxes += [((0.6, 0.25, 0), (0.8, 0.45, 0.08)), ((2.6, -3, 0), (2.8, 3, 2))]
    u, v = np.meshgrid(np.arange(w), np.arange(h))
    ray = np.stack([(u - cx) / f, (v - cy) / f, np.ones((h, w))], axis=-1)
    d = ray @ R.T
    with np.errstate(divide="ignore", invalid="ignore"):
        best = np.where(d[..., 2] < 0, -o[2] / d[..., 2], np.inf)
        for lo, hi in boxes:
            t0 = np.full((h, w), -np.inf)
            t1 = np.full((h, w), np.inf)
            for a in range(3):
                ta = (lo[a] - o[a]) / d[..., a]
                tb = (hi[a] - o[a]) / d[..., a]
                t0 = np.maximum(t0, np.minimum(ta, tb))
                t1 = np.minimum(t1, np.maximum(ta, tb))
            hit = (t0 <= t1) & (t0 > 0) & (t0 < best)
            best[hit] = t0[hit]
    depth = np.where(np.isfinite(best), best, np.nan)
    rng = np.random.default_rng(seed)
    depth = depth + 0.002 * depth * depth * rng.standard_normal(depth.shape)
    return (ray * depth[..., None]).astype(np.float32)


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def mission_rounds(fognav, binary, scenario, rounds):
    """Per way of running: wall times and CPU times (all threads) of the whole call, and the
    mission's own wall time as its report gives it (from the robot's start to the report)."""
    names = ["fognav run (process)", "python3 process", "fognav.run()", "Mission.step() loop"]
    wall = {k: [] for k in names}
    cpu = {k: [] for k in names}
    loop = {k: [] for k in names}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(rounds):
            start, start_cpu = time.perf_counter(), children_cpu()
            subprocess.run([binary, "run", scenario, "--out", f"{tmp}/binary", "--quiet"],
                           check=False, capture_output=True)
            wall[names[0]].append(time.perf_counter() - start)
            cpu[names[0]].append(children_cpu() - start_cpu)
            with open(f"{tmp}/binary/report.json") as f:
                loop[names[0]].append(json.load(f)["wall_time_s"])

            # a fresh interpreter that imports fognav and runs the mission, as a script would
            start, start_cpu = time.perf_counter(), children_cpu()
            subprocess.run([sys.executable, "-c", "import sys, fognav; "
                            "fognav.run(sys.argv[1], out=sys.argv[2])", scenario,
                            f"{tmp}/process"], check=True, capture_output=True,
                           env=dict(os.environ, PYTHONPATH=os.path.dirname(fognav.__path__[0])))
            wall[names[1]].append(time.perf_counter() - start)
            cpu[names[1]].append(children_cpu() - start_cpu)
            with open(f"{tmp}/process/report.json") as f:
                loop[names[1]].append(json.load(f)["wall_time_s"])

            # in this process, warm (the module imported, earlier missions run)
            start, start_cpu = time.perf_counter(), time.process_time()
            report = fognav.run(scenario, out=f"{tmp}/python")
            wall[names[2]].append(time.perf_counter() - start)
            cpu[names[2]].append(time.process_time() - start_cpu)
            loop[names[2]].append(report["wall_time_s"])

            start, start_cpu = time.perf_counter(), time.process_time()
            m = fognav.Mission(scenario, out=f"{tmp}/step")
            while m.step():
                pass
            report = m.report()
            del m
            wall[names[3]].append(time.perf_counter() - start)
            cpu[names[3]].append(time.process_time() - start_cpu)
            loop[names[3]].append(report["wall_time_s"])
            print(f"  round {r + 1}: " + ", ".join(f"{k} {wall[k][-1]:.3f} s" for k in names),
                  file=sys.stderr)
    return wall, cpu, loop


def segment_rounds(fognav, bench, rounds, reps):
    points = bench_points(640, 480)
    labels, planes = fognav.perception.segment(points)
    python_ms, bench_ms = [], []
    for _ in range(rounds):
        samples = []
        for _ in range(reps):  # CPU time of this thread, as the benchmark's cpu_time
            start = time.thread_time()
            fognav.perception.segment(points)
            samples.append(1000 * (time.thread_time() - start))
        python_ms.append(statistics.median(samples))
        out = subprocess.run([bench, "--benchmark_filter=^Segmentation/640x480/",
                              "--benchmark_format=json", f"--benchmark_repetitions={3}",
                              "--benchmark_report_aggregates_only=true"],
                             check=True, capture_output=True, text=True)
        rows = json.loads(out.stdout)["benchmarks"]
        median = next(b for b in rows if b.get("aggregate_name") == "median")
        bench_ms.append(median["cpu_time"])
        bench_planes = median.get("planes")
    return python_ms, bench_ms, len(planes["rms"]), bench_planes


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--scenario", default=os.path.join(ROOT, "scenarios", "narrow_gap.yaml"))
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--skip-mission", action="store_true")
    parser.add_argument("--skip-segment", action="store_true")
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.build, "python"))
    import fognav

    print(f"machine: {os.cpu_count()} cores visible, affinity {sorted(os.sched_getaffinity(0))}")
    if not args.skip_mission:
        wall, cpu, loop = mission_rounds(fognav, os.path.join(args.build, "bin", "fognav"),
                                   args.scenario, args.rounds)
        base_wall = statistics.median(wall["fognav run (process)"])
        base_cpu = statistics.median(cpu["fognav run (process)"])
        base_loop = statistics.median(loop["fognav run (process)"])
        print(f"mission {os.path.basename(args.scenario)}, median of {args.rounds} rounds:")
        for k in wall:
            w, c, m = (statistics.median(x[k]) for x in (wall, cpu, loop))
            print(f"  {k:22s} wall {w:7.3f} s ({100 * (w / base_wall - 1):+5.1f} %)   "
                  f"CPU {c:7.3f} s ({100 * (c / base_cpu - 1):+5.1f} %)   "
                  f"report wall_time_s {m:7.3f} s ({100 * (m / base_loop - 1):+5.1f} %)")
    if not args.skip_segment:
        python_ms, bench_ms, planes, bench_planes = segment_rounds(
            fognav, os.path.join(args.build, "bin", "fognav_bench"), args.rounds, 20)
        p, b = statistics.median(python_ms), statistics.median(bench_ms)
        print(f"segment 640x480 (CPU time), median of {args.rounds} rounds: perception.segment() "
              f"{p:.2f} ms "
              f"({planes} planes), fognav_bench Segmentation/640x480 {b:.2f} ms "
              f"({bench_planes:.0f} planes): {100 * (p / b - 1):+.1f} %")


if __name__ == "__main__":
    main()

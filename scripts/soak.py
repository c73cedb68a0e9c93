#!/usr/bin/env python3
"""Soak: runs one long mission toward a goal it cannot reach and prints the resident size of the
fognav process as the cycles go by (cycles.csv reaches the disk every cycle, so its rows count
them). The robot winds through a slalom of dividers 0.7 m apart along a 30 m corridor toward a
goal walled in at its far end: a mission that gives up on an unreachable goal only after it has
looked for a way, and this one is still looking at cycle 1000.

Usage: scripts/soak.py [--fognav build/bin/fognav] [--cycles 1000] [--out out/soak]
                       [--width 2.0] [--step 0.7] [--gap 0.5]
Prints the resident size every 100 cycles and the growth from cycle 100 to the last; exits 1 if
it grew more than 5% or the mission ended before the last cycle, 0 otherwise.
"""
import argparse
import os
import subprocess
import sys
import time

def scenario(cycles, width, step, gap):
    """A corridor 30 m long and `width` wide: a slalom of dividers `step` apart, each leaving a
    `gap` at alternate sides, then a goal walled in at its far end."""
    objects = []
    x, i = -13.0, 0
    while x < 12.0:
        side = -1 if i % 2 == 0 else 1
        objects.append("    - box: {name: divider_%d, center: [%.2f, %.2f], size: [0.1, %.2f, 0.6]}"
                       % (i, x, side * gap / 2, width - gap))
        x += step
        i += 1
    objects += [
        "    - box: {name: pen_front, center: [13.2, 0.0], size: [0.1, 1.0, 0.6]}",
        "    - box: {name: pen_back, center: [14.4, 0.0], size: [0.1, 1.0, 0.6]}",
        "    - box: {name: pen_left, center: [13.8, 0.45], size: [1.1, 0.1, 0.6]}",
        "    - box: {name: pen_right, center: [13.8, -0.45], size: [1.1, 0.1, 0.6]}"]
    return """name: soak
description: A slalom of dividers along a 30 m corridor to a goal walled in, for scripts/soak.py.
robot: {start: [-14.2, 0.0, 0.0]}
goal: {position: [13.8, 0.0], tolerance: 0.2}
world:
  floor: [30.0, %.2f]
  objects:
%s
limits: {max_cycles: %d, max_steps: 1000000}
""" % (width, "\n".join(objects), cycles)


def resident_kib(pid):
    """VmRSS of a process in KiB, or None once it has gone."""
    try:
        with open("/proc/%d/status" % pid) as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def cycles_logged(path):
    """Cycles in cycles.csv so far (its rows but the header)."""
    try:
        with open(path, "rb") as log:
            return max(0, log.read().count(b"\n") - 1)
    except OSError:
        return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fognav", default="build/bin/fognav")
    parser.add_argument("--cycles", type=int, default=1000)
    parser.add_argument("--out", default="out/soak")
    parser.add_argument("--width", type=float, default=2.0, help="corridor width, metres")
    parser.add_argument("--step", type=float, default=0.7, help="between dividers, metres")
    parser.add_argument("--gap", type=float, default=0.5, help="beside each divider, metres")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "soak.yaml")
    with open(path, "w") as f:
        # a few cycles past the last measured, so that the end of the mission (the ground-truth
        # maps and plan, the pictures) is not measured as its last cycle
        f.write(scenario(args.cycles + 10, args.width, args.step, args.gap))
    log = os.path.join(args.out, "cycles.csv")
    if os.path.exists(log):
        os.remove(log)

    start = time.time()
    process = subprocess.Popen([args.fognav, "run", path, "--out", args.out, "--quiet"])
    marks = list(range(100, args.cycles + 1, 100))
    resident = {}  # cycle -> KiB, read as soon as that cycle's row is on the disk
    while process.poll() is None and marks:
        cycles = cycles_logged(log)
        if cycles >= marks[0]:
            kib = resident_kib(process.pid)
            if kib is not None:
                resident[marks[0]] = kib
                print("cycle %4d (logged %4d): resident %.1f MB, %.0f s"
                      % (marks[0], cycles, kib / 1024, time.time() - start), flush=True)
            marks.pop(0)
        time.sleep(0.02)
    process.wait()
    if 100 not in resident or args.cycles not in resident:
        print("soak: the mission ended after %d cycles, before cycle %d"
              % (cycles_logged(log), args.cycles))
        return 1
    growth = resident[args.cycles] / resident[100] - 1
    print("soak: resident %.1f MB at cycle 100, %.1f MB at cycle %d: %+.1f%% (bound 5%%)"
          % (resident[100] / 1024, resident[args.cycles] / 1024, args.cycles, 100 * growth))
    return 0 if growth <= 0.05 else 1


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Writes variations of the stairs-and-table course as fognav scenario files.

Usage: scripts/course_worlds.py OUT_DIR [--count N] [--seed S] [--prefix NAME]

Each world is a walled corridor (scenarios/stairs_and_table.yaml) holding the course's four
sections in a random order, 0.35-0.5 m apart (0.6-0.7 m after the table, where the robot needs
room to stand up), each with random sizes within the paper's limits:
  blocks  an 8 cm and a 20 cm block to walk round, on either side of a passage of 0.34-0.45 m;
  stairs  1 or 2 treads up (risers of 2-4.5 cm) and the same treads down, across the corridor;
  gap     two 20 cm blocks from the walls, 0.20-0.26 m apart (narrower than the shoulders, so
          the robot side-steps through), in half the worlds with an 8 cm block before one;
  table   across the corridor, its top's upper face 0.56-0.64 m high (above the eyes, about
          0.52 m) and its underside at most 0.56 m (below the head, so the robot crawls).
The whole course (walls, objects, start and goal) is turned about the start by a random angle
and shifted by a random part of a 4 cm map cell; about half the worlds have footstep odometry
noise as in scenarios/noisy_odometry.yaml. The same seed gives the same files. Only the
standard library is used.
"""
import argparse
import math
import os
import random
import sys

from random_worlds import WALL_H, WALL_T, flow, lst

SECTIONS = ("blocks", "stairs", "gap", "table")
# per step as scenarios/noisy_odometry.yaml, and a systematic part drawn once per mission
NOISE = {"xy": 0.005, "yaw_deg": 0.5, "stride_scale": 0.03, "yaw_bias_deg": 0.2}
HEAD_TOP = 0.56  # highest underside of a table top: below the standing head (0.58 m)
MAX_RISE = 0.045  # highest riser: below the paper's 5 cm, which the planner's h_stairs meets exactly


def r2(v):
    return round(v, 2)


def q(v):
    """v on a 2 mm grid, so that boxes between two such edges have 1 mm centres."""
    return round(round(v / 0.002) * 0.002, 3)


class Course:
    """One corridor in the course frame: start at the origin facing +x, y to the left."""

    def __init__(self, rng, name):
        self.rng = rng
        self.name = name
        self.half = q(rng.uniform(0.58, 0.7))  # inner half width of the corridor
        self.order = list(SECTIONS)
        rng.shuffle(self.order)
        self.objects = []
        x = r2(rng.uniform(0.55, 0.7))
        for i, section in enumerate(self.order):
            if i:  # a robot crawling out from under a table stands up only 0.6 m past it
                after_table = self.order[i - 1] == "table"
                x = r2(x + rng.uniform(*(0.6, 0.7) if after_table else (0.35, 0.5)))
            x = getattr(self, "add_" + section)(x)
        self.goal = (r2(x + rng.uniform(0.4, 0.5)), r2(rng.uniform(-0.2, 0.2)))
        self.noise = rng.random() < 0.5
        self.turn = (round(rng.uniform(-180, 180), 1), round(rng.uniform(0, 0.04), 3),
                     round(rng.uniform(0, 0.04), 3))

    def box(self, name, x, y, sx, sy, h):
        self.objects.append(("box", {"name": name, "center": [r2(x), round(y, 3)],
                                     "size": [r2(sx), round(sy, 3), h]}))

    def add_blocks(self, x0):
        """A low and a tall block on either side of a passage; returns the section's end."""
        rng = self.rng
        side = rng.choice([1, -1])
        passage, centre = rng.uniform(0.34, 0.45), rng.uniform(-0.1, 0.1)
        ends = []
        for name, h, s, dx in (("low_block", 0.08, side, 0.0),
                               ("tall_block", 0.2, -side, rng.uniform(0.0, 0.15))):
            sx, sy = r2(rng.uniform(0.15, 0.25)), r2(rng.uniform(0.15, 0.25))
            y = centre + s * (passage / 2 + sy / 2)
            self.box(name, x0 + dx + sx / 2, r2(y), sx, sy, h)
            ends.append(x0 + dx + sx)
        return r2(max(ends))

    def add_stairs(self, x0):
        rng = self.rng
        heights, h = [], 0.0
        for _ in range(rng.randint(1, 2)):
            h += round(rng.uniform(0.02, MAX_RISE), 3)
            heights.append(round(h, 3))
        heights += heights[-2::-1]  # down again by the same treads
        depths = [r2(rng.uniform(0.25, 0.35)) for _ in heights]
        self.objects.append(("stairs", {"name": "steps", "start": [x0, 0.0],
                                        "width": r2(2 * self.half),
                                        "steps": [[d, t] for d, t in zip(depths, heights)]}))
        return r2(x0 + sum(depths))

    def add_gap(self, x0):
        """Two 20 cm blocks from the walls with a gap narrower than the shoulders."""
        rng = self.rng
        gap, gy = q(rng.uniform(0.2, 0.26)), q(rng.uniform(-0.2, 0.2))
        if rng.random() < 0.5:  # an 8 cm block before one of the two
            s = rng.choice([1, -1])
            y = gy + s * (gap / 2 + rng.uniform(0.15, 0.25))
            y = max(-self.half + 0.12, min(self.half - 0.12, y))
            self.box("gap_low", x0 + 0.075, r2(y), 0.15, 0.2, 0.08)
            x0 = r2(x0 + 0.3)
        left0, right1 = q(gy + gap / 2), q(gy - gap / 2)
        self.box("gap_left", x0 + 0.1, (left0 + self.half) / 2, 0.2, self.half - left0, 0.2)
        self.box("gap_right", x0 + 0.1, (right1 - self.half) / 2, 0.2, right1 + self.half, 0.2)
        return r2(x0 + 0.2)

    def add_table(self, x0):
        """A table across the corridor whose top lies above the eyes and below the head."""
        rng = self.rng
        sx, height = r2(rng.uniform(0.5, 0.7)), r2(rng.uniform(0.56, 0.64))
        top = r2(max(rng.uniform(0.03, 0.05), height - HEAD_TOP))
        self.objects.append(("table", {"name": "desk", "center": [r2(x0 + sx / 2), 0.0],
                                       "size": [sx, r2(2 * self.half - 0.04)],
                                       "height": height, "top": top, "leg": 0.04}))
        return r2(x0 + sx)

    def ends(self):
        """The back and front walls' centres along x: 0.5 m behind the start and the goal."""
        return -0.5, self.goal[0] + 0.5

    def walls(self):
        back, front = self.ends()
        length, cx, y = front - back + 2 * WALL_T, (back + front) / 2, self.half + WALL_T / 2
        inner = 2 * self.half
        return [("box", {"name": n, "center": [r2(x), r2(wy)],
                         "size": [round(sx, 3), round(sy, 3), WALL_H]})
                for n, x, wy, sx, sy in (("wall_left", cx, y, length, WALL_T),
                                         ("wall_right", cx, -y, length, WALL_T),
                                         ("wall_back", back, 0.0, WALL_T, inner),
                                         ("wall_front", front, 0.0, WALL_T, inner))]

    def yaml(self, seed):
        deg, dx, dy = self.turn
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))

        def at(p):
            return [round(c * p[0] - s * p[1] + dx, 3), round(s * p[0] + c * p[1] + dy, 3)]

        objects = []
        for kind, spec in self.walls() + self.objects:
            key = "start" if kind == "stairs" else "center"
            objects.append((kind, dict(spec, **{key: at(spec[key]), "yaw": deg})))
        back, front = self.ends()
        length, width = front - back + 2 * WALL_T, 2 * self.half + 4 * WALL_T
        floor = [round(abs(c) * length + abs(s) * width, 3),
                 round(abs(s) * length + abs(c) * width, 3)]
        order = ", ".join(self.order)
        lines = [f"name: {self.name}",
                 f"description: The course's sections in the order {order}, turned by {deg}"
                 " degrees (scripts/course_worlds.py).",
                 f"seed: {seed}",
                 f"robot: {{start: {lst(at((0.0, 0.0)) + [deg])}}}",
                 f"goal: {{position: {lst(at(self.goal))}, tolerance: 0.2}}",
                 "world:",
                 f"  floor: {lst(floor)}",
                 f"  floor_center: {lst(at(((back + front) / 2, 0.0)))}",
                 "  objects:"]
        lines += [f"    - {kind}: {flow(spec)}" for kind, spec in objects]
        if self.noise:
            lines.append(f"odometry_noise: {flow(NOISE)}")
        lines.append("limits: {max_cycles: 600, max_steps: 2000}")
        lines.append("expect: {reach_goal: true, no_collision: true}")
        return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    parser.add_argument("--count", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--prefix", default="course", help="scenario names: PREFIX_000, ...")
    args = parser.parse_args()
    if args.count < 1:
        sys.exit("course_worlds: --count must be at least 1")
    os.makedirs(args.out_dir, exist_ok=True)
    for i in range(args.count):
        course = Course(random.Random(args.seed * 100003 + i), f"{args.prefix}_{i:03d}")
        with open(os.path.join(args.out_dir, course.name + ".yaml"), "w") as f:
            f.write(course.yaml(args.seed * 1000 + i))
    print(f"course_worlds: {args.count} courses in {args.out_dir}")


if __name__ == "__main__":
    main()

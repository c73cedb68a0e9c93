#!/usr/bin/env python3
"""Writes random walled rooms as fognav scenario files, for robustness sweeps.

Usage: scripts/random_worlds.py OUT_DIR [--count N] [--seed S] [--variants] [--dense]
                              [--turn] [--open] [--prefix NAME]

Each room is walled (0.3 m walls), the robot starts at its west end and the goal lies near its
east end. Between them stand a few of: blocks (low enough to step round or high, some turned),
flights of treads up and down, tables (high enough to crawl under, or too low), and dividers
across the room with an opening. Objects keep 0.3 m from each other, from the walls and from
the start and goal, so a way usually exists; `fognav run` reports `optimal_path_length` 0 where
the planner finds none on the ground-truth map, and `fognav sweep` counts such rooms apart.
With --variants every other room also gets a wider camera (55-60 degrees, 320x240), odometry
noise or a start turned away from the goal. With --turn each room (the same rooms as without
it) is turned as a whole by a random angle about the origin and shifted by a random part of a
4 cm map cell, so that its walls and objects lie at angles to the map's cells and cross them
anywhere; the floor grows to the turned floor's bounding box. With --open the rooms (the same
rooms) have no walls: the floor ends where they stood, with nothing beyond, and dividers end at
its edges. Only the standard library is used.
"""
import argparse
import math
import os
import random
import sys

WALL_H = 0.3
WALL_T = 0.1
CLEAR = 0.3  # free margin round every object (--dense: 0.18)


def fmt(v):
    if isinstance(v, float):
        text = f"{v:.3f}".rstrip("0").rstrip(".")
        return "0" if text == "-0" else text
    return str(v)


def flow(d):
    return "{" + ", ".join(f"{k}: {flow(v) if isinstance(v, dict) else lst(v)}"
                           for k, v in d.items()) + "}"


def lst(v):
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(lst(x) for x in v) + "]"
    return fmt(v)


class Room:
    def __init__(self, rng, name, index, variants, dense):
        self.rng = rng
        self.clear = 0.18 if dense else CLEAR
        self.dense = dense
        self.name = name
        self.length = round(rng.uniform(3.4, 5.4), 2)
        self.width = round(rng.uniform(1.6, 3.0), 2)
        self.cx = self.length / 2 - 0.5
        half_w = self.width / 2
        self.start = (0.0, round(rng.uniform(-half_w + 0.5, half_w - 0.5), 2), 0.0)
        self.goal = (round(self.length - 1.0, 2),
                     round(rng.uniform(-half_w + 0.5, half_w - 0.5), 2))
        self.objects = []
        self.boxes = []  # footprints (x0, y0, x1, y1) taken
        self.sensor = None
        self.noise = None
        self.fill()
        if variants and index % 2 == 1:
            self.vary()

    def free(self, x0, y0, x1, y1):
        half_w, c = self.width / 2, self.clear
        if y0 < -half_w + WALL_T + c or y1 > half_w - WALL_T - c:
            return False
        if x0 < 0.5 or x1 > self.length - 0.5 - WALL_T - c:
            return False
        for px, py in (self.start[:2], self.goal):
            if x0 - 0.5 < px < x1 + 0.5 and y0 - 0.5 < py < y1 + 0.5:
                return False
        return all(self.apart((x0, y0, x1, y1), box) for box in self.boxes)

    def apart(self, fp, box, across=True):
        """Whether footprints fp and box are self.clear apart along x (or, if across, y)."""
        (x0, y0, x1, y1), (a0, b0, a1, b1), c = fp, box, self.clear
        return x1 + c <= a0 or a1 + c <= x0 or (across and (y1 + c <= b0 or b1 + c <= y0))

    def place(self, sx, sy, tries=40):
        half_w = self.width / 2
        for _ in range(tries):
            x = self.rng.uniform(0.5 + sx / 2, self.length - 1.0 - sx / 2)
            y = self.rng.uniform(-half_w + sy / 2, half_w - sy / 2)
            fp = (x - sx / 2, y - sy / 2, x + sx / 2, y + sy / 2)
            if self.free(*fp):
                self.boxes.append(fp)
                return round(x, 2), round(y, 2)
        return None

    def fill(self):
        rng = self.rng
        kinds = ["block", "block", "stairs", "table", "divider"]
        for i in range(rng.randint(3, 7) if self.dense else rng.randint(2, 5)):
            kind = rng.choice(kinds)
            getattr(self, "add_" + kind)(f"{kind}_{i}")

    def add_block(self, name):
        rng = self.rng
        sx, sy = round(rng.uniform(0.15, 0.6), 2), round(rng.uniform(0.15, 0.6), 2)
        yaw = rng.choice([0, 0, 0, rng.randint(10, 80)])
        span = max(sx, sy) * 1.42 if yaw else None
        at = self.place(span or sx, span or sy)
        if at:
            h = round(rng.choice([rng.uniform(0.06, 0.12), rng.uniform(0.15, 0.4)]), 2)
            obj = {"name": name, "center": list(at), "size": [sx, sy, h]}
            if yaw:
                obj["yaw"] = yaw
            self.objects.append({"box": obj})

    def add_stairs(self, name):
        rng = self.rng
        n_up = rng.randint(1, 3)
        rises = [round(rng.uniform(0.02, 0.05), 2) for _ in range(n_up)]
        heights, h = [], 0.0
        for r in rises:
            h += r
            heights.append(round(h, 2))
        heights += heights[-2::-1]  # down again, the same treads
        depths = [round(rng.uniform(0.25, 0.4), 2) for _ in heights]
        width = round(rng.uniform(0.8, min(1.6, self.width - 2 * WALL_T)), 2)
        at = self.place(sum(depths), width)
        if at:
            start = [round(at[0] - sum(depths) / 2, 2), at[1]]
            self.objects.append({"stairs": {"name": name, "start": start, "width": width,
                                            "steps": [[d, h] for d, h in zip(depths, heights)]}})

    def add_table(self, name):
        rng = self.rng
        sx, sy = round(rng.uniform(0.4, 0.7), 2), round(rng.uniform(0.5, 1.2), 2)
        at = self.place(sx, sy)
        if at:
            height = round(rng.choice([rng.uniform(0.36, 0.6), rng.uniform(0.2, 0.3)]), 2)
            self.objects.append({"table": {"name": name, "center": list(at), "size": [sx, sy],
                                           "height": height, "top": 0.03, "leg": 0.04}})

    def add_divider(self, name):
        rng = self.rng
        half_w = self.width / 2 - WALL_T / 2
        x = round(rng.uniform(1.0, self.length - 1.6), 2)
        gap = round(rng.uniform(0.25, 0.5) if self.dense else rng.uniform(0.3, 0.7), 2)
        gy = round(rng.uniform(-half_w + gap / 2 + 0.2, half_w - gap / 2 - 0.2), 2)
        fp = (x - WALL_T / 2, -half_w, x + WALL_T / 2, half_w)
        if not all(self.apart(fp, box, across=False) for box in self.boxes):
            return
        self.boxes.append(fp)
        for side, y0, y1 in (("s", -half_w, gy - gap / 2), ("n", gy + gap / 2, half_w)):
            if y1 - y0 > 0.02:
                self.objects.append({"box": {"name": f"{name}_{side}",
                                             "center": [x, round((y0 + y1) / 2, 3)],
                                             "size": [WALL_T, round(y1 - y0, 3), WALL_H]}})

    def vary(self):
        rng = self.rng
        choice = rng.randrange(3)
        if choice == 0:
            self.sensor = {"width": 320, "height": 240, "hfov_deg": rng.choice([55, 60])}
        elif choice == 1:
            self.noise = {"xy": 0.005, "yaw_deg": 0.5, "stride_scale": 0.03, "yaw_bias_deg": 0.2}
        else:
            self.start = (self.start[0], self.start[1], rng.choice([-120, -90, 90, 150]))

    def yaml(self, seed, turn=None, open_floor=False):
        L, W, cx = self.length, self.width, self.cx
        walls = [{"box": {"name": name, "center": [round(x, 3), round(y, 3)],
                          "size": [round(sx, 3), round(sy, 3), WALL_H]}}
                 for name, x, y, sx, sy in (
                     ("wall_n", cx, W / 2 - WALL_T / 2, L, WALL_T),
                     ("wall_s", cx, -W / 2 + WALL_T / 2, L, WALL_T),
                     ("wall_w", cx - L / 2 + WALL_T / 2, 0.0, WALL_T, W - 2 * WALL_T),
                     ("wall_e", cx + L / 2 - WALL_T / 2, 0.0, WALL_T, W - 2 * WALL_T))]
        if open_floor:
            walls = []
        start, goal, objects = self.start, self.goal, walls + self.objects
        floor, floor_center = [L, W], [cx, 0.0]
        if turn:  # everything turned by turn = (degrees, dx, dy) about the origin, then shifted
            deg, dx, dy = turn
            c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))

            def at(p):
                return [round(c * p[0] - s * p[1] + dx, 3), round(s * p[0] + c * p[1] + dy, 3)]

            def yaw(a):
                return round((a + deg + 180) % 360 - 180, 2)

            start = tuple(at(start[:2])) + (yaw(start[2]),)
            goal = tuple(at(goal))
            turned = []
            for obj in objects:
                (kind, spec), = obj.items()
                key = "start" if kind == "stairs" else "center"
                turned.append({kind: dict(spec, **{key: at(spec[key]),
                                                   "yaw": yaw(spec.get("yaw", 0))})})
            objects = turned
            floor = [round(abs(c) * L + abs(s) * W, 3), round(abs(s) * L + abs(c) * W, 3)]
            floor_center = at([cx, 0.0])
        lines = [f"name: {self.name}",
                 f"description: A random {'room without walls' if open_floor else 'walled room'}"
                 " (scripts/random_worlds.py).",
                 f"seed: {seed}",
                 f"robot: {{start: {lst(list(start))}}}",
                 f"goal: {{position: {lst(list(goal))}, tolerance: 0.2}}",
                 "world:",
                 f"  floor: {lst(floor)}",
                 f"  floor_center: {lst(floor_center)}",
                 "  objects:"]
        for obj in objects:
            (kind, spec), = obj.items()
            lines.append(f"    - {kind}: {flow(spec)}")
        if self.sensor:
            lines.append(f"sensor: {flow(self.sensor)}")
        if self.noise:
            lines.append(f"odometry_noise: {flow(self.noise)}")
        lines.append("limits: {max_cycles: 400, max_steps: 2000}")
        lines.append("expect: {reach_goal: true, no_collision: true}")
        return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    parser.add_argument("--count", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--variants", action="store_true",
                        help="every other room: wide camera, odometry noise or turned start")
    parser.add_argument("--prefix", default="room", help="scenario names: PREFIX_000, ...")
    parser.add_argument("--dense", action="store_true",
                        help="3-7 objects 0.18 m apart, divider openings of 0.25-0.5 m")
    parser.add_argument("--turn", action="store_true",
                        help="turn each room by a random angle and shift it by part of a cell")
    parser.add_argument("--open", action="store_true",
                        help="no walls: the floor ends where they stood")
    args = parser.parse_args()
    if args.count < 1:
        sys.exit("random_worlds: --count must be at least 1")
    os.makedirs(args.out_dir, exist_ok=True)
    for i in range(args.count):
        rng = random.Random(args.seed * 100003 + i)
        room = Room(rng, f"{args.prefix}_{i:03d}", i, args.variants, args.dense)
        path = os.path.join(args.out_dir, room.name + ".yaml")
        turn = None
        if args.turn:  # its own generator, so the rooms are those generated without --turn
            t = random.Random(args.seed * 100003 + i + 7777777)
            turn = (round(t.uniform(-180, 180), 1), round(t.uniform(0, 0.04), 3),
                    round(t.uniform(0, 0.04), 3))
        with open(path, "w") as f:
            f.write(room.yaml(args.seed * 1000 + i, turn, args.open))
    print(f"random_worlds: {args.count} rooms in {args.out_dir}")


if __name__ == "__main__":
    main()

"""Tests of scripts/course_worlds.py (no simulation).

Run from the source tree: python3 -m unittest tests/tools/evaluation_scripts_test.py
(ctest does, with FOGNAV_BINARY set to the built program for the `fognav validate` test).
"""
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import course_worlds  # noqa: E402


def read(path):
    with open(path) as f:
        return f.read()


def generate_courses(out_dir, seed, count):
    subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "course_worlds.py"), out_dir,
                    "--seed", str(seed), "--count", str(count)], check=True,
                   stdout=subprocess.DEVNULL)
    return {n: read(os.path.join(out_dir, n)) for n in sorted(os.listdir(out_dir))}


class CourseWorlds(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="fognav_course_worlds_")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def test_same_seed_same_files_other_seed_other_files(self):
        a = generate_courses(os.path.join(self.tmp, "a"), 5, 8)
        b = generate_courses(os.path.join(self.tmp, "b"), 5, 8)
        c = generate_courses(os.path.join(self.tmp, "c"), 6, 8)
        self.assertEqual(len(a), 8)
        self.assertEqual(a, b)
        self.assertEqual(sorted(a), sorted(c))
        self.assertTrue(all(a[n] != c[n] for n in a))

    def test_every_world_validates(self):
        fognav = os.environ.get("FOGNAV_BINARY")
        if not fognav:
            self.skipTest("FOGNAV_BINARY is not set (ctest sets it)")
        worlds = generate_courses(self.tmp, 3, 24)
        for name in worlds:
            done = subprocess.run([fognav, "validate", os.path.join(self.tmp, name)],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, f"{name}: {done.stdout}{done.stderr}")

    def test_worlds_hold_every_element_at_many_headings(self):
        worlds = generate_courses(self.tmp, 3, 24)
        quadrants, noisy, gap_low = set(), 0, 0
        for name, text in worlds.items():
            for element in ("wall_left", "wall_right", "wall_back", "wall_front", "low_block",
                            "tall_block", "steps", "gap_left", "gap_right", "desk"):
                self.assertIn(f"name: {element},", text, name)
            yaw = float(re.search(r"start: \[[-\d.]+, [-\d.]+, ([-\d.]+)\]", text).group(1))
            quadrants.add(int((yaw + 180) // 90))
            noisy += "odometry_noise: {xy: 0.005, yaw_deg: 0.5}" in text
            gap_low += "name: gap_low," in text
            self.assertIn("expect: {reach_goal: true, no_collision: true}", text)
        self.assertEqual(quadrants, {0, 1, 2, 3})
        self.assertTrue(6 <= noisy <= 18, noisy)
        self.assertTrue(0 < gap_low < 24, gap_low)

    def test_sizes_lie_within_the_papers_limits(self):
        orders = set()
        for i in range(60):
            course = course_worlds.Course(random.Random(1000 + i), f"c_{i}")
            orders.add(tuple(course.order))
            parts = {spec["name"]: (kind, spec) for kind, spec in course.objects}
            steps = parts["steps"][1]["steps"]
            levels = [0.0] + [h for _, h in steps] + [0.0]
            rises = [abs(b - a) for a, b in zip(levels, levels[1:])]
            self.assertTrue(all(0.02 - 1e-9 <= r <= 0.05 + 1e-9 for r in rises), rises)
            self.assertLessEqual(len(steps), 3)
            left, right = parts["gap_left"][1], parts["gap_right"][1]
            gap = ((left["center"][1] - left["size"][1] / 2)
                   - (right["center"][1] + right["size"][1] / 2))
            self.assertTrue(0.2 - 1e-6 <= gap <= 0.26 + 1e-6, gap)
            self.assertEqual(left["size"][2], 0.2)
            desk = parts["desk"][1]
            self.assertTrue(0.56 <= desk["height"] <= 0.64, desk)
            underside = desk["height"] - desk["top"]
            self.assertTrue(0.30 <= underside <= course_worlds.HEAD_TOP + 1e-9, desk)
            self.assertEqual(parts["low_block"][1]["size"][2], 0.08)
            self.assertEqual(parts["tall_block"][1]["size"][2], 0.2)
            for kind, spec in course.objects:  # inside the corridor's walls
                if kind == "box":
                    y, sy = spec["center"][1], spec["size"][1]
                    self.assertLessEqual(abs(y) + sy / 2, course.half + 1e-6, spec)
        self.assertGreater(len(orders), 12)  # of the 24 orders of the four sections

    def test_the_turn_keeps_the_course_and_moves_all_of_it(self):
        course = course_worlds.Course(random.Random(7), "c")
        deg, dx, dy = course.turn
        text = course.yaml(1)
        gx, gy = course.goal
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        goal = re.search(r"goal: \{position: \[([-\d.]+), ([-\d.]+)\]", text).groups()
        self.assertAlmostEqual(float(goal[0]), c * gx - s * gy + dx, places=3)
        self.assertAlmostEqual(float(goal[1]), s * gx + c * gy + dy, places=3)
        self.assertEqual(len(re.findall(rf"yaw: {course_worlds.lst(deg)}\}}", text)),
                         len(course.objects) + 4)


if __name__ == "__main__":
    unittest.main()

"""Tests of scripts/course_worlds.py and scripts/evaluate.py (no simulation).

Run from the source tree: python3 -m unittest tests/tools/evaluation_scripts_test.py
(ctest does, with FOGNAV_BINARY set to the built program for the `fognav validate` test).
"""
import json
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
import evaluate  # noqa: E402


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
            noisy += "odometry_noise: {xy: 0.005, yaw_deg: 0.5, stride_scale: 0.03" in text
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
            self.assertTrue(all(0.02 - 1e-9 <= r <= course_worlds.MAX_RISE + 1e-9 for r in rises),
                            rises)
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


class Wilson(unittest.TestCase):
    def test_known_intervals(self):
        for (k, n), (lo, hi) in {(5, 10): (0.2366, 0.7634), (0, 10): (0.0, 0.2775),
                                 (10, 10): (0.7225, 1.0), (97, 100): (0.9155, 0.9897),
                                 (0, 0): (0.0, 1.0)}.items():
            got = evaluate.wilson(k, n)
            self.assertAlmostEqual(got[0], lo, places=4, msg=(k, n))
            self.assertAlmostEqual(got[1], hi, places=4, msg=(k, n))


def report(success, failure=None, way=3.0, spl=None, collisions=0, cycles=40, trav=0.9,
           unsafe=2):
    return {"success": success, "reached_goal": success, "failure": failure,
            "failure_detail": None, "cycles": cycles, "collisions": collisions,
            "spl": (0.9 if success else 0.0) if spl is None else spl,
            "optimal_path_length": way, "wall_time_s": 12.5,
            "fog": {"types": 0.8, "traversability": trav, "unsafe_cells": unsafe,
                    "unsafe_cells_strict": unsafe, "height_error": {}}}


class Evaluate(unittest.TestCase):
    WORLDS = {
        "course_s1_000": report(True, spl=0.8),
        "course_s1_001": report(True, spl=1.0),
        "course_s1_002": report(False, "no_path"),
        "course_s1_003": report(False, "no_path", way=0.0),
        "rooms_s1_000": report(False, "collision", collisions=2, trav=0.7, unsafe=10),
        "rooms_s1_001": report(False, "timeout", way=0.0),
    }

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="fognav_evaluate_")
        for name, r in self.WORLDS.items():
            os.makedirs(os.path.join(self.tmp, name))
            with open(os.path.join(self.tmp, name, "report.json"), "w") as f:
                json.dump(r, f)

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def rows(self):
        # existing reports are read, never run again (the program does not exist)
        return [evaluate.run_world("/nonexistent/fognav", self.tmp, name.split("_")[0], name,
                                   "unused.yaml")[0] for name in self.WORLDS]

    def test_summary_counts_worlds_with_a_way_and_classes_failures(self):
        s = evaluate.summarize(self.rows())
        a = s["all"]
        self.assertEqual((a["worlds"], a["with_way"], a["success"], a["without_way"]),
                         (6, 4, 2, 2))
        self.assertEqual(a["failures"], {"collision": 1, "no_path": 1})
        self.assertEqual(a["without_way_ends"], {"no_path": 1, "timeout": 1})
        self.assertEqual(a["worlds_with_collisions"], 1)
        self.assertAlmostEqual(a["mean_spl"], (0.8 + 1.0) / 4)
        self.assertAlmostEqual(a["success_ci95"][0], evaluate.wilson(2, 4)[0])
        self.assertAlmostEqual(a["mean_fog_traversability"], (5 * 0.9 + 0.7) / 6)
        self.assertAlmostEqual(a["mean_fog_unsafe_cells"], (5 * 2 + 10) / 6)
        course = s["families"]["course"]
        self.assertEqual((course["with_way"], course["success"]), (3, 2))
        self.assertAlmostEqual(course["success_rate"], 2 / 3)
        self.assertEqual(s["families"]["rooms"]["failures"], {"collision": 1})

    def test_compare_lists_changed_outcomes_from_a_results_file(self):
        old_dir = os.path.join(self.tmp, "old")
        os.makedirs(old_dir)
        old = self.rows()
        old[0] = dict(old[0], outcome="timeout")  # course_s1_000 failed before
        old[4] = dict(old[4], outcome="success")  # rooms_s1_000 succeeded before
        evaluate.write_tsv(os.path.join(old_dir, "results.tsv"), old[:5])
        changes = evaluate.compare(self.rows(),
                                   evaluate.read_tsv(os.path.join(old_dir, "results.tsv")))
        self.assertEqual(changes, [("course_s1_000", "timeout", "success"),
                                   ("rooms_s1_000", "success", "collision")])
        text = evaluate.format_summary(evaluate.summarize(self.rows()), changes)
        self.assertIn("changed outcome: 2 worlds (1 now succeed, 1 no longer)", text)
        self.assertIn("success     2/4 = 50.0 % (95 % interval 15.0 % - 85.0 %)", text)

    def test_a_bad_results_file_is_an_error_naming_it(self):
        path = os.path.join(self.tmp, "results.tsv")
        with open(path, "w") as f:
            f.write("world\tresult\n")
        with self.assertRaisesRegex(evaluate.InputError, re.escape(path) + ":1: expected"):
            evaluate.read_tsv(path)

    def test_seeds_file_splits_are_disjoint_and_evaluation_seeds_large(self):
        with open(os.path.join(ROOT, "scripts", "seeds.json")) as f:
            data = json.load(f)
        self.assertIn("never to tune", data["rule"])
        for family, spec in data["families"].items():
            dev = {s["seed"] for s in spec["dev"]}
            ev = {s["seed"] for s in spec["eval"]}
            self.assertFalse(dev & ev, family)
            self.assertTrue(all(s >= 1000 for s in ev), family)
            self.assertTrue(all(s < 1000 for s in dev), family)
        sets = evaluate.load_seeds(os.path.join(ROOT, "scripts", "seeds.json"), "eval", None)
        self.assertGreaterEqual(sum(s["count"] for _, e in sets.values() for s in e), 200)
        with self.assertRaisesRegex(evaluate.InputError, "unknown family 'hills'"):
            evaluate.load_seeds(os.path.join(ROOT, "scripts", "seeds.json"), "eval", ["hills"])

    def test_runs_each_world_once_and_continues_where_it_stopped(self):
        # a stand-in for fognav that writes a report and logs each run
        fake = os.path.join(self.tmp, "fake_fognav")
        log = os.path.join(self.tmp, "runs.log")
        with open(fake, "w") as f:
            f.write(f"#!{sys.executable}\nimport json, os, sys\n"
                    "out = sys.argv[sys.argv.index('--out') + 1]\n"
                    "os.makedirs(out, exist_ok=True)\n"
                    f"open({log!r}, 'a').write(sys.argv[2] + '\\n')\n"
                    "ok = 'rooms' in out\n"
                    f"json.dump({report(True)!r} if ok else "
                    f"{report(False, 'timeout')!r}, open(out + '/report.json', 'w'))\n"
                    "sys.exit(0 if ok else 1)\n")
        os.chmod(fake, 0o755)
        out = os.path.join(self.tmp, "run")
        argv = [out, "--split", "dev", "--fognav", fake, "--jobs", "2", "--count", "5"]
        with open(os.devnull, "w") as null:
            stdout, stderr = sys.stdout, sys.stderr
            sys.stdout = sys.stderr = null
            try:
                self.assertEqual(evaluate.main(argv), 0)
                os.remove(os.path.join(out, "rooms_s9_000", "report.json"))
                self.assertEqual(evaluate.main(argv + ["--compare", out]), 0)
            finally:
                sys.stdout, sys.stderr = stdout, stderr
        runs = read(log).split()
        self.assertEqual(len(runs), 6)  # five, then the one whose report was removed
        self.assertTrue(runs[-1].endswith("rooms_s9_000.yaml"))
        # three course worlds, taken in turn from the two seed sets; two rooms
        with open(os.path.join(out, "results.tsv")) as f:
            names = [line.split("\t")[0] for line in f.read().splitlines()[1:]]
        self.assertEqual(names, ["course_s1_000", "course_s1_001", "course_s2_000",
                                 "rooms_s10_000", "rooms_s9_000"])
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        self.assertEqual(summary["families"]["course"]["failures"], {"timeout": 3})
        self.assertEqual(summary["families"]["rooms"]["success"], 2)
        self.assertEqual(summary["changed"], [])

    def test_noise_seeds_run_noisy_worlds_again_under_other_seeds_only(self):
        scenarios = {"clean": "seed: 3\nrobot: {start: [0, 0, 0]}\n",
                     "zero": "seed: 3\nodometry_noise: {xy: 0.0, yaw_deg: 0}\n",
                     "noisy": "seed: 3\nodometry_noise: {xy: 0.0, yaw_deg: 0.5}\n"}
        worlds = []
        for name, text in scenarios.items():
            path = os.path.join(self.tmp, name + ".yaml")
            with open(path, "w") as f:
                f.write(text)
            worlds.append(("rooms", name, path))
        self.assertEqual([evaluate.noisy(w[2]) for w in worlds], [False, False, True])
        runs = evaluate.with_noise_seeds(worlds, 3)
        self.assertEqual([(r[1], r[3]) for r in runs],
                         [("clean", None), ("zero", None), ("noisy", None), ("noisy.n1", 1),
                          ("noisy.n2", 2)])
        self.assertEqual(evaluate.with_noise_seeds(worlds, 1), [w + (None,) for w in worlds])
        # the seed reaches the program, and each run has a directory of its own
        fake = os.path.join(self.tmp, "fake_fognav")
        with open(fake, "w") as f:
            f.write(f"#!{sys.executable}\nimport json, os, sys\n"
                    "out = sys.argv[sys.argv.index('--out') + 1]\n"
                    "os.makedirs(out, exist_ok=True)\n"
                    "seed = sys.argv[sys.argv.index('--seed') + 1] if '--seed' in sys.argv else ''\n"
                    f"r = {report(True)!r}\n"
                    "r['failure_detail'] = 'seed ' + seed\n"
                    "json.dump(r, open(out + '/report.json', 'w'))\n")
        os.chmod(fake, 0o755)
        out = os.path.join(self.tmp, "seeded")
        rows = [evaluate.run_world(fake, out, *r)[0] for r in runs]
        self.assertEqual([r["failure_detail"] for r in rows],
                         ["seed ", "seed ", "seed ", "seed 1", "seed 2"])
        self.assertIn("all: 5 runs, 5 with a way",
                      evaluate.format_summary(evaluate.summarize(rows), unit="runs"))


if __name__ == "__main__":
    unittest.main()

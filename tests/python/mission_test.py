"""Missions from Python: whole runs against the `fognav run` binary, scenario and parameter
errors, and a mission stepped by a small planner written here in Python."""
import heapq
import json
import math
import os
import subprocess

import numpy as np
import pytest

import fognav

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BINARY = os.environ.get("FOGNAV_BINARY", os.path.join(ROOT, "build", "bin", "fognav"))
NARROW_GAP = os.path.join(ROOT, "scenarios", "narrow_gap.yaml")
NOISY = os.path.join(ROOT, "scenarios", "noisy_odometry.yaml")


def comparable(report):
    """A report without what the clock decides."""
    return {k: v for k, v in report.items() if k not in ("wall_time_s", "timing_ms")}


@pytest.mark.parametrize("scenario, params, seed", [
    (NARROW_GAP, {"planner.sidestep_factor": 1.5, "mission.walk": 0.12}, None),
    (NOISY, {}, 7),
])
def test_run_gives_the_binarys_report(tmp_path, scenario, params, seed):
    args = [BINARY, "run", scenario, "--out", str(tmp_path / "binary"), "--quiet"]
    for key, value in params.items():
        args += ["--set", f"{key}={value}"]
    if seed is not None:
        args += ["--seed", str(seed)]
    subprocess.run(args, check=False, capture_output=True, timeout=600)
    with open(tmp_path / "binary" / "report.json") as f:
        binary = json.load(f)
    report = fognav.run(scenario, out=str(tmp_path / "python"), params=params, seed=seed)
    assert comparable(report) == comparable(binary)
    assert set(report["timing_ms"]) == set(binary["timing_ms"])
    with open(tmp_path / "python" / "report.json") as f:
        assert comparable(json.load(f)) == comparable(report)
    assert (tmp_path / "python" / "report.html").exists()
    # the parameters given show in the report as changed
    assert report["params"] == params


def test_stepping_with_the_built_in_decisions_gives_runs_report(tmp_path):
    report = fognav.run(NOISY, seed=3)
    m = fognav.Mission(NOISY, seed=3, out=str(tmp_path))
    cycles = 0
    while m.step():
        cycles += 1
        assert m.cycles == cycles
    assert m.done()
    stepped = m.report()
    assert comparable(stepped) == comparable(report)
    assert stepped["cycles"] == cycles
    with open(tmp_path / "cycles.csv") as f:
        assert len(f.readlines()) == 1 + cycles
    assert not m.step()


def test_load_scenario_raises_the_validate_message(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nrobot: {start: [0, 0, 0]}\ngoal: {position: [1, 0]}\n"
                   "world:\n  floor: [2, -1]\n")
    validate = subprocess.run([BINARY, "validate", str(bad)], capture_output=True, text=True)
    assert validate.returncode == 2
    with pytest.raises(fognav.InputError) as error:
        fognav.load_scenario(str(bad))
    assert str(error.value) == validate.stderr.strip().removeprefix("fognav: ")
    assert f"{bad}:5: world.floor" in str(error.value)
    with pytest.raises(fognav.InputError, match="cannot read"):
        fognav.load_scenario(str(tmp_path / "missing.yaml"))
    # a bad scenario given by path to run() and Mission() raises the same
    with pytest.raises(ValueError, match="world.floor"):
        fognav.run(str(bad))
    with pytest.raises(ValueError, match="world.floor"):
        fognav.Mission(str(bad))
    s = fognav.load_scenario(NARROW_GAP)
    assert s.name == "narrow_gap" and s.goal == (2.2, 0.0) and s.start == (0.0, 0.0, 0.0)


@pytest.mark.parametrize("params, message", [
    ({"planner.nope": 1}, "params: planner.nope: unknown parameter"),
    ({"planner.sidestep_factor": 1e6}, "planner.sidestep_factor: expected a number from"),
    ({"stereo.num_disparities": 100}, "stereo.num_disparities: "),
    ({"mission.max_explorations": 1.5}, "mission.max_explorations: expected an integer"),
    ({"planner.walk_factor": [1]}, "planner.walk_factor: expected a number or a bool"),
    ("planner.walk_factor=1", "params: expected a dict"),
])
def test_bad_params_raise_naming_the_key(params, message):
    with pytest.raises(fognav.InputError) as error:
        fognav.run(NARROW_GAP, params=params)
    assert message in str(error.value)
    with pytest.raises(fognav.InputError):
        fognav.Mission(NARROW_GAP, params=params)


def test_bad_seed_raises():
    with pytest.raises(ValueError, match="seed"):
        fognav.run(NARROW_GAP, seed=-1)


def test_look_returns_the_view_as_arrays():
    m = fognav.Mission(NARROW_GAP)
    v = m.look(0.0, 0.6)
    h, w = 144, 176
    assert v["left"].shape == v["right"].shape == (h, w, 3) and v["left"].dtype == np.uint8
    assert v["left"].std() > 5 and not np.array_equal(v["left"], v["right"])
    assert v["depth"].shape == (h, w) and v["depth"].dtype == np.float32
    valid = np.isfinite(v["depth"])
    assert 0.3 < valid.mean() < 1.0  # stereo: some pixels have no match
    # the measured depth against the renderer's, where both have one
    both = valid & np.isfinite(v["depth_true"])
    assert np.median(np.abs(v["depth"][both] - v["depth_true"][both])) < 0.02
    np.testing.assert_array_equal(v["depth"], v["points_camera"][..., 2])
    X = v["camera_pose"]
    expected = v["points_camera"] @ X[:3, :3].T + X[:3, 3]
    np.testing.assert_allclose(v["points_grid"], expected, atol=1e-4, equal_nan=True)
    # the floor seen ahead lies at z = 0 in the grid frame
    floor = v["labels"] == 0
    assert floor.sum() > 1000
    assert abs(np.nanmedian(v["points_grid"][floor][:, 2])) < 0.01
    assert v["labels"].shape == (h, w) and v["labels"].max() < len(v["planes"]["rms"])
    assert v["labelled_grid"].shape[1] == 3 and len(v["labelled_heights"]) == len(v["labelled_grid"])
    # without odometry noise the believed camera is the true one
    np.testing.assert_allclose(v["camera_pose"], v["camera_pose_true"], atol=1e-6)
    fog = m.fog()
    assert fog["types"].shape == (100, 100) and fog["types"].dtype == np.uint8
    assert (fog["types"] == fognav.FLOOR).sum() > 100
    assert fog["resolution"] == pytest.approx(0.04)


def test_execute_stops_at_the_first_move_the_body_rules_refuse():
    m = fognav.Mission(NARROW_GAP)
    m.look_around()
    plan = m.plan()
    assert plan["status"] == "ok" and plan["reason"] == "none"
    assert plan["poses"].shape == (len(plan["moves"]), 3) and plan["moves"][0] == "none"
    assert set(plan["moves"][1:]) <= set(fognav.MOVES[1:]) and plan["length"] > 0.5
    # straight ahead through the blocks of the gap's wall (x 1.1 to 1.3), facing them
    x, y, yaw = m.believed_pose()
    poses = [(x, y, yaw)] + [(0.02 + 0.04 * k, 0.02, 0.0) for k in range(1, 41)]
    path = {"poses": np.array(poses), "moves": ["none"] + ["walk"] * 40}
    r = m.execute(path)
    assert r["blocked_at"] is not None and r["collisions"] == 0 and not r["ended"]
    stopped = m.true_pose()
    # stopped short of the blocks: the footprint reaches 0.075 m ahead of the origin
    assert 0.7 < stopped[0] < 1.1 - 0.075
    assert r["reached"] == r["blocked_at"] - 1
    assert stopped[0] == pytest.approx(poses[r["reached"]][0], abs=0.01)
    for bad, message in [({"poses": np.zeros((3, 2)), "moves": ["walk"] * 3}, "N x 3"),
                         ({"poses": np.zeros((3, 3)), "moves": ["walk"] * 2}, "expected 3"),
                         ({"poses": np.zeros((2, 3)), "moves": ["walk", "fly"]}, "'fly'"),
                         ([1, 2, 3], "expected a dict")]:
        with pytest.raises(ValueError, match="execute: path") as error:
            m.execute(bad)
        assert message in str(error.value)
    report = m.report()
    assert report["actions"]["walk"] >= 1 and report["collisions"] == 0
    assert m.done()
    with pytest.raises(Exception, match="report was made"):
        m.look(0, 0.5)


def test_executing_the_built_in_plan_follows_it():
    m = fognav.Mission(NARROW_GAP)
    m.look_around()
    plan = m.plan()
    r = m.execute(plan)
    assert r["blocked_at"] is None and r["reached"] == len(plan["moves"]) - 1
    assert r["steps"] > 0 and r["collisions"] == 0
    end = plan["poses"][-1]
    assert np.allclose(m.believed_pose(), end, atol=0.01)
    assert math.dist(m.true_pose()[:2], end[:2]) < 0.02


# ---- a planner written in Python: A* over cells and the four axis headings ----

HEADING_STEP = [(1, 0), (0, 1), (-1, 0), (0, -1)]  # ahead, per quarter turn; left is the next


class GridPlanner:
    """Walks, side-steps and quarter turns on the FOG, with the built-in planner's footprint
    (`planner.depth` x `planner.shoulder_width` grown by `planner.margin`)."""

    def __init__(self):
        p = fognav.param_defaults()
        self.along = p["planner.depth"] / 2 + p["planner.margin"]
        self.across = p["planner.shoulder_width"] / 2 + p["planner.margin"]
        self.h_floor = p["planner.h_floor"]

    def footprints(self, fog):
        """Per heading parity: where the footprint holds only standable cells, and only seen
        ones (backward and side moves may not go blind); and where a turn's disc is clear."""
        types, heights, res = fog["types"], fog["heights"], fog["resolution"]
        unknown = types == fognav.UNKNOWN
        # as the built-in planner: floor, stairs and border cells (the foot of a wall) on the
        # robot's level, here the floor's
        level = (types == fognav.FLOOR) | (types == fognav.STAIRS) | (types == fognav.BORDER)
        standable = unknown | (level & (np.abs(heights) <= self.h_floor))
        ok, known = [], []
        for along_x in (True, False):
            nx = int(math.floor((self.along if along_x else self.across) / res + 0.5))
            ny = int(math.floor((self.across if along_x else self.along) / res + 0.5))
            ok.append(self.all_within(standable, nx, ny))
            known.append(self.all_within(standable & ~unknown, nx, ny))
        # turning in place sweeps the disc the footprint's corners draw
        radius = math.hypot(self.along, self.across) / res
        n = int(math.ceil(radius))
        disc = np.ones_like(standable)
        for dy in range(-n, n + 1):
            for dx in range(-n, n + 1):
                if math.hypot(dx, dy) <= radius:
                    disc &= self.all_within(standable, 0, 0) if dx == dy == 0 else \
                        np.roll(np.pad(standable, n), (-dy, -dx), (0, 1))[n:-n, n:-n]
        return ok, known, disc

    @staticmethod
    def all_within(mask, nx, ny):
        """Cells whose (2 nx + 1) x (2 ny + 1) neighbourhood is all `mask` (outside: False)."""
        h, w = mask.shape
        padded = np.zeros((h + 2 * ny, w + 2 * nx), dtype=bool)
        padded[ny:ny + h, nx:nx + w] = mask
        out = np.ones_like(mask)
        for dy in range(2 * ny + 1):
            for dx in range(2 * nx + 1):
                out &= padded[dy:dy + h, dx:dx + w]
        return out

    def plan(self, fog, start, goal, tolerance):
        """States (ix, iy, quarter) with the moves that reach them, from the cell under `start`
        to one within `tolerance` of `goal` or, with no way there, the nearest to it."""
        res = fog["resolution"]
        x0, y0 = fog["origin"]
        h, w = fog["types"].shape
        # a goal beyond the window: toward it, to near the window's side
        inside = (min(max(goal[0], x0 + 0.2), x0 + w * res - 0.2),
                  min(max(goal[1], y0 + 0.2), y0 + h * res - 0.2))
        if inside != tuple(goal):
            goal, tolerance = inside, 0.2
        ok, known, disc = self.footprints(fog)
        unknown = fog["types"] == fognav.UNKNOWN
        # the cell as the planner's lattice takes it: global index floor(x / res)
        sx = math.floor(start[0] / res) - round(x0 / res)
        sy = math.floor(start[1] / res) - round(y0 / res)
        sq = round(start[2] / (math.pi / 2)) % 4
        center = lambda ix, iy: (x0 + (ix + 0.5) * res, y0 + (iy + 0.5) * res)
        at_goal = lambda ix, iy: math.dist(center(ix, iy), goal) <= tolerance
        best = {(sx, sy, sq): 0.0}
        came = {}
        nearest = (math.dist(center(sx, sy), goal), (sx, sy, sq))
        queue = [(nearest[0], 0.0, (sx, sy, sq))]
        while queue:
            _, cost, s = heapq.heappop(queue)
            if cost > best[s]:
                continue
            ix, iy, q = s
            if at_goal(ix, iy):
                nearest = (0.0, s)
                break
            nearest = min(nearest, (math.dist(center(ix, iy), goal), s))
            ax, ay = HEADING_STEP[q]
            moves = [((ix + ax, iy + ay, q), "walk", 1.0, ok),
                     ((ix - ax, iy - ay, q), "walk", 1.5, known),
                     ((ix - ay, iy + ax, q), "sidestep", 1.6, known),
                     ((ix + ay, iy - ax, q), "sidestep", 1.6, known)]
            for nq in ((q + 1) % 4, (q + 3) % 4):
                if disc[iy, ix]:
                    moves.append(((ix, iy, nq), "turn", 6.0, None))
            for t, move, factor, allowed in moves:
                tx, ty, tq = t
                if not (0 <= tx < w and 0 <= ty < h):
                    continue
                if allowed is not None and not allowed[tq % 2][ty, tx]:
                    continue
                c = cost + factor * res * (1.5 if unknown[ty, tx] else 1.0)
                if c < best.get(t, math.inf):
                    best[t] = c
                    came[t] = (s, move)
                    heapq.heappush(queue, (c + math.dist(center(tx, ty), goal), c, t))
        # the goal, or where no way leads there, the reachable state nearest to it
        path = [nearest[1]]
        while path[-1] in came:
            path.append(came[path[-1]][0])
        path.reverse()
        return [(path[k], came[path[k]][1] if k else "none") for k in range(len(path))]

    @staticmethod
    def to_path(fog, believed, states, max_cells):
        """The first run of one kind of move of `states` as a path for Mission.execute:
        lattice poses (a quarter turn is four lattice turns), at most max_cells cells. Where the
        believed heading is a lattice heading, the believed pose is the start state (its cell
        and heading) and the moves go on from it; else the first move goes onto the lattice."""
        res = fog["resolution"]
        x0, y0 = fog["origin"]
        center = lambda ix, iy: (x0 + (ix + 0.5) * res, y0 + (iy + 0.5) * res)
        poses, moves = [tuple(believed)], ["none"]
        (ix, iy, q), _ = states[0]
        k = min(range(16), key=lambda k: abs(math.remainder(believed[2] - fognav.HEADINGS[k],
                                                             2 * math.pi)))
        if abs(math.remainder(believed[2] - fognav.HEADINGS[k], 2 * math.pi)) > 1e-3:
            poses.append(center(ix, iy) + (fognav.HEADINGS[4 * q],))
            moves.append("walk")
        else:
            turn = 1 if (4 * q - k) % 16 <= 8 else -1
            while k != 4 * q:
                k = (k + turn) % 16
                poses.append(center(ix, iy) + (fognav.HEADINGS[k],))
                moves.append("turn")
        if len(moves) > 1:
            return {"poses": np.array(poses), "moves": moves}
        kind, cells = states[1][1], 0
        for (ix, iy, nq), move in states[1:]:
            if move != kind or cells >= max_cells:
                break
            if move == "turn":
                turn = 1 if nq == (q + 1) % 4 else -1
                for k in range(1, 5):
                    poses.append(center(ix, iy) + (fognav.HEADINGS[(4 * q + turn * k) % 16],))
                    moves.append("turn")
            else:
                poses.append(center(ix, iy) + (fognav.HEADINGS[4 * nq],))
                moves.append(move)
                cells += 1
            q = nq
        return {"poses": np.array(poses), "moves": moves}


# a corridor closed by two blocks but for a gap of 0.26 m: narrower than the robot's shoulders
# (0.29 m with the margin), wider than its depth (0.15 m): the way on is to turn and side-step
GAP = """name: gap_for_python
seed: 3
robot: {start: [0.0, 0.0, 0.0]}
goal: {position: [2.2, 0.0], tolerance: 0.2}
world:
  floor: [3.4, 1.4]
  floor_center: [1.1, 0.0]
  objects:
    - box: {name: wall_left, center: [1.1, 0.65], size: [3.4, 0.1, 0.3]}
    - box: {name: wall_right, center: [1.1, -0.65], size: [3.4, 0.1, 0.3]}
    - box: {name: gap_left, center: [1.2, 0.375], size: [0.2, 0.49, 0.2]}
    - box: {name: gap_right, center: [1.2, -0.375], size: [0.2, 0.49, 0.2]}
limits: {max_cycles: 200, max_steps: 600}
"""


def test_a_python_planner_drives_the_robot_through_a_gap_with_turns_and_sidesteps(tmp_path):
    (tmp_path / "gap.yaml").write_text(GAP)
    scenario = fognav.load_scenario(str(tmp_path / "gap.yaml"))
    m = fognav.Mission(scenario, out=str(tmp_path / "out"))
    m.look_around()
    planner = GridPlanner()
    views = [(0.0, 0.75), (0.45, 0.6), (0.0, 0.4), (-0.45, 0.6), (0.0, 0.15)]
    executed = []
    stuck = 0
    for cycle in range(150):
        if m.done():
            break
        fog = m.fog()
        believed = m.believed_pose()
        states = planner.plan(fog, believed, scenario.goal, 0.5 * scenario.goal_tolerance)
        if len(states) < 2:
            stuck += 1
            assert stuck < 3, f"cycle {cycle}: no way on from {believed}"
            m.look_around()
            continue
        path = planner.to_path(fog, believed, states, max_cells=3)
        r = m.execute(path)
        assert r["collisions"] == 0 and not r["ended"]
        executed += [mv for mv in path["moves"][1:(r["blocked_at"] or len(path["moves"]))]]
        m.look(*views[cycle % len(views)])
    report = m.report()
    assert report["reached_goal"] and report["success"], report
    assert report["failure"] is None and report["collisions"] == 0
    assert report["actions"]["turn"] >= 2 and report["actions"]["sidestep"] >= 1
    assert "turn" in executed and "sidestep" in executed
    # it went through the gap (between the blocks at y = +-0.13), facing across the corridor
    with open(tmp_path / "out" / "trajectory.csv") as f:
        rows = [line.strip().split(",") for line in f][1:]
    in_gap = [r for r in rows if 1.1 <= float(r[2]) <= 1.3]
    assert in_gap and all(abs(float(r[3])) < 0.13 for r in in_gap)
    assert all(abs(abs(float(r[4])) - math.pi / 2) < 0.2 for r in in_gap)
    assert m.cycles <= scenario.max_cycles


def test_a_mission_releases_the_gil_while_it_runs():
    import threading
    reports = []
    worker = threading.Thread(target=lambda: reports.append(fognav.run(NARROW_GAP)))
    worker.start()
    count = 0
    while worker.is_alive():  # with the GIL held by the mission this loop would not run
        count += 1
    worker.join()
    assert reports and reports[0]["success"]
    assert count > 10000

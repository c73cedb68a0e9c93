#!/usr/bin/env python3
"""Runs fognav on a split of generated worlds (the held-out benchmark) and summarizes the runs.

Usage: scripts/evaluate.py OUT_DIR [--split eval|dev] [--fognav PATH] [--jobs N]
                           [--compare OLD_DIR] [--families course,rooms] [--count N]
                           [--seeds FILE] [--noise-seeds K]

The worlds of each family come from its generator and the seeds of the split in
scripts/seeds.json; they are written to OUT_DIR/worlds/FAMILY/. --count N takes N worlds in all,
shared evenly between the families and, within a family, taken in turn from its seed sets.
Each world runs as `fognav run WORLD --out OUT_DIR/NAME --quiet`, N at a time; a world whose
OUT_DIR/NAME/report.json exists and parses is not run again, so a rerun continues where an
interrupted one stopped. A line per finished world goes to stderr; the summary (overall and
per family) to stdout, OUT_DIR/summary.json and OUT_DIR/results.tsv (one row per world).
With --compare OLD_DIR it also lists the worlds whose outcome differs from OLD_DIR/results.tsv.
With --noise-seeds K, a world with odometry noise also runs under the noise seeds 1 ... K-1
(`fognav run --seed I`, as OUT_DIR/NAME.nI): the outcome of such a world flips with the seed
alone, so a change is judged over its runs; the figures then count runs, not worlds.
Exit code 0 when every world ran (whatever its outcome), 1 when fognav could not run a world
(bad scenario or simulator error: outcome "error"), 2 on bad arguments or a bad seeds file.
Only the standard library is used.
"""
import argparse
import concurrent.futures
import json
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COLUMNS = ("name", "family", "outcome", "success", "reached_goal", "failure", "cycles",
           "collisions", "spl", "optimal_path_length", "traversability", "unsafe_cells",
           "wall_time_s", "failure_detail")


class InputError(Exception):
    """Bad arguments or a bad seeds file: the message names the input and what was expected."""


def wilson(successes, n, z=1.959964):
    """The Wilson score interval (lo, hi) of a success rate at 95 %; (0, 1) when n is 0."""
    if n == 0:
        return 0.0, 1.0
    p = successes / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def load_seeds(path, split, families):
    """The seed sets {family: [set, ...]} of a split, checked; families None means all."""
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: cannot read the seeds file: {e}")
    known = data.get("families", {})
    for family in families or []:
        if family not in known:
            raise InputError(f"--families: unknown family '{family}' (expected one of: "
                             f"{', '.join(sorted(known))})")
    sets = {}
    for family in families or sorted(known):
        spec = known[family]
        entries = spec.get(split)
        if not isinstance(entries, list) or not entries:
            raise InputError(f"{path}: families.{family}.{split}: expected a list of seed sets")
        for i, s in enumerate(entries):
            where = f"{path}: families.{family}.{split}[{i}]"
            if not (isinstance(s.get("seed"), int) and isinstance(s.get("count"), int)
                    and s["count"] > 0 and isinstance(s.get("flags", []), list)):
                raise InputError(f"{where}: expected {{seed: int, count: int > 0, flags: [...]}}")
            if (split == "eval") != (s["seed"] >= 1000):
                raise InputError(f"{where}: {split} seeds must be "
                                 f"{'>= 1000' if split == 'eval' else 'below 1000'}")
        sets[family] = (spec["generator"], entries)
    return sets


def share(count, families):
    """How many of count worlds each family gets: evenly, the remainder to the first ones."""
    n = len(families)
    return {f: count // n + (1 if i < count % n else 0) for i, f in enumerate(families)}


def interleave(lists):
    """The items of lists taken in turn: a0, b0, c0, a1, b1, ..."""
    out = []
    for i in range(max((len(x) for x in lists), default=0)):
        out += [x[i] for x in lists if i < len(x)]
    return out


def generate(out_dir, sets, count):
    """Writes the worlds and returns [(family, name, scenario path)], count of them or all."""
    quota = share(count, list(sets)) if count is not None else {}
    worlds = []
    for family, (generator, entries) in sets.items():
        folder = os.path.join(out_dir, "worlds", family)
        prefixes = [f"{family}_s{s['seed']}" for s in entries]
        names = interleave([[f"{p}_{i:03d}" for i in range(s["count"])]
                            for p, s in zip(prefixes, entries)])
        names = names[:quota.get(family, len(names))]
        for prefix, s in zip(prefixes, entries):
            needed = sum(n.startswith(prefix + "_") for n in names)  # the set's first ones
            if needed:
                command = [sys.executable, os.path.join(ROOT, generator), folder, "--seed",
                           str(s["seed"]), "--count", str(needed), "--prefix", prefix]
                subprocess.run(command + s.get("flags", []), check=True,
                               stdout=subprocess.DEVNULL)
        worlds += [(family, n, os.path.join(folder, n + ".yaml")) for n in names]
    return worlds


def noisy(scenario):
    """Whether a scenario file sets odometry noise above zero (`odometry_noise: {xy: ...}`)."""
    with open(scenario) as f:
        match = re.search(r"^odometry_noise:\s*\{([^}]*)\}", f.read(), re.MULTILINE)
    if not match:
        return False
    values = re.findall(r":\s*([-+0-9.eE]+)", match.group(1))
    return any(float(v) > 0 for v in values)


def with_noise_seeds(worlds, k):
    """The runs [(family, name, scenario, noise seed or None)]: every world once with its own
    seed, and a world with odometry noise also under the noise seeds 1 ... k-1."""
    runs = []
    for family, name, scenario in worlds:
        runs.append((family, name, scenario, None))
        if k > 1 and noisy(scenario):
            runs += [(family, f"{name}.n{i}", scenario, i) for i in range(1, k)]
    return runs


def read_report(run_dir):
    """The run's report.json as a dict, or None when it is missing or does not parse."""
    try:
        with open(os.path.join(run_dir, "report.json")) as f:
            report = json.load(f)
        return report if isinstance(report, dict) else None
    except (OSError, ValueError):
        return None


def number(v, default=math.nan):
    """A report's number as a float; null (a NaN written by fognav) or missing gives default."""
    return default if v is None else float(v)


def row_from_report(family, name, report):
    """One results row from a report.json; outcome is "success" or the failure's class."""
    fog = report.get("fog") or {}
    if report.get("success"):
        outcome = "success"
    elif report.get("failure"):
        outcome = report["failure"]
    else:
        outcome = "goal_not_reached" if not report.get("reached_goal") else "unmet_expectation"
    return {"name": name, "family": family, "outcome": outcome,
            "success": bool(report.get("success")),
            "reached_goal": bool(report.get("reached_goal")),
            "failure": report.get("failure") or "", "cycles": int(report.get("cycles") or 0),
            "collisions": int(report.get("collisions") or 0),
            "spl": number(report.get("spl"), 0.0),
            "optimal_path_length": number(report.get("optimal_path_length"), 0.0),
            "traversability": number(fog.get("traversability")),
            "unsafe_cells": int(fog.get("unsafe_cells") or 0),
            "wall_time_s": number(report.get("wall_time_s"), 0.0),
            "failure_detail": report.get("failure_detail") or ""}


def error_row(family, name, detail):
    """A results row for a world fognav could not run (exit code 2 or 3, or no report)."""
    return {"name": name, "family": family, "outcome": "error", "success": False,
            "reached_goal": False, "failure": "error", "cycles": 0, "collisions": 0, "spl": 0.0,
            "optimal_path_length": math.nan, "traversability": math.nan, "unsafe_cells": 0,
            "wall_time_s": 0.0, "failure_detail": detail}


def run_world(fognav, out_dir, family, name, scenario, noise_seed=None):
    """Runs one world (under odometry noise seed noise_seed, if given) unless its report
    exists; returns (row, whether it was run now)."""
    run_dir = os.path.join(out_dir, name)
    report = read_report(run_dir)
    if report is not None:
        return row_from_report(family, name, report), False
    command = [fognav, "run", scenario, "--out", run_dir, "--quiet"]
    if noise_seed is not None:
        command += ["--seed", str(noise_seed)]
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    report = read_report(run_dir)
    if done.returncode in (0, 1) and report is not None:
        return row_from_report(family, name, report), True
    lines = done.stderr.strip().splitlines()
    return error_row(family, name, f"exit {done.returncode}: {lines[-1] if lines else ''}"), True


def mean(values):
    values = [v for v in values if not math.isnan(v)]
    return sum(values) / len(values) if values else math.nan


def counts(values):
    out = {}
    for v in values:
        out[v] = out.get(v, 0) + 1
    return dict(sorted(out.items()))


def summarize_rows(rows):
    """The figures of one group of results rows (see docs/evaluation.md)."""
    ran = [r for r in rows if r["outcome"] != "error"]
    way = [r for r in ran if r["optimal_path_length"] > 0]
    no_way = [r for r in ran if not r["optimal_path_length"] > 0]
    successes = sum(r["success"] for r in way)
    lo, hi = wilson(successes, len(way))
    return {
        "worlds": len(rows),
        "errors": len(rows) - len(ran),
        "with_way": len(way),
        "success": successes,
        "success_rate": successes / len(way) if way else math.nan,
        "success_ci95": [lo, hi],
        "reached_goal": sum(r["reached_goal"] for r in way),
        "worlds_with_collisions": sum(r["collisions"] > 0 for r in ran),
        "mean_spl": mean([r["spl"] for r in way]),
        "failures": counts(r["outcome"] for r in way if not r["success"]),
        "without_way": len(no_way),
        "without_way_ends": counts(r["failure"] or "reached_goal" for r in no_way),
        "mean_fog_traversability": mean([r["traversability"] for r in ran]),
        "mean_fog_unsafe_cells": mean([float(r["unsafe_cells"]) for r in ran]),
    }


def summarize(rows):
    """{"all": figures, "families": {family: figures}}."""
    families = sorted({r["family"] for r in rows})
    return {"all": summarize_rows(rows),
            "families": {f: summarize_rows([r for r in rows if r["family"] == f])
                         for f in families}}


def compare(rows, old_rows):
    """The worlds in both runs whose outcome differs: [(name, old outcome, new outcome)]."""
    old = {r["name"]: r["outcome"] for r in old_rows}
    return [(r["name"], old[r["name"]], r["outcome"]) for r in sorted(rows, key=lambda r: r["name"])
            if r["name"] in old and old[r["name"]] != r["outcome"]]


def cell(v):
    if isinstance(v, bool):
        return "1" if v else "0"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else f"{v:.4f}"
    return str(v).replace("\t", " ").replace("\n", " ")


def write_tsv(path, rows):
    with open(path, "w") as f:
        f.write("\t".join(COLUMNS) + "\n")
        for r in sorted(rows, key=lambda r: r["name"]):
            f.write("\t".join(cell(r[c]) for c in COLUMNS) + "\n")


def read_tsv(path):
    """Rows of a results.tsv (name, family and outcome are all that --compare needs)."""
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise InputError(f"--compare: cannot read {path}: {e.strerror}")
    header = lines[0].split("\t") if lines else []
    if not {"name", "family", "outcome"} <= set(header):
        raise InputError(f"{path}:1: expected a results.tsv header with name, family, outcome")
    return [dict(zip(header, line.split("\t"))) for line in lines[1:] if line]


def pct(x):
    return "n/a" if math.isnan(x) else f"{100 * x:.1f} %"


def num(x, digits=3):
    return "n/a" if math.isnan(x) else f"{x:.{digits}f}"


def classes(d):
    return ", ".join(f"{k} {v}" for k, v in d.items()) or "none"


def format_figures(label, s, unit="worlds"):
    lo, hi = s["success_ci95"]
    lines = [f"{label}: {s['worlds']} {unit}, {s['with_way']} with a way on the ground truth"
             + (f", {s['errors']} could not run" if s["errors"] else ""),
             f"  success     {s['success']}/{s['with_way']} = {pct(s['success_rate'])} "
             f"(95 % interval {pct(lo)} - {pct(hi)}), reached the goal {s['reached_goal']}",
             f"  collisions  {s['worlds_with_collisions']} {unit}",
             f"  mean SPL    {num(s['mean_spl'])}",
             f"  failures    {classes(s['failures'])}",
             f"  no way      {s['without_way']} {unit}, ended: {classes(s['without_way_ends'])}",
             f"  FOG         mean traversability {num(s['mean_fog_traversability'])}, "
             f"mean unsafe cells {num(s['mean_fog_unsafe_cells'], 1)}"]
    return lines


def format_summary(summary, changes=None, unit="worlds"):
    lines = format_figures("all", summary["all"], unit)
    for family, s in summary["families"].items():
        lines += format_figures(family, s, unit)
    if changes is not None:
        lines.append(f"changed outcome: {len(changes)} {unit}"
                     f" ({sum(n == 'success' for _, _, n in changes)} now succeed,"
                     f" {sum(o == 'success' for _, o, _ in changes)} no longer)")
        lines += [f"  {name}: {old} -> {new}" for name, old, new in changes]
    return "\n".join(lines) + "\n"


def json_safe(x):
    """NaN becomes null, so summary.json is strict JSON."""
    if isinstance(x, float) and math.isnan(x):
        return None
    if isinstance(x, dict):
        return {k: json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [json_safe(v) for v in x]
    return x


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    parser.add_argument("--split", choices=["eval", "dev"], default="eval")
    parser.add_argument("--fognav", default=os.path.join(ROOT, "build", "bin", "fognav"))
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--compare", metavar="OLD_DIR")
    parser.add_argument("--families", help="comma-separated, default all in the seeds file")
    parser.add_argument("--count", type=int, help="worlds in all, default every seed set's")
    parser.add_argument("--seeds", default=os.path.join(ROOT, "scripts", "seeds.json"))
    parser.add_argument("--noise-seeds", type=int, default=1, metavar="K",
                        help="run worlds with odometry noise under K noise seeds (default 1)")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")
    if args.noise_seeds < 1:
        parser.error("--noise-seeds must be at least 1")
    if args.count is not None and args.count < 1:
        parser.error("--count must be at least 1")
    return args


def main(argv=None):
    args = parse_args(argv)
    try:
        families = args.families.split(",") if args.families else None
        sets = load_seeds(args.seeds, args.split, families)
        old_rows = read_tsv(os.path.join(args.compare, "results.tsv")) if args.compare else None
        if not (os.path.isfile(args.fognav) and os.access(args.fognav, os.X_OK)):
            raise InputError(f"--fognav: {args.fognav} is not an executable (build it first: "
                             "scripts/setup.sh build)")
    except InputError as e:
        print(f"evaluate: {e}", file=sys.stderr)
        return 2
    os.makedirs(args.out_dir, exist_ok=True)
    worlds = with_noise_seeds(generate(args.out_dir, sets, args.count), args.noise_seeds)
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_world, args.fognav, args.out_dir, *w) for w in worlds]
        for future in concurrent.futures.as_completed(futures):
            row, ran = future.result()
            rows.append(row)
            note = f"{row['cycles']} cycles, {row['wall_time_s']:.0f} s" if ran else "kept"
            if row["outcome"] == "error":
                note = row["failure_detail"]
            print(f"[{len(rows)}/{len(worlds)}] {row['name']}: {row['outcome']} ({note})",
                  file=sys.stderr, flush=True)
    summary = summarize(rows)
    changes = compare(rows, old_rows) if old_rows is not None else None
    write_tsv(os.path.join(args.out_dir, "results.tsv"), rows)
    out = dict(summary, split=args.split, seeds=os.path.relpath(args.seeds, ROOT),
               noise_seeds=args.noise_seeds)
    if changes is not None:
        out["changed"] = [{"name": n, "old": o, "new": w} for n, o, w in changes]
    with open(os.path.join(args.out_dir, "summary.json"), "w") as f:
        json.dump(json_safe(out), f, indent=2, sort_keys=True)
        f.write("\n")
    sys.stdout.write(format_summary(summary, changes,
                                    "runs" if args.noise_seeds > 1 else "worlds"))
    return 1 if summary["all"]["errors"] else 0


if __name__ == "__main__":
    sys.exit(main())

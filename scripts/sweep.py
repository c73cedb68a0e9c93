#!/usr/bin/env python3
"""Runs fognav on many scenarios side by side and tabulates the results.

Usage: scripts/sweep.py OUT_DIR SCENARIO.yaml... [--perceive] [--fognav PATH] [--jobs N]
                        [--compare OLD_DIR]

Missions (default): each runs as `fognav run SCENARIO --out OUT_DIR/NAME --quiet`;
OUT_DIR/results.tsv gets a row per mission (exit code, success, failure, detail, SPL, cycles,
collisions, the end map's FOG traversability and unsafe cells) and the summary counts the passes (exit code 0). Missions whose world has no way
on the ground-truth map (optimal path length 0) are counted apart.
--perceive: each runs `fognav perceive` instead (the start look-around, scored against ground
truth); the rows hold segmentation accuracy, coverage and correct detections and the FOG
scores (docs/scores.md), and the summary their means.
--compare lists the scenarios whose outcome differs from an earlier sweep's results.tsv.
OUT_DIR/index.html shows the summary and a table of the worlds (sorted by a click on a column's
head), each with a thumbnail of its map that links to its report.html.
Only the standard library is used.
"""
import argparse
import concurrent.futures
import html
import json
import os
import subprocess
import sys

MISSION_COLUMNS = ["name", "exit", "success", "failure", "detail", "spl", "cycles", "collisions",
                   "traversability", "unsafe"]
PERCEIVE_COLUMNS = ["name", "exit", "accuracy", "coverage", "correct", "surfaces", "fog_accuracy",
                    "fog_cells", "traversability", "unsafe"]


def run_one(fognav, scenario, out_root, perceive):
    name = os.path.splitext(os.path.basename(scenario))[0]
    out = os.path.join(out_root, name)
    row = {c: "" for c in MISSION_COLUMNS + PERCEIVE_COLUMNS}
    row.update(name=name, optimal="", wall_time="")
    command = [fognav, "perceive", scenario, "--out", out] if perceive else \
        [fognav, "run", scenario, "--out", out, "--quiet"]
    report_path = os.path.join(out, "perception.json" if perceive else "report.json")
    if os.path.exists(report_path):
        os.remove(report_path)  # a run that writes none must not show an earlier sweep's
    try:
        proc = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              text=True)
    except OSError as error:
        row["detail"] = str(error)[:60]
        return row
    row["exit"] = proc.returncode
    try:
        with open(report_path) as f:
            report = json.load(f)
    except (OSError, ValueError):
        row["detail"] = (proc.stderr.strip().splitlines() or ["no report"])[-1][:60]
        return row
    fog = report.get("fog", {})  # docs/scores.md
    if fog:
        row.update(traversability=f"{fog.get('traversability', 0):.4f}",
                   unsafe=fog.get("unsafe_cells", ""))
    if perceive:
        seg = report.get("segmentation", {})
        row.update(accuracy=f"{seg.get('accuracy', 0):.4f}",
                   coverage=f"{seg.get('coverage', 0):.4f}", correct=seg.get("correct", ""), surfaces=seg.get("truth_surfaces", ""),
                   fog_accuracy=f"{report.get('fog_accuracy', 0):.4f}",
                   fog_cells=report.get("fog_observed_cells", ""))
    else:
        row.update(success=report.get("success"), failure=report.get("failure") or "",
                   detail=report.get("failure_detail") or "", spl=f"{report.get('spl', 0):.3f}",
                   cycles=report.get("cycles"), collisions=report.get("collisions"),
                   optimal=report.get("optimal_path_length", 0),
                   wall_time=f"{report.get('wall_time_s', 0):.1f}")
    return row


def read_results(path):
    with open(path) as f:
        header = f.readline().rstrip("\n").split("\t")
        return {r["name"]: r for r in (dict(zip(header, line.rstrip("\n").split("\t")))
                                       for line in f)}


def mean(rows, key):
    values = [float(r[key]) for r in rows if r[key] != ""]
    return sum(values) / max(1, len(values))


# sorts the table by the clicked column, numbers as numbers; a second click reverses
SORT_SCRIPT = """
document.querySelectorAll('th').forEach((th, column) => th.addEventListener('click', () => {
  const body = th.closest('table').tBodies[0];
  const up = th.dataset.order !== 'up';
  th.dataset.order = up ? 'up' : 'down';
  const key = row => row.cells[column].dataset.sort ?? row.cells[column].textContent;
  const rows = Array.from(body.rows).sort((a, b) => {
    const x = key(a), y = key(b), nx = parseFloat(x), ny = parseFloat(y);
    const order = !isNaN(nx) && !isNaN(ny) ? nx - ny : x.localeCompare(y);
    return up ? order : -order;
  });
  rows.forEach(row => body.appendChild(row));
}));
"""


def write_index(out_dir, rows, summary, perceive):
    """OUT_DIR/index.html: the summary, then a sortable table of the worlds with thumbnails."""
    if perceive:
        columns = [("world", "name"), ("exit", "exit"), ("segmentation accuracy", "accuracy"),
                   ("coverage", "coverage"), ("FOG traversability", "traversability"),
                   ("unsafe cells", "unsafe"), ("FOG six-type accuracy", "fog_accuracy")]
        thumbnail = "maps/plan.png"
    else:
        columns = [("world", "name"), ("outcome", "outcome"), ("failure", "failure"),
                   ("detail", "detail"), ("SPL", "spl"), ("cycles", "cycles"),
                   ("wall time [s]", "wall_time"), ("FOG traversability", "traversability"),
                   ("unsafe cells", "unsafe")]
        thumbnail = "maps/mission.png"
    e = html.escape
    lines = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             f"<title>fognav {e(summary)}</title>",
             "<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
             "td,th{border:1px solid #ddd;padding:2px 8px;text-align:left}"
             "th{background:#f4f4f4;cursor:pointer}.bad{color:#c62828}.ok{color:#1a7f37}"
             "img{max-width:240px;max-height:120px}</style></head><body>",
             f"<h1>fognav sweep</h1><p id=\"summary\">{e(summary)}</p>",
             "<p>Click a column's head to sort by it.</p>",
             "<table><thead><tr>" + "".join(f"<th>{e(c)}</th>" for c, _ in columns) +
             "<th>map</th></tr></thead><tbody>"]
    for r in rows:
        page = f"{r['name']}/report.html"
        cells = []
        for _, key in columns:
            value = r.get(key, "")
            if key == "name":
                cells.append(f'<td><a href="{e(page)}">{e(str(value))}</a></td>')
            elif key == "outcome":
                cls = "ok" if value == "success" else "bad"
                cells.append(f'<td class="{cls}">{e(str(value))}</td>')
            else:
                cells.append(f"<td>{e(str(value))}</td>")
        image = os.path.join(r["name"], thumbnail)
        if os.path.exists(os.path.join(out_dir, image)):
            cells.append(f'<td><a href="{e(page)}"><img src="{e(image)}" alt="map of '
                         f'{e(r["name"])}"></a></td>')
        else:
            cells.append("<td></td>")
        lines.append("<tr>" + "".join(cells) + "</tr>")
    lines += ["</tbody></table>", f"<script>{SORT_SCRIPT}</script>", "</body></html>"]
    with open(os.path.join(out_dir, "index.html"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    parser.add_argument("scenarios", nargs="+")
    parser.add_argument("--perceive", action="store_true",
                        help="run `fognav perceive` and tabulate its scores")
    parser.add_argument("--fognav", default=os.path.join(os.path.dirname(__file__), "..", "build",
                                                         "bin", "fognav"))
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--compare", metavar="OLD_DIR")
    args = parser.parse_args()
    if not os.access(args.fognav, os.X_OK):
        sys.exit(f"sweep: {args.fognav} is not an executable (build first: scripts/setup.sh)")
    names = [os.path.splitext(os.path.basename(s))[0] for s in args.scenarios]
    if len(set(names)) != len(names):
        sys.exit("sweep: two scenarios share a file name; their outputs would overwrite")
    os.makedirs(args.out_dir, exist_ok=True)

    rows = []
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        futures = [pool.submit(run_one, args.fognav, s, args.out_dir, args.perceive)
                   for s in args.scenarios]
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            row = future.result()
            rows.append(row)
            print(f"[{done}/{len(futures)}] {row['name']}: exit {row['exit']} "
                  f"{row['failure'] or 'ok'} {row['detail']}", file=sys.stderr, flush=True)
    rows.sort(key=lambda r: r["name"])
    columns = PERCEIVE_COLUMNS if args.perceive else MISSION_COLUMNS
    with open(os.path.join(args.out_dir, "results.tsv"), "w") as f:
        f.write("\t".join(columns) + "\n")
        for r in rows:
            f.write("\t".join(str(r[c]) for c in columns) + "\n")

    if args.perceive:
        done = [r for r in rows if r["exit"] == 0]
        for r in rows:
            if r["exit"] != 0:
                print(f"FAIL {r['name']}: exit {r['exit']} {r['detail']}")
        summary = (f"sweep: {len(done)}/{len(rows)} perceived; mean segmentation accuracy "
                   f"{mean(done, 'accuracy'):.4f}, coverage {mean(done, 'coverage'):.4f}, "
                   f"FOG traversability {mean(done, 'traversability'):.4f}, unsafe cells "
                   f"{sum(int(r['unsafe'] or 0) for r in done)}, six-type accuracy "
                   f"{mean(done, 'fog_accuracy'):.4f}")
    else:
        valid = [r for r in rows if r["optimal"] != 0]
        passed = [r for r in valid if r["exit"] == 0]
        for r in valid:
            if r["exit"] != 0:
                print(f"FAIL {r['name']}: exit {r['exit']} {r['failure']} {r['detail']}")
        summary = (f"sweep: {len(passed)}/{len(valid)} passed, mean SPL "
                   f"{mean(valid, 'spl'):.3f}; {len(rows) - len(valid)} without a way on the "
                   f"ground truth")
        for r in rows:
            r["outcome"] = {0: "success", 1: "failed"}.get(r["exit"], f"error (exit {r['exit']})")
    print(summary)
    write_index(args.out_dir, rows, summary, args.perceive)
    if args.compare:
        old = read_results(os.path.join(args.compare, "results.tsv"))
        key = "fog_accuracy" if args.perceive else "failure"
        for r in rows:
            before = old.get(r["name"])
            if before and (before["exit"] != str(r["exit"]) or before[key] != str(r[key])):
                print(f"CHANGED {r['name']}: exit {before['exit']} {before[key]} -> "
                      f"exit {r['exit']} {r[key]}")


if __name__ == "__main__":
    main()

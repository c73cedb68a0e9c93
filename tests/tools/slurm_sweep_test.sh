#!/usr/bin/env bash
# `fognav sweep --backend slurm` on a real one-node cluster (scripts/slurm-local.sh): 4 small
# worlds x 2 seeds give the same results as the local backend, report for report but for the
# timings; tasks cancelled with scancel, running or pending, are reported by run name with their
# state, and the rerun does their runs alone. Exit 77 (skipped) where slurm-wlm, munge or python3
# is not installed.
# Usage: slurm_sweep_test.sh FOGNAV_BINARY WORK_DIR
set -euo pipefail
fognav="$1"
work="$2"
root="$(cd "$(dirname "$0")/../.." && pwd)"
if ! command -v python3 > /dev/null; then echo "SKIPPED: python3 is not installed"; exit 77; fi
rm -rf "$work"
mkdir -p "$work/worlds"
status=0
"$root/scripts/slurm-local.sh" start "$work/cluster" || status=$?
if [ "$status" -eq 77 ]; then echo "SKIPPED: slurm-wlm or munge is not installed"; exit 77; fi
[ "$status" -eq 0 ] || exit 1
trap '"$root/scripts/slurm-local.sh" stop "$work/cluster"' EXIT
export SLURM_CONF="$work/cluster/slurm.conf"

# small worlds of about a second a mission, with odometry noise so the seeds matter; the last
# one runs out of cycles
world() {  # NAME GOAL_X GOAL_Y MAX_CYCLES
  cat > "$work/worlds/$1.yaml" << EOF
name: $1
robot: {start: [0.0, 0.0, 0.0]}
goal: {position: [$2, $3], tolerance: 0.2}
world: {floor: [2.0, 1.6], floor_center: [0.5, 0.0]}
odometry_noise: {xy: 0.01, yaw_deg: 1.0}
limits: {max_cycles: $4, max_steps: 200}
expect: {reach_goal: true}
EOF
}
world ahead 0.8 0.0 40
world left 0.7 0.3 40
world right 0.7 -0.3 40
world short 0.8 0.0 1

seconds() { date +%s.%N; }
t0="$(seconds)"
"$fognav" sweep "$work/worlds" --seeds 2 --jobs 2 --out "$work/local" > "$work/local.log" 2>&1 ||
  [ $? -eq 1 ]
t1="$(seconds)"
"$fognav" sweep "$work/worlds" --seeds 2 --backend slurm --out "$work/slurm" \
  > "$work/slurm.log" 2>&1 || [ $? -eq 1 ]
t2="$(seconds)"
awk -v a="$t0" -v b="$t1" -v c="$t2" \
  'BEGIN { printf "8 runs: local (2 workers) %.1f s, slurm %.1f s\n", b - a, c - b }'

# the same results, report for report, without the timings
python3 - "$work/local" "$work/slurm" << 'EOF'
import json, os, sys
local, slurm = sys.argv[1], sys.argv[2]
def table(d):
    with open(os.path.join(d, "results.tsv")) as f:
        rows = [line.rstrip("\n").split("\t") for line in f]
    drop = rows[0].index("wall_time_s")
    return [r[:drop] + r[drop + 1:] for r in rows]
def report(d, name):
    with open(os.path.join(d, "runs", name, "report.json")) as f:
        r = json.load(f)
    for key in ("wall_time_s", "timing_ms"):
        r.pop(key)
    return r
a, b = table(local), table(slurm)
assert len(a) == 9, f"expected 8 runs, got {len(a) - 1}"
assert a == b, f"the tables differ:\n{a}\n{b}"
for row in a[1:]:
    assert report(local, row[0]) == report(slurm, row[0]), f"{row[0]}: the reports differ"
outcome = a[0].index("outcome")
assert [r[outcome] for r in a[1:]].count("success") == 6, a
print("slurm = local: 8 runs, report for report")
EOF

# tasks cancelled with scancel, one running and one pending: reported by run name with their
# Slurm state, redone by the rerun; a_far (a longer mission) is task 0, right task 3
mkdir -p "$work/cancel_worlds"
cp "$work/worlds/"*.yaml "$work/cancel_worlds/"
cat > "$work/cancel_worlds/a_far.yaml" << EOF
name: a_far
robot: {start: [0.0, 0.0, 0.0]}
goal: {position: [1.8, 0.0], tolerance: 0.2}
world: {floor: [3.2, 1.6], floor_center: [1.0, 0.0]}
limits: {max_cycles: 80, max_steps: 400}
expect: {reach_goal: true}
EOF
out="$work/cancelled"
"$fognav" sweep "$work/cancel_worlds" --out "$out" --backend slurm > "$work/cancelled.log" 2>&1 &
sweep=$!
job=""
for _ in $(seq 300); do
  job="$(sed -n 's/^sweep: submitted Slurm job \([0-9]*\),.*/\1/p' "$work/cancelled.log")"
  [ -n "$job" ] && break
  sleep 0.1
done
[ -n "$job" ] || { cat "$work/cancelled.log"; exit 1; }
scancel "${job}_3"
for _ in $(seq 300); do
  [ "$(squeue -h -j "${job}_0" -o '%T' 2> /dev/null)" = RUNNING ] && break
  sleep 0.1
done
sleep 0.5  # a_far's mission under way
scancel "${job}_0"
code=0
wait "$sweep" || code=$?
cat "$work/cancelled.log"
[ "$code" -eq 1 ] || { echo "expected exit code 1, got $code"; exit 1; }
grep -q "^NOT PASSED a_far: error (Slurm task ${job}_0 CANCELLED" "$work/cancelled.log"
grep -q "^NOT PASSED right: error (Slurm task ${job}_3 CANCELLED" "$work/cancelled.log"
grep -q "<error type=" "$out/junit.xml"
"$fognav" sweep "$work/cancel_worlds" --out "$out" --backend slurm > "$work/resumed.log" 2>&1 ||
  [ $? -eq 1 ]
cat "$work/resumed.log"
grep -q "sweep: 5 runs, 3 finished before, 2 to run (slurm)" "$work/resumed.log"
grep -q ", 2 tasks of up to 1 runs" "$work/resumed.log"
grep -q "^a_far	.*	success	" "$out/results.tsv"
grep -q "^right	.*	success	" "$out/results.tsv"
echo "the cancelled tasks were reported and redone"

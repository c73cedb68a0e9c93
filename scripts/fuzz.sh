#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz/ with clang, AddressSanitizer and UBSan
# (build-fuzz/), then runs each for SECONDS (default 60) from its seed corpus: the shipped
# scenarios and tests/fuzz/scenario_seeds/ for the loader, inputs made from the perception
# tests' analytic scenes for the rest.
# A finding (crash, sanitizer report, uncaught exception, leak, timeout) fails the run; its input
# is saved in build-fuzz/findings/ and printed in base64. What the fuzzers found new stays in
# build-fuzz/corpus/, so a later run goes on from there.
# Usage: scripts/fuzz.sh [SECONDS [FUZZER...]]   (FUZZER: scenario segmentation stereo map_update)
# FUZZ_SEED=N fixes libFuzzer's random seed (CI: the same inputs for the same commit, so a run
# fails or passes alike every time); unset, each run draws its own.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
fuzzers=("$@")
((${#fuzzers[@]})) || fuzzers=(scenario segmentation stereo map_update)

scripts/setup.sh build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFOGNAV_FUZZ=ON \
  -DCMAKE_CXX_COMPILER=clang++-14
out=build-fuzz
rm -rf "$out/seeds"
"$out/bin/make_seeds" "$out/seeds" > /dev/null
mkdir -p "$out/seeds/scenario" "$out/findings"
cp scenarios/*.yaml tests/fuzz/scenario_seeds/*.yaml "$out/seeds/scenario/"

failed=()
for name in "${fuzzers[@]}"; do
  mkdir -p "$out/corpus/$name"
  rm -f "$out/findings/$name-"*
  log="$out/fuzz_$name.log"
  echo "fuzz: $name for ${seconds} s"
  # -timeout: an input that takes longer is a finding (a hang); the first folder takes new inputs
  if ASAN_OPTIONS=detect_leaks=1 "$out/bin/${name}_fuzz" -max_total_time="$seconds" \
      -timeout=25 -print_final_stats=1 -artifact_prefix="$out/findings/$name-" \
      ${FUZZ_SEED:+-seed="$FUZZ_SEED"} \
      "$out/corpus/$name" "$out/seeds/$name" > "$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz: $name: ${runs:-?} executions, no finding"
  else
    failed+=("$name")
    tail -n 40 "$log"
    for finding in "$out/findings/$name-"*; do
      [ -f "$finding" ] || continue
      echo "fuzz: $name: finding $finding (base64):"
      base64 "$finding"
    done
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]} (inputs in $out/findings/)"
  exit 1
fi

#!/usr/bin/env bash
# Builds fognav and runs every test: the Release build (all tests, missions included), then
# the ASan + UBSan build (every test but the whole missions, which the Release run covers).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"

scripts/setup.sh build
(cd build && DISPLAY= ctest --output-on-failure -j"$jobs")

scripts/setup.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFOGNAV_SANITIZE=ON
(cd build-asan && ctest --output-on-failure -j"$jobs" -LE mission)

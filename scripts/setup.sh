#!/usr/bin/env bash
# Installs fognav's Debian packages (only when one is missing), then configures and builds.
# Usage: scripts/setup.sh [BUILD_DIR [extra cmake args...]]   (default build/, Release)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(cmake g++ make libmujoco-dev libosmesa6-dev libeigen3-dev libopencv-dev
          libopencv-contrib-dev libgtest-dev libbenchmark-dev libyaml-cpp-dev
          nlohmann-json3-dev libcli11-dev python3
          pybind11-dev python3-dev python3-numpy python3-pytest)  # the Python module, its tests
# the fuzzers' build (scripts/fuzz.sh) needs clang and its libFuzzer
if [[ " $* " == *" -DFOGNAV_FUZZ=ON "* ]]; then packages+=(clang-14 libclang-rt-14-dev); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build_dir="${1:-build}"
shift || true
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" > /dev/null
fi
cmake --build "$build_dir" -j"$(nproc)"

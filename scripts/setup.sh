#!/usr/bin/env bash
# Installs every Debian package poundbench uses, then configures and builds it.
#   scripts/setup.sh [--build-dir DIR] [--build-type TYPE] [--sanitize] [--werror]
# Safe to run again: packages already installed are not fetched again.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
build_type=Release
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build_dir=$2; shift 2 ;;
    --build-type) build_type=$2; shift 2 ;;
    --sanitize) extra+=(-DPOUNDBENCH_SANITIZE=ON); shift ;;
    --werror) extra+=(-DPOUNDBENCH_WERROR=ON); shift ;;
    *) echo "setup.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done

packages=(
  g++ cmake make ninja-build pkg-config lld
  libeigen3-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev
  libode-dev libbullet-dev libsiconos-kernel-dev libsundials-dev
  libmujoco-dev libgl-dev libglx-dev libopengl-dev libqhull-dev
  libdart-dev libsimbody-dev
  libopenmpi-dev openmpi-bin
  python3 python3-matplotlib python3-numpy python3-jsonschema
  python3-scipy python3-dev pybind11-dev
  chromium chromium-driver python3-selenium
  universal-ctags
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
fi

# A new build directory (one already configured keeps its settings) is built by Ninja, which
# compiles any target's files while others link where make builds one target at a time, and as
# a unity build: CMake compiles each target's files eight to a translation unit, so the headers
# they share (Eigen, GoogleTest, CLI11, the engines') are parsed once per eight files, not once
# per file: the larger part of a fresh build's time (README, Development). A developer who
# edits one file at a time may configure a directory of their own with -DCMAKE_UNITY_BUILD=OFF.
[ -f "$build_dir/CMakeCache.txt" ] || extra+=(-G Ninja -DCMAKE_UNITY_BUILD=ON)
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" "${extra[@]}" > /dev/null
cmake --build "$build_dir" -j "$(nproc)"

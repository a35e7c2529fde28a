#!/usr/bin/env bash
# One entry point for a fresh clone: install the Debian packages (fast when present), configure a
# Release build in build/ (once), and build it. Extra arguments go to the CMake configure step, e.g.
#   cmake/setup.sh -DRIGIDLAB_SANITIZE=ON      (builds into build-sanitize/ instead)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/cmake/install_deps.sh"

build_dir="$root/build"
for arg in "$@"; do
  [ "$arg" = "-DRIGIDLAB_SANITIZE=ON" ] && build_dir="$root/build-sanitize"
done
jobs=$(nproc 2>/dev/null || echo 2)

if [ ! -f "$build_dir/CMakeCache.txt" ] || [ $# -gt 0 ]; then
  cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
fi
cmake --build "$build_dir" -j "$jobs"

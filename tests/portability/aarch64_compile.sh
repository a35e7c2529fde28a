#!/bin/sh
# Compile-only check that the physics core builds for aarch64 (docs/building.md "Other
# processors"): every engine/core source through the cross compiler's front end and semantic
# checks (-fsyntax-only: target attributes, builtins and intrinsics that only x86 has fail here),
# with the project's warnings as errors. The cross compiler is Debian's g++-aarch64-linux-gnu,
# which cmake/install_deps.sh installs; without it the check fails rather than pass unseen.
#   aarch64_compile.sh REPOSITORY
set -eu
root=$1
cxx=${AARCH64_CXX:-aarch64-linux-gnu-g++}
if ! command -v "$cxx" >/dev/null 2>&1; then
  echo "aarch64 compile check: $cxx not found (cmake/install_deps.sh installs g++-aarch64-linux-gnu)" >&2
  exit 1
fi
count=$(ls "$root"/engine/core/src/*.cpp | wc -l)
ls "$root"/engine/core/src/*.cpp | xargs -P 2 -n 4 "$cxx" -std=c++20 -fsyntax-only -Wall -Wextra -Werror \
  -I"$root/engine/core/include" -I"$root/engine/core/src" -I/usr/include/eigen3
echo "aarch64: the $count sources of engine/core compile ($("$cxx" -dumpmachine), $("$cxx" -dumpversion))"

#!/usr/bin/env bash
# Builds the peer programs and runs the peer scenes, one JSON line per configuration (stdout).
# usage: ./run.sh [--build-only] [OUTDIR]   (OUTDIR default /tmp/rigidlab-peers)
#   --build-only   build box2d_bench and chipmunk_bench in OUTDIR and stop (rigidlab bench --compare
#                  does this, then runs them itself alternated with rigidlab)
# Run it in the same session as rigidlab's own benchmark and compare ratios, not absolute times
# (shared machines are noisy).
# It installs nothing: without the peers' Debian packages (libbox2d-dev, libchipmunk-dev; their
# headers are what the compiler, $CXX or g++, is asked for) it names the missing ones and the
# command that installs them on standard error and exits with 3.
set -eu
build_only=0
if [ "${1:-}" = --build-only ]; then build_only=1; shift; fi
cd "$(dirname "$0")"
missing=""
for need in libbox2d-dev:box2d/box2d.h libchipmunk-dev:chipmunk/chipmunk.h; do
  # shellcheck disable=SC2086  # CXX may carry options ("g++ -m32")
  echo "#include <${need#*:}>" | ${CXX:-g++} -x c++ -E - >/dev/null 2>&1 || missing="$missing ${need%%:*}"
done
if [ -n "$missing" ]; then
  echo "peers: missing Debian packages:$missing" >&2
  echo "peers: install them with: sudo apt-get install$missing" >&2
  exit 3
fi
B=${1:-/tmp/rigidlab-peers}; mkdir -p "$B"
cp ./*.h ./*.cpp Makefile "$B"/ && cd "$B"
make -s CXXFLAGS="-O2" >/dev/null
[ "$build_only" = 1 ] && exit 0
for e in box2d_bench chipmunk_bench; do
  for n in 20 40 100; do ./$e pyramid --n=$n --reps=3; done
  for n in 10 20; do ./$e stack --n=$n --reps=3; done
  for n in 1000 4000; do ./$e rain --n=$n --reps=3; done
  ./$e massratio --top=heavy --heavy-half=0.5 --heavy-mass=100 --reps=1
  ./$e bullet --n=1 --reps=1
done 2>>"$B/stderr.log"

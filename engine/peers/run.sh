#!/usr/bin/env bash
# Builds the peer programs and runs the peer scenes, one JSON line per configuration (stdout).
# usage: ./run.sh [--build-only] [OUTDIR]   (OUTDIR default /tmp/rigidlab-peers)
#   --build-only   build box2d_bench and chipmunk_bench in OUTDIR and stop (rigidlab bench --compare
#                  does this, then runs them itself alternated with rigidlab)
# Run it in the same session as rigidlab's own benchmark and compare ratios, not absolute times
# (shared machines are noisy).
set -eu
build_only=0
if [ "${1:-}" = --build-only ]; then build_only=1; shift; fi
cd "$(dirname "$0")"
dpkg -s libbox2d-dev libchipmunk-dev >/dev/null 2>&1 || \
  { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q libbox2d-dev libchipmunk-dev; } >/dev/null
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

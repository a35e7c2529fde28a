#!/bin/sh
# The interface of engine/peers/run.sh that `rigidlab bench --compare` uses: --build-only OUTDIR
# puts the two peer programs in OUTDIR; here both are fake_engine.sh (bench_cli.cmake).
set -eu
[ "$1" = --build-only ] || { echo "fake peers: only --build-only" >&2; exit 2; }
mkdir -p "$2"
cp "$(dirname "$0")/fake_engine.sh" "$2/box2d_bench"
cp "$(dirname "$0")/fake_engine.sh" "$2/chipmunk_bench"

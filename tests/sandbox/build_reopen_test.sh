#!/usr/bin/env bash
# The world build_test.sh made with the tools and saved, opened headless by rigidlab itself:
# `rigidlab run` takes 60 steps of it and reports its 3 bodies. The file calls the scene API of
# shapes and joints (world:add_revolute, body:add_shape, ...). $5: build_test.sh's scratch
# directory.
source "$(dirname "$0")/lib.sh"
saved=$5/build_saved.lua
[ -f "$saved" ] || { fail "no $saved: build_test.sh did not save"; finish; }
if ! out=$("$RIGIDLAB" run "$saved" --steps 60 --json 2> "$WORK/stderr.txt"); then
  fail "rigidlab run $saved failed: $(cat "$WORK/stderr.txt")"
  finish
fi
echo "$out" > "$WORK/run.json"
[ "$(grep -o '"name"' "$WORK/run.json" | wc -l)" -ge 3 ] || fail "expected 3 bodies in the run's JSON: $out"
grep -q '"crate"' "$WORK/run.json" || fail "the crate is missing from the run's JSON"
finish

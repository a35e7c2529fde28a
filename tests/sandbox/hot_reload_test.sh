#!/usr/bin/env bash
# Hot reload as a user sees it: the sandbox runs scenes/shapes.lua (copied to a scratch directory);
# the scene is rewritten as most editors save (temporary file + rename) with the ball moved from
# (2, 1) to (2, -1). Checks: the `reloaded <file>` line within 200 ms of the rename, and a final
# picture with the ball at its new place and not at the old one (and different from a picture of
# the original scene).
source "$(dirname "$0")/lib.sh"
require_xvfb
# The sanitizer build runs 2-3x slower: it checks what is reloaded, the Release build the 200 ms.
LIMIT_MS=$(( 200 * ${RIGIDLAB_RELOAD_LIMIT_SCALE:-1} ))

scene="$WORK/scene.lua"
cp "$SCENES/shapes.lua" "$scene"
start_sandbox "$scene" 2 "$WORK/before.png"
wait_sandbox
[ "$SANDBOX_STATUS" -eq 0 ] || fail "first run: exit status $SANDBOX_STATUS"

start_sandbox "$scene" 240 "$WORK/after.png"  # 4 s at the 60 Hz frame cap
if ! wait_for " opened $scene" 1 10000 >/dev/null; then
  fail "the sandbox did not open the scene within 10 s"
  stop_sandbox
  finish
fi
sleep 0.3
sed 's/position = {2, 1}/position = {2, -1}/' "$scene" > "$WORK/moved.lua"
written=$(now_ms)
atomic_write "$scene" < "$WORK/moved.lua"
if arrived=$(wait_for " reloaded $scene" 1 2000); then
  latency=$((arrived - written))
  echo "reload latency: $latency ms (limit $LIMIT_MS ms)"
  [ "$latency" -le "$LIMIT_MS" ] || fail "reloaded after $latency ms, more than $LIMIT_MS ms"
else
  fail "no 'reloaded $scene' line within 2 s"
fi
wait_sandbox
[ "$SANDBOX_STATUS" -eq 0 ] || fail "exit status $SANDBOX_STATUS"
[ "$(count_lines ' reloaded ')" -eq 1 ] || fail "expected exactly one reload, got $(count_lines ' reloaded ')"

expect_dynamic "$WORK/before.png" 764 308 "before: ball at (2, 1)"
expect_dynamic "$WORK/after.png" 764 452 "after: ball at (2, -1)"
expect_pixel "$WORK/after.png" 764 308 "$BACKGROUND" "after: nothing left at (2, 1)"
expect_pixel "$WORK/after.png" 496 288 "$STATIC" "after: the static box is still there"
# The world area (between the panels) changed substantially: a whole ball moved.
changed=$("$PNG_CHECK" diff "$WORK/before.png" "$WORK/after.png" 300 100 940 640)
echo "pixels changed in the world area: $changed"
[ "$changed" -ge 5000 ] || fail "only $changed pixels changed"
finish

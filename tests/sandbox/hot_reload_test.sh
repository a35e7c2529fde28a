#!/usr/bin/env bash
# Hot reload as a user sees it: the sandbox runs scenes/shapes.lua (copied to a scratch directory);
# the scene is rewritten as most editors save (temporary file + rename) with the ball moved from
# (2, 1) to (2, -1). Checks: the `reloaded <file>` line within 200 ms of the rename, and a final
# picture with the ball at its new place and not at the old one (and different from a picture of
# the original scene).
# The latency is a wall-clock figure on a shared machine: a busy neighbour (another test, a compile)
# can delay the sandbox's frame or this script's own clock readings. A reload later than the limit
# is therefore measured again (ball back, then moved again) up to three times in all, and the best
# must be within the limit: a watcher or session that is really slow misses it every time.
source "$(dirname "$0")/lib.sh"
require_xvfb
# The sanitizer build runs 2-3x slower: it checks what is reloaded, the Release build the 200 ms.
LIMIT_MS=$(( 200 * ${RIGIDLAB_RELOAD_LIMIT_SCALE:-1} ))

scene="$WORK/scene.lua"
cp "$SCENES/shapes.lua" "$scene"
start_sandbox "$scene" 2 "$WORK/before.png"
wait_sandbox
[ "$SANDBOX_STATUS" -eq 0 ] || fail "first run: exit status $SANDBOX_STATUS"

start_sandbox "$scene" 360 "$WORK/after.png"  # 6 s at the 60 Hz frame cap
if ! wait_for " opened $scene" 1 10000 >/dev/null; then
  fail "the sandbox did not open the scene within 10 s"
  stop_sandbox
  finish
fi
sed 's/position = {2, 1}/position = {2, -1}/' "$scene" > "$WORK/moved.lua"
cp "$scene" "$WORK/original.lua"

# save FILE: writes FILE's text into the scene and waits for its reload; sets LATENCY (ms).
reloads=0
save() {
  local written arrived
  sleep 0.3
  written=$(now_ms)
  atomic_write "$scene" < "$1"
  reloads=$((reloads + 1))
  arrived=$(wait_for " reloaded $scene" "$reloads" 2000) || return 1
  LATENCY=$((arrived - written))
}

best=""
latencies=""
for attempt in 1 2 3; do
  if [ "$attempt" -gt 1 ]; then  # put the ball back first (not timed), then move it again
    save "$WORK/original.lua" || { fail "no reload of the original scene within 2 s"; break; }
  fi
  if ! save "$WORK/moved.lua"; then
    fail "no 'reloaded $scene' line within 2 s"
    break
  fi
  latency=$LATENCY
  latencies="$latencies $latency"
  if [ -z "$best" ] || [ "$latency" -lt "$best" ]; then best=$latency; fi
  [ "$latency" -le "$LIMIT_MS" ] && break
done
echo "reload latency: best $best ms of:$latencies (limit $LIMIT_MS ms)"
[ -n "$best" ] && [ "$best" -le "$LIMIT_MS" ] || fail "reloaded after ${best:-?} ms at best, more than $LIMIT_MS ms"
wait_sandbox
[ "$SANDBOX_STATUS" -eq 0 ] || fail "exit status $SANDBOX_STATUS"
[ "$(count_lines ' reloaded ')" -eq "$reloads" ] || fail "expected $reloads reloads (one per save), got $(count_lines ' reloaded ')"

expect_dynamic "$WORK/before.png" 764 308 "before: ball at (2, 1)"
expect_dynamic "$WORK/after.png" 764 452 "after: ball at (2, -1)"
expect_pixel "$WORK/after.png" 764 308 "$BACKGROUND" "after: nothing left at (2, 1)"
expect_pixel "$WORK/after.png" 496 288 "$STATIC" "after: the static box is still there"
# The world area (between the panels) changed substantially: a whole ball moved.
changed=$("$PNG_CHECK" diff "$WORK/before.png" "$WORK/after.png" 300 100 940 640)
echo "pixels changed in the world area: $changed"
[ "$changed" -ge 5000 ] || fail "only $changed pixels changed"
finish

#!/usr/bin/env bash
# Nothing crashes, nothing is lost:
# 1. While the sandbox runs scenes/shapes.lua, the scene is saved with a syntax error, then with an
#    error in PopulateWorld: no reload happens, each failure is reported with file:line, the old
#    world keeps running and is what the final picture shows, under the red error overlay; the
#    exit status is 0.
# 2. A Lua force that fails during the run pauses the simulation and shows the error.
source "$(dirname "$0")/lib.sh"
require_xvfb

scene="$WORK/scene.lua"
cp "$SCENES/shapes.lua" "$scene"
start_sandbox "$scene" 150 "$WORK/broken.png"
if ! wait_for " opened $scene" 1 10000 >/dev/null; then
  fail "the sandbox did not open the scene within 10 s"
  stop_sandbox
  finish
fi
sleep 0.3
# Line 12 loses its closing brace; the ball also moves, so a wrong swap would show.
sed 's/position = {2, 1}, name = "ball"}/position = {2, -1}, name = "ball"/' "$scene" | atomic_write "$scene"
sleep 0.6
grep -q "reload failed: .*scene.lua:1[0-9]:" "$WORK/stderr.txt" || fail "no 'reload failed: …scene.lua:LINE:' message for the syntax error"
cp "$SCENES/shapes.lua" "$WORK/runtime.lua"
sed -i 's/^function PopulateWorld(world)$/function PopulateWorld(world)\n  world:add_circle{radius = 2, position = {2, -1}}\n  error("populate fails")/' "$WORK/runtime.lua"
atomic_write "$scene" < "$WORK/runtime.lua"
sleep 0.6
grep -q "reload failed: .*scene.lua:1[0-9]: .*populate fails" "$WORK/stderr.txt" || fail "no 'reload failed' message for the PopulateWorld error"
wait_sandbox
[ "$SANDBOX_STATUS" -eq 0 ] || fail "exit status $SANDBOX_STATUS"
[ "$(count_lines ' reloaded ')" -eq 0 ] || fail "a broken scene was swapped in"
expect_dynamic "$WORK/broken.png" 764 308 "the old world's ball at (2, 1)"
expect_pixel "$WORK/broken.png" 764 452 "$BACKGROUND" "no new ball at (2, -1)"
expect_pixel "$WORK/broken.png" 496 288 "$STATIC" "the old world's static box"
# The overlay: a dark red panel at the top centre.
read -r r g b <<< "$("$PNG_CHECK" pixel "$WORK/broken.png" 640 12)"
{ [ "$r" -ge 60 ] && [ "$g" -le 40 ] && [ "$b" -le 40 ]; } || fail "no red error overlay at the top (pixel 640,12 is $r $g $b)"

# 2. A force that fails at t = 0.5 s pauses the run: after 2 s of frames the ball is still near x = -2.5.
start_sandbox "$SCENES/failing_force.lua" 120 "$WORK/paused.png"
wait_sandbox
[ "$SANDBOX_STATUS" -eq 0 ] || fail "failing force: exit status $SANDBOX_STATUS"
grep -q "paused: .*failing_force.lua:9: .*this force fails on purpose" "$WORK/stderr.txt" ||
  fail "no 'paused: …failing_force.lua:9: …' message"
expect_dynamic "$WORK/paused.png" 460 374 "ball stopped near (-2.5, -0.2)"
expect_pixel "$WORK/paused.png" 554 374 "$BACKGROUND" "ball did not go on to (-1.2, -0.2)"
read -r r g b <<< "$("$PNG_CHECK" pixel "$WORK/paused.png" 640 12)"
{ [ "$r" -ge 60 ] && [ "$g" -le 40 ] && [ "$b" -le 40 ]; } || fail "no red error overlay after the force failed ($r $g $b)"
finish

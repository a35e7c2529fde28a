#!/usr/bin/env bash
# The sandbox draws the shapes of a scene where the scene puts them: runs scenes/shapes.lua for a
# few frames under Xvfb, takes a screenshot and checks pixels against the scene's coordinates.
# Camera centre (0, 0), 10 m tall in 720 px: 72 px per metre, world (x, y) → pixel (640 + 72x, 360 − 72y).
source "$(dirname "$0")/lib.sh"
require_xvfb

shot="$WORK/shapes.png"
start=$(now_ms)
start_sandbox "$SCENES/shapes.lua" 3 "$shot"
wait_sandbox
echo "3 frames in $(( $(now_ms) - start )) ms (including Xvfb start)"
[ "$SANDBOX_STATUS" -eq 0 ] || fail "exit status $SANDBOX_STATUS"
[ -f "$shot" ] || { fail "no screenshot written"; finish; }
[ "$("$PNG_CHECK" size "$shot")" = "1280 720" ] || fail "screenshot is $("$PNG_CHECK" size "$shot"), expected 1280 720"
grep -q "^[0-9]* opened .*shapes.lua" "$WORK/log.txt" || fail "no 'opened' line"

expect_pixel "$shot" 496 288 "$STATIC" "static box at (-2, 1)"
expect_pixel "$shot" 530 270 "$STATIC" "static box, off centre (-1.53, 1.25)"
expect_dynamic "$shot" 764 308 "ball at (2, 1), left of its rotation line"
expect_dynamic "$shot" 800 300 "ball, right part"
expect_dynamic "$shot" 654 518 "triangle near (0.2, -2.2)"
# Background where the scene has nothing (away from the grid lines at whole metres).
expect_pixel "$shot" 892 612 "$BACKGROUND" "empty space at (3.5, -3.5)"
expect_pixel "$shot" 546 540 "$BACKGROUND" "empty space left of the triangle (-1.3, -2.5)"
expect_pixel "$shot" 878 252 "$BACKGROUND" "empty space right of the ball (3.3, 1.5)"
expect_pixel "$shot" 460 330 "$BACKGROUND" "empty space under the box (-2.5, 0.4)"
finish

#!/usr/bin/env bash
# Building with the tools, with a real mouse and keyboard (xdotool under Xvfb), on scenes/build.lua
# (world (x, y) → pixel (640 + 72x, 360 − 72y)):
#   running: drag the ball from (2, 0) to (2, 2) → it follows the cursor (a motor joint);
#   Space pauses; polygon tool (4): a concave L of six clicks → a body of two convex pieces;
#   joint tool (6): the crate, then empty space at (0.5, -2.5) → pinned to the world there;
#   the L, then the crate at (-1.2, -1.6) → the two joined there;
#   select tool (1): click the pin's anchor → the joint; Delete, Ctrl+Z → back;
#   click the crate, Delete → it and both joints gone; Ctrl+Z → all back;
#   Ctrl+S, Enter → saved as a new scene file (format 3: shapes and joints).
# The final picture must show exactly that, and the saved file must hold it: read back through
# scripts/saved_world.lua by the scene API double (open_saved, $5). Opening it in rigidlab itself
# is build_reopen_test.sh.
source "$(dirname "$0")/lib.sh"
OPEN_SAVED=$5
require_xvfb
command -v xdotool >/dev/null 2>&1 || { echo "SKIP: xdotool is not installed (cmake/install_deps.sh installs it)"; exit 77; }

scene="$WORK/build.lua"
cp "$SCENES/build.lua" "$scene"
ANCHOR="178 255 217"  # a joint's anchor (core debug_draw.cpp: 0.7, 1.0, 0.85)

cat > "$WORK/drive.sh" <<'DRIVE'
set -u
source "$4"  # xdotool.sh
open_window "$1" "$2" "$3"

drag 784 360 784 216 1.5        # running: pull the ball to (2, 2)
sleep 0.5
key space                       # pause
key 4                           # polygon tool: an L
click 388 396                   # (-3.5, -0.5)
click 532 396                   # (-1.5, -0.5)
click 532 360                   # (-1.5, 0)
click 424 360                   # (-3, 0)
click 424 252                   # (-3, 1.5)
click 388 252                   # (-3.5, 1.5)
key Return
key 6                           # joint tool (revolute)
click 568 504                   # the crate at (-1, -2)
click 676 540                   # empty space at (0.5, -2.5): pinned to the world
click 496 378                   # the L at (-2, -0.25)
click 554 475                   # the crate at (-1.2, -1.6): joined
key 1                           # select tool
click 676 540                   # the pin's anchor: the joint
key Delete                      # the pin deleted
key ctrl+z                      # back
click 568 520                   # the crate
key Delete                      # the crate and its two joints deleted
key ctrl+z                      # all back
save_and_close "$3"             # Ctrl+S, Enter: saved under a new name
DRIVE
saved="$WORK/build_saved.lua"
drive "$scene" "$saved"

shot="$WORK/final.png"
expect_dynamic "$shot" 774 226 "the ball, pulled to (2, 2)"
expect_pixel "$shot" 806 382 "$BACKGROUND" "nothing left where the ball was (2.3, -0.3)"
expect_dynamic "$shot" 496 386 "the L's lower arm (-2, -0.36)"
expect_dynamic "$shot" 406 288 "the L's upright (-3.25, 1)"
expect_pixel "$shot" 460 324 "$BACKGROUND" "inside the L's hull, outside the L (-2.5, 0.5): no silent hull"
expect_pixel "$shot" 676 540 "$ANCHOR" "the pin's anchor at (0.5, -2.5) (deleted, then undone)"
expect_pixel "$shot" 554 475 "$ANCHOR" "the L-crate joint's anchor at (-1.2, -1.6)"
expect_dynamic "$shot" 580 524 "the crate, back after its deletion was undone (-0.83, -2.28)"

if [ -f "$saved" ]; then
  grep -q "version = 3" "$saved" || fail "the saved file is not format 3"
  [ "$(grep -c 'kind = "revolute"' "$saved")" -eq 2 ] || fail "the saved file should have two revolute joints"
  grep -q 'kind = "motor"' "$saved" && fail "the mouse's motor joint was saved"
  grep -q "shapes = {" "$saved" || fail "the L is not saved as a body of several shapes"
  if out=$("$OPEN_SAVED" "$saved" 2>&1); then
    [ "$out" = "bodies 3 joints 2 shapes 1 1 2" ] || fail "the saved file opens (API double) as '$out', expected 'bodies 3 joints 2 shapes 1 1 2'"
  else
    fail "the saved file does not open through saved_world.lua (API double): $out"
  fi
fi
finish

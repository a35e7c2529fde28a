#!/usr/bin/env bash
# The interaction of docs/design/thesis.md §11 with a real mouse and keyboard (xdotool under Xvfb), on
# scenes/interact.lua (world (x, y) → pixel (640 + 72x, 360 − 72y)):
#   drag the ball while running from (2, 0) to (2, 2) → it follows the cursor (mouse force);
#   Space pauses; drag the static box from (-2, 2) to (-2, -2) → moved;
#   circle tool (2): click at (0, -3) and (3, -3) → two circles; Delete removes the second;
#   Ctrl+Z brings it back, Ctrl+Z again undoes adding it, Ctrl+Y redoes, Ctrl+Z undoes;
#   select tool (1): click the ball, T → static; Ctrl+S, Enter → saved as a new scene file.
# The final picture must show exactly that, and the saved file, opened in a second run, too.
source "$(dirname "$0")/lib.sh"
require_xvfb
command -v xdotool >/dev/null 2>&1 || { echo "SKIP: xdotool is not installed (cmake/install_deps.sh installs it)"; exit 77; }

scene="$WORK/interact.lua"
cp "$SCENES/interact.lua" "$scene"

cat > "$WORK/drive.sh" <<'DRIVE'
set -u
source "$4"  # xdotool.sh
open_window "$1" "$2" "$3"

drag 784 360 784 216 1.5        # running: pull the ball to (2, 2)
sleep 0.5
key space                       # pause
drag 496 216 496 504 0.2        # move the static box to (-2, -2)
key 2                           # circle tool
click 640 576                   # circle A at (0, -3)
click 856 576                   # circle B at (3, -3), selected
key Delete                      # B deleted
key ctrl+z                      # B back
key ctrl+z                      # adding B undone
key ctrl+y                      # redone
key ctrl+z                      # undone again: B absent
key 1                           # select tool
click 784 216                   # select the ball (at (2, 2))
key t                           # static
save_and_close "$3"             # Ctrl+S, Enter: saved under a new name
DRIVE
saved="$WORK/interact_saved.lua"
drive "$scene" "$saved"

check_picture() {  # IMAGE LABEL
  expect_pixel "$1" 764 236 "$STATIC" "$2: the ball, pulled to (2, 2) and made static"
  expect_pixel "$1" 806 382 "$BACKGROUND" "$2: nothing left where the ball was (2.3, -0.3)"
  expect_pixel "$1" 516 514 "$STATIC" "$2: the box, moved to (-2, -2)"
  expect_pixel "$1" 470 205 "$BACKGROUND" "$2: nothing left where the box was (-2.36, 2.15)"
  expect_dynamic "$1" 625 590 "$2: circle A at (0, -3)"
  expect_pixel "$1" 840 590 "$BACKGROUND" "$2: circle B at (3, -3) is gone (undo, redo, undo)"
}
check_picture "$WORK/final.png" "sandbox"

# The saved world opens where it was left, camera included.
if [ -f "$saved" ]; then
  start_sandbox "$saved" 2 "$WORK/reopened.png"
  wait_sandbox
  [ "$SANDBOX_STATUS" -eq 0 ] || fail "the saved scene: exit status $SANDBOX_STATUS"
  check_picture "$WORK/reopened.png" "saved scene"
fi
finish

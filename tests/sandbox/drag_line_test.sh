#!/usr/bin/env bash
# A line while dragging a body (as Box2D's samples draw their mouse joint), with a real mouse
# (xdotool under Xvfb): on scenes/drag_line.lua (a bar pinned at its centre, 72 px per metre), the
# left button pressed on the bar at (0.8, 0) and the cursor taken to (4, 3) and held there while
# the window is closed: the last frame shows the drag's colour along the 4 m or more between the
# grabbed point and the cursor; a frame without a drag shows none of it.
source "$(dirname "$0")/lib.sh"
require_xvfb
command -v xdotool >/dev/null 2>&1 || { echo "SKIP: xdotool is not installed (cmake/install_deps.sh installs it)"; exit 77; }
DRAG="77 242 115"  # renderer.h Palette::drag (0.3, 0.95, 0.45)

start_sandbox "$SCENES/drag_line.lua" 5 "$WORK/still.png"
wait_sandbox
[ "$SANDBOX_STATUS" -eq 0 ] || fail "without a drag: exit status $SANDBOX_STATUS"
# shellcheck disable=SC2086
still=$("$PNG_CHECK" count "$WORK/still.png" 0 0 1280 720 $DRAG 40)
[ "$still" -eq 0 ] || fail "without a drag, $still pixels have the drag's colour"

cat > "$WORK/drive.sh" <<'DRIVE'
set -u
source "$4"  # xdotool.sh
open_window "$1" "$2" "$3"
xdotool search --sync --name rigidlab windowfocus --sync > /dev/null
xdotool mousemove 698 360; step    # on the bar at (0.8, 0)
xdotool mousedown 1; sleep 0.1
for i in 1 2 3 4 5 6 7 8; do xdotool mousemove $(( 698 + (928 - 698) * i / 8 )) $(( 360 - 216 * i / 8 )); sleep 0.03; done
sleep 1                            # held at (4, 3): the bar turns towards it, the line stays
kill -TERM "$pid"                  # the frame drawn while the button is down is the screenshot
wait "$pid"
echo "exit $?" >> "$3/out.txt"
xdotool mouseup 1
DRIVE
xvfb-run -a -s "-screen 0 1280x720x24" bash "$WORK/drive.sh" "$RIGIDLAB" "$SCENES/drag_line.lua" "$WORK" \
  "$(dirname "${BASH_SOURCE[0]}")/xdotool.sh" || true
cp "$WORK/out.txt" "$WORK/log.txt"
grep -q "^exit 0$" "$WORK/out.txt" || fail "the sandbox did not exit cleanly: $(tail -n 1 "$WORK/out.txt")"
[ -f "$WORK/final.png" ] || { fail "no screenshot"; finish; }
# shellcheck disable=SC2086
dragged=$("$PNG_CHECK" count "$WORK/final.png" 0 0 1280 720 $DRAG 40)
# shellcheck disable=SC2086
near_cursor=$("$PNG_CHECK" count "$WORK/final.png" 900 134 940 174 $DRAG 40)
echo "drag colour: $dragged pixels, $near_cursor of them within 20 px of the cursor"
[ "$dragged" -ge 150 ] || fail "while dragging, only $dragged pixels have the drag's colour (a line of 4 m or more: 150 or more)"
[ "$near_cursor" -ge 10 ] || fail "the drag line does not reach the cursor at (928, 144): $near_cursor pixels there"

finish

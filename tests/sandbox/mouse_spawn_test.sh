#!/usr/bin/env bash
# The mod hooks with a real mouse and keyboard (xdotool under Xvfb), on scripts/scenes/mouse_spawn.lua
# (world (x, y) → pixel (640 + 72x, 360 − 72y)): Space pauses, so bodies stay where they appear;
# the circle tool (2) is chosen, so a click the scene did not consume would also add a circle;
#   left clicks at (-3, 2) and (3, 2) → OnMouse spawns a ball at each (the scene prints where; its
#   own clicks at t = 0 and 0.5 s come before, as headless, how many depends on when Space came);
#   R → the scene's (scene.keys), which clears its balls: the scene is not reset;
#   a left click at (1, 1) → one ball there.
# The scene's lines must give those positions; the final picture must show the ball at (1, 1),
# nothing at the two cleared places (no circle of the tool's either), and the scene's HUD (a filled
# rectangle drawn with draw.screen in the window's bottom-right corner).
source "$(dirname "$0")/lib.sh"
require_xvfb
command -v xdotool >/dev/null 2>&1 || { echo "SKIP: xdotool is not installed (cmake/install_deps.sh installs it)"; exit 77; }

scene="$WORK/mouse_spawn.lua"
cp "$(dirname "$0")/../../scripts/scenes/mouse_spawn.lua" "$scene"

cat > "$WORK/drive.sh" <<'DRIVE'
set -u
source "$4"  # xdotool.sh
open_window "$1" "$2" "$3"
# The keys go to the focused window: wait until the sandbox has the focus, or a loaded machine
# may send Space before it does (then nothing pauses, the scene's own second click lands between
# ours, and the balls fall).
xdotool search --sync --name rigidlab windowfocus --sync > /dev/null
key space                       # pause
key 2                           # circle tool
click 424 216                   # (-3, 2)
click 856 216                   # (3, 2)
key r                           # the scene's: clear
click 712 288                   # (1, 1)
sleep 0.5
kill -TERM "$pid"
wait "$pid"
echo "exit $?" >> "$3/out.txt"
DRIVE
xvfb-run -a -s "-screen 0 1280x720x24" bash "$WORK/drive.sh" "$RIGIDLAB" "$scene" "$WORK" \
  "$(dirname "${BASH_SOURCE[0]}")/xdotool.sh" || true
cp "$WORK/out.txt" "$WORK/log.txt"
grep -q "^exit 0$" "$WORK/out.txt" || fail "the sandbox did not exit cleanly: $(tail -n 1 "$WORK/out.txt")"
grep -q "reloaded" "$WORK/out.txt" && fail "R reset the scene: it should have been the scene's key"

# The scene's own clicks first (1 or 2 lines), then ours.
got=$(grep -E "^(spawned|cleared) " "$WORK/stderr.txt" | tail -n 4 | sed -E 's/^(spawned|cleared) [0-9]+/\1 N/' || true)
expected="spawned N at -3.000 2.000
spawned N at 3.000 2.000
cleared N
spawned N at 1.000 1.000"
[ "$got" = "$expected" ] || fail "the scene's last lines: expected
$expected
got
$got"
tail -n 1 "$WORK/stderr.txt" | grep -q "^spawned 1 at 1.000 1.000$" || fail "R did not clear the list: $(tail -n 1 "$WORK/stderr.txt")"
first=$(grep -c "^spawned" "$WORK/stderr.txt")
[ "$first" -ge 4 ] && [ "$first" -le 5 ] || fail "expected 1 or 2 of the scene's own clicks before ours, $first spawns in all"

shot="$WORK/final.png"
if [ -f "$shot" ]; then
  expect_dynamic "$shot" 719 292 "the ball spawned at (1, 1)"
  expect_pixel "$shot" 413 227 "$BACKGROUND" "nothing at (-3, 2) after R (neither the scene's ball nor a tool circle)"
  expect_pixel "$shot" 867 227 "$BACKGROUND" "nothing at (3, 2) after R"
  expect_pixel "$shot" 1250 680 "204 26 26" "the HUD's filled rectangle (draw.screen:polygon)"
else
  fail "no screenshot"
fi
finish

#!/usr/bin/env bash
# The sandbox's docked panels and its camera, checked from the rectangles the sandbox itself reports
# (--layout-file: every window Dear ImGui shows, the free view area, the scene's HUD, the camera and
# the followed body), not by eye:
#   the default layout (no scene given: playground with the scene browser) at 1280x800 and
#   1920x1080: the usual panels, none over another, all inside the window, none over the free view;
#   mouse_spawn at 1280x800: no panel over its screen-space HUD (bottom right), its Controls panel
#   docked too;
#   car.lua (scene.camera.follow = chassis) at 4 s and 8 s: the chassis is in the middle of the free
#   view and drawn there (its fill colour counted around that point), while the camera has moved on
#   with it (the scene's own centre is x = 12).
source "$(dirname "$0")/lib.sh"
require_xvfb
SCREEN="-screen 0 1920x1080x24"

# run_layout NAME SIZE FRAMES [SCENE]: the sandbox for FRAMES frames in a window of SIZE, its last
# frame in $WORK/NAME.png and its layout in $WORK/NAME.txt.
run_layout() {
  local name=$1 size=$2 frames=$3 scene=${4:-}
  local args=(--size "$size" --frames "$frames" --screenshot "$WORK/$name.png" --layout-file "$WORK/$name.txt")
  [ -n "$scene" ] && args=("$scene" "${args[@]}")
  local status=0
  xvfb-run -a -s "$SCREEN" "$RIGIDLAB" "${args[@]}" >>"$WORK/log.txt" 2>>"$WORK/stderr.txt" || status=$?
  [ "$status" -eq 0 ] || fail "$name: exit status $status"
  [ -f "$WORK/$name.txt" ] || { fail "$name: no layout file"; return 1; }
  [ "$("$PNG_CHECK" size "$WORK/$name.png")" = "${size/x/ }" ] || fail "$name: the picture is $("$PNG_CHECK" size "$WORK/$name.png"), not $size"
  grep -q "^window ${size/x/ }$" "$WORK/$name.txt" || fail "$name: $(grep '^window' "$WORK/$name.txt"), expected $size"
  echo "--- $name"; cat "$WORK/$name.txt"
}

# check_apart NAME: no panel over another, over the free view area or over the HUD; all inside
# the window (from the layout file's rectangles).
check_apart() {
  local problems
  problems=$(awk '
    BEGIN { n = 0; nh = 0 }
    $1 == "window" { W = $2; H = $3 }
    $1 == "view" { vx0 = $2; vy0 = $3; vx1 = $4; vy1 = $5 }
    $1 == "hud" { hx0[nh] = $2; hy0[nh] = $3; hx1[nh] = $4; hy1[nh] = $5; nh++ }
    $1 == "panel" { x0[n] = $2; y0[n] = $3; x1[n] = $4; y1[n] = $5; name[n] = substr($0, index($0, $6)); n++ }
    function meet(ax0, ay0, ax1, ay1, bx0, by0, bx1, by1) { return ax0 < bx1 && bx0 < ax1 && ay0 < by1 && by0 < ay1 }
    END {
      for (i = 0; i < n; i++) {
        if (x0[i] < 0 || y0[i] < 0 || x1[i] > W || y1[i] > H) print name[i] " leaves the window"
        if (meet(x0[i], y0[i], x1[i], y1[i], vx0, vy0, vx1, vy1)) print name[i] " is over the free view area"
        for (j = i + 1; j < n; j++)
          if (meet(x0[i], y0[i], x1[i], y1[i], x0[j], y0[j], x1[j], y1[j])) print name[i] " overlaps " name[j]
        for (k = 0; k < nh; k++)
          if (meet(x0[i], y0[i], x1[i], y1[i], hx0[k], hy0[k], hx1[k], hy1[k])) print name[i] " covers the scene'\''s HUD"
      }
    }' "$WORK/$1.txt")
  [ -z "$problems" ] || fail "$1: $problems"
}

has_panel() { grep -q "^panel .* $2$" "$WORK/$1.txt" || fail "$1: no panel '$2'"; }

for size in 1280x800 1920x1080; do
  name=default_$size
  run_layout "$name" "$size" 10 || continue
  for panel in rigidlab Scenes Statistics Energy Profile; do has_panel "$name" "$panel"; done
  check_apart "$name"
done

run_layout hud 1280x800 10 "$(dirname "$0")/../../scripts/scenes/mouse_spawn.lua" && {
  grep -q "^hud " "$WORK/hud.txt" || fail "hud: mouse_spawn's HUD was not reported"
  has_panel hud Controls
  check_apart hud
}

# The car, followed: the chassis (3 m x 0.5 m) in the middle of the free view, its fill there.
for seconds in 4 8; do
  name=car_$seconds
  run_layout "$name" 1280x720 $((seconds * 60)) "$(dirname "$0")/../../scripts/scenes/car.lua" || continue
  check_apart "$name"
  read -r _ ppm cx _ < <(grep '^camera ' "$WORK/$name.txt")
  read -r _ fx fy _ < <(grep '^follow ' "$WORK/$name.txt" || echo "follow")
  [ -n "$fx" ] || { fail "$name: no followed body"; continue; }
  read -r _ vx0 vy0 vx1 vy1 < <(grep '^view ' "$WORK/$name.txt")
  awk -v x="$fx" -v y="$fy" -v a="$vx0" -v b="$vy0" -v c="$vx1" -v d="$vy1" \
    'BEGIN { exit !(x > a + 100 && x < c - 100 && y > b + 100 && y < d - 100) }' ||
    fail "$name: the chassis is drawn at ($fx, $fy), not well inside the free view ($vx0 $vy0 $vx1 $vy1)"
  awk -v x="$cx" -v s="$seconds" 'BEGIN { exit !(x > 4 * s) }' || fail "$name: the camera is at x = $cx m: it did not drive on"
  # The chassis' fill in a box of its size about its centre (joint lines cross it): most of it.
  hw=$(awk -v p="$ppm" 'BEGIN { printf "%d", 1.5 * p }') hh=$(awk -v p="$ppm" 'BEGIN { printf "%d", 0.25 * p }')
  read -r x0 y0 x1 y1 < <(awk -v x="$fx" -v y="$fy" -v w="$hw" -v h="$hh" 'BEGIN { printf "%d %d %d %d\n", x - w, y - h, x + w, y + h }')
  # shellcheck disable=SC2086
  filled=$("$PNG_CHECK" count "$WORK/$name.png" "$x0" "$y0" "$x1" "$y1" $DYNAMIC "$TOLERANCE")
  area=$(( (x1 - x0) * (y1 - y0) ))
  echo "$name: chassis fill $filled of $area pixels about ($fx, $fy)"
  [ "$filled" -gt $(( area * 6 / 10 )) ] || fail "$name: only $filled of $area pixels about the chassis' centre are its fill"
done
finish

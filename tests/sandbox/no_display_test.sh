#!/usr/bin/env bash
# Without a display, `rigidlab [SCENE.lua]` says so in one line, runs the scene headless and prints
# its summary (exit 0), so the README's first command does something useful on any machine. SDL
# would otherwise fall back to its invisible "offscreen" driver: the sandbox must not count that as
# a display.
source "$(dirname "$0")/lib.sh"
status=0
env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$RIGIDLAB" "$SCENES/shapes.lua" \
  > "$WORK/out.txt" 2> "$WORK/err.txt" || status=$?
cat "$WORK/err.txt"
[ "$status" -eq 0 ] || fail "exit status $status"
[ "$(wc -l < "$WORK/err.txt")" -eq 1 ] || fail "expected one line on standard error, got $(wc -l < "$WORK/err.txt")"
grep -qi "no display" "$WORK/err.txt" || fail "the line does not say 'no display'"
grep -q "rigidlab run" "$WORK/err.txt" || fail "the line does not point to 'rigidlab run'"
grep -q "ball" "$WORK/out.txt" || fail "no summary of the scene's bodies on standard output"
# --screenshot cannot work without a display: a clear failure, not a silent success.
env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$RIGIDLAB" "$SCENES/shapes.lua" --frames 2 --screenshot "$WORK/x.png" \
  > /dev/null 2>&1 && fail "--screenshot without a display exited 0"
[ -f "$WORK/x.png" ] && fail "a screenshot was written without a display"
cp "$WORK/out.txt" "$WORK/log.txt"
finish

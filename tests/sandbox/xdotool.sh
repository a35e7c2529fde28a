# Mouse and keyboard helpers for the drive scripts of the Xvfb tests (sourced inside xvfb-run).
step() { sleep 0.35; }
drag() {  # x0 y0 x1 y1 hold_seconds
  xdotool mousemove "$1" "$2"; step
  xdotool mousedown 1; sleep 0.1
  for i in 1 2 3 4 5 6 7 8; do
    xdotool mousemove $(( $1 + ($3 - $1) * i / 8 )) $(( $2 + ($4 - $2) * i / 8 )); sleep 0.03
  done
  sleep "$5"
  xdotool mouseup 1; step
}
click() { xdotool mousemove "$1" "$2"; sleep 0.1; xdotool click 1; step; }
key() { xdotool key "$@"; step; }
# Dear ImGui 1.86 samples key state once per frame: a key it must see (in a dialog) is held a while.
hold() { xdotool keydown "$1"; sleep 0.15; xdotool keyup "$1"; step; }
# open_window RIGIDLAB SCENE WORK: starts the sandbox on SCENE (the last frame's screenshot goes to
# WORK/final.png, its output to WORK/out.txt) and waits for its window; $pid is the sandbox.
open_window() {
  "$1" "$2" --frames 100000 --screenshot "$3/final.png" > "$3/out.txt" 2> "$3/stderr.txt" &
  pid=$!
  xdotool search --sync --name rigidlab > /dev/null
  sleep 0.8
}
# save_and_close WORK: Ctrl+S and Enter (the suggested new name), then closes the window (SIGTERM:
# the last frame is the screenshot) and appends "exit STATUS" to WORK/out.txt.
save_and_close() {
  key ctrl+s
  hold Return
  sleep 0.5
  kill -TERM "$pid"
  wait "$pid"
  echo "exit $?" >> "$1/out.txt"
}

#!/usr/bin/env bash
# Every hostile scene (tests/hostile/*.lua) opened in the sandbox and hot-reloaded under Xvfb. For
# each: the sandbox starts on a scratch copy (with the links and files its header asks for), the
# scene is rewritten as an editor saves it (temporary file + rename), and half a second after the
# reload (or its failure) the process must still be alive; it is then closed (SIGTERM, a window
# close) and must exit normally. A scene whose headless run fails (`-- exit: 1`) must have its error
# printed, unless its header says `-- sandbox: no-overlay` (errors of the headless runner alone,
# such as its step limit); if it failed to load, the red error overlay must be on the last frame
# (one that failed while running is paused with its error, and stays paused, without the error,
# after the reload). Frames of the heaps of thousands of large discs take about 0.4 s under Xvfb's
# software renderer, so the waits are generous.
#
# One Xvfb server serves every scene (started here with -displayfd, which picks a free display
# without the race of several `xvfb-run -a` started at once by parallel tests).
source "$(dirname "$0")/lib.sh"
require_xvfb
command -v Xvfb >/dev/null 2>&1 || { echo "SKIP: Xvfb is not installed"; exit 77; }
HOSTILE=$(cd "$SCENES/../../hostile" && pwd)

Xvfb -displayfd 3 -screen 0 1280x720x24 -nolisten tcp 3> "$WORK/display" 2> "$WORK/xvfb.log" &
XVFB_PID=$!
trap 'kill "$XVFB_PID" 2>/dev/null || true' EXIT
for _ in $(seq 100); do [ -s "$WORK/display" ] && break; sleep 0.05; done
[ -s "$WORK/display" ] || { echo "FAIL: Xvfb did not start: $(cat "$WORK/xvfb.log")"; exit 1; }
DISPLAY_NUMBER=$(head -n 1 "$WORK/display")

# run_sandbox SCENE SCREENSHOT: like lib.sh's start_sandbox, on the shared server, until stopped.
run_sandbox() {
  : > "$WORK/log.txt"
  (
    set -o pipefail
    DISPLAY=":$DISPLAY_NUMBER" sh -c 'echo $$ > "$0"; exec "$@"' "$WORK/pid" "$RIGIDLAB" "$1" --frames 1000000 \
      --screenshot "$2" 2> "$WORK/stderr.txt" |
      while IFS= read -r line; do echo "$(now_ms) $line"; done >> "$WORK/log.txt"
  ) &
  SANDBOX_JOB=$!
}

# prepare SCENE DIR: the copy, and the links and files of its header.
prepare() {
  local scene=$1 dir=$2 line
  mkdir -p "$dir/scene"
  cp "$scene" "$dir/scene/"
  while IFS= read -r line; do
    case "$line" in
      "-- link: "*)
        local spec=${line#-- link: } name target
        name=${spec%% -> *}; target=${spec#* -> }
        case "$target" in /*) ;; *) target="$dir/$target" ;; esac
        mkdir -p "$(dirname "$dir/scene/$name")"
        ln -sfn "$target" "$dir/scene/$name" ;;
      "-- file: "*)
        local path=${line#-- file: }
        mkdir -p "$(dirname "$dir/$path")"
        echo 'return "outside"' > "$dir/$path" ;;
      --*) ;;
      *) break ;;
    esac
  done < "$scene"
}

# wait_until TIMEOUT_MS COMMAND...: until COMMAND succeeds; returns 1 on timeout.
wait_until() {
  local timeout=$1 start
  shift
  start=$(now_ms)
  until "$@"; do
    if [ $(( $(now_ms) - start )) -gt "$timeout" ]; then return 1; fi
    sleep 0.02
  done
}
# in_either STDOUT_PATTERN STDERR_PATTERN: the sandbox printed the first or the second.
in_either() { grep -q -- "$1" "$WORK/log.txt" 2>/dev/null || grep -q -- "$2" "$WORK/stderr.txt" 2>/dev/null; }
in_stderr() { grep -q -- "$1" "$WORK/stderr.txt" 2>/dev/null; }

count=0
for scene in "$HOSTILE"/*.lua; do
  name=$(basename "$scene" .lua)
  dir="$WORK/$name"
  prepare "$scene" "$dir"
  copy="$dir/scene/$name.lua"
  start=$(now_ms)
  rm -f "$WORK/pid"
  run_sandbox "$copy" "$dir/last.png"
  if ! wait_until 15000 in_either " opened " "rigidlab: "; then
    fail "$name: neither opened nor reported an error within 15 s"
  fi
  sleep 0.3
  { cat "$scene"; echo "-- saved again by hostile_test.sh"; } | atomic_write "$copy"
  wait_until 20000 in_either " reloaded " "reload failed" || fail "$name: no reload and no reload failure within 20 s"
  sleep 0.5
  pid=$(cat "$WORK/pid" 2>/dev/null || echo 0)
  [ "$pid" != 0 ] || fail "$name: the sandbox did not start"
  kill -0 "$pid" 2>/dev/null || fail "$name: the sandbox died (stderr: $(tail -c 400 "$WORK/stderr.txt"))"
  expects_error=0
  if grep -q "^-- exit: 1$" "$scene" && ! grep -q "^-- sandbox: no-overlay$" "$scene"; then expects_error=1; fi
  # A scene that fails while running (pile_growing: at its 4th step, each a heap of hundreds of
  # overlapping boxes) may need seconds of frames under the sanitizers on a loaded machine.
  if [ "$expects_error" = 1 ]; then wait_until 20000 in_stderr "rigidlab: " || true; fi
  stop_sandbox
  case "$SANDBOX_STATUS" in
    0|1) ;;
    *) fail "$name: exit status $SANDBOX_STATUS after SIGTERM" ;;
  esac
  if [ "$expects_error" = 1 ]; then
    grep -q "rigidlab: " "$WORK/stderr.txt" || fail "$name: the error was not printed within 20 s"
    if grep -q "rigidlab: paused: " "$WORK/stderr.txt"; then
      :  # failed while running: paused with its error (printed, checked above), reloaded paused
    elif [ -f "$dir/last.png" ]; then
      read -r r g b <<< "$("$PNG_CHECK" pixel "$dir/last.png" 640 12)"
      { [ "$r" -ge 60 ] && [ "$g" -le 40 ] && [ "$b" -le 40 ]; } || fail "$name: no red error overlay (pixel 640,12 is $r $g $b)"
    else
      fail "$name: no screenshot of the last frame"
    fi
  fi
  cp "$WORK/stderr.txt" "$dir/stderr.txt"
  echo "$name: survived open and reload ($(( $(now_ms) - start )) ms), exit $SANDBOX_STATUS"
  count=$((count + 1))
done
[ "$count" -ge 30 ] || fail "only $count hostile scenes found in $HOSTILE"
finish

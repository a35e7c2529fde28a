# Shared helpers for the sandbox's Xvfb tests (sourced). Arguments of every test script:
#   $1 rigidlab binary   $2 png_check binary   $3 tests/sandbox/scenes   $4 a scratch directory
set -euo pipefail
RIGIDLAB=$1
PNG_CHECK=$2
SCENES=$3
WORK=$4
rm -rf "$WORK"
mkdir -p "$WORK"
FAILURES=0

# Colours of the default palette in a screenshot (core debug_draw.cpp fills over the sandbox's
# background, renderer.h Palette), 8-bit RGB.
DYNAMIC="57 98 160"   # dynamic fill (0.25, 0.45, 0.75, α 0.8) over the background
SLEEPING="42 63 93"   # a dynamic body asleep (0.18, 0.28, 0.42, α 0.8): at rest for 0.5 s
STATIC="89 97 107"    # static fill (0.35, 0.38, 0.42)
BACKGROUND="28 31 36" # (0.11, 0.12, 0.14)
TOLERANCE=12

require_xvfb() {
  if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "SKIP: xvfb-run is not installed (cmake/install_deps.sh installs xvfb, xauth and Mesa)"
    exit 77
  fi
}

fail() {
  echo "FAIL: $*"
  FAILURES=$((FAILURES + 1))
}

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }

# start_sandbox SCENE FRAMES [SCREENSHOT]: runs the sandbox under Xvfb in the background. Its
# standard output lines are logged with their arrival time in ms ($WORK/log.txt: "<ms> <line>"),
# standard error goes to $WORK/stderr.txt, its pid to $WORK/pid.
start_sandbox() {
  local scene=$1 frames=$2 shot=${3:-}
  local args=("$scene" --frames "$frames")
  [ -n "$shot" ] && args+=(--screenshot "$shot")
  : > "$WORK/log.txt"
  (
    set -o pipefail
    xvfb-run -a -s "-screen 0 1280x720x24" sh -c 'echo $$ > "$0"; exec "$@"' "$WORK/pid" "$RIGIDLAB" "${args[@]}" \
      2> "$WORK/stderr.txt" |
      while IFS= read -r line; do echo "$(now_ms) $line"; done >> "$WORK/log.txt"
  ) &
  SANDBOX_JOB=$!
}

# wait_sandbox: waits for the background sandbox, sets SANDBOX_STATUS.
wait_sandbox() {
  SANDBOX_STATUS=0
  wait "$SANDBOX_JOB" || SANDBOX_STATUS=$?
}

# stop_sandbox: ends the sandbox we started (SIGTERM is a window close for SDL) and waits.
stop_sandbox() {
  [ -f "$WORK/pid" ] && kill -TERM "$(cat "$WORK/pid")" 2>/dev/null || true
  wait_sandbox
}

count_lines() { grep -c -- "$1" "$WORK/log.txt" || true; }

# wait_for LINE_PATTERN COUNT TIMEOUT_MS: until the log has COUNT matching lines. Prints the arrival
# time (ms) of the COUNT-th one; returns 1 on timeout.
wait_for() {
  local pattern=$1 count=$2 timeout=$3 start
  start=$(now_ms)
  while [ "$(count_lines "$pattern")" -lt "$count" ]; do
    if [ $(( $(now_ms) - start )) -gt "$timeout" ]; then return 1; fi
    sleep 0.01
  done
  grep -- "$pattern" "$WORK/log.txt" | sed -n "${count}p" | cut -d' ' -f1
}

# expect_pixel IMAGE X Y "R G B" WHAT
expect_pixel() {
  local image=$1 x=$2 y=$3 rgb=$4 what=$5 out
  # shellcheck disable=SC2086
  if ! out=$("$PNG_CHECK" near "$image" "$x" "$y" $rgb "$TOLERANCE"); then fail "$what: $out"; fi
}

# expect_dynamic IMAGE X Y WHAT: a dynamic body's fill, awake or asleep.
expect_dynamic() {
  local out
  # shellcheck disable=SC2086
  if ! "$PNG_CHECK" near "$1" "$2" "$3" $DYNAMIC "$TOLERANCE" > /dev/null &&
     ! out=$("$PNG_CHECK" near "$1" "$2" "$3" $SLEEPING "$TOLERANCE"); then
    fail "$4: ${out/expected/expected a dynamic body ($DYNAMIC awake) or}"
  fi
}

# atomic_write FILE: stdin → FILE by temporary file + rename, as most editors save.
atomic_write() {
  local tmp
  tmp="$(dirname "$1")/.$(basename "$1").edit-tmp"
  cat > "$tmp"
  mv -f "$tmp" "$1"
}

# drive SCENE SAVED: runs $WORK/drive.sh (its arguments: rigidlab, SCENE, $WORK and xdotool.sh, whose
# helpers it uses) under Xvfb, then checks that the sandbox exited cleanly, said "saved SAVED" and
# left its last frame in $WORK/final.png.
drive() {
  xvfb-run -a -s "-screen 0 1280x720x24" bash "$WORK/drive.sh" "$RIGIDLAB" "$1" "$WORK" \
    "$(dirname "${BASH_SOURCE[0]}")/xdotool.sh" || true
  cp "$WORK/out.txt" "$WORK/log.txt"
  grep -q "^exit 0$" "$WORK/out.txt" || fail "the sandbox did not exit cleanly: $(tail -n 1 "$WORK/out.txt")"
  grep -q "^saved $2$" "$WORK/out.txt" || fail "no 'saved $2' line"
  [ -f "$WORK/final.png" ] || { fail "no screenshot"; finish; }
}

finish() {
  if [ "$FAILURES" -gt 0 ]; then
    echo "--- sandbox stdout"; cat "$WORK/log.txt" 2>/dev/null || true
    echo "--- sandbox stderr"; cat "$WORK/stderr.txt" 2>/dev/null || true
    echo "$FAILURES check(s) failed"
    exit 1
  fi
  echo "all checks passed"
}

#!/usr/bin/env bash
# Bounded fuzz run for CI (docs/design/reliability.md V3): replays every regression input, then fuzzes each
# target for SECONDS (default 60) from the committed corpus plus the scenes as read-only seeds.
# New corpus entries go to a temporary directory (copy them into tests/fuzz/corpus/ by hand if
# they are worth keeping). Exit status 1 and the crashing input's path if anything crashes, leaks,
# trips a sanitizer or hangs (-timeout).
#
# The mutations follow FUZZ_SEED (default 1), so a run repeats what an earlier one on the same
# commit explored, up to where the time ran out; FUZZ_SEED=0 lets libFuzzer pick a seed, for
# longer hunts (FUZZ_SEED=0 tests/fuzz/run.sh build-fuzz 3600).
#
# Usage: tests/fuzz/run.sh BUILD_DIR [SECONDS]
#   BUILD_DIR: a build of tests/fuzz (CC=clang CXX=clang++ cmake -S tests/fuzz -B BUILD_DIR)
set -euo pipefail
build=$(cd "$1" && pwd)
seconds=${2:-60}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
work=$(mktemp -d /tmp/rigidlab-fuzz.XXXXXX)
trap 'rm -rf "$work"' EXIT
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

status=0
# 1. Regressions: every input that ever crashed (and the regression scenes) must now pass.
regressions=("$here"/regressions/scene/* "$root"/tests/scenes/regression_*.lua)
existing=()
for f in "${regressions[@]}"; do [ -f "$f" ] && existing+=("$f"); done
if [ ${#existing[@]} -gt 0 ]; then
  "$build/fuzz_scene" "${existing[@]}" >"$work/replay_scene.log" 2>&1 || { status=1; tail -40 "$work/replay_scene.log"; }
fi
world_regressions=()
for f in "$here"/regressions/world/*; do [ -f "$f" ] && world_regressions+=("$f"); done
if [ ${#world_regressions[@]} -gt 0 ]; then
  "$build/fuzz_world" "${world_regressions[@]}" >"$work/replay_world.log" 2>&1 || { status=1; tail -40 "$work/replay_world.log"; }
fi
snapshot_regressions=()
for f in "$here"/regressions/snapshot/*; do [ -f "$f" ] && snapshot_regressions+=("$f"); done
if [ ${#snapshot_regressions[@]} -gt 0 ]; then
  "$build/fuzz_snapshot" "${snapshot_regressions[@]}" >"$work/replay_snapshot.log" 2>&1 || { status=1; tail -40 "$work/replay_snapshot.log"; }
fi
runner_regressions=()
for f in "$here"/regressions/runner/*; do [ -f "$f" ] && runner_regressions+=("$f"); done
if [ ${#runner_regressions[@]} -gt 0 ]; then
  "$build/fuzz_runner" "${runner_regressions[@]}" >"$work/replay_runner.log" 2>&1 || { status=1; tail -40 "$work/replay_runner.log"; }
fi
echo "fuzz: replayed $(( ${#existing[@]} + ${#world_regressions[@]} + ${#snapshot_regressions[@]} + ${#runner_regressions[@]} )) regression inputs"

# 2. Fuzz each target for $seconds.
fuzz() {  # TARGET OPTION... -- SEED_DIR...
  local target=$1; shift
  local options=() seeds=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do options+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  seeds=("$@")
  mkdir -p "$work/$target"
  cp -r "$here/corpus/${target#fuzz_}/." "$work/$target/"
  local log="$work/$target.log"
  if "$build/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -seed="${FUZZ_SEED:-1}" \
       -artifact_prefix="$work/$target-" "${options[@]}" "$work/$target" "${seeds[@]}" >"$log" 2>&1; then
    echo "fuzz: $target: $(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}') runs in ${seconds} s," \
         "$(grep -E '^stat::average_exec_per_sec' "$log" | awk '{print $2}') exec/s, no crash"
  else
    status=1
    echo "fuzz: $target FAILED:"
    # the sanitizer's or libFuzzer's report, the engine's own abort message (RIGIDLAB_VERIFY_CACHES)
    # and the top of the stack, so that a failure seen only in CI's log can be found
    grep -E 'ERROR|SUMMARY|Test unit written|==[0-9]+==|fuzz_world:|fuzz_runner:|^rigidlab:|^ +#[0-9]+ .* in (rigidlab::|LLVMFuzzerTestOneInput)' "$log" | head -30
    for a in "$work/$target"-*; do
      [ -f "$a" ] || continue
      mkdir -p "${FUZZ_ARTIFACTS:-$root/build-fuzz-artifacts}"
      cp "$a" "${FUZZ_ARTIFACTS:-$root/build-fuzz-artifacts}/"
      echo "fuzz: input kept in ${FUZZ_ARTIFACTS:-$root/build-fuzz-artifacts}/$(basename "$a")"
    done
  fi
}
fuzz fuzz_scene -dict="$here/lua.dict" -max_len=8192 -- "$root/scripts/scenes" "$root/tests/scenes"
fuzz fuzz_world -max_len=4096 --
fuzz fuzz_snapshot -max_len=65536 --
fuzz fuzz_runner -max_len=16384 --
exit $status

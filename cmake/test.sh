#!/usr/bin/env bash
# Every test, as CI runs it (README "Quick start"; .ci/run runs the README's command):
#   1. the Release build in build/ and its whole ctest suite;
#   2. the same suite built with AddressSanitizer + UndefinedBehaviorSanitizer in build-sanitize/;
#   3. the libFuzzer targets (clang, tests/fuzz) in build-fuzz/: every regression input replayed,
#      then each target fuzzed for FUZZ_SECONDS (default 30; 600 with --nightly).
# Each stage installs and builds what it needs first (cmake/setup.sh). Stops at the first failure.
#
#   cmake/test.sh            all three stages (what CI runs)
#   cmake/test.sh --quick    stage 1 only (what to run while working)
#   cmake/test.sh --nightly  all three, with the slow runs the default leaves out: the tests
#                            labelled "nightly" (ctest -L nightly) and 10 min of fuzzing per target
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=$(nproc 2>/dev/null || echo 2)
quick=0
nightly=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    --nightly) nightly=1 ;;
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "cmake/test.sh: unknown option '$arg' (try --help)" >&2; exit 2 ;;
  esac
done

# Tests labelled "nightly" are slow runs whose checks the default run makes elsewhere (the label's
# users say where); --nightly runs them too.
exclude=(-LE nightly)
[ "$nightly" = 1 ] && exclude=()
fuzz_seconds=${FUZZ_SECONDS:-30}
[ "$nightly" = 1 ] && fuzz_seconds=${FUZZ_SECONDS:-600}

stage() { echo; echo "== cmake/test.sh: $* ($(date +%H:%M:%S))"; }

stage "1/3 Release build and the test suite"
"$root/cmake/setup.sh"
ctest --test-dir "$root/build" --output-on-failure -j "$jobs" "${exclude[@]}"
[ "$quick" = 1 ] && exit 0

stage "2/3 the test suite under ASan + UBSan"
"$root/cmake/setup.sh" -DRIGIDLAB_SANITIZE=ON
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
  ctest --test-dir "$root/build-sanitize" --output-on-failure -j "$jobs" "${exclude[@]}"

stage "3/3 fuzzing (libFuzzer, $fuzz_seconds s per target)"
if [ ! -f "$root/build-fuzz/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$root/tests/fuzz" -B "$root/build-fuzz" >/dev/null
fi
cmake --build "$root/build-fuzz" -j "$jobs"
"$root/tests/fuzz/run.sh" "$root/build-fuzz" "$fuzz_seconds"
stage "all tests passed"

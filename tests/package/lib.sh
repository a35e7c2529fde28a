# Shared helpers of the package tests (sourced): a scratch folder outside the trees, runs with the
# build and source trees out of reach, and the verdict.
set -euo pipefail

# make_scratch NAME: $work, a fresh folder under ${TMPDIR:-/tmp}; kept (and named) when a check fails.
make_scratch() {
  work=$(mktemp -d "${TMPDIR:-/tmp}/$1.XXXXXX")
  work=$(realpath "$work")
  case "$work/" in
    "$build"/*|"$source"/*) echo "FAIL: the scratch folder $work is inside the build or source tree (TMPDIR)"; exit 1 ;;
  esac
}

fail() {
  echo "FAIL: $*"
  echo "(scratch folder kept: $work)"
  exit 1
}

# run_hidden BUILD SOURCE COMMAND...: runs COMMAND in a mount namespace of its own in which BUILD
# and SOURCE are empty folders (tmpfs mounted over them), so nothing in them can be found. Sets
# HIDDEN=1 if that worked; without mount namespaces (no `unshare`, or not allowed) it runs COMMAND
# as it is and sets HIDDEN=0.
run_hidden() {
  local b=$1 s=$2
  shift 2
  # shellcheck disable=SC2016
  local hide='mount -t tmpfs none "$1" && mount -t tmpfs none "$2" && [ -z "$(ls -A "$1")" ] && [ -z "$(ls -A "$2")" ] ||
                exit 97
              shift 2; exec "$@"'
  HIDDEN=1
  for flags in -rm -m; do
    if unshare "$flags" true 2>/dev/null; then
      local status=0
      unshare "$flags" sh -c "$hide" hide "$b" "$s" "$@" || status=$?
      [ "$status" -ne 97 ] && return "$status"
    fi
  done
  HIDDEN=0
  "$@"
}

# section NAME: the lines of $work/runs.log after "== NAME", up to the next "== ".
section() {
  awk -v name="== $1" '$0 == name {on = 1; next} /^== / {on = 0} on' "$work/runs.log"
}

# finish MESSAGE: passes (scratch removed), or is skipped when the trees could not be hidden.
finish() {
  if [ "${HIDDEN:-0}" != 1 ]; then
    echo "SKIP: no mount namespace (unshare) to put the build and source trees out of reach; the runs above prove nothing"
    rm -rf "$work"
    exit 77
  fi
  rm -rf "$work"
  echo "$1"
}

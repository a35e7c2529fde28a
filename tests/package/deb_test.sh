#!/usr/bin/env bash
# `cpack -G DEB` makes a Debian package that installs a working rigidlab: its control fields and
# contents are checked (dpkg-deb), then it is unpacked into a fresh folder (dpkg-deb -x, as dpkg
# would install it under /) and its /usr/bin/rigidlab, run from another folder with the build and
# source trees out of reach, prints its version, runs an installed scene and a scene of the user's
# that requires the installed `check` module, and (under Xvfb, when present) opens the sandbox with
# its assets and takes a screenshot.
#   $1: the build tree (already built)   $2: the source tree
source "$(dirname "$0")/lib.sh"
build=$(realpath "$1") source=$(realpath "$2")
command -v dpkg-deb >/dev/null || { echo "SKIP: dpkg-deb is not installed (Debian's dpkg)"; exit 77; }
make_scratch rigidlab-deb

cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work/cpack" >"$work/cpack.log" 2>&1 ||
  fail "cpack -G DEB: $(tail -20 "$work/cpack.log")"
version=$(sed -n 's/^project(rigidlab VERSION \([0-9.]*\) .*/\1/p' "$source/CMakeLists.txt")
deb=("$work"/cpack/rigidlab_"$version"_*.deb)
[ -f "${deb[0]}" ] || fail "no rigidlab_${version}_<arch>.deb in $work/cpack: $(ls "$work/cpack")"
deb=${deb[0]}
echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) KiB"

# Control fields: the name, the version of the CMake project, the libraries the program needs.
dpkg-deb -f "$deb" Package Version Architecture Depends >"$work/control.txt"
grep -qx "Package: rigidlab" "$work/control.txt" || fail "control: $(cat "$work/control.txt")"
grep -qx "Version: $version" "$work/control.txt" || fail "control version, expected $version: $(cat "$work/control.txt")"
grep -q "^Depends: .*libsdl2" "$work/control.txt" || fail "control: no libsdl2 in Depends: $(cat "$work/control.txt")"

# Contents: the program, its scripts and assets, the libraries, headers and package config, the license.
dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./||' >"$work/contents.txt"
for f in usr/bin/rigidlab usr/share/rigidlab/scripts/scenes/pyramid.lua usr/share/rigidlab/scripts/check.lua \
         usr/share/rigidlab/assets/shaders/ usr/lib/librigidlab_core.a usr/lib/librigidlab_lua.a \
         usr/include/rigidlab/world.h usr/lib/cmake/rigidlab/rigidlabConfig.cmake \
         usr/share/doc/rigidlab/LICENSE usr/share/doc/rigidlab/CHANGELOG.md; do
  grep -qx "$f" "$work/contents.txt" || fail "the .deb has no $f"
done
if grep -v -e '^usr/' -e '^$' "$work/contents.txt" | grep -q .; then
  fail "the .deb installs outside /usr: $(grep -v -e '^usr/' -e '^$' "$work/contents.txt" | head -3)"
fi

mkdir -p "$work/root" "$work/elsewhere"
dpkg-deb -x "$deb" "$work/root"
cp "$work/root/usr/share/rigidlab/scripts/scenes/free_fall.lua" "$work/elsewhere/my_scene.lua"

cat >"$work/runs.sh" <<'EOF'
# The unpacked program, from $work/elsewhere, with nothing of the build or source tree in reach.
set -u
work=$1
cd "$work/elsewhere"
unset RIGIDLAB_SCRIPTS RIGIDLAB_ASSETS
rigidlab=$work/root/usr/bin/rigidlab
echo "== version"; "$rigidlab" --version; echo "exit $?"
echo "== run pyramid"; "$rigidlab" run "$work/root/usr/share/rigidlab/scripts/scenes/pyramid.lua"; echo "exit $?"
echo "== run my_scene"; "$rigidlab" run my_scene.lua; echo "exit $?"
if command -v xvfb-run >/dev/null; then
  echo "== sandbox"
  # (Leak checking off for the window alone, as in tests/sandbox: under ASan, LeakSanitizer reports
  # what libdbus and the Mesa driver never free, none of it rigidlab's; address checks stay on.)
  ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 \
    xvfb-run -a -s "-screen 0 1280x720x24" "$rigidlab" --frames 3 --screenshot "$work/sandbox.png" 2>&1
  echo "exit $?"
fi
EOF
run_hidden "$build" "$source" bash "$work/runs.sh" "$work" >"$work/runs.log" 2>&1

section version | grep -q "^rigidlab $version (" || fail "--version printed: $(section version)"
section "run pyramid" | grep -q "^check  *passed" || fail "run pyramid.lua printed: $(section "run pyramid")"
section "run my_scene" | grep -q "^check  *passed" || fail "run my_scene.lua printed: $(section "run my_scene")"
for s in version "run pyramid" "run my_scene"; do
  section "$s" | grep -q "^exit 0$" || fail "$s: $(section "$s" | tail -1)"
done
if command -v xvfb-run >/dev/null; then
  section sandbox | grep -q "^opened .*playground.lua" || fail "the sandbox did not open its default scene: $(section sandbox)"
  section sandbox | grep -q "^exit 0$" || fail "the sandbox: $(section sandbox | tail -3)"
  [ -s "$work/sandbox.png" ] || fail "the sandbox wrote no screenshot"
else
  echo "(xvfb-run missing: the sandbox was not opened)"
fi
finish "package: $(basename "$deb") unpacked into a fresh folder runs rigidlab and its scenes: ok"

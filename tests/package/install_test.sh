#!/usr/bin/env bash
# rigidlab as another project uses it: installed into a fresh prefix, then examples/ configured
# against that prefix alone (find_package(rigidlab)), built, and run: the C++ example's box comes to
# rest, the Lua example runs the installed pyramid scene (found relative to nothing but the install)
# and its Check passes. Also: the installed program finds its scripts in the prefix.
#   $1: the build tree (already built)   $2: the source tree   $3: a scratch directory
set -euo pipefail
build=$1 source=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" || fail "cmake --install: $(tail -5 "$work/install.log")"
for f in lib/librigidlab_core.a lib/librigidlab_lua.a include/rigidlab/world.h include/rigidlab/lua/scene.h \
         lib/cmake/rigidlab/rigidlabConfig.cmake share/rigidlab/scripts/scenes/pyramid.lua bin/rigidlab; do
  [ -e "$work/prefix/$f" ] || fail "the install has no $f"
done
# Nothing installed points back into the build or source tree.
if grep -rl -e "$build" -e "$source" "$work/prefix/lib/cmake" >/dev/null; then
  fail "the package config names the build or source tree: $(grep -rl -e "$build" -e "$source" "$work/prefix/lib/cmake")"
fi

cmake -S "$source/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$work/configure.log" 2>&1 || fail "configuring examples/: $(tail -20 "$work/configure.log")"
cmake --build "$work/examples" -j 2 >"$work/build.log" 2>&1 || fail "building examples/: $(tail -30 "$work/build.log")"

# Run from a directory where no share/rigidlab is in reach but the prefix's.
out=$(cd "$work" && env -u RIGIDLAB_SCRIPTS "$work/examples/hello_world") || fail "hello_world exited $?: $out"
echo "$out" | grep -q "t = 2.00 s  box at" || fail "hello_world printed: $out"
out=$(cd "$work" && env -u RIGIDLAB_SCRIPTS "$work/examples/lua_scene" "$work/prefix/share/rigidlab/scripts/scenes/pyramid.lua") \
  || fail "lua_scene exited $?: $out"
echo "$out" | grep -q "pyramid.lua: .* bodies after .*Check passed" || fail "lua_scene printed: $out"
# The installed program, moved away from the build tree, finds its own scripts (relative to bin/).
out=$(cd "$work" && env -u RIGIDLAB_SCRIPTS "$work/prefix/bin/rigidlab" run "$work/prefix/share/rigidlab/scripts/scenes/free_fall.lua" 2>&1) \
  || fail "installed rigidlab run exited $?: $out"
echo "package: installed, examples built against the prefix and run: ok"

#!/usr/bin/env bash
# rigidlab as another project uses it: installed into a fresh prefix, then examples/ (copied out of
# the source tree) configured against that prefix alone (find_package(rigidlab)), built, and run
# from another folder with the build tree and the source tree made unreachable (covered by empty
# folders in a mount namespace of the run's own, `unshare`): the C++ example's box comes to rest;
# the Lua example runs the installed pyramid scene by default, and a scene of the user's that
# requires the installed `check` module; $RIGIDLAB_SCRIPTS still wins over the package; the
# installed program finds its own scripts too.
#   $1: the build tree (already built)   $2: the source tree
# Scratch: a fresh folder under ${TMPDIR:-/tmp} (outside both trees), removed when the test passes.
# Exit status 77 (ctest: skipped) when no mount namespace can be made: the runs without hiding the
# trees are then no proof.
source "$(dirname "$0")/lib.sh"
build=$(realpath "$1") source=$(realpath "$2")
make_scratch rigidlab-package

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" || fail "cmake --install: $(tail -5 "$work/install.log")"
for f in lib/librigidlab_core.a lib/librigidlab_lua.a include/rigidlab/world.h include/rigidlab/lua/scene.h \
         lib/cmake/rigidlab/rigidlabConfig.cmake share/rigidlab/scripts/scenes/pyramid.lua share/rigidlab/scripts/check.lua \
         share/doc/rigidlab/LICENSE bin/rigidlab; do
  [ -e "$work/prefix/$f" ] || fail "the install has no $f"
done
# Nothing installed points back into the build or source tree.
if grep -rl -e "$build" -e "$source" "$work/prefix/lib/cmake" >/dev/null; then
  fail "the package config names the build or source tree: $(grep -rl -e "$build" -e "$source" "$work/prefix/lib/cmake")"
fi

cp -r "$source/examples" "$work/examples-src"
cmake -S "$work/examples-src" -B "$work/examples" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$work/configure.log" 2>&1 || fail "configuring examples/: $(tail -20 "$work/configure.log")"
cmake --build "$work/examples" -j 2 >"$work/build.log" 2>&1 || fail "building examples/: $(tail -30 "$work/build.log")"
# No program names a data folder of the build or source tree (a path it could fall back on). Their
# source files' names may appear: a sanitizer or debug build's library carries them in its
# diagnostics and debug information, and they point at no data.
for program in hello_world lua_scene; do
  if grep -a -q -e "$build/share" -e "$source/scripts" -e "$source/assets" "$work/examples/$program"; then
    fail "$program names a data folder of the build or source tree"
  fi
done

# A scene of the user's own, elsewhere, that requires the installed `check` module; and a scripts
# folder of the user's own, whose pyramid.lua is a single ball.
mkdir -p "$work/elsewhere" "$work/own_scripts/scenes"
cp "$work/prefix/share/rigidlab/scripts/scenes/free_fall.lua" "$work/elsewhere/my_scene.lua"
grep -q 'require "check"' "$work/elsewhere/my_scene.lua" || fail "free_fall.lua no longer requires check: pick another scene"
cat >"$work/own_scripts/scenes/pyramid.lua" <<'EOF'
scene = { duration = 0.5 }
function PopulateWorld(world) world:add_circle{ radius = 0.5, position = {0, 3} } end
EOF

cat >"$work/runs.sh" <<'EOF'
# The runs, from $work/elsewhere, with nothing of the build or source tree in reach.
set -u
work=$1
cd "$work/elsewhere"
unset RIGIDLAB_SCRIPTS RIGIDLAB_ASSETS
echo "== hello_world"; "$work/examples/hello_world"; echo "exit $?"
echo "== lua_scene"; "$work/examples/lua_scene"; echo "exit $?"
echo "== lua_scene my_scene.lua"; "$work/examples/lua_scene" my_scene.lua; echo "exit $?"
echo "== RIGIDLAB_SCRIPTS lua_scene"; RIGIDLAB_SCRIPTS="$work/own_scripts" "$work/examples/lua_scene"; echo "exit $?"
echo "== rigidlab run my_scene.lua"; "$work/prefix/bin/rigidlab" run my_scene.lua; echo "exit $?"
EOF
run_hidden "$build" "$source" bash "$work/runs.sh" "$work" >"$work/runs.log" 2>&1

section hello_world | grep -q "t = 2.00 s  box at" || fail "hello_world printed: $(section hello_world)"
section lua_scene | grep -q "^pyramid.lua: .* bodies after .*Check passed" || fail "lua_scene printed: $(section lua_scene)"
section "lua_scene my_scene.lua" | grep -q "^my_scene.lua: .* bodies after .*Check passed" ||
  fail "lua_scene my_scene.lua printed: $(section "lua_scene my_scene.lua")"
section "RIGIDLAB_SCRIPTS lua_scene" | grep -q "^pyramid.lua: 1 bodies after 0.50 s" ||
  fail "\$RIGIDLAB_SCRIPTS did not win: $(section "RIGIDLAB_SCRIPTS lua_scene")"
section "rigidlab run my_scene.lua" | grep -q "^check  *passed" || fail "installed rigidlab run printed: $(section "rigidlab run my_scene.lua")"
for s in hello_world lua_scene "lua_scene my_scene.lua" "RIGIDLAB_SCRIPTS lua_scene" "rigidlab run my_scene.lua"; do
  section "$s" | grep -q "^exit 0$" || fail "$s: $(section "$s" | tail -1)"
done
finish "package: installed, examples built against the prefix and run with the build and source trees out of reach: ok"

-- A SaveState that returns what cannot be saved, met by --save-state: a scene error, exit 1 (it
-- exited 2, the usage status, with the right message), and no state file.
-- exit: 1
-- sandbox: no-overlay
-- run: --time 0.1 --quiet --save-state state.snap
-- expect: save_state_function.lua:10: SaveState: value at state is a function; only nil, booleans, numbers, strings, tables and body/shape/joint/force handles can be saved
-- reject: --save-state
-- absent: state.snap
function PopulateWorld(world) world:add_circle{ radius = 1 } end
function SaveState(world) return function() end end

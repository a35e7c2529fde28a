-- --save-state into a folder that does not exist is an error, as for every other output path: it
-- used to make the missing folders (one at the file system's root).
-- exit: 2
-- run: --time 0.1 --quiet --save-state missing/deeper/state.snap
-- expect: run: --save-state: missing/deeper/state.snap: cannot write the file: the folder missing/deeper does not exist
-- absent: missing
function PopulateWorld(world) world:add_circle{ radius = 1 } end

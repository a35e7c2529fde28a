-- --load-state of a device that never ends: the header (30 bytes) is read and refused. It used to
-- read until 2.1 GB were resident and end in std::bad_alloc.
-- exit: 2
-- run: --load-state /dev/zero --force --quiet
-- expect: run: --load-state: /dev/zero: snapshot: not a rigidlab snapshot (no "RIGIDLAB-SNAPSHOT" header)
-- reject: bad_alloc
function PopulateWorld(world) world:add_circle{ radius = 1 } end

-- dt = 1e-300 overflowed the step count's conversion to an integer: the run exited 0 with zero
-- steps taken. The count is checked before it is converted.
-- exit: 1
-- sandbox: no-overlay
-- run: --quiet
-- expect: takes 1e+301 steps, more than the limit of 10000000 steps per run
-- reject: run     0 steps
scene = { dt = 1e-300 }
function PopulateWorld(world) world:add_circle{ radius = 1 } end

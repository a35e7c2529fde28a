-- Degenerate step sizes: dt = 1e-12 with a 1 s run asked for 1e12 steps and hung. A run of more
-- than 10 000 000 steps is refused before it starts.
-- exit: 1
-- sandbox: no-overlay
-- run: --quiet
-- expect: run: reaching t = 1 s with steps of dt = 1e-12 s takes 1e+12 steps, more than the limit of 10000000 steps per run
scene = { dt = 1e-12, duration = 1 }
function PopulateWorld(world) world:add_circle{ radius = 1 } end

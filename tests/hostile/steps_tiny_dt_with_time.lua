-- The scene's own dt asks for 5e11 steps: a scene error (exit 1) whatever --time says; it used to
-- exit 2 (usage) when --time was given. --steps or --dt too large stay the command line's (2).
-- exit: 1
-- sandbox: no-overlay
-- run: --time 0.5 --quiet
-- expect: run: reaching t = 0.5 s with steps of dt = 1e-12 s takes 5e+11 steps, more than the limit of 10000000 steps per run
scene = { dt = 1e-12 }
function PopulateWorld(world) world:add_circle{ radius = 1 } end

-- A force that acts for a limited time (docs/design/accuracy.md §3.7, with t_off = 1.04 s instead of 1.05 s):
-- F = 10 N on m = 2 kg for 0 ≤ t < 1.04 s, then nothing; x(2) = ½ (F/m) t_off² + (F t_off/m)(2 − t_off)
-- = 7.696 m, v = 5.2 m/s. 1.04 s is on none of the sweep's step grids (1.04 · 30 · 2^k is never a
-- whole number), so every run has a step that straddles the end time; 1.05 s would be on the grid
-- for every dt ≤ 1/60 and test nothing.
-- The force is a Lua force with `duration = 1.04`: the core splits the straddling step at the end
-- time, so RK4 stays exact (piecewise constant force) and the Euler variants keep their
-- ±½(F/m) t h error. Compare time_limited_naive.lua, which switches the force off itself.
scene = { sleeping = false, title = "Time-limited force (duration)", gravity = {0, 0}, dt = 1 / 60, duration = 2,
          camera = { center = {4, 0}, height = 4 } }

local F, m, t_off = 10.0, 2.0, 1.04

accuracy = {
  group = "smooth",
  t_end = 2,
  reference_length = 1,  -- absolute error [m]
  metrics = { "velocity" },
  reference_speed = 1,
  expected_order = { rk4 = "exact" },
  note = "the step is split at the force's end time: RK4 exact",
}

function PopulateWorld(world)
  local box = world:add_circle{ name = "body", radius = 0.1, mass = m }
  world:add_force{ body = box, duration = t_off, evaluate = function() return F, 0 end }
end

function Exact(t)
  local a = F / m
  if t <= t_off then return { body = { position = { 0.5 * a * t * t, 0 }, velocity = { a * t, 0 } } } end
  return { body = { position = { 0.5 * a * t_off * t_off + a * t_off * (t - t_off), 0 }, velocity = { a * t_off, 0 } } }
end

-- The pitfall of docs/design/accuracy.md §3.7: the same force as time_limited_force.lua (10 N on 2 kg until
-- t = 1.04 s), but switched off by its own `evaluate` when `s.time` reaches 1.04 s instead of
-- through `duration`. The integrator does not know the force has a discontinuity, so a step that
-- contains it sees the wrong force for part of the step and every integrator, RK4 included, is
-- first order. Shown in the report beside the split version.
scene = { sleeping = false, title = "Time-limited force (switched in evaluate)", gravity = {0, 0}, dt = 1 / 60, duration = 2,
          camera = { center = {4, 0}, height = 4 } }

local F, m, t_off = 10.0, 2.0, 1.04

accuracy = {
  group = "smooth",
  t_end = 2,
  reference_length = 1,  -- absolute error [m]
  metrics = { "velocity" },
  reference_speed = 1,
  expected_order = { rk4 = 1 },
  note = "a discontinuity the integrator cannot see: order 1 for every integrator",
}

function PopulateWorld(world)
  local box = world:add_circle{ name = "body", radius = 0.1, mass = m }
  world:add_force{ body = box, evaluate = function(s)
    if s.time < t_off then return F, 0 end
    return 0, 0
  end }
end

function Exact(t)
  local a = F / m
  if t <= t_off then return { body = { position = { 0.5 * a * t * t, 0 }, velocity = { a * t, 0 } } } end
  return { body = { position = { 0.5 * a * t_off * t_off + a * t_off * (t - t_off), 0 }, velocity = { a * t_off, 0 } } }
end

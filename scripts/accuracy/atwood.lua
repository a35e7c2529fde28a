-- An Atwood machine: two boxes of m1 = 3 kg and m2 = 1 kg hang from a pulley joint whose rope runs
-- over two fixed points 4 m above them, released at rest. The heavier side goes down at
-- a = g (m1 − m2)/(m1 + m2) = g/2, the lighter one up at the same rate: a constant acceleration,
-- which RK4 integrates exactly; the Euler methods are first order.
local m1, m2, g, H = 3.0, 1.0, 9.81, 4.0
scene = { sleeping = false, title = "Atwood machine (pulley joint)", gravity = { 0, -g }, dt = 1 / 60,
          duration = 1, camera = { center = {0, 1}, height = 8 } }

local a = g * (m1 - m2) / (m1 + m2)

accuracy = {
  group = "mechanism",
  t_end = 1,
  reference_length = 1,
  expected_order = { euler = 1, semi_implicit_euler = 1, rk4 = "exact", implicit_euler = 1 },
  note = string.format("a = g (m1 − m2)/(m1 + m2) = %.4f m/s²", a),
}

function PopulateWorld(world)
  local heavy = world:add_box{ name = "heavy", width = 0.4, height = 0.4, mass = m1, position = { -1, 0 } }
  local light = world:add_box{ name = "light", width = 0.4, height = 0.4, mass = m2, position = { 1, 0 } }
  world:add_pulley{ a = heavy, b = light, anchor_a = { -1, 0 }, anchor_b = { 1, 0 }, ground_a = { -1, H },
                    ground_b = { 1, H } }
end

function Exact(t)
  local s = 0.5 * a * t * t
  return { heavy = { position = { -1, -s } }, light = { position = { 1, s } } }
end

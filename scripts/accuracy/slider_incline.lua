-- A slider on an incline: a 2 kg block on a prismatic joint to the world along a 30° slope, no
-- friction (the joint holds it on the line, nothing touches), released at rest. Along the slope
-- s = ½ g sin α t²: a constant acceleration, which RK4 integrates exactly, and the joint's force
-- m g cos α is constant too; the Euler methods are first order.
local m, g, alpha = 2.0, 9.81, math.rad(30)
local u = { math.cos(alpha), -math.sin(alpha) }  -- down the slope
scene = { sleeping = false, title = "Slider on a 30° incline (prismatic joint)", gravity = { 0, -g }, dt = 1 / 60,
          duration = 2, camera = { center = {4, -2}, height = 8 } }

accuracy = {
  group = "mechanism",
  t_end = 2,
  reference_length = 1,
  expected_order = { euler = 1, semi_implicit_euler = 1, rk4 = "exact", implicit_euler = 1 },
  note = "s = ½ g sin α t², α = 30°",
}

function PopulateWorld(world)
  local block = world:add_box{ name = "block", width = 0.4, height = 0.2, mass = m, position = { 0, 0 },
                               angle = -alpha }
  world:add_prismatic{ a = block, anchor = { 0, 0 }, axis = u }
end

function Exact(t)
  local s = 0.5 * g * math.sin(alpha) * t * t
  return { block = { position = { s * u[1], s * u[2] }, angle = -alpha } }
end

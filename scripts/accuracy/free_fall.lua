-- Free fall from rest (docs/design/accuracy.md §3.1, the thesis's Table 4.1): y(t) = −½ g t².
-- A round-off sanity check, not an order fit: explicit Euler gives −½gT(T − h), semi-implicit Euler
-- −½gT(T + h) (error ½gTh, order 1), RK4 is exact for constant acceleration (round-off only).
scene = { sleeping = false, title = "Free fall", dt = 1 / 60, duration = 10, camera = { center = {0, -245}, height = 520 } }

local g = 9.80665

accuracy = {
  group = "sanity",
  t_end = 10,
  reference_length = 490.3325,  -- the drop in 10 s [m]
  expected_order = { rk4 = "exact" },
  note = "RK4 exact for constant acceleration; Euler variants off by ±½gTh",
}

function PopulateWorld(world)
  world:add_circle{ name = "ball", radius = 0.5, mass = 1 }
end

function Exact(t)
  return { ball = { position = {0, -0.5 * g * t * t}, velocity = {0, -g * t} } }
end

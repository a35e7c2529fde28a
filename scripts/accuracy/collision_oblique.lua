-- Oblique frictionless impact of equal discs (docs/design/accuracy.md §3.10): m = 1 kg, r = 1 m; A at rest, B
-- moving at (2, 0) m/s along a line 1 m off A's centre (impact parameter = half the sum of the
-- radii), so at the impact the normal from A to B is n = (−√3/2, ½). With j = (1 + e) √3/2:
--   e = 1:   vB' = (0.5, 0.866025), vA' = (1.5, −0.866025), 2 J kept, vA' ⊥ vB'
--   e = 0.5: vB' = (0.875, 0.649519), vA' = (1.125, −0.649519), 1.4375 J kept
-- No friction, so the spins stay 0. Two lanes 6 m apart; the impacts are at t = 0.5 s.
scene = { sleeping = false, title = "Oblique collisions, e = 1 and 0.5", gravity = {0, 0}, dt = 1 / 60, duration = 1.5,
          camera = { center = {0, 3}, height = 12 } }

local m, r, speed, tc = 1.0, 1.0, 2.0, 0.5
local lanes = { { e = 1, y = 0 }, { e = 0.5, y = 6 } }
local nx, ny = -math.sqrt(3) / 2, 0.5  -- normal from A to B at the impact
local bx, by = -math.sqrt(3), 1.0      -- B's centre relative to A's at the impact

accuracy = {
  group = "impact",
  -- Straight flights (no gravity) with the impact located inside the step: every integrator is
  -- exact to round-off (measured: at most 7.5e-13 m; 0.027 m at 1/60 with impacts once per step).
  expected_order = { euler = "exact", semi_implicit_euler = "exact", rk4 = "exact", implicit_euler = "exact" },
  t_end = 1.5,
  reference_length = 1,  -- absolute error [m]
  metrics = { "momentum", "velocity" },
  reference_speed = 1,
  note = "frictionless: impulse along the normal only",
}

function PopulateWorld(world)
  for i, lane in ipairs(lanes) do
    world:add_circle{ name = "a" .. i, radius = r, mass = m, position = {0, lane.y}, restitution = lane.e, friction = 0 }
    world:add_circle{ name = "b" .. i, radius = r, mass = m, position = { bx - speed * tc, lane.y + by },
                      velocity = {speed, 0}, restitution = lane.e, friction = 0 }
  end
end

function Exact(t)
  local out = {}
  for i, lane in ipairs(lanes) do
    local va, vb = {0, 0}, {speed, 0}
    if t > tc then
      -- j = −(1 + e) (v_rel · n) / (1/mA + 1/mB), v_rel = vB − vA
      local j = -(1 + lane.e) * (speed * nx) / (2 / m)
      va = { -j * nx / m, -j * ny / m }
      vb = { speed + j * nx / m, j * ny / m }
    end
    local s = t - tc
    out["a" .. i] = { position = { va[1] * s, lane.y + va[2] * s }, velocity = va }
    out["b" .. i] = { position = { bx + vb[1] * s, lane.y + by + vb[2] * s }, velocity = vb }
  end
  return out
end

-- Two discs colliding in flight under gravity: the oblique impact of collision_oblique.lua thrown
-- upwards together. Equal discs, m = 1 kg, r = 1 m, frictionless; both start with the same upward
-- velocity (0, 4) m/s under g = 9.80665 m/s², B also moving at (2, 0) m/s along a line 1 m off
-- A's centre. Gravity and the common velocity move both discs alike, so the relative motion is a
-- straight line and the impact is at t_c = 0.537 s (off every step grid of the sweep) with the
-- normal from A to B n = (−√3/2, ½), as without gravity. The impulse j = (1 + e) √3/2 depends only
-- on the relative velocity, so each disc's motion is the gravity-free answer plus the common
-- parabola (0, 4 t − ½ g t²):
--   e = 1:   vB' − vB = (−1.5, 0.866025), vA' − vA = (1.5, −0.866025)
--   e = 0.5: vB' − vB = (−1.125, 0.649519), vA' − vA = (1.125, −0.649519)
scene = { sleeping = false, title = "Two discs colliding in flight under gravity, e = 1 and 0.5", dt = 1 / 60,
          duration = 1.5, camera = { center = {0, 2}, height = 18 } }

local g, m, r, speed, up, tc = 9.80665, 1.0, 1.0, 2.0, 4.0, 0.537
local lanes = { { e = 1, y = 0 }, { e = 0.5, y = 6 } }
local nx, ny = -math.sqrt(3) / 2, 0.5  -- normal from A to B at the impact
local bx, by = -math.sqrt(3), 1.0      -- B's centre relative to A's at the impact

accuracy = {
  group = "impact",
  -- Parabolas: RK4 integrates them exactly and the impact is located inside its step, so RK4 is
  -- exact to round-off; the Euler family keeps its own order 1 in flight.
  expected_order = { rk4 = "exact" },
  t_end = 1.5,
  reference_length = 1,  -- absolute error [m]
  metrics = { "momentum", "velocity" },
  reference_speed = 1,
  note = "frictionless impact between two parabolas, off the step grid",
}

function PopulateWorld(world)
  for i, lane in ipairs(lanes) do
    world:add_circle{ name = "a" .. i, radius = r, mass = m, position = {0, lane.y}, velocity = {0, up},
                      restitution = lane.e, friction = 0 }
    world:add_circle{ name = "b" .. i, radius = r, mass = m, position = { bx - speed * tc, lane.y + by },
                      velocity = {speed, up}, restitution = lane.e, friction = 0 }
  end
end

function Exact(t)
  local out = {}
  local lift, vlift = up * t - 0.5 * g * t * t, up - g * t  -- the common parabola
  for i, lane in ipairs(lanes) do
    local va, vb = {0, 0}, {speed, 0}
    if t > tc then
      -- j = −(1 + e) (v_rel · n) / (1/mA + 1/mB), v_rel = vB − vA (gravity-free parts)
      local j = -(1 + lane.e) * (speed * nx) / (2 / m)
      va = { -j * nx / m, -j * ny / m }
      vb = { speed + j * nx / m, j * ny / m }
    end
    local s = t - tc
    out["a" .. i] = { position = { va[1] * s, lane.y + va[2] * s + lift }, velocity = { va[1], va[2] + vlift } }
    out["b" .. i] = { position = { bx + vb[1] * s, lane.y + by + vb[2] * s + lift },
                      velocity = { vb[1], vb[2] + vlift } }
  end
  return out
end

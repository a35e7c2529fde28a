-- Head-on collisions of discs with restitution (docs/design/accuracy.md §3.10): m1 = 1 kg at +2 m/s meets
-- m2 = 3 kg at −1 m/s (total momentum −1 kg·m/s, 3.5 J). Newton's law along the normal gives
--   e = 1:   v1' = −2.5,   v2' = 0.5    (3.5 J kept)
--   e = 0.5: v1' = −1.375, v2' = 0.125  (2.53125 J lost)
--   e = 0:   v1' = v2' = −0.25          (3.375 J lost)
-- One lane per restitution, 4 m apart; in each the discs (r = 0.5 m) touch at x = 0 at t = 0.5 s.
-- The impulse algebra is exact, and the impact is located inside the step: every integrator is exact
-- to round-off (so it was once per step too: t = 0.5 s lies on every step grid of the sweep).
scene = { sleeping = false, title = "Head-on collisions, e = 1, 0.5, 0", gravity = {0, 0}, dt = 1 / 60, duration = 1.5,
          camera = { center = {0, 4}, height = 12 } }

local m1, m2, v1, v2, r, tc = 1.0, 3.0, 2.0, -1.0, 0.5, 0.5
local lanes = { { e = 1, y = 0 }, { e = 0.5, y = 4 }, { e = 0, y = 8 } }

accuracy = {
  group = "impact",
  expected_order = { euler = "exact", semi_implicit_euler = "exact", rk4 = "exact", implicit_euler = "exact" },
  t_end = 1.5,
  reference_length = 1,  -- absolute error [m]
  metrics = { "momentum", "velocity" },
  reference_speed = 1,
  note = "velocities after impact exact to round-off; position error from the impact time",
}

function PopulateWorld(world)
  for i, lane in ipairs(lanes) do
    world:add_circle{ name = "a" .. i, radius = r, mass = m1, position = { -r - v1 * tc, lane.y }, velocity = {v1, 0},
                      restitution = lane.e, friction = 0 }
    world:add_circle{ name = "b" .. i, radius = r, mass = m2, position = { r - v2 * tc, lane.y }, velocity = {v2, 0},
                      restitution = lane.e, friction = 0 }
  end
end

function Exact(t)
  local out = {}
  for i, lane in ipairs(lanes) do
    local u1, u2, x1, x2 = v1, v2, -r, r  -- velocities (before or after) and positions at the impact
    if t > tc then
      local j = (1 + lane.e) * (v1 - v2) / (1 / m1 + 1 / m2)
      u1, u2 = v1 - j / m1, v2 + j / m2
    end
    local s = t - tc
    out["a" .. i] = { position = { x1 + u1 * s, lane.y }, velocity = { u1, 0 } }
    out["b" .. i] = { position = { x2 + u2 * s, lane.y }, velocity = { u2, 0 } }
  end
  return out
end

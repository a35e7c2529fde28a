-- The thesis's frictional impact (docs/design/thesis.md §12 experiment 1, docs/design/accuracy.md §3.11) and a stick-regime
-- variant. Unit-mass solid discs of r = 2 m (I = 2 kg·m²), e = 1, μ = 0.5, no gravity; A at rest,
-- B moving at (−1, 0) m/s, spinning at ω_B; they touch at t = 1 s with n = (1, 0) from A to B.
--   sliding (ω_B = 2 rad/s): slip 4 m/s needs 2/3 N·s > μ j_n = 0.5, so j_t = 0.5:
--     vA = (−1, −0.5), vB = (0, 0.5), ωA = −0.5, ωB = 1.5
--   sticking (ω_B = 0.5 rad/s): slip 1 m/s needs 1/6 N·s < 0.5, so the slip stops:
--     vA = (−1, −1/6), vB = (0, 1/6), ωA = −1/6, ωB = 1/3
-- The sliding result does not depend on the inertia; the sticking one does.
scene = { sleeping = false, title = "Frictional impacts (thesis experiment 1 and a sticking variant)", gravity = {0, 0},
          dt = 1 / 60, duration = 2, camera = { center = {2, 5}, height = 20 } }

local r, m, I, e, mu, tc = 2.0, 1.0, 2.0, 1.0, 0.5, 1.0
local lanes = { { w = 2, y = 0 }, { w = 0.5, y = 10 } }

accuracy = {
  group = "impact",
  -- Straight flights (no gravity) with the impact located inside the step: every integrator is
  -- exact to round-off (measured: at most 2.6e-12 m; 0.0093 m at 1/60 with impacts once per step).
  expected_order = { euler = "exact", semi_implicit_euler = "exact", rk4 = "exact", implicit_euler = "exact" },
  t_end = 2,
  reference_length = 1,  -- absolute error [m]
  metrics = { "momentum", "velocity" },
  reference_speed = 1,
  note = "Coulomb friction in the impact: sliding and sticking regimes",
}

function PopulateWorld(world)
  for i, lane in ipairs(lanes) do
    world:add_circle{ name = "a" .. i, radius = r, mass = m, position = {0, lane.y}, restitution = e, friction = mu }
    world:add_circle{ name = "b" .. i, radius = r, mass = m, position = { 2 * r + tc, lane.y }, velocity = {-1, 0},
                      angular_velocity = lane.w, restitution = e, friction = mu }
  end
end

function Exact(t)
  local out = {}
  for i, lane in ipairs(lanes) do
    local jn = (1 + e) * 1 / (1 / m + 1 / m)            -- normal impulse on B along +x (approach speed 1)
    local need = r * lane.w / (2 / m + 2 * r * r / I)   -- tangential impulse that stops the slip
    local jt = math.max(-mu * jn, math.min(mu * jn, need))
    local va, vb, wa, wb = {0, 0}, {-1, 0}, 0, lane.w
    if t > tc then
      va = { -jn / m, -jt / m }
      vb = { -1 + jn / m, jt / m }
      wa = (r * -jt) / I         -- rA = (r, 0), J_A = (−jn, −jt): rA × J_A = −r jt
      wb = lane.w + (-r * jt) / I  -- rB = (−r, 0), J_B = (jn, jt): rB × J_B = −r jt
    end
    local s = t - tc
    out["a" .. i] = { position = { va[1] * s, lane.y + va[2] * s }, velocity = va,
                      angular_velocity = wa }
    out["b" .. i] = { position = { 2 * r + vb[1] * s, lane.y + vb[2] * s }, velocity = vb,
                      angular_velocity = wb }
  end
  return out
end

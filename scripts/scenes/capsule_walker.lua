-- A capsule character with fixed rotation walking up a 20° slope, as a game drives one: after
-- every step OnStep sets its velocity to the commanded walk along the slope, v = 2 m/s, for 1.5 s,
-- then to zero once, and leaves it. Two walkers, on slopes of different friction:
--   grip (μ = μ_s = 0.8 > tan 20° = 0.364): it walks, then stands where it stopped;
--   slip (μ = μ_s = 0.2 < tan 20°): it walks, then slides back down from rest at
--     a = g (sin θ − μ cos θ) (the block's law: the capsule cannot turn, so it cannot roll).
-- While walking the capsule slides over the slope at the commanded speed, so during each step it
-- decelerates at a_w = g sin θ + μ g cos θ (gravity along the slope and sliding friction, μ times
-- the normal force m g cos θ), from the v set before the step: it climbs v dt − ½ a_w dt² per step,
-- a speed of v − ½ a_w dt (RK4, the default integrator, is exact under a constant acceleration):
-- 1.91061 m/s for grip, 1.95671 m/s for slip. A walker that caught on the slope, rolled, bounced
-- or felt the wrong friction would climb otherwise. It never turns (angle and angular velocity
-- exactly 0) and keeps touching the slope: its lower end stays one radius from the surface.
local check = require "check"

scene = { title = "Capsule walker (fixed rotation on a slope)", dt = 1 / 60, duration = 3,
          camera = { center = {2, 0}, height = 9 } }

local theta, speed, walk_time = math.rad(20), 2, 1.5
local radius, half = 0.25, 0.25  -- the segment's ends 0.25 m above and below the centre: 1 m tall
local t = vec2(math.cos(theta), math.sin(theta))  -- up the slope
local n = vec2(-t.y, t.x)                          -- the slope's outward normal
local walkers = {
  { name = "grip", friction = 0.8, origin = vec2(0, 2) },
  { name = "slip", friction = 0.2, origin = vec2(0, -2) },
}

function PopulateWorld(world)
  for _, w in ipairs(walkers) do
    -- The slope: a long box whose top face passes through `origin`.
    world:add_box{ width = 12, height = 1, angle = theta, position = w.origin - n * 0.5, static = true,
                   friction = w.friction, static_friction = w.friction }
    -- Upright, its lower end's circle touching the slope: that centre one radius along the normal.
    w.body = world:add_capsule{ name = w.name, a = {0, -half}, b = {0, half}, radius = radius,
                                position = w.origin + n * radius + vec2(0, half), fixed_rotation = true,
                                friction = w.friction, static_friction = w.friction }
    w.start = w.body.position
    w.body.velocity = t * speed
    w.climbs, w.gap_error, w.untouched, w.turned = {}, 0, 0, 0
  end
end

-- Distance up the slope from the start, and the lower end's distance from the surface minus r.
local function along(w) return (w.body.position - w.start):dot(t) end
local function gap(w) return (w.body.position - vec2(0, half) - w.origin):dot(n) - radius end

function OnStep(world, dt)
  for _, w in ipairs(walkers) do
    local s = along(w)
    if world.time <= walk_time + 1e-9 then
      w.climbs[#w.climbs + 1] = (s - (w.last or 0)) / dt
      w.gap_error = math.max(w.gap_error, math.abs(gap(w)))
      if #w.body:contacts() == 0 then w.untouched = w.untouched + 1 end
    end
    if w.body.angle ~= 0 or w.body.angular_velocity ~= 0 then w.turned = w.turned + 1 end
    w.last = s
    if world.time < walk_time - 1e-9 then
      w.body.velocity = t * speed  -- the drive: the commanded walk, every step
    elseif world.time < walk_time + dt - 1e-9 then
      -- The step at the end of the walk, told by the clock rather than by a Lua variable, so that a
      -- run resumed from a snapshot (docs/testing.md 'Snapshots') stops alike.
      w.stopped = { time = world.time, s = s }
      w.body.velocity = {0, 0}  -- stop once; from now on only gravity, the slope and friction act
    end
  end
end

function Check(world)
  local g = -world.gravity.y
  local dt = scene.dt
  for _, w in ipairs(walkers) do
    local expected = speed - 0.5 * (g * math.sin(theta) + w.friction * g * math.cos(theta)) * dt
    local lo, hi = math.huge, -math.huge
    for _, v in ipairs(w.climbs) do lo, hi = math.min(lo, v), math.max(hi, v) end
    print(string.format("%s: climbed at %.9f to %.9f m/s per step (v - a_w dt / 2 = %.9f), gap %.2g m", w.name,
                        lo, hi, expected, w.gap_error))
    check.greater(w.name .. ": walked every step", #w.climbs, 80)
    check.near(w.name .. ": slowest step's climb = v - (g sin + mu g cos) dt / 2", lo, expected, 1e-6 * speed)
    check.near(w.name .. ": fastest step's climb = v - (g sin + mu g cos) dt / 2", hi, expected, 1e-6 * speed)
    check.near(w.name .. ": climbed in the walk", w.stopped.s, expected * walk_time, 1e-6 * speed * walk_time)
    check.less(w.name .. ": keeps its lower end on the slope (gap to the surface)", w.gap_error, 2e-3)
    check.near(w.name .. ": touching the slope every step of the walk", w.untouched, 0, 0)
    check.near(w.name .. ": never turned (fixed rotation, angle and spin exactly 0)", w.turned, 0, 0)
  end
  -- After the stop: grip holds (friction allows), slip slides back ½ a τ² from rest.
  local grip, slip = walkers[1], walkers[2]
  local tau = world.time - slip.stopped.time
  print(string.format("grip: moved %.3g m since the stop; slip: %.6f m down in %.3f s (½ a τ² = %.6f m)",
                      along(grip) - grip.stopped.s, slip.stopped.s - along(slip), tau,
                      0.5 * g * (math.sin(theta) - slip.friction * math.cos(theta)) * tau * tau))
  check.less("grip: stands where it stopped (static friction 0.8 > tan 20°)", math.abs(along(grip) - grip.stopped.s), 1e-6)
  local a = g * (math.sin(theta) - slip.friction * math.cos(theta))
  check.near("slip: slides back ½ a τ², a = g (sin θ − μ cos θ)", slip.stopped.s - along(slip), 0.5 * a * tau * tau,
             1e-6 * 0.5 * a * tau * tau)
end

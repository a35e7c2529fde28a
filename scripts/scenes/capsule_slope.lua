-- Capsules lying on slopes. A capsule lying on a slope touches it along its straight side, so it
-- cannot roll (rolling would lift it onto its round end): it slides or stays, like a block. The
-- closed form is the block's: with tan θ > μ_s it slides down the slope at a = g (sin θ − μ cos θ),
-- with tan θ ≤ μ_s friction holds it. (A round body would roll without slipping while
-- μ_s ≥ tan θ / (1 + m r² / I); a capsule on its side has no rolling motion to compare.)
-- Slope 30°, μ = 0.2: a = 9.81 (0.5 − 0.2 · 0.866) = 3.206 m/s²; slope 10°, μ = 0.6 > tan 10° = 0.18: held.
local check = require "check"

scene = { title = "Capsules on slopes", dt = 1/60, duration = 1.5, camera = { center = {0, 0}, height = 10 } }

local radius, half_length = 0.2, 0.5
local cases = {
  { name = "sliding", theta = math.rad(30), friction = 0.2, origin = vec2(0, 0) },
  { name = "held", theta = math.rad(10), friction = 0.6, origin = vec2(0, -6) },
}

-- Distance travelled down the slope since the start, m.
local function down_slope(case)
  local t = vec2(math.cos(case.theta), math.sin(case.theta))
  return -(case.capsule.center - case.start):dot(t)
end

function PopulateWorld(world)
  for _, case in ipairs(cases) do
    local t = vec2(math.cos(case.theta), math.sin(case.theta))
    local n = vec2(-t.y, t.x)
    -- The slope: a long box whose top face passes through `origin`.
    world:add_box{ width = 30, height = 1, angle = case.theta, position = case.origin - n * 0.5, static = true,
                   friction = case.friction }
    -- The capsule on its side, lying along the slope and touching it (centre a radius above it).
    case.capsule = world:add_capsule{ a = {-half_length, 0}, b = {half_length, 0}, radius = radius, angle = case.theta,
                                      position = case.origin + n * radius, friction = case.friction }
    case.start = case.capsule.center
  end
end

function Check(world)
  local g = -world.gravity.y
  for _, case in ipairs(cases) do
    case.travelled = down_slope(case)
    print(string.format("%s capsule: travelled %.6f m down the slope, angle off the slope %.3g rad", case.name,
                        case.travelled, case.capsule.angle - case.theta))
    check.near(case.name .. " capsule lies along the slope", case.capsule.angle, case.theta, 1e-6)
  end
  -- RK4 (the default integrator) moves exactly ½ a t² under a constant acceleration.
  local slide = cases[1]
  local a = g * (math.sin(slide.theta) - slide.friction * math.cos(slide.theta))
  print(string.format("sliding: ½ a t² = %.9f m, travelled %.9f m", a * world.time ^ 2 / 2, slide.travelled))
  check.near("sliding: distance vs ½ a t², a = g (sin θ − μ cos θ)", slide.travelled, a * world.time ^ 2 / 2,
             1e-6 * slide.travelled)
  check.less("held: static friction keeps it", math.abs(cases[2].travelled), 1e-4)
end

-- A kinematic platform moved by set_target carries a crate by friction, as a platformer's lift:
-- every step the platform is sent to where x(t) = A (1 − cos ωt) says it is one step later (it
-- starts at rest: no jerk the crate could not follow). The crate rides without slipping while the
-- friction it needs, at most m A ω², is at most μ m g: here
-- A ω² = 1.5 · (2π/3)² = 6.58 m/s² ≤ μ g = 0.8 · 9.81 = 7.85 m/s². The platform has infinite mass:
-- the crate's weight does not push it down, nor the crate's inertia it sideways.
--
-- Semi-implicit Euler, Box2D's integrator: the crate moves exactly with the platform (measured
-- 4e-10 m). So it does under rk4 (rigidlab's default) and euler (measured 3.9e-10 m with
-- --integrator rk4 or euler): the part of the crate's velocity change that follows the platform's
-- velocity jump moves it for the whole step, as the platform moves by h v_k (position_correction.cpp).
-- Before that rule, rk4 moved the crate by h (v_k−1 + v_k) / 2 and it ran h v / 2 behind (0.0262 m).
local check = require "check"

scene = { title = "Moving platform", dt = 1/60, integrator = "semi_implicit_euler", duration = 3, camera = { center = {0, 2}, height = 6 } }

local amplitude, omega, platform_y = 1.5, 2 * math.pi / 3, 1.0
local platform, crate, offset0
local worst_slip, worst_platform_y, worst_platform_x = 0, 0, 0

local function platform_x(t) return amplitude * (1 - math.cos(omega * t)) end

function PopulateWorld(world)
  platform = world:add_box{ width = 3, height = 0.2, position = {0, platform_y}, type = "kinematic", friction = 0.8 }
  -- A crate resting on it (bottom face on the platform's top face), off centre.
  crate = world:add_box{ width = 0.6, height = 0.6, position = {0.5, platform_y + 0.1 + 0.3}, friction = 0.8 }
  offset0 = crate.position.x - platform.position.x
  platform:set_target{ position = {platform_x(scene.dt), platform_y}, time = scene.dt }
end

function OnStep(world, dt)
  -- The platform is exactly where it was sent (it was sent there one step ago).
  worst_platform_x = math.max(worst_platform_x, math.abs(platform.position.x - platform_x(world.time)))
  worst_platform_y = math.max(worst_platform_y, math.abs(platform.position.y - platform_y))
  worst_slip = math.max(worst_slip, math.abs(crate.position.x - platform.position.x - offset0))
  platform:set_target{ position = {platform_x(world.time + dt), platform_y}, time = dt }
end

function Check(world)
  print(string.format("platform off its path by %.3g m (x), %.3g m (y); crate slipped at most %.3g m",
                      worst_platform_x, worst_platform_y, worst_slip))
  check.less("the platform follows its targets", worst_platform_x, 1e-9)
  check.less("the crate does not push the platform down", worst_platform_y, 1e-12)
  check.near("nor turn it", platform.angle, 0, 1e-12)
  check.less("the crate rides with the platform (x follows)", worst_slip, 1e-6)
  check.near("the crate sits on the platform", crate.position.y, platform_y + 0.4, 5e-3)
end

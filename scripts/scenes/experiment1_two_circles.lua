-- Experiment 1 of the thesis (docs/design/thesis.md §12.1): a spinning circle hits a resting one.
-- Two discs of 1 kg and radius 2 m, no gravity, restitution 1, dynamic friction 0.5. A rests at
-- the origin; B comes from the right at 1 m/s spinning at 2 rad/s. The contact slides through
-- the whole impact, so friction takes its full value f·j_n (docs/design/accuracy.md §3.11).
-- Published: v'A = (-1, -0.5), v'B = (0, 0.5); the same impulses give ω'A = -0.5, ω'B = 1.5 rad/s.
local check = require "check"

scene = { title = "Experiment 1: two circles", gravity = {0, 0}, dt = 1e-3, duration = 1,
          camera = { center = {2, 0}, height = 10 } }

function PopulateWorld(world)
  world:add_circle{ name = "A", radius = 2, mass = 1, restitution = 1, friction = 0.5 }
  world:add_circle{ name = "B", radius = 2, mass = 1, restitution = 1, friction = 0.5,
                    position = {4, 0}, velocity = {-1, 0}, angular_velocity = 2 }
end

function Check(world)
  local a, b = world:find("A"), world:find("B")
  -- Linear velocities are exact: the normal impulse is 1 N·s, friction its full 0.5 N·s.
  check.near("A vx", a.velocity.x, -1.0, 1e-9)
  check.near("A vy", a.velocity.y, -0.5, 1e-9)
  check.near("B vx", b.velocity.x, 0.0, 1e-9)
  check.near("B vy", b.velocity.y, 0.5, 1e-9)
  -- Spins: the lever arm is R minus half the overlap at detection (≤ v·dt), an error ≤ dt/8.
  local tolerance = world.dt / 8 + 1e-9
  check.near("A spin", a.angular_velocity, -0.5, tolerance)
  check.near("B spin", b.angular_velocity, 1.5, tolerance)
  -- Energy: 4.5 J before; friction takes f·j_n·(mean slip speed) = 0.5·1·2.5 = 1.25 J.
  check.near("kinetic energy", world:kinetic_energy(), 3.25, 4 * tolerance)
end

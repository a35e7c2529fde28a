-- A hammer as one compound body, the way a Box2D user builds it: a body, then a handle and a heavy
-- head as two shapes (no weld). It is thrown spinning at a wall. A compound body is rigid: the head
-- is where its offset says at every step, so while the hammer flies its angular velocity is
-- constant (gravity puts no torque about the centre of mass) and after the hit the head is still at
-- its offset. Its mass, centre of mass and inertia are the parallel-axis sums of its two boxes.
local check = require "check"

scene = { title = "Hammer: a compound body", dt = 1/120, duration = 1.5, camera = { center = {3, 2}, height = 6 } }

local handle_w, handle_h, handle_density = 0.08, 0.9, 1.0
local head_w, head_h, head_density = 0.5, 0.16, 8.0
local head_offset = vec2(0, 0.5)
local wall_x = 5.0
local spin = 6.0

local hammer, head, inertia0, flight_spin_error, flight_vx_error, hit_time = nil, nil, nil, 0, 0, nil

-- A box's own moment of inertia about its centre: m (w² + h²) / 12.
local function box_inertia(m, w, h) return m * (w * w + h * h) / 12 end

function PopulateWorld(world)
  world:add_chain{ points = {{20, 0}, {-20, 0}} }
  world:add_box{ width = 0.4, height = 4, position = {wall_x + 0.2, 2}, static = true, name = "wall" }
  hammer = world:add_body{ position = {0, 1.5}, name = "hammer" }
  hammer:add_shape{ shape = "box", width = handle_w, height = handle_h }
  head = hammer:add_shape{ shape = "box", width = head_w, height = head_h, offset = head_offset, density = head_density }

  -- Parallel-axis sums: M = m1 + m2, c = (m1 c1 + m2 c2) / M, I = Σ (I_i + m_i |c_i − c|²).
  local m1, m2 = handle_density * handle_w * handle_h, head_density * head_w * head_h
  local mass = m1 + m2
  local c = head_offset * (m2 / mass)  -- the handle is centred on the origin
  local inertia = box_inertia(m1, handle_w, handle_h) + m1 * c:length() ^ 2 +
                  box_inertia(m2, head_w, head_h) + m2 * (head_offset - c):length() ^ 2
  check.near("mass = m_handle + m_head", hammer.mass, mass, 1e-12)
  check.near("centre of mass x", hammer.local_center.x, c.x, 1e-12)
  check.near("centre of mass y = m_head · 0.5 / M", hammer.local_center.y, c.y, 1e-12)
  check.near("inertia = parallel-axis sum", hammer.inertia, inertia, 1e-12)

  inertia0 = inertia
  hammer.velocity = vec2(7, 4)  -- of the centre of mass
  hammer.angular_velocity = spin
end

function OnStep(world, dt)
  -- Free flight lasts until the first contact changes the spin.
  if not hit_time then
    if math.abs(hammer.angular_velocity - spin) > 1e-9 then
      hit_time = world.time
    else
      flight_spin_error = math.max(flight_spin_error, math.abs(hammer.angular_velocity - spin))
      flight_vx_error = math.max(flight_vx_error, math.abs(hammer.velocity.x - 7))
    end
  end
end

function Check(world)
  print(string.format("hit after %.3f s; spin error in flight %.3g rad/s; hammer at x = %.3f, vx = %.3f",
                      hit_time or -1, flight_spin_error, hammer.center.x, hammer.velocity.x))
  check.that("the hammer hit something", hit_time ~= nil)
  check.less("spin constant in free flight (no torque about the centre of mass)", flight_spin_error, 1e-12)
  check.less("and the centre of mass's horizontal speed", flight_vx_error, 1e-12)
  -- The shape never moves in its body: the head's centre is its offset, exactly.
  check.near("head offset x after the hit", head.center.x, head_offset.x, 0)
  check.near("head offset y after the hit", head.center.y, head_offset.y, 0)
  check.near("inertia after the hit", hammer.inertia, inertia0, 1e-12)
  check.less("the hammer bounced off the wall (it stays in front of it)", hammer.center.x, wall_x)
  check.less("and moves away from it or lies still", hammer.velocity.x, 1e-6)
end

-- A pulley joint with ratio r = 2 (a block and tackle): the rope keeps length_a + r · length_b
-- constant, so the block on side b moves 1/r as far as the one on side a, and the rope pulls it
-- with r times the tension T of side a (virtual work: T δl_a + r T δl_b = 0). With masses m_a, m_b
-- on vertical ropes, taking a_a as side a's downward acceleration (side b then rises at a_a / r):
--   m_a a_a = m_a g − T,   m_b a_a / r = r T − m_b g
--   ⇒ a_a = g r (r m_a − m_b) / (r² m_a + m_b),
-- Atwood's machine g (m_a − m_b) / (m_a + m_b) at r = 1. Here m_a = 3, m_b = 2: a_a = 4 g / 7.
local check = require "check"

scene = { title = "Pulley (ratio 2)", dt = 1/60, duration = 1, camera = { center = {1.5, 2}, height = 6 } }

local m_a, m_b, ratio = 3, 2, 2
local ground_a, ground_b = vec2(0, 5), vec2(3, 5)
local a_block, b_block, pulley, rope0, start_a, start_b
local worst_rope = 0

local function rope(j) return (j.anchor_a - ground_a):length() + ratio * (j.anchor_b - ground_b):length() end

function PopulateWorld(world)
  a_block = world:add_box{ width = 0.4, height = 0.4, position = {0, 2}, mass = m_a }
  b_block = world:add_box{ width = 0.4, height = 0.4, position = {3, 1}, mass = m_b }
  pulley = world:add_pulley{ a = a_block, b = b_block, anchor_a = {0, 2.2}, anchor_b = {3, 1.2},
                             ground_a = ground_a, ground_b = ground_b, ratio = ratio }
  rope0, start_a, start_b = rope(pulley), a_block.position.y, b_block.position.y
end

function OnStep(world, dt)
  worst_rope = math.max(worst_rope, math.abs(rope(pulley) - rope0))
end

function Check(world)
  local g = -world.gravity.y
  local expected = g * ratio * (ratio * m_a - m_b) / (ratio * ratio * m_a + m_b)
  -- RK4 (the default integrator) moves exactly ½ a t² under a constant acceleration.
  local per_a = world.time ^ 2 / 2
  local down_a, up_b = (start_a - a_block.position.y) / per_a, (b_block.position.y - start_b) / per_a
  print(string.format("a_a = %.6f m/s² (closed form %.6f), a_b = %.6f m/s² (a_a / r = %.6f); rope off by %.2g m",
                      down_a, expected, up_b, expected / ratio, worst_rope))
  check.less("length_a + r · length_b stays constant", worst_rope, 1e-4)
  check.near("side a falls at g r (r m_a − m_b) / (r² m_a + m_b)", down_a, expected, 1e-4 * expected)
  check.near("side b rises at a_a / r", up_b, expected / ratio, 1e-4 * expected)
  check.near("the ropes stay vertical", a_block.position.x, 0, 1e-9)
end

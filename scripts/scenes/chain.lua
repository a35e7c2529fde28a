-- A chain of 30 links (capsules pinned end to end by revolute joints) hangs from a fixed point.
-- Two of them: one hangs still and its top pin holds exactly the chain's weight, N m g, with the
-- chain at its full length; the other is started in the shape of its slowest swing and swings at
-- that mode's period. For a uniform hanging chain of length L the horizontal displacement of that
-- mode is u(z) ∝ J₀(2ω √(z/g)) at height z above the free end, and the fixed top needs
-- J₀(2ω √(L/g)) = 0: ω = (j₀,₁ / 2) √(g/L), j₀,₁ = 2.404826, T = 4π √(L/g) / j₀,₁ (D. Bernoulli).
-- A chain of 30 rigid links is not quite the continuous one: measured 0.01 % longer.
local check = require "check"
local watch = require "watch"

scene = { title = "Hanging chains", dt = 1/120, duration = 2.4, camera = { center = {1, -1.5}, height = 4 } }

local n, link, link_mass, amplitude = 30, 0.1, 0.05, 0.05
local length = n * link
local hanging, swinging = {}, {}
local crossings, last_x = {}, nil

-- J₀ by its power series Σ (−1)^k (x/2)^{2k} / (k!)²: ample for x ≤ 2.41.
local function j0(x)
  local sum, term = 0, 1
  for k = 0, 30 do
    sum = sum + term
    term = -term * (x / 2) ^ 2 / ((k + 1) ^ 2)
  end
  return sum
end
local j01 = 2.404825557695773

-- A chain from `top`; `shape(z)` is the horizontal offset of the point z above its free end.
local function chain(world, top, shape, into)
  local links, joints = {}, {}
  local function at(i) return top + vec2(shape(length - i * link), -i * link) end  -- the i-th joint point
  for i = 1, n do
    local p, q = at(i - 1), at(i)
    links[i] = world:add_capsule{ a = p - (p + q) * 0.5, b = q - (p + q) * 0.5, radius = 0.02, position = (p + q) * 0.5,
                                  mass = link_mass, group = -1 }
    joints[i] = i == 1 and world:add_revolute{ a = links[1], anchor = p }
                       or world:add_revolute{ a = links[i - 1], b = links[i], anchor = p }
  end
  into.links, into.joints = links, joints
end

function PopulateWorld(world)
  chain(world, vec2(0, 0), function(z) return 0 end, hanging)
  chain(world, vec2(2, 0), function(z) return amplitude * j0(j01 * math.sqrt(z / length)) end, swinging)
end

function OnStep(world, dt)
  -- The bottom of the swinging chain crosses the vertical under its top.
  local x = swinging.links[n].position.x - 2
  if last_x and (x > 0) ~= (last_x > 0) then crossings[#crossings + 1] = world.time - dt * x / (x - last_x) end
  last_x = x
end

function Check(world)
  local g = -world.gravity.y
  local top = hanging.joints[1]
  local bottom = hanging.links[n].position.y - link / 2
  local period = 4 * math.pi * math.sqrt(length / g) / j01
  check.that("the swinging chain's bottom crossed the vertical twice", #crossings >= 2, #crossings .. " crossings")
  local measured = 2 * (crossings[2] - crossings[1])  -- from one crossing to the next: half a period
  print(string.format("top pin holds %.6f N (N m g = %.6f N); chain bottom at %.9f m; gap %.2g m",
                      top.reaction_force.y, n * link_mass * g, bottom, watch.gap(hanging.joints)))
  print(string.format("swing period %.4f s, continuous chain %.4f s (%.2f %%)", measured, period,
                      100 * (measured / period - 1)))
  check.near("top pin force = the chain's weight", top.reaction_force.y, n * link_mass * g, 1e-6 * n * link_mass * g)
  check.near("and no sideways force", top.reaction_force.x, 0, 1e-9)
  check.near("the chain hangs at its full length", bottom, -length, 1e-6)  -- measured to 1e-9 m
  check.near("swing period vs the hanging chain's 4π √(L/g) / j₀,₁", measured, period, 0.005 * period)
end

-- The default scene: a little of everything. A pyramid, a ramp with balls, a spring pendulum, a
-- chain of springs and a box pushed by a custom Lua force. In the sandbox, press B to drop a ball
-- at a random spot (OnKey) and watch the readout in the corner (OnDraw).
local check = require "check"
local spring = require "forces.spring"

scene = { title = "Playground", integrator = "rk4", duration = 10, camera = { center = {0, 6}, height = 18 } }

local dropped = 0

function PopulateWorld(world)
  world:add_box{ name = "ground", width = 60, height = 1, position = {0, -0.5}, static = true }
  world:add_box{ name = "ramp", width = 8, height = 0.4, position = {-12, 5}, angle = -0.35, static = true,
                 friction = 0.2 }

  -- A pyramid of boxes, base 6.
  for row = 0, 5 do
    for i = 0, 5 - row do
      world:add_box{ width = 1, height = 1, position = {4 + (i - (5 - row) / 2) * 1.02, 0.5 + row} }
    end
  end

  -- Balls rolling down the ramp.
  for i = 0, 4 do
    world:add_circle{ radius = 0.35, position = {-15 + i * 0.8, 7.5 + i * 0.3}, restitution = 0.3,
                      friction = 0.4 }
  end

  -- A spring pendulum (built-in spring) and a chain of Lua springs (forces.spring).
  local bob = world:add_circle{ name = "bob", radius = 0.4, position = {-4, 9}, restitution = 0.5 }
  world:add_spring{ a = bob, anchor = {-6, 13}, stiffness = 40, rest_length = 3, damping = 0.2 }
  local above = nil
  for i = 1, 4 do
    local link = world:add_box{ width = 0.5, height = 0.3, position = {2 + i * 0.8, 13 - i * 0.2}, density = 2 }
    if above then
      spring.add(world, { a = above, b = link, stiffness = 150, rest_length = 0.8, damping = 1 })
    else
      spring.add(world, { a = link, anchor = {2, 13.5}, stiffness = 150, rest_length = 0.8, damping = 1 })
    end
    above = link
  end

  -- A triangle pushed to the left by a Lua force for the first two seconds.
  local tri = world:add_polygon{ name = "pushed", vertices = {{-0.6, 0}, {0.6, 0}, {0, 0.9}}, position = {14, 0.05} }
  world:add_force{ body = tri, duration = 2, evaluate = function(s) return -8 * s.mass, 0, 0 end }
end

function OnKey(world, key)
  if key == "b" then
    dropped = dropped + 1
    world:add_circle{ radius = 0.3 + 0.2 * math.random(), position = {math.random(-14, 14), 16}, restitution = 0.4 }
  end
end

function OnDraw(draw)
  draw:text({-8, 14.5}, string.format("balls dropped with B: %d", dropped), {1, 1, 0.6})
end

function Check(world)
  for _, body in ipairs(world:bodies()) do
    check.that("body " .. body.id .. " has a finite position",
               body.position.x == body.position.x and body.position.y == body.position.y)
    if not body.static then check.greater("height of body " .. body.id .. " (nothing falls through the ground)",
                                          body.position.y, -0.01) end
  end
  check.less("the pushed triangle moved left (x)", world:find("pushed").position.x, 12)
end

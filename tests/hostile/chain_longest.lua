-- The documented largest chain, 65 536 points, made a sensor and back through its body: well
-- within the 1 s budget. Making it took 21 s in one C++ call (each segment recomputed the body's
-- mass over the segments before it), and body.sensor = true 36 s more.
-- exit: 0
-- run: --steps 10 --quiet
-- reject: budget
function PopulateWorld(world)
  local points = {}
  for i = 1, 65536 do points[i] = {i * 0.1 - 3000, math.sin(i) * 0.01} end
  local ground = world:add_chain{ points = points, friction = 0.4 }
  ground.sensor = true
  ground.sensor = false
  world:add_circle{ radius = 0.5, position = {0, 2} }
end
function Check(world)
  local ground = world:bodies()[1]
  assert(#ground.shapes == 65535 and not ground.shapes[65535].sensor, "the chain's segments")
end

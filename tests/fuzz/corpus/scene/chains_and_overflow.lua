-- Chains (long, looped, sensors, a body made a sensor), concave outlines, and inputs whose
-- differences overflow, for every query and shape (issue 32).
function PopulateWorld(world)
  local points = {}
  for i = 1, 4096 do points[i] = {i * 0.1, math.sin(i) * 0.01} end
  local ground = world:add_chain{ points = points, friction = 0.3 }
  local loop = world:add_chain{ points = {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, loop = true, sensor = true }
  loop.sensor = false
  ground.sensor = true
  ground.friction = 0.5
  world:add_polygon{ concave = true, vertices = {{0, 0}, {4, 0}, {4, 4}, {2, 1}, {0, 4}}, position = {2, 6} }
  pcall(world.add_chain, world, { points = {{-1.7e308, 0}, {1.7e308, 0}} })
  pcall(world.add_capsule, world, { a = {-1e300, 0}, b = {1e300, 0}, radius = 1 })
  pcall(world.add_box, world, { width = 1.7e308, height = 1.7e308 })
  pcall(world.add_circle, world, { radius = 1e200 })
  pcall(world.query_box, world, { lower = {-1.7e308, -1.7e308}, upper = {1.7e308, 1.7e308} })
  pcall(world.ray_cast, world, { from = {-1.7e308, 0}, to = {1.7e308, 0} })
  pcall(world.shape_cast, world, { shape = {shape = "circle", radius = 1}, from = {-1.7e308, 0}, to = {1.7e308, 0} })
  pcall(world.explode, world, { position = {1e200, 0}, radius = 1e308, impulse = 1 })
  local t = {}
  for i = 1, 10000 do t["k" .. i] = i end
  for k in pairs(t) do break end
end
function SaveState(world) local t = {} for i = 1, 5000 do t[i] = i end return t end
function Check(world) world:remove(world:bodies()[1]) end

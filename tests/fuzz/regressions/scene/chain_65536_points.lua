-- The documented largest chain took 21 s in one C++ call (quadratic), past every budget.
function PopulateWorld(world)
  local points = {}
  for i = 1, 65536 do points[i] = {i * 0.1, math.sin(i) * 0.01} end
  local b = world:add_chain{ points = points, sensor = true }
  b.sensor = false
end

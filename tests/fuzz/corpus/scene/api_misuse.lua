function PopulateWorld(world)
  local b = world:add_box{ width = 1, height = 1, position = {0, 1}, velocity = vec2(1, 0) }
  world:add_polygon{ vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, position = {3, 0}, static = true }
  world:add_spring{ a = b, anchor = {0, 5}, stiffness = 10, damping = 0.1 }
  world:add_damper{ body = b, coefficient = 0.5 }
  pcall(world.add_circle, world, { radius = 0/0 })
  pcall(function() b.mass = -1 end)
  pcall(function() world:remove(b); return b.position end)
end
function Exact(t) return { } end

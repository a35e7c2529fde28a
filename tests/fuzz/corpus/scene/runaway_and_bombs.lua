scene = { memory_limit = 16, dt = 1/120 }
function PopulateWorld(world)
  local b = world:add_circle{ radius = 0.5, position = {0, 2} }
  world:add_force{ body = b, evaluate = function(s) return pcall(function() while true do end end) and 0 or 0, 0 end }
  local s = ("a"):rep(64)
  pcall(string.find, s, ".-.-.-b")
  pcall(function() local t = {} while true do t[#t + 1] = {} end end)
end
function OnStep(world, dt) world.gravity = {0, -9.81} end

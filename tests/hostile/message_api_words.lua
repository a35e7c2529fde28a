-- Lua-facing errors named C++ functions ("createBody is not allowed while the world is stepping"):
-- they speak the Lua API's words.
-- exit: 1
-- expect: message_api_words.lua:9: add_box: not allowed while the world is stepping (from inside a force)
-- reject: createBody
function PopulateWorld(world)
  local b = world:add_circle{ radius = 1 }
  world:add_force{ body = b, evaluate = function(s)
    world:add_box{ width = 1, height = 1 }
    return 0, 0
  end }
end

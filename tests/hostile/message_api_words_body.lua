-- The same for edits of a body and of the world from inside a force.
-- exit: 1
-- expect: message_api_words_body.lua:10: body.position: not allowed while the world is stepping (from inside a force)
-- reject: setTransform
function PopulateWorld(world)
  local b = world:add_circle{ radius = 1 }
  world:add_force{ body = b, evaluate = function(s)
    assert(not pcall(function() world.gravity = {0, 0} end))
    assert(not pcall(world.step, world))
    b.position = {1, 1}
    return 0, 0
  end }
end

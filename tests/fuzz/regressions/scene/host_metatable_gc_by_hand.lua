-- getmetatable of a handle gave sol2's metatable; calling its __gc by hand overflowed the heap
-- (ASan in ~LuaForceHandle), replacing it installed a finalizer run against a dead world.
function PopulateWorld(world)
  local b = world:add_circle{ radius = 1 }
  local f = world:add_force{ body = b, evaluate = function() return 0, 0 end }
  for _, h in ipairs{ world, b, f } do
    local mt = getmetatable(h)
    if type(mt) == "table" then
      local gc = rawget(mt, "__gc")
      if gc then gc(h) gc(h) end
      mt.__gc = function() world:add_circle{ radius = 1 } end
    end
  end
end

-- Host metatables: getmetatable of a world, body, force, spring or draw handle returned sol2's real,
-- writable metatable; calling its __gc by hand corrupted the heap. Every handle's metatable is
-- locked (shape and joint handles too), and no field or iteration reaches it.
-- expect: every handle is locked
local function locked(x, what)
  assert(getmetatable(x) == false, what .. ": getmetatable is " .. tostring(getmetatable(x)))
  assert(not pcall(rawget, getmetatable(x), "__gc"), what)
  assert(not pcall(setmetatable, x, {}), what)
  assert(not pcall(pairs, x), what)
  assert(not pcall(next, x), what)
  for _, field in ipairs{"__gc", "__index", "__newindex", "class_check", "__pairs", "__name"} do
    assert(not pcall(function() return x[field] end), what .. "." .. field)
  end
end
function PopulateWorld(world)
  local b = world:add_circle{ radius = 1 }
  local other = world:add_circle{ radius = 1, position = {3, 0} }
  locked(world, "world")
  locked(b, "body")
  locked(world:add_force{ body = b, evaluate = function() return 0, 0 end }, "force")
  locked(world:add_spring{ a = b, b = other, stiffness = 1 }, "spring")
  locked(world:add_damper{ body = b, coefficient = 1 }, "damper")
  locked(b.shapes[1], "shape")
  locked(world:add_revolute{ a = b, b = other, anchor = {1.5, 0} }, "joint")
  print("every handle is locked")
end
function OnDraw(draw) locked(draw, "draw") end

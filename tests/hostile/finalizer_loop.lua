-- Finalizers: a __gc that loops forever used to hang the close of the scene (Lua runs finalizers
-- with hooks off, so no budget stops one). None can be installed, so the run ends.
-- expect: closing
local function forever() while true do end end
pcall(setmetatable, {}, { __gc = forever })
local mt = {}
garbage = setmetatable({}, mt)
mt.__gc = forever
function PopulateWorld(world)
  local hm = getmetatable(world)
  if type(hm) == "table" then hm.__gc = forever end
  garbage = nil
  print("closing")
end

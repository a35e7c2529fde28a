-- The same with a million small pieces: the total is what counts.
-- expect: load_reader_pieces.lua:4: load: the reader function returned more than 1048576 bytes in all
local n = 0
local f, message = load(function()
  n = n + 1
  if n == 1 then return "return " end
  if n < 2e6 then return "1+" end
  if n == 2e6 then return "1" end
end)
print(message)
assert(f == nil)
function PopulateWorld(world) end

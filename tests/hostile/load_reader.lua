-- load() with a reader function got round the 1 MiB limit on chunks (96 MiB parsed in one
-- uninterruptible call, 1.4 s over a 1 s budget): the pieces a reader returns count together.
-- expect: load refused: load_reader.lua:6: load: the reader function returned more than 1048576 bytes in all
local piece = "local x = 1\n" .. string.rep(" ", 1024 * 1024)
local calls = 0
local f, message = load(function()
  calls = calls + 1
  if calls <= 96 then return piece end
end)
print("load refused: " .. tostring(message))
assert(f == nil and calls == 1)
function PopulateWorld(world) end

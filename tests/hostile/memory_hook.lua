-- A memory error inside a hook named no file and line ("PopulateWorld: not enough memory"): it is
-- located at the line that was allocating.
-- exit: 1
-- expect: memory_hook.lua:9: PopulateWorld: not enough memory (the scene's limit is 8 MiB)
scene = { memory_limit = 8 }
function PopulateWorld(world)
  local t = {}
  for i = 1, 1e8 do
    t[i] = { i, i }
  end
end

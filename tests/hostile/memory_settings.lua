-- Host reads under memory pressure: a scene that keeps 3 MiB alive and then sets memory_limit = 1
-- aborted with "terminate called ... sol::error" (a memory error thrown while the host read the
-- scene table, outside a protected call). Now it is a located error.
-- exit: 1
-- expect: memory_settings.lua:8: scene: memory_limit is 1 MiB, less than the
keep = {}
for i = 1, 3 * 1024 do keep[i] = string.rep("x", 1000) .. i end
scene = {
  memory_limit = 1,
  title = "memory",
}
function PopulateWorld(world) end

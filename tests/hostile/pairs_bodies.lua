-- Runs were not bit-identical when a scene iterated string-keyed tables: a pile of 20 boxes built
-- inside pairs() ended at x = 0.15617, 0.13907, 0.14677, 0.14346 in four runs (Lua seeds its
-- string hash per process). Three processes must print the same JSON, bit for bit.
-- run: --time 3 --json
-- repeat: 3
-- json
scene = { integrator = "semi_implicit_euler" }
local boxes = {}
for i, name in ipairs{"alpha", "bravo", "charlie", "delta", "echo", "foxtrot", "golf", "hotel", "india", "juliett",
                      "kilo", "lima", "mike", "november", "oscar", "papa", "quebec", "romeo", "sierra", "tango"} do
  boxes[name] = 0.3 + 0.02 * i
end
function PopulateWorld(world)
  world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
  local i = 0
  for name, size in pairs(boxes) do
    i = i + 1
    world:add_box{ name = name, width = size, height = size, position = {0.02 * (i % 3), 0.5 + 0.8 * i} }
  end
  local by_table = {}
  for _, b in ipairs(world:bodies()) do by_table[{b}] = b end
  for _, b in pairs(by_table) do  -- order shows in nothing, but must not crash
    if not b.static then b.angular_velocity = 0.01 * b.id end
  end
end

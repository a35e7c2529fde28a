-- OnDraw output is bounded per frame (300 000 lines froze the sandbox past 120 s): the calls past
-- the allowance are dropped and the sandbox says so. Headless, OnDraw is not called; the scene
-- loads and runs.
-- expect: check   none
-- run: --time 0.1
function PopulateWorld(world) world:add_circle{ radius = 1 } end
local long = string.rep("t\27[2J", 20000)
function OnDraw(draw)
  for i = 1, 300000 do draw:line({0, 0}, {i * 1e-3, 1}) end
  for i = 1, 20000 do draw:circle({0, 0}, i * 1e-3) end
  for i = 1, 5000 do draw:text({0, i * 0.1}, long) end
end

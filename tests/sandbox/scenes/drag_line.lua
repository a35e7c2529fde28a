-- Sandbox drag line test (tests/sandbox/drag_line_test.sh): no gravity; a bar pinned to the world
-- at its centre, so that a drag turns it but cannot bring it to the cursor; 72 px per metre in a
-- 1280×720 window, world (x, y) → pixel (640 + 72x, 360 − 72y).
scene = {title = "drag line test", gravity = {0, 0}, camera = {center = {0, 0}, height = 10}}

function PopulateWorld(world)
  local bar = world:add_box{width = 2, height = 0.4, name = "bar"}
  world:add_revolute{a = bar, anchor = {0, 0}}
end

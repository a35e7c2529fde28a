-- Sandbox picture test: shapes at known places, no gravity, camera fixed, so a screenshot can be
-- checked pixel by pixel (tests/sandbox/screenshot_test.sh).
--   camera centre (0, 0), 10 m tall: in a 1280×720 window 72 px per metre, origin at (640, 360).
scene = {
  title = "sandbox picture test",
  gravity = {0, 0},
  camera = {center = {0, 0}, height = 10},
}

function PopulateWorld(world)
  world:add_box{width = 2, height = 1, position = {-2, 1}, static = true, name = "static box"}
  world:add_circle{radius = 0.8, position = {2, 1}, name = "ball"}
  world:add_polygon{vertices = {{-0.8, -0.6}, {0.8, -0.6}, {0, 0.8}}, position = {0, -2}, name = "triangle"}
end

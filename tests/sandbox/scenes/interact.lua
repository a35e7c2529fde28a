-- Sandbox interaction test (tests/sandbox/interaction_test.sh): no gravity; a static box and a
-- heavily damped ball (it stops as soon as it is let go), 72 px per metre in a 1280×720 window.
scene = {title = "interaction test", gravity = {0, 0}, camera = {center = {0, 0}, height = 10}}

function PopulateWorld(world)
  world:add_box{width = 2, height = 1, position = {-2, 2}, static = true, name = "box"}
  local ball = world:add_circle{radius = 0.5, position = {2, 0}, name = "ball"}
  world:add_damper{body = ball, coefficient = 10}
end

-- Sandbox building test (tests/sandbox/build_test.sh): no gravity; a heavily damped ball and crate
-- (they stop as soon as they are let go), 72 px per metre in a 1280×720 window.
scene = {title = "building test", gravity = {0, 0}, camera = {center = {0, 0}, height = 10}}

function PopulateWorld(world)
  local ball = world:add_circle{radius = 0.5, position = {2, 0}, name = "ball"}
  world:add_damper{body = ball, coefficient = 10}
  local crate = world:add_box{width = 1, height = 1, position = {-1, -2}, name = "crate"}
  world:add_damper{body = crate, coefficient = 10}
end

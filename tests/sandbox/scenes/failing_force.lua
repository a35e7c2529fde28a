-- Sandbox test: a Lua force that fails during the run (tests/sandbox/broken_save_test.sh). The ball
-- moves right at 1 m/s from (-3, 0); after 0.5 s its force raises an error, which must pause the
-- simulation with the error shown: the ball stays near x = -2.5 instead of reaching x = -1 at 2 s.
scene = {title = "failing force", gravity = {0, 0}, camera = {center = {0, 0}, height = 10}}

function PopulateWorld(world)
  local ball = world:add_circle{radius = 0.4, position = {-3, 0}, velocity = {1, 0}, name = "ball"}
  world:add_force{body = ball, evaluate = function(s)
    if s.time > 0.5 then error("this force fails on purpose") end
    return 0, 0, 0
  end}
end

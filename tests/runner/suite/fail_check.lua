-- Fails: its Check raises.
scene = { title = "runner: failing check", dt = 0.02, duration = 0.5 }

function PopulateWorld(world)
  world:add_circle{ name = "ball", radius = 0.5, position = {0, 2} }
end

function Check(world)
  print("the ball is at y = " .. world:find("ball").position.y)
  error("expected the ball to float")
end

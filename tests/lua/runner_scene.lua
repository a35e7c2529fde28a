-- A small scene for the runner's command-line tests (tests/lua/runner_checks.cmake).
scene = { title = "runner", gravity = {0, -10}, dt = 0.1, duration = 1 }

function PopulateWorld(world)
  world:add_box{ name = "floor", width = 10, height = 1, position = {0, -0.5}, static = true }
  world:add_circle{ name = "ball, \"quoted\"", radius = 0.5, position = {0, 10}, velocity = {1, 0} }
end

function Check(world)
  if world.time > 50 then error("ran too long") end
end

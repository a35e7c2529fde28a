-- Passes: a ball falls onto a floor and rests there.
scene = { title = "runner: pass", dt = 0.02, duration = 1 }

function PopulateWorld(world)
  world:add_box{ name = "floor", width = 10, height = 1, position = {0, -0.5}, static = true }
  world:add_circle{ name = "ball", radius = 0.5, position = {0, 2} }
end

function Check(world)
  local y = world:find("ball").position.y
  if y < 0 then error("the ball fell through the floor: y = " .. y) end
end

-- Golden trajectory: a ball rolls off a box onto a slope. The runner's test switches PERTURB on
-- (a nudge of the ball at step 30) and raises the tolerance.
local PERTURB = false
scene = { title = "runner: golden", dt = 0.01, duration = 1, golden = "ball", golden_every = 5 }

function PopulateWorld(world)
  world:add_box{ name = "slope", width = 8, height = 0.5, position = {0, 0}, angle = -0.3, static = true }
  world:add_circle{ name = "ball", radius = 0.3, position = {-2, 2}, velocity = {1, 0} }
  world:add_box{ name = "crate", width = 0.5, height = 0.5, position = {1, 2} }
end

function OnStep(world)
  if PERTURB and world.step_count == 30 then
    local ball = world:find("ball")
    ball.position = {ball.position.x + 1e-9, ball.position.y}
  end
end

function Check(world)
  if world:find("ball").position.y > 2 then error("the ball rose") end
end

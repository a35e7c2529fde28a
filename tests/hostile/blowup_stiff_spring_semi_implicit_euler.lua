-- A blow-up that stays finite is a blow-up (issue 33): a k = 1e7 spring on a 1 kg ball at
-- dt = 1/60 (ωh ≈ 53, far past every explicit integrator's stability limit) multiplies the energy
-- by thousands each step. The energy watch (docs/stability.md "Blow-ups caught") marks it within
-- 8 steps: an incident naming the ball and the step, exit status 3.
-- exit: 3
-- run: --steps 8
-- expect: body 1 'ball' blew up at step
-- expect: the run blew up (exit status 3)
scene = { integrator = "semi_implicit_euler", dt = 1 / 60 }
function PopulateWorld(world)
  local ball = world:add_circle{ name = "ball", radius = 0.1, mass = 1, position = {0, 1.1} }
  world:add_spring{ a = ball, anchor = {0, 2}, stiffness = 1e7, rest_length = 1 }
end

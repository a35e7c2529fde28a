-- The same k = 1e7 spring at dt = 1/60 as blowup_stiff_spring_*.lua, with implicit Euler, which is
-- stable at any stiffness: no blow-up is reported, exit status 0.
-- run: --time 5
-- reject: blew up
-- expect: check   passed
scene = { integrator = "implicit_euler", dt = 1 / 60 }
function PopulateWorld(world)
  local ball = world:add_circle{ name = "ball", radius = 0.1, mass = 1, position = {0, 1.1} }
  world:add_spring{ a = ball, anchor = {0, 2}, stiffness = 1e7, rest_length = 1 }
end
function Check(world)
  local v = world:find("ball").velocity
  assert(math.abs(v.x) + math.abs(v.y) < 1, "the ball came to rest on its spring")
end

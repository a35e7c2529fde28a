-- A body frozen by the NaN firewall, seen in --json: "incidents" lists it and the exit is 3.
-- exit: 3
-- run: --time 0.5 --json
-- json
-- expect: "incidents":["body 1 'runaway' frozen at step
scene = { gravity = {0, 0}, integrator = "semi_implicit_euler" }
function PopulateWorld(world)
  local b = world:add_circle{ radius = 0.5, name = "runaway", velocity = {1.7e308, 0} }
  world:add_force{ body = b, evaluate = function(s) return 1e308, 0 end }
end

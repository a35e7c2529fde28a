-- A scene about the firewall declares it: scene.expect_incidents = true, exit 0, still reported.
-- run: --time 0.5
-- expect: (expected: scene.expect_incidents): the run blew up
scene = { gravity = {0, 0}, integrator = "semi_implicit_euler", expect_incidents = true }
function PopulateWorld(world)
  local b = world:add_circle{ radius = 0.5, name = "runaway", velocity = {1.7e308, 0} }
  world:add_force{ body = b, evaluate = function(s) return 1e308, 0 end }
end

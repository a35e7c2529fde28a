-- A run that blew up said it passed: a chain whose links were all frozen by the NaN firewall
-- reported potential energy `inf J`, "check passed", exit 0. It exits 3 and lists the incidents.
-- exit: 3
-- run: --time 1
-- expect: check   passed
-- expect: incidents 3: the run blew up (exit status 3)
-- expect: the energy became non-finite at step 1
scene = { gravity = {0, 0}, integrator = "euler", dt = 0.1 }
function PopulateWorld(world)
  local previous = world:add_circle{ radius = 0.2, static = true }
  for i = 1, 30 do
    local link = world:add_circle{ radius = 0.2, position = {i, 0}, name = "link" .. i }
    world:add_spring{ a = previous, b = link, stiffness = 1e300, rest_length = 0.5 }
    previous = link
  end
end
function Check(world) end

-- Hangs: every step's OnStep takes a while (each call well inside its 1 s budget), for 20 000
-- steps; only the runner's --timeout stops it.
scene = { title = "runner: hang", dt = 0.01, duration = 200 }

function PopulateWorld(world)
  world:add_circle{ radius = 0.5 }
end

function OnStep(world)
  local n = 0
  for i = 1, 3000000 do n = n + i end
end

function Check(world) end

-- The same heap built a little every step from OnStep: the step that goes over the cap fails,
-- and the error says at which step.
-- exit: 1
-- run: --time 5 --quiet
-- expect: pile_growing.lua: step: too many bodies on top of each other at step
-- expect: bodies overlap around (0,
function PopulateWorld(world) end
function OnStep(world)
  for i = 1, 200 do world:add_box{ width = 1, height = 1, position = {0, 0.001 * i}, velocity = {0, 0} } end
end

-- "unknown option 'mask' (did you mean 'mass'?)" suggested a field of another meaning: a short
-- name one letter away is another word, not a typo. Real typos are still suggested. (mask is a
-- collision filter option now; 'mast' is one letter from both mass and mask.)
-- exit: 1
-- expect: message_suggestion.lua:13: add_circle: unknown option 'mast'
-- reject: did you mean 'mass'
-- reject: did you mean 'mask'
function PopulateWorld(world)
  local ok, m = pcall(world.add_circle, world, { radius = 1, radus = 2 })
  assert(not ok and m:find("unknown option 'radus' (did you mean 'radius'?)", 1, true), m)
  print(m)
  world:add_circle{ radius = 1, mask = 1 }  -- a real option
  world:add_circle{ radius = 1, mast = 1 }
end

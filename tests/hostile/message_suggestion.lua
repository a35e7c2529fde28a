-- "unknown option 'mask' (did you mean 'mass'?)" suggested a field of another meaning: a short
-- name one letter away is another word, not a typo. Real typos are still suggested.
-- exit: 1
-- expect: message_suggestion.lua:10: add_circle: unknown option 'mask'
-- reject: did you mean 'mass'
function PopulateWorld(world)
  local ok, m = pcall(world.add_circle, world, { radius = 1, radus = 2 })
  assert(not ok and m:find("unknown option 'radus' (did you mean 'radius'?)", 1, true), m)
  print(m)
  world:add_circle{ radius = 1, mask = 1 }
end

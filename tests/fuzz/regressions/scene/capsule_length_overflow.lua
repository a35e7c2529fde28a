-- A capsule whose length overflowed was refused as "b must differ from a".
function PopulateWorld(world)
  world:add_capsule{ a = {-1e300, 0}, b = {1e300, 0}, radius = 1 }
end

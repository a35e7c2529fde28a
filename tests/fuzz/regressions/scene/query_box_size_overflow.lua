-- A box query whose size overflows was refused in C++'s words ("PopulateWorld: width must be > 0,
-- got inf"): now "query_box: upper is too far from lower: the box's size overflows, ...".
function PopulateWorld(world)
  world:add_circle{ radius = 1 }
  world:query_box{ lower = {-1.7e308, -1.7e308}, upper = {1.7e308, 1.7e308} }
end

-- Regression (found by tests/fuzz/fuzz_world): a body whose bounding box lies beyond 2^63 grid
-- cells from the origin made the broad phase convert an out-of-range double to int64
-- (engine/core/src/spatial_grid.cpp, UBSan: "6.47174e+23 is outside the range of representable
-- values of type 'long'"). A finite position, however far, must step without undefined behaviour.
function PopulateWorld(world)
  world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
  world:add_circle{ name = "far", radius = 0.5, position = {1e30, 0} }
  world:add_circle{ name = "near", radius = 0.5, position = {0, 0.5} }
end

function Check(world)
  local near = world:find("near")
  assert(near.position.y > 0 and near.position.y < 1, "the near ball rests on the ground")
end

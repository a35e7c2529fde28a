-- Inputs whose differences, squares or areas overflow are refused naming the call and the option
-- in the Lua API's words (issue 32). They used to say "PopulateWorld: width must be > 0, got inf"
-- (query_box), "b must differ from a" (a capsule 2e300 long), "vertices has only 1 distinct
-- points" (a box 1.7e308 wide), "translation must be finite" (shape_cast), "length must be finite"
-- (add_distance), or were taken (a ray from -1.7e308 to 1.7e308 found nothing; a revolute anchor
-- at 1.7e308 froze both bodies in the first step; a shape offset 1.7e308 away had an infinite extent).
-- exit: 0
-- expect: query_box: upper is too far from lower: the box's size overflows, got lower (-1.7e+308, -1.7e+308) and upper (1.7e+308, 1.7e+308)
-- expect: ray_cast: to is too far from from: the ray's length overflows, got from (-1.7e+308, 0) and to (1.7e+308, 0)
-- expect: ray_cast_all: to is too far from from: the ray's length overflows
-- expect: shape_cast: to is too far from from: the cast's length overflows
-- expect: overlap: shape: radius 1e+308 makes the circle too large: its area or moment of inertia overflows (area inf m², moment of inertia inf m⁴)
-- expect: add_capsule: b is too far from a: the length from a = (-1e+300, 0) to b = (1e+300, 0) overflows
-- expect: add_segment: b is too far from a: the length from a = (-1.7e+308, 0) to b = (1.7e+308, 0) overflows
-- expect: add_box: width 1.7e+308 makes the box too large: its corners' distances overflow
-- expect: add_circle: radius 1e+200 makes the circle too large: its area or moment of inertia overflows
-- expect: add_polygon: vertices[1] (-1e+308, -1e+308) is too far from the body's origin: its distance overflows (a shape's points must lie within about 1e154 m of it)
-- expect: add_polygon: vertices spanning (-1e+100, -1e+100) to (1e+100, 1e+100) makes the polygon too large: its area or moment of inertia overflows
-- expect: add_chain: points[2] (1e+154, 0) is too far from the point before it, (-1e+154, 0): the segment's length overflows
-- expect: add_chain: points[1] (-1.7e+308, 0) is too far from the body's origin
-- expect: add_shape: offset (1.7e+308, 0) puts the shape out of range
-- expect: explode: radius is too large: radius + falloff (1e+308) must be below about 1e154 m (its square overflows)
-- expect: add_revolute: anchor (1.7e+308, 0) is too far from body a: the lever arm overflows
-- expect: add_distance: anchor_a (-1.7e+308, 0) is too far from body a: the lever arm overflows
-- expect: prismatic axis (1.7e+308, 1.7e+308): ok
-- expect: query_box 2e100 wide: 2 shapes
-- reject: PopulateWorld: width
-- reject: must differ
-- reject: distinct points
-- reject: translation
function PopulateWorld(world)
  local function try(f, ...)
    local ok, message = pcall(f, world, ...)
    print(ok and "accepted" or message)
  end
  try(world.query_box, { lower = {-1.7e308, -1.7e308}, upper = {1.7e308, 1.7e308} })
  try(world.explode, { position = {1e200, 0}, radius = 1e308, impulse = 1 })
  try(world.ray_cast, { from = {-1.7e308, 0}, to = {1.7e308, 0} })
  try(world.ray_cast_all, { from = {-1.7e308, 0}, to = {1.7e308, 0} })
  try(world.shape_cast, { shape = {shape = "circle", radius = 1}, from = {-1.7e308, 0}, to = {1.7e308, 0} })
  try(world.overlap, { shape = {shape = "circle", radius = 1e308} })
  try(world.add_capsule, { a = {-1e300, 0}, b = {1e300, 0}, radius = 1 })
  try(world.add_segment, { a = {-1.7e308, 0}, b = {1.7e308, 0} })
  try(world.add_box, { width = 1.7e308, height = 1.7e308 })
  try(world.add_circle, { radius = 1e200 })
  try(world.add_polygon, { vertices = {{-1e308, -1e308}, {1e308, -1e308}, {0, 1e308}} })
  try(world.add_polygon, { vertices = {{-1e100, -1e100}, {1e100, -1e100}, {1e100, 1e100}} })
  try(world.add_chain, { points = {{-1e154, 0}, {1e154, 0}} })
  try(world.add_chain, { points = {{-1.7e308, 0}, {1.7e308, 0}} })
  local body = world:add_body{}
  print(select(2, pcall(body.add_shape, body, { shape = "circle", radius = 1, offset = {1.7e308, 0} })))
  local a = world:add_circle{ radius = 1 }
  local b = world:add_circle{ radius = 1, position = {3, 0} }
  try(world.add_revolute, { a = a, b = b, anchor = {1.7e308, 0} })
  try(world.add_distance, { a = a, b = b, anchor_a = {-1.7e308, 0}, anchor_b = {1.7e308, 0} })
  -- A direction whose length overflows is still a direction.
  local slider = world:add_prismatic{ a = a, b = b, anchor = {0, 0}, axis = {1.7e308, 1.7e308} }
  print("prismatic axis (1.7e+308, 1.7e+308): " .. (slider and "ok" or "refused"))
  -- A box query too large to be a shape (its moment of inertia would overflow) still answers.
  print("query_box 2e100 wide: " .. #world:query_box{ lower = {-1e100, -1e100}, upper = {1e100, 1e100} } .. " shapes")
end

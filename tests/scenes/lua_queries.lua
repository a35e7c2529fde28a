-- Queries through the Lua API on every shape kind, against closed forms: ray_cast's point, normal
-- and fraction on a circle, a turned box, a triangle, a capsule, a segment (both sides) and a chain
-- (from its front; from behind it is not hit: chains are one-sided); ray_cast_all's order;
-- query_point, query_box and overlap (circle, box, polygon and capsule query shapes) just inside
-- and just outside the curved and slanted boundaries; shape_cast's time of impact; filters and
-- sensors.
local check = require "check"

scene = { title = "Lua API: queries", dt = 1 / 60, duration = 0.05, gravity = {0, 0} }

local theta = 0.3
local bodies = {}

local function near_vec(name, v, x, y, tolerance)
  check.near(name .. ".x", v.x, x, tolerance)
  check.near(name .. ".y", v.y, y, tolerance)
end

function PopulateWorld(world)
  bodies.circle = world:add_circle{ name = "circle", radius = 1, static = true, category = 4 }
  bodies.box = world:add_box{ name = "box", width = 2, height = 2, position = {10, 0}, angle = theta, static = true }
  bodies.triangle = world:add_polygon{ name = "triangle", vertices = {{-1, -1}, {1, -1}, {0, 1}}, position = {20, 0},
                                       static = true }
  bodies.capsule = world:add_capsule{ name = "capsule", a = {-1, 0}, b = {1, 0}, radius = 0.5, position = {30, 0},
                                      static = true }
  bodies.segment = world:add_segment{ name = "segment", a = {-1, 0}, b = {1, 0}, position = {40, 0} }
  -- Listed right to left: the surface faces up.
  bodies.chain = world:add_chain{ name = "chain", points = {{52, 0}, {48, 0}} }
  bodies.sensor = world:add_circle{ name = "sensor", radius = 0.5, position = {0, -5}, static = true, sensor = true }
end

-- The hit of a ray straight down (or up) at x.
local function vertical(world, x, up)
  if up then return world:ray_cast{ from = {x, -5}, to = {x, 5} } end
  return world:ray_cast{ from = {x, 5}, to = {x, -5} }
end

local function expect_down(name, hit, body, x, y, nx, ny)
  check.that(name .. ": hit", hit ~= nil and hit.body == body, hit and hit.body.name or "nil")
  check.that(name .. ": shape", hit.shape == body.shapes[1])
  near_vec(name .. " point", hit.point, x, y, 1e-12)
  near_vec(name .. " normal", hit.normal, nx, ny, 1e-12)
  check.near(name .. " fraction", hit.fraction, (5 - y) / 10, 1e-12)
end

function Check(world)
  -- Ray casts from above, 0.3 m right of each centre.
  local y = math.sqrt(1 - 0.09)
  expect_down("circle", vertical(world, 0.3), bodies.circle, 0.3, y, 0.3, y)
  local yb = (1 + 0.3 * math.sin(theta)) / math.cos(theta)  -- the top face (p − c)·n = 1
  expect_down("turned box", vertical(world, 10.3), bodies.box, 10.3, yb, -math.sin(theta), math.cos(theta))
  local s5 = math.sqrt(5)
  expect_down("triangle's slanted edge", vertical(world, 20.3), bodies.triangle, 20.3, 0.4, 2 / s5, 1 / s5)
  expect_down("capsule's side", vertical(world, 30.3), bodies.capsule, 30.3, 0.5, 0, 1)
  expect_down("segment from above", vertical(world, 40.3), bodies.segment, 40.3, 0, 0, 1)
  local under = vertical(world, 40.3, true)
  check.that("segment from below", under and under.body == bodies.segment)
  near_vec("segment from below: normal", under.normal, 0, -1, 1e-12)
  expect_down("chain from its front", vertical(world, 50.3), bodies.chain, 50.3, 0, 0, 1)
  check.that("chain from behind: no hit", vertical(world, 50.3, true) == nil)
  check.that("a ray starting inside a shape does not hit it", world:ray_cast{ from = {0, 0}, to = {0, 0.5} } == nil)

  -- ray_cast_all: along y = 0.2 through the four shapes with area, in order of distance.
  local all = world:ray_cast_all{ from = {-5, 0.2}, to = {60, 0.2} }
  local names = {}
  for i, h in ipairs(all) do
    names[i] = h.body.name
    if i > 1 then check.greater("fractions increase", h.fraction, all[i - 1].fraction) end
  end
  check.that("ray_cast_all", table.concat(names, ",") == "circle,box,triangle,capsule", table.concat(names, ","))
  check.near("first hit", all[1].point.x, -math.sqrt(1 - 0.04), 1e-12)
  -- Filters: the circle is in category 4.
  local no4 = world:ray_cast_all{ from = {-5, 0.2}, to = {60, 0.2}, mask = ~4 }
  check.that("mask leaves the circle out", #no4 == 3 and no4[1].body == bodies.box)
  check.that("category not in the shape's mask", #world:ray_cast_all{ from = {-5, 0.2}, to = {60, 0.2}, category = 0 } == 0)
  check.that("sensors left out", world:ray_cast{ from = {-5, -5}, to = {5, -5} } == nil)
  local sensed = world:ray_cast{ from = {-5, -5}, to = {5, -5}, sensors = true }
  check.that("unless asked for", sensed and sensed.body == bodies.sensor)

  -- query_point: inside, and just outside the curved or slanted boundary (inside the bounding box).
  local function point_count(x, y) return #world:query_point{ point = {x, y} } end
  local r = 1 / math.sqrt(2)
  check.that("point in the circle", point_count(r * 0.999999, r * 0.999999) == 1)
  check.that("point outside the circle", point_count(r * 1.000001, r * 1.000001) == 0)
  check.that("point in the triangle", point_count(20.5, -0.0000001) == 1)   -- its edge meets y = 0 at x = 20.5
  check.that("point outside the triangle", point_count(20.5, 0.0000001) == 0)
  check.that("point in the capsule's end", point_count(31.4999999, 0) == 1)
  check.that("point past the capsule's end", point_count(31.5000001, 0) == 0)
  check.that("segments and chains contain no point", point_count(40, 0) == 0 and point_count(50, 0) == 0)
  local shapes = world:query_point{ point = {10, 0} }
  check.that("query_point gives shapes", #shapes == 1 and shapes[1] == bodies.box.shapes[1])

  -- query_box: the circle's bounding-box corner without the disc, then with it.
  check.that("box off the disc", #world:query_box{ lower = {0.75, 0.75}, upper = {0.8, 0.8} } == 0)
  check.that("box on the disc", #world:query_box{ lower = {0.7, 0.7}, upper = {0.8, 0.8} } == 1)
  local on_segment = world:query_box{ lower = {39.5, -0.1}, upper = {40.5, 0.1} }
  check.that("box on the segment", #on_segment == 1 and on_segment[1].body == bodies.segment)
  local on_chain = world:query_box{ lower = {49, -0.1}, upper = {51, 0.1} }
  check.that("box on the chain", #on_chain == 1 and on_chain[1].body == bodies.chain)

  -- overlap with each query shape kind, just clear of the boundary and just into it.
  local function overlaps(shape, x, y, angle)
    return #world:overlap{ shape = shape, position = {x, y}, angle = angle }
  end
  local small_circle = { shape = "circle", radius = 0.1 }
  check.that("circle clear of the capsule's end", overlaps(small_circle, 31.6001, 0) == 0)
  check.that("circle into the capsule's end", overlaps(small_circle, 31.5999, 0) == 1)
  local small_box = { shape = "box", width = 0.2, height = 0.2 }
  check.that("box clear of the circle", overlaps(small_box, 0, 1.1001) == 0)
  check.that("box into the circle", overlaps(small_box, 0, 1.0999) == 1)
  check.that("a turned box reaches further", overlaps(small_box, 0, 1.1001, math.pi / 4) == 1)
  local small_capsule = { shape = "capsule", a = {-0.1, 0}, b = {0.1, 0}, radius = 0.05 }
  check.that("capsule clear of the triangle's apex", overlaps(small_capsule, 20, 1.0501) == 0)
  check.that("capsule on the triangle's apex", overlaps(small_capsule, 20, 1.0499) == 1)
  local small_triangle = { shape = "polygon", vertices = {{-0.1, -0.1}, {0.1, -0.1}, {0, 0.1}} }
  check.that("polygon inside the box", overlaps(small_triangle, 10, 0) == 1)
  check.that("polygon touching the segment", overlaps(small_triangle, 40, 0.0999) == 1)
  check.that("polygon clear of the segment", overlaps(small_triangle, 40, 0.1001) == 0)

  -- shape_cast: a circle dropped onto the capsule's side, a box onto the chain.
  local h = world:shape_cast{ shape = { shape = "circle", radius = 0.5 }, from = {30, 5}, to = {30, -5} }
  check.that("shape_cast hits the capsule", h and h.body == bodies.capsule)
  check.near("time of impact", h.fraction, 0.4, 1e-6)  -- the circle's centre stops at y = 1
  near_vec("contact point", h.point, 30, 0.5, 1e-6)
  near_vec("normal", h.normal, 0, 1, 1e-6)
  local onto_chain = world:shape_cast{ shape = { shape = "box", width = 1, height = 1 }, from = {50, 5}, to = {50, -5} }
  check.that("shape_cast hits the chain", onto_chain and onto_chain.body == bodies.chain)
  check.near("time of impact on the chain", onto_chain.fraction, 0.45, 1e-6)
  check.that("stops short", world:shape_cast{ shape = small_circle, from = {30, 5}, to = {30, 2} } == nil)
end

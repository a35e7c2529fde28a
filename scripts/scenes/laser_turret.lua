-- A laser turret at the origin fires rays (world:ray_cast) at three targets; each hit's point,
-- normal and fraction are checked against the closed-form intersection of the ray with
--   a box turned by 0.3 rad: the face plane (p − c)·n = half width, n = the face's outward normal;
--   a circle, along a ray that passes it at r (1 − 1e-6) from its centre (the tangent region, where
--     the hit is √(r² − d²) ≈ 1.4 mm from the tangent point): p = o + t u, t = u·(c − o) − √(r² − d²);
--   a capsule turned by 0.5 rad, on its straight side: the plane (p − c)·n = r, n ⟂ its axis.
-- A ray just outside the circle (d = r (1 + 1e-6)) misses it. The turret sweeps the beam once
-- through the scene (ray_cast_all), which must meet the three targets in order of distance.
local check = require "check"

scene = { title = "Laser turret (ray casts)", dt = 1 / 60, duration = 0.1, gravity = {0, 0},
          camera = { center = {10, 0}, height = 24 } }

local reach = 30  -- length of the beam
local box, circle, capsule
local box_c, box_angle = vec2(8, -4), 0.3
local circle_c, r = vec2(10, 3), 1
local capsule_c, capsule_angle, capsule_r = vec2(15, -1), 0.5, 0.5
local sweep = {}

function PopulateWorld(world)
  world:add_box{ name = "turret", width = 1, height = 1, static = true }  -- the beam starts inside it
  box = world:add_box{ name = "box", width = 2, height = 2, position = box_c, angle = box_angle, static = true }
  circle = world:add_circle{ name = "circle", radius = r, position = circle_c, static = true }
  capsule = world:add_capsule{ name = "capsule", a = {-2, 0}, b = {2, 0}, radius = capsule_r, position = capsule_c,
                               angle = capsule_angle, static = true }
end

local function fire(world, direction)
  local u = direction:normalized()
  return world:ray_cast{ from = {0, 0}, to = u * reach }, u
end

local function near_vec(name, v, w, tolerance)
  check.near(name .. ".x", v.x, w.x, tolerance)
  check.near(name .. ".y", v.y, w.y, tolerance)
end

-- The hit of a ray o + t u (o = 0) with the plane (p − c)·n = offset.
local function plane_hit(u, c, n, offset)
  local t = (offset + c:dot(n)) / u:dot(n)
  return u * t, t
end

local function expect(name, hit, body, point, normal, t)
  check.that(name .. ": hit", hit ~= nil)
  check.that(name .. ": the right body", hit.body == body, hit.body.name)
  near_vec(name .. " point", hit.point, point, 1e-9)
  near_vec(name .. " normal", hit.normal, normal, 1e-9)
  check.near(name .. " fraction", hit.fraction, t / reach, 1e-9)
end

function OnStep(world)
  -- The sweep: 90 beams from -60° to 60°, each noting the first body it meets.
  if world.step_count > 1 then return end
  for i = 0, 89 do
    local a = math.rad(-60 + 120 * i / 89)
    local hit = fire(world, vec2(math.cos(a), math.sin(a)))
    if hit and sweep[#sweep] ~= hit.body.name then sweep[#sweep + 1] = hit.body.name end
  end
end

function Check(world)
  -- The box: aimed at its centre, the beam meets the face whose outward normal is (−cos θ, −sin θ).
  local n_box = vec2(-math.cos(box_angle), -math.sin(box_angle))
  local hit, u = fire(world, box_c)
  local p, t = plane_hit(u, box_c, n_box, 1)
  expect("box face", hit, box, p, n_box, t)

  -- The circle's tangent region: the beam passes its centre at d = r (1 − 1e-6).
  local dist = circle_c:length()
  for _, side in ipairs{ 1, -1 } do
    local d = r * (1 - 1e-6)
    local a = math.atan(circle_c.y, circle_c.x) + side * math.asin(d / dist)
    hit, u = fire(world, vec2(math.cos(a), math.sin(a)))
    local along = u:dot(circle_c)
    t = along - math.sqrt(r * r - (dist * dist - along * along))
    p = u * t
    expect("circle tangent region " .. side, hit, circle, p, (p - circle_c) / r, t)
    local miss = fire(world, vec2(math.cos(a + side * 2e-6 * r / dist), math.sin(a + side * 2e-6 * r / dist)))
    check.that("just outside the circle: no hit on it " .. side, miss == nil or miss.body ~= circle)
  end

  -- The capsule's side: aimed 0.7 m along its axis from its centre, the beam meets the side facing
  -- the turret (normal −(−sin α, cos α) points towards the origin here).
  local axis = vec2(math.cos(capsule_angle), math.sin(capsule_angle))
  local side_n = vec2(-axis.y, axis.x)
  if side_n:dot(capsule_c) > 0 then side_n = -side_n end
  hit, u = fire(world, capsule_c + axis * 0.7)
  p, t = plane_hit(u, capsule_c, side_n, capsule_r)
  check.less("the capsule hit lies on its straight side", math.abs((p - capsule_c):dot(axis)), 2)
  expect("capsule side", hit, capsule, p, side_n, t)

  -- The sweep met the targets by angle: the box below, then the capsule, then the circle above.
  check.that("the sweep", table.concat(sweep, ",") == "box,capsule,circle", table.concat(sweep, ","))
  -- ray_cast_all along the box's ray: only the box (the turret, where the beam starts, is not hit).
  local all = world:ray_cast_all{ from = {0, 0}, to = box_c:normalized() * reach }
  check.that("ray_cast_all: the box alone", #all == 1 and all[1].body == box, #all .. " hits")
end

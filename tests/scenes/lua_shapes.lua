-- Shapes through the Lua API: compound bodies from body:add_shape against closed forms, shape
-- handles (every field read back, writes), shape:remove(), concave outlines, capsules, segments,
-- chains, collision filters (64-bit bits, groups) and sensors in a simulation, and the messages of
-- the mistakes a scene can make with them.
local check = require "check"

scene = { title = "Lua API: shapes", duration = 1, integrator = "semi_implicit_euler" }

local pi = math.pi
local function near_vec(name, v, x, y, tolerance)
  check.near(name .. ".x", v.x, x, tolerance)
  check.near(name .. ".y", v.y, y, tolerance)
end
-- The message of the error f raises, which must contain `text`.
local function refused(name, text, f, ...)
  local ok, message = pcall(f, ...)
  check.that(name .. " is refused", not ok, "no error")
  check.that(name .. ": message", message:find(text, 1, true) ~= nil, message)
end

local ground_box, through, stopped, low, high, ghost, ball_on_sensor, rolling

function PopulateWorld(world)
  -- An L of two boxes: masses 2 and 2 (density 1), centre (0.75, 1.25); each box's own I is
  -- m (w² + h²) / 12, plus m d² (parallel-axis theorem).
  local l = world:add_body{ position = {-20, 20}, gravity_scale = 0 }
  check.near("a body without shapes is a unit point mass", l.mass, 1, 0)
  check.that("no shapes", #l.shapes == 0 and l.shape == nil and l.radius == nil and l.friction == nil)
  local s1 = l:add_shape{ shape = "box", width = 2, height = 1, offset = {1, 0.5}, friction = 0.2, restitution = 0.5 }
  local s2 = l:add_shape{ shape = "box", width = 1, height = 2, offset = {0.5, 2} }
  check.near("L mass", l.mass, 4, 1e-12)
  near_vec("L local centre", l.local_center, 0.75, 1.25, 1e-12)
  near_vec("L centre, world", l.center, -20 + 0.75, 20 + 1.25, 1e-12)
  check.near("L inertia", l.inertia, 2 * (2 * 5 / 12 + 2 * (0.0625 + 0.5625)), 1e-12)
  check.that("shapes in the order added", #l.shapes == 2 and l.shapes[1] == s1 and l.shapes[2] == s2)
  check.that("the same shape is the same handle", rawequal(l.shapes[1], s1))
  check.that("shape.body", s1.body == l)
  check.that("shape.kind of a box", s1.kind == "polygon" and #s1.vertices == 4 and s1.radius == nil and s1.a == nil)
  check.near("shape mass", s1.mass, 2, 1e-12)
  check.near("shape area", s1.area, 2, 1e-12)
  near_vec("shape centre (body coordinates)", s1.center, 1, 0.5, 1e-12)
  check.near("shape friction", s1.friction, 0.2, 0)
  check.near("static_friction defaults to friction", s1.static_friction, 0.2, 0)
  check.near("shape restitution", s1.restitution, 0.5, 0)
  check.near("default density", s2.density, 1, 0)
  check.that("default filter", s2.category == 1 and s2.mask == -1 and s2.group == 0 and s2.sensor == false)
  check.that("integers", math.type(s2.category) == "integer" and math.type(s2.mask) == "integer")

  -- The body's fields for its one shape say what to use instead on a compound body.
  refused("body.radius of a compound", "body.radius: the body has 2 shapes; read body.shapes[i].radius",
          function() return l.radius end)
  refused("body.shape of a compound", "body.shape: the body has 2 shapes; read body.shapes[i].kind",
          function() return l.shape end)
  refused("body.friction when the shapes differ",
          "body.friction: the body's 2 shapes differ in friction (shape 1: 0.2, shape 2: 0.6); read body.shapes[i].friction",
          function() return l.friction end)
  l.friction = 0.4  -- writes every shape
  check.that("body.friction writes every shape", s1.friction == 0.4 and s2.friction == 0.4 and l.friction == 0.4)
  l.category, l.mask, l.group = 4, ~4, 7
  check.that("body filter writes every shape", s1.category == 4 and s2.mask == ~4 and s2.group == 7 and l.group == 7)
  refused("body.restitution 2", "body.restitution: must be between 0 and 1, got 2", function() l.restitution = 2 end)

  -- Writes to a shape, read back; density moves the mass.
  s2.density = 3
  check.near("shape density written", s2.density, 3, 0)
  check.near("L mass after density 3", l.mass, 2 + 6, 1e-12)
  near_vec("L centre after density 3", l.local_center, (2 * 1 + 6 * 0.5) / 8, (2 * 0.5 + 6 * 2) / 8, 1e-12)
  s1.restitution, s1.friction, s1.static_friction, s1.sensor = 0.25, 0.7, 0.9, true
  s1.category, s1.mask, s1.group = 1 << 63, 2 ^ 3, -5
  check.that("shape material written", s1.restitution == 0.25 and s1.friction == 0.7 and s1.static_friction == 0.9)
  check.that("shape sensor written", s1.sensor == true)
  check.that("bit 63", s1.category == math.mininteger and s1.category == 1 << 63)
  check.that("a float with a whole value is an integer bit set", s1.mask == 8 and math.type(s1.mask) == "integer")
  check.near("group", s1.group, -5, 0)
  refused("shape.mask 0.5", "shape.mask: must be an integer set of bits (e.g. 1 << 3, 0x8 or -1 for all 64), got 0.5",
          function() s1.mask = 0.5 end)
  refused("shape.group 2^31", "shape.group: must be between -2147483648 and 2147483647, got 2147483648",
          function() s1.group = 1 << 31 end)
  refused("shape.density 0", "shape.density: must be > 0, got 0", function() s1.density = 0 end)
  refused("shape.area", "shape.area: is read-only", function() s1.area = 1 end)
  refused("shape.frction", "shape: has no field 'frction' (did you mean 'friction'?)", function() return s1.frction end)

  -- shape:remove() recomputes the mass; the handle then says removed.
  s2:remove()
  check.that("removed", s2.removed and #l.shapes == 1 and not s1.removed)
  check.near("L mass after remove", l.mass, 2, 1e-12)
  near_vec("centre after remove", l.local_center, 1, 0.5, 1e-12)
  refused("a removed shape's fields", "shape.mass: the shape was removed", function() return s2.mass end)
  s2:remove()  -- again: nothing
  world:remove(s1)
  check.that("world:remove(shape)", s1.removed and #l.shapes == 0)
  check.near("no shapes: unit mass again", l.mass, 1, 0)

  -- A ring of eight circles: I = Σ (½ m r² + m R²).
  local ring = world:add_body{ position = {-30, 20}, gravity_scale = 0 }
  local R, r = 2, 0.25
  for i = 0, 7 do
    local t = 2 * pi * i / 8
    ring:add_shape{ shape = "circle", radius = r, offset = {R * math.cos(t), R * math.sin(t)} }
  end
  local m = pi * r * r
  check.near("ring mass", ring.mass, 8 * m, 1e-12)
  check.near("ring inertia", ring.inertia, 8 * (0.5 * m * r * r + m * R * R), 1e-12)
  near_vec("ring centre", ring.local_center, 0, 0, 1e-12)
  near_vec("circle centre", ring.shapes[3].center, 0, 2, 1e-12)
  check.near("circle radius", ring.shapes[3].radius, 0.25, 0)

  -- A turned box and a polygon, capsule and segment shape at an offset.
  local parts = world:add_body{ position = {-40, 20}, type = "kinematic" }
  local turned = parts:add_shape{ shape = "box", width = 2, height = 1, angle = pi / 2 }
  local xs, ys = 0, 0
  for _, v in ipairs(turned.vertices) do xs, ys = math.max(xs, math.abs(v.x)), math.max(ys, math.abs(v.y)) end
  check.near("turned box half width", xs, 0.5, 1e-12)
  check.near("turned box half height", ys, 1, 1e-12)
  local tri = parts:add_shape{ shape = "polygon", vertices = {{0, 0}, {1, 0}, {0, 1}}, offset = {5, 0} }
  near_vec("polygon centre", tri.center, 5 + 1 / 3, 1 / 3, 1e-12)
  local pill = parts:add_shape{ shape = "capsule", a = {-1, 0}, b = {1, 0}, radius = 0.5, offset = {0, 5} }
  check.that("capsule shape", pill.kind == "capsule" and pill.radius == 0.5)
  near_vec("capsule a", pill.a, -1, 5, 1e-12)
  local line = parts:add_shape{ shape = "segment", a = {0, 0}, b = {2, 0}, offset = {0, -5} }
  check.that("segment shape", line.kind == "segment" and line.mass == 0 and line.area == 0 and line.density == nil)
  near_vec("segment centre", line.center, 1, -5, 1e-12)
  refused("density of a segment", "shape.density: a segment has no area, so no density", function() line.density = 2 end)
  refused("a width for a circle", "add_shape: width is not an option of a circle shape (it takes radius, offset and angle)",
          parts.add_shape, parts, { shape = "circle", radius = 1, width = 2 })
  refused("an unknown kind", 'add_shape: shape must be "circle", "box", "polygon", "capsule" or "segment", got "square"',
          parts.add_shape, parts, { shape = "square" })
  refused("a segment on a dynamic body", 'add_shape: shape "segment" needs a static or kinematic body, and this one is dynamic',
          ring.add_shape, ring, { shape = "segment", a = {0, 0}, b = {1, 0} })
  refused("a concave shape",
          "add_shape: polygon is not convex: it turns clockwise at vertices[4] (1, 1) (a shape is convex: add one shape per convex piece",
          ring.add_shape, ring, { shape = "polygon", vertices = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}} })
  refused("add_shape with a dot", "add_shape: call it as body:add_shape{...}, with a colon", parts.add_shape, { shape = "circle" })

  -- A capsule body: mass and inertia in closed form (a rectangle and two half discs).
  local rho, cr, cl = 3, 0.5, 2
  local cap = world:add_capsule{ a = {-1, 0}, b = {1, 0}, radius = cr, density = rho, position = {-50, 20}, gravity_scale = 0 }
  check.that("one-shape capsule", cap.shape == "capsule" and cap.radius == cr and cap.vertices == nil)
  check.near("capsule mass", cap.mass, rho * (2 * cr * cl + pi * cr * cr), 1e-12)
  local m_rect, m_half, c = rho * 2 * cr * cl, rho * pi * cr * cr / 2, 4 * cr / (3 * pi)
  check.near("capsule inertia", cap.inertia,
             m_rect * (cl * cl + 4 * cr * cr) / 12 + 2 * (m_half * (cr * cr / 2 - c * c) + m_half * (cl / 2 + c) ^ 2), 1e-12)
  refused("a capsule of one point", "add_capsule: b must differ from a, got a = (0, 0) and b = (0, 0)",
          world.add_capsule, world, { a = {0, 0}, b = {0, 0}, radius = 1 })

  -- A concave outline: refused without concave = true, a compound of convex pieces with it.
  local outline = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}
  refused("a concave outline", "add_polygon: polygon is not convex: it turns clockwise at vertices[4] (1, 1) (give concave = true to make the body of convex pieces)",
          world.add_polygon, world, { vertices = outline })
  local concave = world:add_polygon{ vertices = outline, concave = true, mass = 6, position = {-60, 20}, gravity_scale = 0,
                                     angular_velocity = 1, velocity = {2, 0} }
  check.that("pieces", #concave.shapes >= 2)
  local area = 0
  for _, s in ipairs(concave.shapes) do area = area + s.area end
  check.near("pieces cover the outline", area, 3, 1e-12)
  check.near("concave mass", concave.mass, 6, 1e-12)
  -- Two rectangles: [0, 2] × [0, 1] and [0, 1] × [1, 2], density 2.
  near_vec("concave centre", concave.local_center, 2.5 / 3, 2.5 / 3, 1e-12)
  local function rect(mass, w, h, cx, cy)
    local d2 = (cx - 2.5 / 3) ^ 2 + (cy - 2.5 / 3) ^ 2
    return mass * (w * w + h * h) / 12 + mass * d2
  end
  check.near("concave inertia", concave.inertia, rect(4, 2, 1, 1, 0.5) + rect(2, 1, 1, 0.5, 1.5), 1e-12)
  near_vec("the velocity given is the centre of mass's", concave.velocity, 2, 0, 1e-12)
  local convex = world:add_polygon{ vertices = {{0, 0}, {1, 0}, {0, 1}}, concave = true, position = {-70, 20}, gravity_scale = 0 }
  check.that("a convex outline with concave = true is one shape", convex.shape == "polygon" and #convex.shapes == 1)
  refused("a crossing outline", "add_polygon: vertices: outline crosses itself: edge 1 meets edge 3", world.add_polygon, world,
          { vertices = {{0, 0}, {1, 1}, {1, 0}, {0, 1}}, concave = true })

  -- Segments and chains: static by default, never dynamic.
  local seg = world:add_segment{ a = {0, 0}, b = {1, 0}, position = {-80, 20} }
  check.that("a segment body is static", seg.type == "static" and seg.shape == "segment")
  local moving = world:add_segment{ a = {0, 0}, b = {1, 0}, type = "kinematic", velocity = {1, 0}, position = {-90, 20} }
  check.that("or kinematic", moving.type == "kinematic")
  refused("a dynamic segment", 'add_segment: type "dynamic" is refused: a segment has no area',
          world.add_segment, world, { a = {0, 0}, b = {1, 0}, type = "dynamic" })
  refused("static = false for a segment", "add_segment: static = false is refused",
          world.add_segment, world, { a = {0, 0}, b = {1, 0}, static = false })
  refused("a segment's mass", "add_segment: mass cannot be given: a segment or chain has no area",
          world.add_segment, world, { a = {0, 0}, b = {1, 0}, mass = 1 })
  local loop = world:add_chain{ points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, loop = true, position = {-100, 20}, friction = 0.3 }
  check.that("a loop of 4 points has 4 segments", #loop.shapes == 4 and loop.shapes[1].kind == "chain_segment")
  check.near("chain friction", loop.friction, 0.3, 0)
  near_vec("chain segment a, body coordinates", loop.shapes[2].a, 1, 0, 0)
  refused("a chain that repeats a point", "add_chain: points[3] repeats the point before it, (1, 0)",
          world.add_chain, world, { points = {{0, 0}, {1, 0}, {1, 0}} })
  refused("a kinematic chain", 'add_chain: type "kinematic" is refused: a chain belongs to a static body',
          world.add_chain, world, { points = {{0, 0}, {1, 0}}, type = "kinematic" })
  refused("a loop of 2", "add_chain: points needs at least 3 points, got 2",
          world.add_chain, world, { points = {{0, 0}, {1, 0}}, loop = true })

  -- Simulation: the ground is a chain (listed right to left: its top faces up) in category 2.
  world:add_chain{ points = {{10, 0}, {-10, 0}}, category = 2 }
  ground_box = world:add_box{ width = 4, height = 0.2, position = {6, 2}, static = true, category = 2 }
  -- A box whose mask leaves out category 2 falls through; an ordinary one stops on the ground.
  through = world:add_box{ width = 0.5, height = 0.5, position = {-6, 1}, mask = ~2 }
  stopped = world:add_box{ width = 0.5, height = 0.5, position = {-4, 1} }
  -- Two boxes of the same negative group overlap and never collide; both rest on the ground.
  low = world:add_box{ width = 1, height = 1, position = {0, 0.5}, group = -1 }
  high = world:add_box{ width = 1, height = 1, position = {0, 1.0}, group = -1 }
  -- A sensor box holds nothing up: the ball falls through it onto the box below.
  ghost = world:add_box{ width = 2, height = 0.2, position = {6, 3}, static = true, sensor = true }
  ball_on_sensor = world:add_circle{ radius = 0.25, position = {6, 3.5} }
  check.that("body.sensor of a one-shape body", ghost.sensor == true and ball_on_sensor.sensor == false)
  rolling = world:add_circle{ radius = 0.5, position = {-8, 0.5}, velocity = {2, 0}, friction = 1 }
end

function Check(world)
  check.less("masked box fell through the ground", through.position.y, -1)
  check.near("ordinary box on the chain", stopped.position.y, 0.25, 0.02)
  check.near("low box of the group on the ground", low.position.y, 0.5, 0.02)
  check.near("high box of the group inside it, on the ground", high.position.y, 0.5, 0.02)
  check.near("ball through the sensor, on the box", ball_on_sensor.position.y, 2.1 + 0.25, 0.02)
  check.near("ball rolls on the chain", rolling.position.y, 0.5, 0.02)
  check.greater("ball rolled", rolling.position.x, -7)
end

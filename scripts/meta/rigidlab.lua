---@meta
-- Type annotations of rigidlab's Lua scene API for editors (lua-language-server). Not loaded by
-- rigidlab. Keep in step with the bindings: tests/lua/test_annotations.cpp compares the two.
-- Units are SI: metres, kilograms, seconds, radians.

---A 2D vector: a table {x = ..., y = ...} with arithmetic. Wherever the API takes a vector it
---also accepts {x, y} or {x = x, y = y}.
---@class rigidlab.Vec2
---@field x number
---@field y number
---@operator add(rigidlab.Vec2): rigidlab.Vec2
---@operator sub(rigidlab.Vec2): rigidlab.Vec2
---@operator mul(number): rigidlab.Vec2
---@operator div(number): rigidlab.Vec2
---@operator unm: rigidlab.Vec2
local Vec2 = {}

---Dot product.
---@param other rigidlab.VecLike
---@return number
function Vec2:dot(other) end

---2D cross product x₁y₂ − y₁x₂.
---@param other rigidlab.VecLike
---@return number
function Vec2:cross(other) end

---@return number
function Vec2:length() end

---Unit vector in the same direction; the zero vector stays zero.
---@return rigidlab.Vec2
function Vec2:normalized() end

---Counter-clockwise perpendicular (−y, x).
---@return rigidlab.Vec2
function Vec2:perp() end

---Rotated counter-clockwise by `angle` radians.
---@param angle number
---@return rigidlab.Vec2
function Vec2:rotated(angle) end

---@alias rigidlab.VecLike rigidlab.Vec2|number[]|{x: number, y: number}

---Creates a vector.
---@param x number
---@param y number
---@return rigidlab.Vec2
function vec2(x, y) end

---A rigid body made of shapes. Handles are compared with ==; the same body is always the same handle.
---@class rigidlab.Body
---@field position rigidlab.Vec2 body origin in world coordinates (read/write)
---@field angle number radians, counter-clockwise (read/write)
---@field velocity rigidlab.Vec2 velocity of the centre of mass, m/s; a static body's must stay zero (read/write)
---@field angular_velocity number rad/s; a static body's must stay zero (read/write)
---@field mass number kg; writing keeps the shapes and their proportions, changes the densities (read/write)
---@field static boolean type == "static"; writing false makes the body dynamic (read/write)
---@field type "static"|"kinematic"|"dynamic" (read/write)
---@field name string (read/write)
---@field restitution number 0..1, of every shape; reading it on a compound body whose shapes differ is an error (read/write)
---@field friction number dynamic friction coefficient of every shape (read/write)
---@field static_friction number static friction coefficient of every shape (read/write)
---@field awake boolean false while the body sleeps; write true to wake it and its island (read/write)
---@field id integer 1, 2, 3, ... in creation order, never reused (read only)
---@field center rigidlab.Vec2 world centre of mass (read only)
---@field local_center rigidlab.Vec2 centre of mass in body coordinates (read only)
---@field inertia number kg·m² about the centre of mass; writing one replaces the shapes' until they change (body:reset_mass) (read/write)
---@field density number kg/m²: the shapes' density if they share one, else mass / area (read only)
---@field shape "circle"|"polygon"|"capsule"|"segment"|"chain_segment"|nil a one-shape body's kind; an error on a compound body (read only)
---@field radius number|nil a one-shape circle's or capsule's radius (read only)
---@field vertices rigidlab.Vec2[]|nil a one-shape polygon's corners, body coordinates (read only)
---@field shapes rigidlab.Shape[] in the order they were added (read only)
---@field removed boolean true once world:remove(body) was called (read only)
---@field linear_damping number 1/s, implicit: never flips a velocity (read/write)
---@field angular_damping number 1/s (read/write)
---@field gravity_scale number multiplies the world's gravity (or the body's own) for this body (read/write)
---@field gravity rigidlab.Vec2|nil the body's own gravity, m/s², in place of the world's (still times gravity_scale); nil: the world's (read/write)
---@field sleeping_allowed boolean false: the body never falls asleep, nor lets its island sleep (read/write)
---@field world rigidlab.World the world the body is in (read only)
---@field fixed_rotation boolean the body never turns (read/write)
---@field bullet boolean also swept against dynamic bodies (read/write)
---@field enabled boolean false: out of the simulation, kept as it is (read/write)
---@field user_data any any Lua value, kept with the body as it is (not copied); never read by rigidlab (read/write)
---@field sensor boolean every shape is a sensor (read/write)
---@field category integer collision category bits of every shape, 64-bit (read/write)
---@field mask integer bits of the categories every shape collides with; -1 is all (read/write)
---@field group integer collision group of every shape: same positive group always collides, same negative never (read/write)
local Body = {}

---Changes the momentum at once: Δv = j / m, Δω = (point − center) × j / I.
---@param impulse rigidlab.VecLike N·s
---@param point? rigidlab.VecLike world point, default the centre of mass
function Body:apply_impulse(impulse, point) end

---Applies a constant force at a world point (which then moves with the body).
---@param force rigidlab.VecLike N
---@param point? rigidlab.VecLike world point, default the centre of mass
---@param duration? number seconds; default: the next step only
function Body:apply_force(force, point, duration) end

---Applies a constant torque (counter-clockwise > 0).
---@param torque number N·m
---@param duration? number seconds; default: the next step only
function Body:apply_torque(torque, duration) end

---Changes the angular momentum at once: Δω = j / I.
---@param impulse number N·m·s
function Body:apply_angular_impulse(impulse) end

---A point given in the body's coordinates, in world coordinates (LÖVE's getWorldPoint).
---@param point rigidlab.VecLike
---@return rigidlab.Vec2
function Body:world_point(point) end

---A world point in the body's coordinates (LÖVE's getLocalPoint).
---@param point rigidlab.VecLike
---@return rigidlab.Vec2
function Body:local_point(point) end

---A direction given in the body's coordinates, in world coordinates (turned, not moved).
---@param vector rigidlab.VecLike
---@return rigidlab.Vec2
function Body:world_vector(vector) end

---A world direction in the body's coordinates.
---@param vector rigidlab.VecLike
---@return rigidlab.Vec2
function Body:local_vector(vector) end

---The velocity of the body's material point at a world point: v + ω × (p − center).
---@param point rigidlab.VecLike world point
---@return rigidlab.Vec2
function Body:velocity_at(point) end

---The mass, centre of mass and inertia from the shapes again (after body.inertia was written).
function Body:reset_mass() end

---Adds a shape; the mass, centre of mass and inertia become the sums over the shapes.
---@param options rigidlab.AddShapeOptions
---@return rigidlab.Shape
function Body:add_shape(options) end

---Kinematic bodies: sets the velocity that reaches the pose in `time` seconds (and keeps it).
---@param options rigidlab.TargetOptions
function Body:set_target(options) end

---The joints attached to the body.
---@return rigidlab.Joint[]
function Body:joints() end

---The body's touching contacts now (approach_speed: the closing speed now; impulses: the last step's).
---@return rigidlab.Contact[]
function Body:contacts() end

---A shape of a body (body:add_shape returns one; body.shapes lists them).
---@class rigidlab.Shape
---@field kind "circle"|"polygon"|"capsule"|"segment"|"chain_segment" (read only)
---@field body rigidlab.Body (read only)
---@field radius number|nil circles and capsules; writing it changes the shape, and its body's mass (read/write)
---@field center rigidlab.Vec2 centroid, body coordinates; a circle's may be written, the others' follow their points (read/write)
---@field vertices rigidlab.Vec2[]|nil polygons: corners, counter-clockwise, body coordinates; writable as the polygon option (read/write)
---@field a rigidlab.Vec2|nil capsules, segments, chain segments: first point, body coordinates (read/write)
---@field b rigidlab.Vec2|nil second point (read/write)
---@field ghost1 rigidlab.Vec2|nil chain segments: the chain's point before a (LÖVE's previous vertex) (read/write)
---@field ghost2 rigidlab.Vec2|nil chain segments: the chain's point after b (LÖVE's next vertex) (read/write)
---@field density number|nil kg/m²; nil for segments (read/write)
---@field mass number kg, 0 for segments (read only)
---@field area number m², 0 for segments (read only)
---@field inertia number kg·m² about the shape's own centroid, 0 for segments (read only)
---@field bounds {lower: rigidlab.Vec2, upper: rigidlab.Vec2} the world box around the shape now (read only)
---@field tangent_speed number m/s: the surface moves along itself, clockwise around the shape (a conveyor belt); contacts' speeds add (read/write)
---@field rolling_resistance number ≥ 0, as Box2D v3: a contact resists turning with at most c · r · N (r: the larger radius) (read/write)
---@field user_data any any Lua value, kept with the shape; readable after it was removed (read/write)
---@field restitution number 0..1 (read/write)
---@field friction number (read/write)
---@field static_friction number (read/write)
---@field sensor boolean a sensor collides with nothing (read/write)
---@field category integer the categories the shape belongs to, 64 bits (read/write)
---@field mask integer the categories it collides with; -1 (every bit) by default (read/write)
---@field group integer same positive group: always collide; same negative group: never (read/write)
---@field removed boolean (read only)
---@field contact_events boolean its contacts' begin and end are reported (OnContactBegin, OnContactEnd) (read/write)
---@field hit_events boolean impacts of at least hit_speed are reported (OnHit) (read/write)
---@field hit_speed number m/s ≥ 0: the closing speed that makes a hit (read/write)
---@field one_way rigidlab.Vec2|nil a one-way platform: the unit normal of the side to stand on, body coordinates (read/write)
---@field pre_solve fun(contact: rigidlab.Contact): boolean|nil|nil called during the step for its contacts; false disables the contact this step (read/write)
local Shape = {}

---Removes the shape from its body (no-op if already removed); the body's mass is recomputed.
function Shape:remove() end

---Whether the world point lies in the shape (segments contain none).
---@param point rigidlab.VecLike
---@return boolean
function Shape:test_point(point) end

---The shape alone: where the segment from → to enters it, as world:ray_cast reports hits, or nil.
---@param options {from: rigidlab.VecLike, to: rigidlab.VecLike}
---@return rigidlab.QueryHit|nil
function Shape:ray_cast(options) end

---The distance between this shape's surface and another's (0 when they overlap), and the closest
---point on each, world coordinates.
---@param other rigidlab.Shape
---@return number distance
---@return rigidlab.Vec2 on_this
---@return rigidlab.Vec2 on_other
function Shape:distance(other) end

---A joint handle (world:add_revolute and the other joint functions return one). Which fields a
---joint has depends on its kind; a field of another kind is an error.
---@class rigidlab.Joint
---@field kind "revolute"|"prismatic"|"distance"|"weld"|"wheel"|"motor"|"friction"|"pulley"|"gear" (read only)
---@field a rigidlab.Body (read only)
---@field b rigidlab.Body|nil nil: the joint pins a to the world (read only)
---@field name string (read/write)
---@field collide_connected boolean may a and b collide (read/write)
---@field break_force number N; math.huge: never breaks (read/write)
---@field break_torque number N·m (read/write)
---@field user_data any any Lua value, kept with the joint; readable after it broke (read/write)
---@field local_anchor_a rigidlab.Vec2 the anchor on a in a's coordinates (read only)
---@field local_anchor_b rigidlab.Vec2 the anchor on b in b's coordinates (the world's when b is nil) (read only)
---@field axis rigidlab.Vec2 prismatic, wheel: the axis now, unit, world (read only)
---@field motor_torque number revolute, wheel: the motor's torque in the last step, N·m (read only)
---@field motor_force number prismatic: the motor's force in the last step, N (read only)
---@field length_a number pulley: a's rope now, m (read only)
---@field length_b number pulley: b's rope now, m (read only)
---@field angle number revolute, wheel, weld: b's angle relative to a since creation (a's own when b is nil), rad (read only)
---@field speed number revolute, wheel: relative angular speed, rad/s; prismatic: along the axis, m/s (read only)
---@field translation number prismatic, wheel: along the axis, m; distance: current length, m (read only)
---@field reaction_force rigidlab.Vec2 force the joint applied in the last step to b (to a when b is nil), N (read only)
---@field reaction_torque number N·m (read only)
---@field anchor_a rigidlab.Vec2 the anchor on a, world coordinates now (read only)
---@field anchor_b rigidlab.Vec2 the anchor on b (or the world), world coordinates now (read only)
---@field broken boolean the joint broke (and was removed) (read only)
---@field removed boolean (read only)
---@field enable_limit boolean revolute, prismatic, wheel, distance (read/write)
---@field lower_angle number revolute, rad; writing it enables the limit (read/write)
---@field upper_angle number revolute, rad (read/write)
---@field lower number prismatic, wheel: m (read/write)
---@field upper number prismatic, wheel: m (read/write)
---@field enable_motor boolean revolute, prismatic, wheel (read/write)
---@field motor_speed number rad/s (prismatic: m/s); writing it enables the motor (read/write)
---@field max_motor_torque number revolute, wheel: N·m (read/write)
---@field max_motor_force number prismatic: N (read/write)
---@field enable_spring boolean revolute, prismatic, wheel, distance (read/write)
---@field spring_hertz number Hz; writing > 0 enables the spring, 0 disables it (read/write)
---@field spring_damping number damping ratio (read/write)
---@field length number distance: rest length, m; pulley: the constant length_a + ratio · length_b (read/write)
---@field min_length number distance, m (read/write)
---@field max_length number distance, m; math.huge: none (read/write)
---@field max_spring_force number distance, N (read/write)
---@field linear_hertz number weld, Hz (0: rigid) (read/write)
---@field linear_damping number weld (read/write)
---@field angular_hertz number weld, Hz (read/write)
---@field angular_damping number weld (read/write)
---@field reference_angle number revolute, prismatic, weld, wheel: b's relative angle that counts as 0, rad (read only)
---@field linear_offset rigidlab.Vec2 motor: target of b's anchor in a's frame (world when b is nil) (read/write)
---@field angular_offset number motor: target angle of b relative to a, rad (read/write)
---@field linear_velocity rigidlab.Vec2 motor: velocity target, m/s (read/write)
---@field angular_velocity number motor: angular velocity target, rad/s (read/write)
---@field max_force number motor, friction: N (read/write)
---@field max_torque number motor, friction: N·m (read/write)
---@field motor_hertz number motor: stiffness of the drive, Hz (0: as stiff as joints) (read/write)
---@field motor_damping number motor: damping ratio (read/write)
---@field ground_a rigidlab.Vec2 pulley: fixed point of a's rope (read only)
---@field ground_b rigidlab.Vec2 pulley: fixed point of b's rope (read only)
---@field ratio number pulley, gear; written, the coupling holds from where the bodies are (read/write)
---@field joint_a rigidlab.Joint|nil gear: the first geared joint (read only)
---@field joint_b rigidlab.Joint|nil gear: the second geared joint (read only)
local Joint = {}

---Removes the joint (no-op if already removed or broken).
function Joint:remove() end

---Revolute, prismatic, wheel: both limits at once (lower ≤ upper) and enables them; distance:
---min_length and max_length.
---@param lower number
---@param upper number
function Joint:set_limits(lower, upper) end

---A force, spring or damper handle.
---@class rigidlab.ForceHandle
---@field kind string "spring", "damper" or "lua force"
---@field removed boolean
local ForceHandle = {}

---Removes the force (no-op if already removed or expired).
function ForceHandle:remove() end

---A snapshot of the world (world:snapshot()), for world:restore.
---@class rigidlab.Snapshot
---@field time number simulated time when it was taken, s
---@field step_count integer steps made when it was taken
---@field bytes integer memory it holds
local Snapshot = {}

---Options every function that makes a body accepts (world:add_body takes only these).
---@class rigidlab.BodyOptions
---@field position? rigidlab.VecLike body origin, default {0, 0}
---@field angle? number default 0
---@field velocity? rigidlab.VecLike of the centre of mass, default {0, 0} (a static body: must be zero)
---@field angular_velocity? number default 0
---@field type? "static"|"kinematic"|"dynamic" default "dynamic" ("static" for add_segment, add_chain)
---@field static? boolean the older spelling of type = "static" (not together with type)
---@field name? string
---@field linear_damping? number 1/s ≥ 0, default 0
---@field angular_damping? number 1/s ≥ 0, default 0
---@field gravity_scale? number default 1
---@field fixed_rotation? boolean default false
---@field bullet? boolean default false
---@field enabled? boolean default true
---@field user_data? any any Lua value, kept with the body
---@field awake? boolean default true; false: created asleep (a dynamic body at rest, in a world that sleeps)
---@field gravity? rigidlab.VecLike the body's own gravity, m/s², in place of the world's; default: the world's
---@field sleeping_allowed? boolean default true; false: it never sleeps

---The options of a shape: body:add_shape and, for their one shape, the add_* body functions.
---@class rigidlab.ShapeOptions
---@field density? number kg/m², default 1 (not for segments and chains)
---@field restitution? number 0..1, default 0
---@field friction? number default 0.6
---@field static_friction? number default: friction
---@field sensor? boolean default false: a sensor collides with nothing
---@field category? integer 64-bit category bits, default 1 (a float with a whole value is taken too)
---@field mask? integer 64-bit bits of the categories it collides with, default -1 (all)
---@field group? integer 32-bit: same positive group always collides, same negative never; default 0
---@field tangent_speed? number m/s, default 0: the surface moves along itself (a conveyor), clockwise around the shape
---@field rolling_resistance? number ≥ 0, default 0 (Box2D v3's rolling resistance; circles and capsules)
---@field contact_events? boolean default false: report its contacts' begin and end
---@field hit_events? boolean default false (true when hit_speed is given): report impacts
---@field hit_speed? number m/s ≥ 0, default 1: the closing speed of a hit
---@field one_way? rigidlab.VecLike a one-way platform: the side to stand on, body coordinates (normalised)
---@field pre_solve? fun(contact: rigidlab.Contact): boolean|nil called during the step for its contacts; false disables the contact this step

---A body with one shape (add_box, add_circle, add_polygon, add_capsule, add_segment, add_chain).
---@class rigidlab.ShapedBodyOptions: rigidlab.BodyOptions, rigidlab.ShapeOptions
---@field mass? number kg (sets the density; not together with density)

---@class rigidlab.BoxOptions: rigidlab.ShapedBodyOptions
---@field width number m
---@field height number m

---@class rigidlab.CircleOptions: rigidlab.ShapedBodyOptions
---@field radius number m

---@class rigidlab.PolygonOptions: rigidlab.ShapedBodyOptions
---@field vertices rigidlab.VecLike[] body coordinates; convex, 3..32 points, any winding (concave: up to 256)
---@field concave? boolean default false; true: the outline may be concave, the body is made of convex pieces

---@class rigidlab.CapsuleOptions: rigidlab.ShapedBodyOptions
---@field a rigidlab.VecLike first centre, body coordinates
---@field b rigidlab.VecLike second centre
---@field radius number m

---A segment has no area: static (the default) or kinematic bodies only; no density or mass.
---@class rigidlab.SegmentOptions: rigidlab.ShapedBodyOptions
---@field a rigidlab.VecLike body coordinates
---@field b rigidlab.VecLike

---A chain of segments on a static body; one-sided: it faces the right of the direction from a
---point to the next (list ground from right to left; a counter-clockwise loop is solid inside).
---@class rigidlab.ChainOptions: rigidlab.ShapedBodyOptions
---@field points rigidlab.VecLike[] body coordinates, at least 2 (a loop: 3)
---@field loop? boolean default false

---@class rigidlab.AddShapeOptions: rigidlab.ShapeOptions
---@field shape "circle"|"box"|"polygon"|"capsule"|"segment"
---@field radius? number circle, capsule
---@field width? number box
---@field height? number box
---@field vertices? rigidlab.VecLike[] polygon: convex, 3..32 points, shape coordinates
---@field a? rigidlab.VecLike capsule, segment: shape coordinates
---@field b? rigidlab.VecLike capsule, segment
---@field offset? rigidlab.VecLike where the shape's origin lies in the body, default {0, 0}
---@field angle? number how far the shape is turned in the body, default 0
---@field user_data? any the shape's (the add_* body functions' user_data is the body's)

---@class rigidlab.TargetOptions
---@field position? rigidlab.VecLike the body origin to reach, default where it is
---@field angle? number default the body's angle
---@field time number seconds > 0

---@class rigidlab.SpringOptions
---@field a rigidlab.Body
---@field b? rigidlab.Body the other end (or anchor)
---@field anchor? rigidlab.VecLike a fixed world point (or b)
---@field local_a? rigidlab.VecLike attachment on a, body coordinates, default {0, 0}
---@field local_b? rigidlab.VecLike attachment on b, body coordinates, default {0, 0}
---@field stiffness number N/m
---@field rest_length? number m, default: the distance when created
---@field damping? number N·s/m along the spring, default 0

---@class rigidlab.DamperOptions
---@field body rigidlab.Body
---@field coefficient number F = −c v, N·s/m
---@field angular_coefficient? number τ = −c_ω ω, N·m·s, default 0

---Options every joint function accepts.
---@class rigidlab.JointOptions
---@field collide_connected? boolean default false: the joined bodies do not collide
---@field break_force? number N, default math.huge (never)
---@field break_torque? number N·m, default math.huge
---@field name? string for world:find_joint
---@field user_data? any any Lua value, kept with the joint

---Every kind that takes an anchor (anchor, or anchor_a and anchor_b) takes instead each body's own
---anchor in its coordinates, local_anchor_a and local_anchor_b (Box2D's and LÖVE's form; b's is a
---world point when b is nil). The two forms cannot be mixed. A missing one is where the other is
---now (a distance or pulley joint's: the body's centre of mass).

---A pin: the bodies turn about `anchor`. Giving lower_angle and upper_angle enables the limit;
---motor_speed (with max_motor_torque) the motor; spring_hertz > 0 the spring.
---@class rigidlab.RevoluteOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike a's anchor, a's coordinates (instead of the world anchors)
---@field local_anchor_b? rigidlab.VecLike b's anchor, b's coordinates (the world's when b is nil)
---@field b? rigidlab.Body default: the world
---@field anchor rigidlab.VecLike world point
---@field enable_limit? boolean overrides what the limit options imply
---@field lower_angle? number rad, b's angle relative to a from now (a's own when b is nil)
---@field upper_angle? number rad
---@field enable_motor? boolean
---@field motor_speed? number rad/s (needs max_motor_torque)
---@field max_motor_torque? number N·m
---@field enable_spring? boolean
---@field spring_hertz? number Hz, towards the angle at creation
---@field spring_damping? number damping ratio
---@field reference_angle? number rad: b's angle relative to a that counts as 0, default the angle now

---A slider: b moves along `axis` (fixed in a; in the world when b is nil) without turning.
---@class rigidlab.PrismaticOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike a's anchor, a's coordinates (instead of the world anchors)
---@field local_anchor_b? rigidlab.VecLike b's anchor, b's coordinates (the world's when b is nil)
---@field b? rigidlab.Body
---@field anchor rigidlab.VecLike world point
---@field axis rigidlab.VecLike direction, not zero
---@field enable_limit? boolean
---@field lower? number m along the axis
---@field upper? number m
---@field enable_motor? boolean
---@field motor_speed? number m/s (needs max_motor_force)
---@field max_motor_force? number N
---@field enable_spring? boolean
---@field spring_hertz? number Hz, towards translation 0
---@field spring_damping? number
---@field reference_angle? number rad: b's angle relative to a that counts as 0, default the angle now

---The anchors keep their distance (rigid), stay within min_length..max_length (a rope is
---max_length alone) or are held by a spring.
---@class rigidlab.DistanceOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike a's anchor, a's coordinates (instead of the world anchors)
---@field local_anchor_b? rigidlab.VecLike b's anchor, b's coordinates (the world's when b is nil)
---@field b? rigidlab.Body
---@field anchor_a? rigidlab.VecLike world point on a, default its centre of mass
---@field anchor_b? rigidlab.VecLike world point on b, default its centre of mass (required when b is nil)
---@field length? number m, default the distance now
---@field enable_limit? boolean
---@field min_length? number m (enables the limit)
---@field max_length? number m (enables the limit)
---@field enable_spring? boolean
---@field spring_hertz? number Hz (> 0: a spring instead of a rigid length)
---@field spring_damping? number
---@field max_spring_force? number N, default math.huge

---@class rigidlab.WeldOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike a's anchor, a's coordinates (instead of the world anchors)
---@field local_anchor_b? rigidlab.VecLike b's anchor, b's coordinates (the world's when b is nil)
---@field b? rigidlab.Body
---@field anchor rigidlab.VecLike world point
---@field linear_hertz? number Hz, 0 (default): rigid
---@field linear_damping? number
---@field angular_hertz? number Hz, 0: rigid
---@field angular_damping? number
---@field reference_angle? number rad: b's angle relative to a that counts as 0, default the angle now

---A car's wheel: b's anchor stays on `axis` (fixed in a); b turns freely. Without spring_hertz
---the wheel slides freely along the axis.
---@class rigidlab.WheelOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike a's anchor, a's coordinates (instead of the world anchors)
---@field local_anchor_b? rigidlab.VecLike b's anchor, b's coordinates (the world's when b is nil)
---@field b? rigidlab.Body
---@field anchor rigidlab.VecLike world point
---@field axis rigidlab.VecLike suspension direction, not zero
---@field enable_limit? boolean
---@field lower? number m
---@field upper? number m
---@field enable_motor? boolean
---@field motor_speed? number rad/s (needs max_motor_torque)
---@field max_motor_torque? number N·m
---@field enable_spring? boolean
---@field spring_hertz? number Hz: the suspension
---@field spring_damping? number
---@field reference_angle? number rad: b's angle relative to a that counts as 0, default the angle now

---Drives b towards a pose relative to a (the world when b is nil) with limited force and torque.
---@class rigidlab.MotorJointOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike the target in a's coordinates (the linear offset)
---@field local_anchor_b? rigidlab.VecLike the driven point in b's coordinates
---@field b? rigidlab.Body
---@field anchor? rigidlab.VecLike the driven point (world), default the driven body's centre of mass
---@field linear_offset? rigidlab.VecLike target of the driven point in a's frame; default where it is
---@field angular_offset? number target angle relative to a; default as now
---@field linear_velocity? rigidlab.VecLike velocity target, m/s
---@field angular_velocity? number rad/s
---@field max_force? number N, default 0
---@field max_torque? number N·m, default 0
---@field motor_hertz? number Hz, 0 (default): as stiff as joints
---@field motor_damping? number default 1

---Top-down friction: resists relative motion up to max_force and max_torque.
---@class rigidlab.FrictionJointOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike a's anchor, a's coordinates (instead of the world anchors)
---@field local_anchor_b? rigidlab.VecLike b's anchor, b's coordinates (the world's when b is nil)
---@field b? rigidlab.Body
---@field anchor? rigidlab.VecLike default the centre of mass of b (of a when b is nil)
---@field max_force? number N
---@field max_torque? number N·m

---Two bodies on a rope over two fixed points: length_a + ratio · length_b stays constant.
---@class rigidlab.PulleyOptions: rigidlab.JointOptions
---@field a rigidlab.Body
---@field local_anchor_a? rigidlab.VecLike a's anchor, a's coordinates (instead of the world anchors)
---@field local_anchor_b? rigidlab.VecLike b's anchor, b's coordinates (the world's when b is nil)
---@field b rigidlab.Body
---@field anchor_a? rigidlab.VecLike world, default a's centre of mass
---@field anchor_b? rigidlab.VecLike world, default b's centre of mass
---@field ground_a rigidlab.VecLike the fixed point a's rope runs over
---@field ground_b rigidlab.VecLike
---@field ratio? number > 0, default 1

---Couples two revolute or prismatic joints: coordinate_a + ratio · coordinate_b stays constant;
---or two bodies' angles (a, b): angle_a + ratio · angle_b stays constant (Chipmunk's gear).
---@class rigidlab.GearOptions: rigidlab.JointOptions
---@field joint_a? rigidlab.Joint
---@field joint_b? rigidlab.Joint
---@field a? rigidlab.Body instead of the joints
---@field b? rigidlab.Body
---@field ratio? number not 0, default 1

---The state a Lua force sees, at the integrator stage being evaluated. Only valid during the call.
---@class rigidlab.BodyState
---@field position rigidlab.Vec2 body origin
---@field velocity rigidlab.Vec2 centre-of-mass velocity
---@field center rigidlab.Vec2 centre of mass
---@field angle number
---@field angular_velocity number
---@field mass number
---@field inertia number
---@field time number the stage's simulation time

---@class rigidlab.ForceOptions
---@field body rigidlab.Body
---@field evaluate fun(s: rigidlab.BodyState, other?: rigidlab.BodyState): number, number, number? returns fx, fy [, torque]
---@field duration? number seconds; default: permanent
---@field point? rigidlab.VecLike where the force applies, body coordinates; default the centre of mass
---@field other? rigidlab.Body evaluate also receives this body's state at the same stage

---The world a scene builds in PopulateWorld.
---@class rigidlab.World
---@field gravity rigidlab.Vec2 m/s², default (0, −9.80665) (read/write)
---@field integrator "euler"|"semi_implicit_euler"|"rk4"|"implicit_euler" (read/write)
---@field dt number step size, s (read/write)
---@field solver "auto"|"sequential_impulses"|"soft_step" contact solver (read/write); see SceneSettings
---@field iterations integer sequential impulses: velocity passes per step (read/write)
---@field substeps integer soft step: sub-steps per step (read/write)
---@field sleeping boolean whether still islands fall asleep (read/write; false wakes everything)
---@field exact_joints boolean whether jointed bodies that touch nothing are integrated with their joints (read/write)
---@field time number simulated time, s (read only)
---@field step_count integer steps taken (read only)
---@field title string the scene's title (read only)
---@field locked boolean true while the world steps (inside a force, a pre_solve function, ShouldCollide) (read only)
---@field controls table<string, number> the scene's sliders by name (scene.controls): what the sandbox's slider says, the default headless; `world.controls.size = 0.5` sets one within its range; a button has no value (OnControl)
local World = {}

---A body without shapes (add them with body:add_shape).
---@param options rigidlab.BodyOptions
---@return rigidlab.Body
function World:add_body(options) end

---@param options rigidlab.BoxOptions
---@return rigidlab.Body
function World:add_box(options) end

---@param options rigidlab.CircleOptions
---@return rigidlab.Body
function World:add_circle(options) end

---@param options rigidlab.PolygonOptions
---@return rigidlab.Body
function World:add_polygon(options) end

---@param options rigidlab.CapsuleOptions
---@return rigidlab.Body
function World:add_capsule(options) end

---@param options rigidlab.SegmentOptions
---@return rigidlab.Body
function World:add_segment(options) end

---@param options rigidlab.ChainOptions
---@return rigidlab.Body
function World:add_chain(options) end

---@param options rigidlab.SpringOptions
---@return rigidlab.ForceHandle
function World:add_spring(options) end

---@param options rigidlab.DamperOptions
---@return rigidlab.ForceHandle
function World:add_damper(options) end

---@param options rigidlab.ForceOptions
---@return rigidlab.ForceHandle
function World:add_force(options) end

---@param options rigidlab.RevoluteOptions
---@return rigidlab.Joint
function World:add_revolute(options) end

---@param options rigidlab.PrismaticOptions
---@return rigidlab.Joint
function World:add_prismatic(options) end

---@param options rigidlab.DistanceOptions
---@return rigidlab.Joint
function World:add_distance(options) end

---@param options rigidlab.WeldOptions
---@return rigidlab.Joint
function World:add_weld(options) end

---@param options rigidlab.WheelOptions
---@return rigidlab.Joint
function World:add_wheel(options) end

---@param options rigidlab.MotorJointOptions
---@return rigidlab.Joint
function World:add_motor_joint(options) end

---@param options rigidlab.FrictionJointOptions
---@return rigidlab.Joint
function World:add_friction_joint(options) end

---@param options rigidlab.PulleyOptions
---@return rigidlab.Joint
function World:add_pulley(options) end

---@param options rigidlab.GearOptions
---@return rigidlab.Joint
function World:add_gear(options) end

---All joints.
---@return rigidlab.Joint[]
function World:joints() end

---The first joint with this name, or nil.
---@param name string
---@return rigidlab.Joint|nil
function World:find_joint(name) end

---All bodies, in creation order.
---@return rigidlab.Body[]
function World:bodies() end

---The first body with this name, or nil.
---@param name string
---@return rigidlab.Body|nil
function World:find(name) end

---Removes a body (with its shapes, joints and forces), a shape, a joint, or a force, spring or damper.
---@param what rigidlab.Body|rigidlab.Shape|rigidlab.Joint|rigidlab.ForceHandle
function World:remove(what) end

---Advances the world by dt (default world.dt). Does not call OnStep.
---@param dt? number
function World:step(dt) end

---Σ ½ m v² + ½ I ω², J
---@return number
function World:kinetic_energy() end

---The whole simulation state now (bodies, shapes, joints, forces, contacts and their warm starts,
---sleep timers, the clock, the settings), to come back to with world:restore. The scene's Lua
---variables only as SaveState returns them (called first, if defined). Kept until the scene
---closes; its memory counts against the scene's limit.
---@return rigidlab.Snapshot
function World:snapshot() end

---Puts the world back to a snapshot of this scene, bit-exactly: the steps that follow repeat the
---steps that followed the snapshot. Handles of bodies made after it are stale afterwards. Then
---calls LoadState(world, value) if defined, with the value SaveState returned (nil if none).
---@param snapshot rigidlab.Snapshot
function World:restore(snapshot) end

---Gravity (zero at the origin) plus springs, J
---@return number
function World:potential_energy() end

---The argument of OnDraw: overlays in world coordinates. Colors are {r, g, b [, a]} in 0..1; `color`
---(the outline) defaults to white, a shape is filled only when `fill` is given. `draw.screen` has the
---same functions in pixels from the window's top-left corner, y down (a HUD): positions and radii in
---pixels. Per frame at most 20 000 lines, 2 000 circles, 2 000 polygons and capsules together, 500 texts.
---@class rigidlab.Draw
---@field screen rigidlab.Draw the same functions in window pixels, y down
local Draw = {}

---@param a rigidlab.VecLike
---@param b rigidlab.VecLike
---@param color? number[]
function Draw:line(a, b, color) end

---@param center rigidlab.VecLike
---@param radius number
---@param color? number[]
---@param fill? number[]
function Draw:circle(center, radius, color, fill) end

---@param position rigidlab.VecLike
---@param text string
---@param color? number[]
function Draw:text(position, text, color) end

---3 to 256 points in order; a concave outline is filled too, one that crosses itself is drawn as its outline.
---@param points rigidlab.VecLike[]
---@param color? number[]
---@param fill? number[]
function Draw:polygon(points, color, fill) end

---@param a rigidlab.VecLike
---@param b rigidlab.VecLike
---@param radius number
---@param color? number[]
---@param fill? number[]
function Draw:capsule(a, b, radius, color, fill) end

---A mouse event in the sandbox, as OnMouse receives it.
---@class rigidlab.MouseEvent
---@field kind "press"|"release"|"move"|"wheel"
---@field button? "left"|"right"|"middle" for a press or release; nil for a move or wheel (other buttons are not passed)
---@field position rigidlab.Vec2 the cursor in world coordinates, m
---@field screen rigidlab.Vec2 the cursor in pixels from the window's top-left corner, y down
---@field shift boolean
---@field ctrl boolean
---@field alt boolean
---@field wheel? number for "wheel" only: notches turned, > 0 away from the user

---A slider or a button of the sandbox's Controls panel (scene.controls).
---@class rigidlab.ControlOptions
---@field name string required; letters, digits and underscores: world.controls.<name>
---@field kind? "slider"|"button" default "slider"
---@field min? number a slider's lowest value (required for a slider)
---@field max? number a slider's highest value, > min (required for a slider)
---@field value? number a slider's starting value, default min; also the value headless

---Scene settings; every field is optional.
---@class rigidlab.SceneSettings
---@field title? string
---@field gravity? rigidlab.VecLike default {0, -9.80665}
---@field dt? number default 1/60
---@field integrator? "euler"|"semi_implicit_euler"|"rk4"|"implicit_euler" default "rk4"
---@field solver? "auto"|"sequential_impulses"|"soft_step" default "auto": islands of fewer than 256 contact points by sequential impulses (exact impacts, rigid stacks), larger piles by the soft step (sub-stepped soft contacts, which keep them standing)
---@field impacts? "located"|"per_step" default "located": impacts of a few bodies in free flight (islands of at most 8 bodies with no touching contact, no joint, while at most 128 bodies are awake) are found and resolved at the moment of contact inside the step, so RK4 keeps its order through them; "per_step": every contact once per step, at the step's end (first order)
---@field iterations? integer sequential impulses: velocity passes per step, default 10
---@field substeps? integer soft step: sub-steps per step, 1 to 64, default 8
---@field sleeping? boolean default true: islands that stay still for 0.5 s stop being simulated
---@field exact_joints? boolean default true: jointed bodies that touch nothing are integrated with their joints (the integrator's order, joints held to round-off); false: every joint solved after the integrator by the contact solvers (first order)
---@field duration? number length of a headless run, s, default 10
---@field camera? {center?: rigidlab.VecLike, height?: number, follow?: rigidlab.Body|string} initial sandbox view, metres; follow: a body (set in PopulateWorld) or a body's name the camera keeps in view
---@field memory_limit? number MiB the scene's Lua may allocate, at most the host's cap (256 by default)
---@field expect_incidents? boolean default false: bodies frozen by the NaN firewall or a non-finite energy are expected (a headless run then still exits with 0, not 3)
---@field keys? string[] keys the scene takes from the sandbox's bindings while it runs (OnKey gets them), e.g. {"space", "r"}
---@field controls? rigidlab.ControlOptions[] sliders and buttons in the sandbox's Controls panel; kept across hot reloads; headless, sliders keep their `value`
---@field golden? string rigidlab test: name of the recorded trajectory golden/<name>.txt beside the scene that a run must reproduce (record it with rigidlab test --update)
---@field golden_every? integer rigidlab test: steps between two samples of the golden trajectory, default 10
---@field golden_tolerance? number rigidlab test: largest difference allowed in any golden value, default 0 (bit for bit)
---@field skip? string rigidlab test: why the scene is not run (reported as skipped)

---@type rigidlab.SceneSettings
scene = {}

---Required: builds the world.
---@param world rigidlab.World
function PopulateWorld(world) end

---Optional: after every step.
---@param world rigidlab.World
---@param dt number
function OnStep(world, dt) end

---Optional: at the end of a headless run; an error fails the run.
---@param world rigidlab.World
function Check(world) end

---Optional: a key pressed in the sandbox that it does not bind ("a", "b", ...), or one of scene.keys.
---@param world rigidlab.World
---@param key string
function OnKey(world, key) end

---Optional: every frame in the sandbox.
---@param draw rigidlab.Draw
---@param world rigidlab.World
function OnDraw(draw, world) end

---Optional: a mouse event in the sandbox (between steps: the world may be edited). Return true to
---consume it: the sandbox's tool then does not act on it.
---@param world rigidlab.World
---@param event rigidlab.MouseEvent
---@return boolean|nil
function OnMouse(world, event) end

---Optional: a button of scene.controls was pressed, or a slider moved, in the sandbox (between steps).
---@param world rigidlab.World
---@param name string
function OnControl(world, name) end

---A value SaveState may return: nil, booleans, numbers (integer or float, kept exactly), strings,
---plain tables of these (nested, shared, cyclic; vec2 too; keys: booleans, numbers, strings,
---handles) and body, shape, joint and force handles and the world, saved by id.
---@alias rigidlab.SavedState nil|boolean|number|string|table|rigidlab.Body|rigidlab.Shape|rigidlab.Joint|rigidlab.ForceHandle|rigidlab.World

---Optional: the scene's own state for a snapshot (world:snapshot(), --save-state, the sandbox's
---timeline): the Lua variables its hooks read. A function, coroutine or other userdata in it is an
---error naming its path (state.enemies[3].think). math.random's state cannot be saved: keep a
---generator of your own in the state instead.
---@param world rigidlab.World
---@return rigidlab.SavedState
function SaveState(world) end

---Optional: after every restore of a snapshot (world:restore, --load-state, the sandbox's rewind),
---with the value SaveState returned when it was taken (a fresh copy; its handles name the restored
---bodies, shapes and joints), or nil if the snapshot holds none.
---@param world rigidlab.World
---@param state rigidlab.SavedState
function LoadState(world, state) end

---A body's exact state at a time, for Exact(t).
---@class rigidlab.ExactState
---@field position rigidlab.VecLike
---@field velocity? rigidlab.VecLike
---@field angle? number
---@field angular_velocity? number

---Optional: the closed-form solution, keyed by body name (or body). `rigidlab accuracy` measures
---the error against it; the sandbox shows the live error.
---@param t number
---@return table<string|rigidlab.Body, rigidlab.ExactState>
function Exact(t) end

-- --- events and queries

---A contact, as event hooks, pre_solve functions, body:contacts() and world:contact_events() give it.
---@class rigidlab.Contact
---@field a rigidlab.Body|nil nil if the body was removed since
---@field b rigidlab.Body|nil
---@field shape_a rigidlab.Shape
---@field shape_b rigidlab.Shape
---@field point rigidlab.Vec2 world; the middle of the contact's points
---@field normal rigidlab.Vec2 unit, from a to b
---@field approach_speed number m/s, > 0 approaching: events at the start of the step, otherwise now
---@field normal_impulse number N·s the step applied (in pre_solve: the last step's, which the solve starts from)
---@field tangent_impulse number N·s
---@field points rigidlab.ContactPoint[] the manifold's points (one or two)
---@field friction number the contact's dynamic friction (the shapes' mix); writable in pre_solve, for that step (also sets static_friction unless that is written)
---@field static_friction number writable in pre_solve, for that step
---@field restitution number 0..1; writable in pre_solve, for that step
---@field tangent_speed number m/s, the shapes' tangent speeds added; writable in pre_solve, for that step
---@field rolling_resistance number the bound of the rolling torque per unit of normal force, m
---@field touching boolean false for an end event
---@field enabled boolean|nil in pre_solve: writing false disables the contact for the step (as returning false does)
---@field kind "begin"|"end"|"hit"|nil world:contact_events() only

---A point of a contact's manifold.
---@class rigidlab.ContactPoint
---@field point rigidlab.Vec2 world
---@field separation number m, < 0: overlap
---@field normal_impulse number N·s the step applied at this point
---@field tangent_impulse number N·s

---A hit of world:ray_cast, ray_cast_all or shape_cast.
---@class rigidlab.QueryHit
---@field body rigidlab.Body
---@field shape rigidlab.Shape
---@field point rigidlab.Vec2 world
---@field normal rigidlab.Vec2 the surface's outward unit normal there
---@field fraction number 0..1 along from → to (shape_cast: the time of impact)

---The filter every query takes.
---@class rigidlab.QueryFilterOptions
---@field category? integer default 1: found shapes have (shape.mask & category) ~= 0
---@field mask? integer default -1: found shapes have (shape.category & mask) ~= 0
---@field sensors? boolean default false: sensors are left out

---@class rigidlab.RayCastOptions: rigidlab.QueryFilterOptions
---@field from rigidlab.VecLike
---@field to rigidlab.VecLike

---@class rigidlab.QueryBoxOptions: rigidlab.QueryFilterOptions
---@field lower rigidlab.VecLike
---@field upper rigidlab.VecLike

---@class rigidlab.QueryPointOptions: rigidlab.QueryFilterOptions
---@field point rigidlab.VecLike

---A shape for queries: as body:add_shape takes it (no segment).
---@class rigidlab.QueryShape
---@field shape "circle"|"box"|"polygon"|"capsule"
---@field radius? number
---@field width? number
---@field height? number
---@field vertices? rigidlab.VecLike[]
---@field a? rigidlab.VecLike
---@field b? rigidlab.VecLike

---@class rigidlab.OverlapOptions: rigidlab.QueryFilterOptions
---@field shape rigidlab.QueryShape
---@field position? rigidlab.VecLike default {0, 0}
---@field angle? number default 0

---@class rigidlab.ShapeCastOptions: rigidlab.QueryFilterOptions
---@field shape rigidlab.QueryShape
---@field from rigidlab.VecLike where the shape starts
---@field to rigidlab.VecLike where it would end
---@field angle? number default 0

---@class rigidlab.ExplodeOptions
---@field position rigidlab.VecLike
---@field radius? number m > 0, default 1: full impulse within it
---@field falloff? number m ≥ 0, default 0: the impulse falls linearly to 0 at radius + falloff
---@field impulse? number N·s per metre of the width a shape shows to the centre, ≥ 0, default 1
---@field category? integer
---@field mask? integer

---This step's contact events (begin, end, hit), by shape pair.
---@return rigidlab.Contact[]
function World:contact_events() end

---Every touching contact now, by shape pair: a table per contact, so its cost grows with the
---contacts (a pile of 1 000 boxes: 1 000 tables and their points each call).
---@return rigidlab.Contact[]
function World:contacts() end

---The closest hit of the segment from → to, or nil.
---@param options rigidlab.RayCastOptions
---@return rigidlab.QueryHit|nil
function World:ray_cast(options) end

---Every hit of the segment, by fraction.
---@param options rigidlab.RayCastOptions
---@return rigidlab.QueryHit[]
function World:ray_cast_all(options) end

---The shapes overlapping the box.
---@param options rigidlab.QueryBoxOptions
---@return rigidlab.Shape[]
function World:query_box(options) end

---The shapes containing the point.
---@param options rigidlab.QueryPointOptions
---@return rigidlab.Shape[]
function World:query_point(options) end

---The shapes overlapping a shape placed at position, angle.
---@param options rigidlab.OverlapOptions
---@return rigidlab.Shape[]
function World:overlap(options) end

---The first shape a moving shape touches, or nil.
---@param options rigidlab.ShapeCastOptions
---@return rigidlab.QueryHit|nil
function World:shape_cast(options) end

---Pushes the dynamic bodies near position away from it; returns them.
---@param options rigidlab.ExplodeOptions
---@return rigidlab.Body[]
function World:explode(options) end

---Optional event hooks, called after every step (Scene step, not world:step()) and before OnStep,
---in this order: contact events by shape pair (OnContactBegin, OnContactEnd, OnHit), then sensor
---events by sensor and visitor, then joint breaks. The world may be edited inside them; every
---argument is made before the first hook runs.
---@param world rigidlab.World
---@param contact rigidlab.Contact
function OnContactBegin(world, contact) end

---@param world rigidlab.World
---@param contact rigidlab.Contact
function OnContactEnd(world, contact) end

---@param world rigidlab.World
---@param contact rigidlab.Contact
function OnHit(world, contact) end

---@param world rigidlab.World
---@param sensor rigidlab.Shape
---@param visitor rigidlab.Shape
function OnSensorBegin(world, sensor, visitor) end

---@param world rigidlab.World
---@param sensor rigidlab.Shape
---@param visitor rigidlab.Shape
function OnSensorEnd(world, sensor, visitor) end

---@param world rigidlab.World
---@param joint rigidlab.Joint removed by the core when it broke: kind, broken, removed and user_data are readable
function OnJointBreak(world, joint) end

---Optional collision filter, called during the step once for each pair of shapes whose boxes
---begin to overlap (and that their category, mask, group, sensors and joints let collide): false
---keeps them from colliding until their boxes part. Costs a call per new pair; the world may not
---be edited inside it.
---@param shape_a rigidlab.Shape
---@param shape_b rigidlab.Shape
---@return boolean|nil
function ShouldCollide(shape_a, shape_b) end

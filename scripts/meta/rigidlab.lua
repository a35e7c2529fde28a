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

---A rigid body. Handles are compared with ==; the same body is always the same handle.
---@class rigidlab.Body
---@field position rigidlab.Vec2 body origin in world coordinates (read/write)
---@field angle number radians, counter-clockwise (read/write)
---@field velocity rigidlab.Vec2 velocity of the centre of mass, m/s (read/write)
---@field angular_velocity number rad/s (read/write)
---@field mass number kg (read/write; keeps the shape, changes the density)
---@field static boolean static bodies have infinite mass and do not move (read/write)
---@field name string (read/write)
---@field restitution number 0..1 (read/write)
---@field friction number dynamic friction coefficient (read/write)
---@field static_friction number static friction coefficient (read/write)
---@field awake boolean false while the body sleeps (read; write true to wake it and its island)
---@field id integer 1, 2, 3, ... in creation order, never reused (read only)
---@field center rigidlab.Vec2 world centre of mass (read only)
---@field inertia number kg·m² about the centre of mass (read only)
---@field density number kg/m² (read only)
---@field shape "circle"|"polygon" (read only)
---@field radius number|nil circles only (read only)
---@field vertices rigidlab.Vec2[]|nil polygons only, body coordinates (read only)
---@field removed boolean true once world:remove(body) was called (read only)
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

---A force, spring or damper handle.
---@class rigidlab.ForceHandle
---@field kind string "spring", "damper" or "lua force"
---@field removed boolean
local ForceHandle = {}

---Removes the force (no-op if already removed or expired).
function ForceHandle:remove() end

---Options every add_* body function accepts.
---@class rigidlab.BodyOptions
---@field position? rigidlab.VecLike default {0, 0}
---@field angle? number default 0
---@field velocity? rigidlab.VecLike default {0, 0}
---@field angular_velocity? number default 0
---@field density? number kg/m², default 1 (not together with mass)
---@field mass? number kg (sets the density)
---@field restitution? number 0..1, default 0
---@field friction? number default 0.6
---@field static_friction? number default: friction
---@field static? boolean default false
---@field name? string

---@class rigidlab.BoxOptions: rigidlab.BodyOptions
---@field width number m
---@field height number m

---@class rigidlab.CircleOptions: rigidlab.BodyOptions
---@field radius number m

---@class rigidlab.PolygonOptions: rigidlab.BodyOptions
---@field vertices rigidlab.VecLike[] body coordinates; convex, 3..32 points, any winding

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
---@field time number simulated time, s (read only)
---@field step_count integer steps taken (read only)
---@field title string the scene's title (read only)
local World = {}

---@param options rigidlab.BoxOptions
---@return rigidlab.Body
function World:add_box(options) end

---@param options rigidlab.CircleOptions
---@return rigidlab.Body
function World:add_circle(options) end

---@param options rigidlab.PolygonOptions
---@return rigidlab.Body
function World:add_polygon(options) end

---@param options rigidlab.SpringOptions
---@return rigidlab.ForceHandle
function World:add_spring(options) end

---@param options rigidlab.DamperOptions
---@return rigidlab.ForceHandle
function World:add_damper(options) end

---@param options rigidlab.ForceOptions
---@return rigidlab.ForceHandle
function World:add_force(options) end

---All bodies, in creation order.
---@return rigidlab.Body[]
function World:bodies() end

---The first body with this name, or nil.
---@param name string
---@return rigidlab.Body|nil
function World:find(name) end

---Removes a body (with its forces) or a force, spring or damper.
---@param what rigidlab.Body|rigidlab.ForceHandle
function World:remove(what) end

---Advances the world by dt (default world.dt). Does not call OnStep.
---@param dt? number
function World:step(dt) end

---Σ ½ m v² + ½ I ω², J
---@return number
function World:kinetic_energy() end

---Gravity (zero at the origin) plus springs, J
---@return number
function World:potential_energy() end

---The argument of OnDraw: overlays in world coordinates. Colors are {r, g, b [, a]} in 0..1.
---@class rigidlab.Draw
local Draw = {}

---@param a rigidlab.VecLike
---@param b rigidlab.VecLike
---@param color? number[]
function Draw:line(a, b, color) end

---@param center rigidlab.VecLike
---@param radius number
---@param color? number[]
function Draw:circle(center, radius, color) end

---@param position rigidlab.VecLike
---@param text string
---@param color? number[]
function Draw:text(position, text, color) end

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
---@field duration? number length of a headless run, s, default 10
---@field camera? {center?: rigidlab.VecLike, height?: number} initial sandbox view, metres
---@field memory_limit? number MiB the scene's Lua may allocate, at most the host's cap (256 by default)
---@field expect_incidents? boolean default false: bodies frozen by the NaN firewall or a non-finite energy are expected (a headless run then still exits with 0, not 3)

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

---Optional: a key pressed in the sandbox ("space", "a", ...).
---@param world rigidlab.World
---@param key string
function OnKey(world, key) end

---Optional: every frame in the sandbox.
---@param draw rigidlab.Draw
function OnDraw(draw) end

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

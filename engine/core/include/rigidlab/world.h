// The world: owns bodies and forces and advances them in time (docs/design/thesis.md §6, Algorithm 4).
//
//   World world;                                   // defaults: WorldDef below
//   BodyDef def; def.shape = makeCircle(0.5); def.position = {0, 5};
//   BodyId ball = world.createBody(def);
//   world.step(1.0 / 60.0);
//
// The step pipeline is in engine/core/src/world.cpp (World::step).
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rigidlab/body.h"
#include "rigidlab/debug_draw.h"
#include "rigidlab/force.h"
#include "rigidlab/forces.h"
#include "rigidlab/joint.h"
#include "rigidlab/world_snapshot.h"

namespace rigidlab {

// Time integrators for the non-contact forces (docs/design/thesis.md §5; docs/design/accuracy.md §2).
enum class Integrator {
  ExplicitEuler,      // "euler":  x += h v_n,     v += h a_n           order 1, gains energy
  SemiImplicitEuler,  // "semi_implicit_euler": v += h a_n, x += h v_{n+1}   order 1, symplectic
  RungeKutta4,        // "rk4": classic four-stage Runge–Kutta, forces at every stage   order 4
  ImplicitEuler,      // "implicit_euler": springs and dampers linearised backward Euler   order 1,
                      //   stable at any stiffness, never gains energy (stiff springs)
};
std::string_view integratorName(Integrator);
std::optional<Integrator> parseIntegrator(std::string_view name);
std::string integratorNames();  // "euler, semi_implicit_euler, rk4, implicit_euler" for error messages

// How contacts are solved. Islands (bodies linked by contacts) are solved independently.
enum class ContactSolver {
  Auto,                // "auto": islands with fewer than soft_step_points contact points by
                       //   sequential impulses, larger ones (piles, pyramids) by the soft step. The
                       //   default: exact small collisions and stacks, large piles that stand.
  SequentialImpulses,  // "sequential_impulses": the thesis's solver (docs/design/thesis.md §8–10): `iterations`
                       //   passes of impulses on the velocities (contact_solver.cpp), small islands
                       //   iterated to convergence, then position correction (position_correction.cpp).
                       //   Contacts are rigid; a pile of more than about 50 rows sinks and spreads.
  SoftStep,            // "soft_step": the step is cut into `substeps` sub-steps; in each, the
                       //   step's forces add their share of velocity, the contacts are solved as
                       //   stiff damped springs that also push overlaps apart, the positions move, and
                       //   a second pass without the push removes the push's velocity; restitution
                       //   last (soft_step.cpp; E. Catto, "Solver2D", 2024, as in Box2D v3). Piles of
                       //   any size stand; contacts give slightly under load (a few mm per row).
};
std::string_view contactSolverName(ContactSolver);
std::optional<ContactSolver> parseContactSolver(std::string_view name);
std::string contactSolverNames();  // "auto, sequential_impulses, soft_step" for error messages

// How penetration left after the velocity solve is removed (docs/design/thesis.md §9; sequential impulses only).
enum class PositionCorrection {
  LinearProjection,      // "linear_projection": move both bodies apart along the normal by the
                         //   whole depth, without rotating them (the thesis's method)
  NonlinearGaussSeidel,  // "nonlinear_gauss_seidel": iterate over the contact points, moving and
                         //   rotating the bodies to remove a fraction of each point's current depth
                         //   (Box2D 2.4's position solver); steadier stacks. The default.
};
std::string_view positionCorrectionName(PositionCorrection);
std::optional<PositionCorrection> parsePositionCorrection(std::string_view name);

// How impacts are handled: two shapes that come into contact during a step (a contact touching at
// the step's start is resting or persistent contact, which the contact solver always handles).
enum class ImpactHandling {
  Located,  // "located": in the islands the rule below picks, the earliest time within the step at
            //   which a pair's gap reaches zero is found on the integrator's own dense output (RK4:
            //   the cubic Hermite interpolant), the bodies are integrated exactly to it, the impact is
            //   resolved there (Newton restitution, Coulomb friction, every touching point of the
            //   bodies at once) and the step continues from it (event_location.cpp). RK4 then keeps
            //   its order through isolated impacts. Other islands are handled once per step.
  PerStep,  // "per_step": contacts found and resolved once per step at the step's end (the thesis's
            //   scheme, docs/design/thesis.md §5): any problem with a collision is first order in dt.
};
std::string_view impactHandlingName(ImpactHandling);
std::optional<ImpactHandling> parseImpactHandling(std::string_view name);
std::string impactHandlingNames();  // "located, per_step" for error messages

// How candidate pairs are found (broad phase). Both report the same pairs in the same order.
enum class BroadPhaseKind {
  Grid,      // "grid": a uniform grid rebuilt each step, O(n); the default
  AllPairs,  // "all_pairs": the thesis's test of every pair, O(n²); fine for a few dozen bodies
};

struct WorldDef {
  Vec2 gravity = Vec2(0.0, -9.80665);          // [m/s²], docs/design/thesis.md §1
  Integrator integrator = Integrator::RungeKutta4;  // docs/design/thesis.md §5: RK4 for all ordinary forces
  ContactSolver contact_solver = ContactSolver::Auto;
  int soft_step_points = 256;                   // auto: islands with at least this many contact
                                                //   points use the soft step, ≥ 1
  int substeps = 8;                             // soft step: sub-steps per step, 1…64
  double contact_hertz = 60.0;                  // soft step: stiffness of a contact as the frequency
                                                //   of a mass on a spring [Hz] > 0; at most an eighth
                                                //   of the sub-step rate is used, twice against static
                                                //   bodies (soft_step.cpp says why)
  double contact_damping_ratio = 10.0;          // soft step: ζ of that spring, > 0 (overdamped)
  double contact_push_speed = 3.0;              // soft step: fastest push out of an overlap [m/s] > 0
  int iterations = 10;                          // sequential impulses: velocity passes, ≥ 1
  // Start each persisting contact point from last step's impulses (matched by feature id). Off
  // reproduces the thesis's solver, which starts every step from zero.
  bool warm_starting = true;
  PositionCorrection position_correction = PositionCorrection::NonlinearGaussSeidel;
  int position_iterations = 3;             // passes of the nonlinear Gauss–Seidel correction, ≥ 1
  double allowed_penetration = 0.005;      // [m] ≥ 0: overlap the correction leaves (keeps contacts
                                           //   persistent); capped at a tenth of the smaller body's size
  double position_correction_rate = 0.2;   // fraction of the remaining depth removed per pass, (0, 1]
  // Move each body by the displacement its contact impulses would have caused during the step
  // (position_correction.cpp), so friction and resting contacts hold positions, not only
  // velocities. Off reproduces the thesis, where held bodies creep by their gravity travel.
  bool contact_displacement = true;
  BroadPhaseKind broad_phase = BroadPhaseKind::Grid;
  // Bound on the contact pipeline, checked inside the broad phase (broad_phase.cpp): a step stops
  // as soon as it has found more than min(pair_cap_max, max(pair_cap, pair_cap_per_body × bodies))
  // candidate pairs, or made 64 times that many box tests, and throws InputError saying how many
  // bodies crowd where; the world is left as it was before the step. Memory and time of a step
  // are then linear in the number of bodies and bounded whatever their number (a pair costs
  // about 700 bytes through the pipeline: at most ~0.7 GB). Piles have about 3 pairs per body
  // (pyramid of 5050 boxes: 2.96, rain of 4000 circles: 2.4), so the cap stops only bodies heaped
  // on each other, whose pairs grow as n²/2 (3000 circles at one point: 4.5 million pairs, 3.2 GB
  // for one step).
  size_t pair_cap = 100000;       // ≥ 1
  int pair_cap_per_body = 32;     // ≥ 1
  size_t pair_cap_max = 1000000;  // ≥ pair_cap
  // Impacts (ImpactHandling above). With Located, an island (dynamic bodies linked by last step's
  // contacts, joints and two-body forces) gets located impacts when it has at most
  // impact_island_bodies bodies, no joint, and no contact point touching (separation ≤ 1e-9 m) at
  // the step's start: a few bodies in free flight. Stacks, piles and resting bodies (touching
  // contacts) and jointed islands are handled once per step; so is every island while more than
  // impact_max_bodies dynamic bodies are awake, which keeps large scenes (a rain of 1000 discs)
  // exactly as fast as before. Measured and explained in docs/physics.md "Impacts: located or once per step".
  ImpactHandling impacts = ImpactHandling::Located;
  int impact_island_bodies = 8;   // ≥ 1
  int impact_max_bodies = 128;    // ≥ 0
  // Continuous collision detection of fast bodies against static ones (continuous.cpp): a body
  // that moves more than half its inner radius in a step is stopped at the first static body on
  // its way instead of tunnelling through it.
  bool continuous = true;
  // Sleeping: an island of touching (or spring-linked) bodies whose speeds all stay below these for
  // time_to_sleep stops being simulated until something touches, pushes or edits it.
  bool sleeping = true;
  double sleep_linear_speed = 0.01;        // [m/s] ≥ 0
  double sleep_angular_speed = 0.0349;     // [rad/s] ≥ 0 (2°/s)
  double time_to_sleep = 0.5;              // [s] ≥ 0
  // Speculative contact distance: pairs closer than this get contact points before they touch, and
  // the solver lets them close at most the gap in the next step (v_n ≥ −gap / h). Keeps resting
  // contacts from flickering on and off at zero separation. [m] ≥ 0
  double contact_margin = 0.02;
  // Restitution applies only to contacts approaching faster than this, so resting contacts do not
  // bounce on the g·dt of every step (0.16 m/s at 60 Hz). [m/s] ≥ 0
  double restitution_threshold = 0.5;
  // Threads a step runs on, the caller included: 0 takes the machine's cores
  // (std::thread::hardware_concurrency), 1 runs everything in the caller; 0…64. The narrow phase's
  // manifolds and the soft step's passes are then split across them (worker threads owned by the
  // world, started by its first step that has enough work); results are bit-identical whatever the
  // count (docs/physics.md "Threads"). Not simulation state: snapshots neither save nor restore it.
  // Default 1: on a shared 2-core machine two threads were slower than one in most measured rounds.
  int threads = 1;
  // Joints' rigid constraints in the soft step: the frequency and damping ratio of the soft bias that
  // removes their position error (at most a quarter of the sub-step rate is used). [Hz] > 0, ≥ 0
  double joint_hertz = 120.0;
  double joint_damping_ratio = 1.0;
  // Islands of jointed bodies that touch nothing (pendulums, linkages, chains, ragdolls in flight)
  // are integrated with their joints: the joints' forces solved exactly at every stage of the
  // integrator and the bodies projected back onto the joints after each step, so the integrator
  // keeps its order and every joint holds to round-off (docs/integrators.md "Joints inside the
  // integrator"; which joints and islands in docs/physics.md). Off: every joint is solved by the
  // contact solvers after the integrator (first order), as before.
  bool exact_joints = true;
  // Static friction (f_s) is used when the tangential speed at the start of the step is below this,
  // dynamic friction (f_d) otherwise (docs/design/thesis.md §10, the "small ε"). [m/s] ≥ 0
  double static_friction_speed = 0.01;
};

// One contact manifold, for drawing and tests. Points are world coordinates; separation < 0 means
// overlap; impulses are what the last step applied at each point [N·s] (the soft step's sum over its
// sub-steps, restitution included).
struct ContactInfo {
  BodyId a, b;
  ShapeId shape_a, shape_b;
  Vec2 normal = Vec2::Zero();  // unit, from a to b
  int count = 0;
  Vec2 points[2] = {Vec2::Zero(), Vec2::Zero()};
  double separations[2] = {0, 0};
  double normal_impulses[2] = {0, 0};
  double tangent_impulses[2] = {0, 0};
  uint32_t ids[2] = {0, 0};  // feature ids, stable while the same features touch
  bool touching = false;     // a point overlapped at some step since the contact began (not only speculative)
  // The contact's surface this step: the shapes' combined values (shape.h Material, ShapeDef), or
  // what the pre-solve callback made of them. The callback may change friction (dynamic),
  // static_friction, restitution and tangent_speed for this step only.
  double friction = 0.0, static_friction = 0.0, restitution = 0.0;
  double tangent_speed = 0.0;       // [m/s], the sum of the shapes' (ShapeDef::tangent_speed)
  double rolling_resistance = 0.0;  // [m]: the coefficient times the larger radius (ShapeDef)
};

// What went wrong in a step: a body frozen by the NaN firewall, or a blow-up (energy grown beyond what
// the scene's sources can put in, docs/stability.md); which body, when, and why.
struct Incident {
  uint32_t uid = 0;       // Body::uid
  std::string name;       // the body's name
  long step = 0;          // World::stepCount() of the step in which it happened (1-based)
  double time = 0.0;      // simulation time at the start of that step [s]
  std::string cause;      // e.g. "spring returned a non-finite force" or "state became non-finite in ..."
  bool frozen = true;     // false: a blow-up, the body left as it is
  std::string message() const;  // "body 3 'ball' frozen at step 120 (t = 2 s): <cause>", or "blew up at"
};

// Wall-clock cost and counts of the last step, per stage.
struct StepStats {
  double integrate_ms = 0, broad_phase_ms = 0, narrow_phase_ms = 0, solve_ms = 0, correct_ms = 0,
         finish_ms = 0;
  double forces_ms = 0;     // part of integrate_ms spent in Force::evaluate
  int bodies = 0, dynamic_bodies = 0, awake_bodies = 0, forces = 0;
  int pairs = 0, contacts = 0, contact_points = 0, joints = 0;
  long force_evaluations = 0;  // calls of Force::evaluate in this step
  int ccd_sweeps = 0, ccd_hits = 0;  // fast bodies swept against static ones, and those stopped
  int impact_bodies = 0;     // bodies whose impacts were located this step (ImpactHandling::Located)
  int impacts_located = 0;   // located impacts resolved in this step
  int impact_searches = 0;   // gap evaluations of the located impacts' root search
  bool pairs_reused = false;  // the broad phase filtered the kept pair list instead of rebuilding
  int rk4_handovers = 0;  // intervals RK4 left to semi-implicit Euler: a damper too stiff for it
  int joint_position_passes = 0;  // Gauss–Seidel passes of the joints' position correction (sequential impulses)
  int joint_newton_steps = 0;     // Newton steps of the joints' direct position solve (sequential impulses)
  int exact_joints = 0;           // joints integrated exactly this step (WorldDef::exact_joints), also in `joints`
  int mechanism_newton = 0;       // Newton iterations of their projections onto the joints
  int mechanism_retries = 0;      // intervals integrated again in more steps: a step drifted too far off the joints
  double mechanism_residual = 0;  // largest joint error their projections left [m or rad]
  double total_ms() const { return integrate_ms + broad_phase_ms + narrow_phase_ms + solve_ms + correct_ms + finish_ms; }
};

struct DrawOptions {
  bool shapes = true, springs = true, forces = true;
  // Joints: anchors, the lines from the bodies' centres to them, prismatic and wheel axes,
  // revolute and axis limits, distance joints as a line, rope or spring, pulley ropes.
  bool joints = true;
  bool contacts = false, normals = false, impulses = false, aabbs = false, centers = false, velocities = false;
  BodyId selected;
  // If not empty: the transform to draw for each body slot (indexed by BodyId::index), e.g.
  // interpolated between the last two steps by the sandbox's fixed-step loop.
  std::span<const Transform> transforms;
};

// Queries (World::rayCast, ...): a shape is found when it passes the query's filter:
// (shape.category & filter.mask) != 0 and (filter.category & shape.mask) != 0. Sensors are left out
// unless `sensors` is set.
struct QueryFilter {
  uint64_t category = 1;
  uint64_t mask = ~uint64_t{0};
  bool sensors = false;
};
struct RayHit {
  ShapeId shape;
  BodyId body;
  Vec2 point = Vec2::Zero();   // world [m]
  Vec2 normal = Vec2::Zero();  // the surface's outward unit normal at the point
  double fraction = 0.0;       // along from → to, 0 … 1
};
// An explosion at `position` (Box2D 3.1's b2World_Explode): every dynamic body's shapes within
// radius + falloff get an impulse away from the centre at their closest point, of
//   impulse · (the width they show to the centre) · scale,  scale 1 within `radius`, falling
//   linearly to 0 at radius + falloff
// (`impulse` per metre of width [N·s/m]). Returns the bodies pushed, each once, in slot order.
struct ExplosionDef {
  Vec2 position = Vec2::Zero();
  double radius = 1.0;   // [m] > 0
  double falloff = 0.0;  // [m] ≥ 0
  double impulse = 1.0;  // [N·s/m] ≥ 0
  QueryFilter filter;
};

struct WorldImpl;

class World {
 public:
  explicit World(const WorldDef& def = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  // --- settings (validated; InputError on a bad value)
  const WorldDef& settings() const;
  void setGravity(const Vec2& g);
  void setIntegrator(Integrator integrator);
  void setContactSolver(ContactSolver solver);
  void setSubsteps(int substeps);
  void setIterations(int iterations);
  void setExactJoints(bool on);  // WorldDef::exact_joints
  void setWarmStarting(bool on);
  void setContactDisplacement(bool on);
  void setPositionCorrection(PositionCorrection pc);
  void setPositionIterations(int iterations);
  void setRestitutionThreshold(double speed);
  void setStaticFrictionSpeed(double speed);
  void setContactMargin(double distance);
  void setBroadPhase(BroadPhaseKind kind);
  void setSleeping(bool on);  // off wakes every body
  void setContinuous(bool on);
  void setImpacts(ImpactHandling impacts);
  void setThreads(int threads);  // WorldDef::threads: 0 (the machine's cores) … 64

  // --- bodies
  BodyId createBody(const BodyDef& def);  // InputError names the bad field and value
  void destroyBody(BodyId id);            // also removes its shapes and the forces attached to it
  bool isValid(BodyId id) const;
  const Body& body(BodyId id) const;      // InputError("body", ...) for a stale handle
  std::vector<BodyId> bodyIds() const;    // live bodies in creation order
  int bodyCount() const;
  std::optional<BodyId> findBody(std::string_view name) const;  // first body with this name
  std::optional<BodyId> findBody(uint32_t uid) const;

  void setTransform(BodyId id, const Vec2& position, double angle);
  // Static bodies cannot move: a velocity other than zero is refused (InputError "velocity"); a
  // kinematic body moves by it.
  void setVelocity(BodyId id, const Vec2& velocity);
  void setAngularVelocity(BodyId id, double angular_velocity);
  // Static bodies have their velocity zeroed. A body with a segment or chain shape cannot be dynamic.
  void setType(BodyId id, BodyType type);
  void setMass(BodyId id, double mass);    // keeps the shapes and their relative densities
  void setMaterial(BodyId id, const Material& material);  // of every shape of the body
  void setName(BodyId id, std::string name);
  void setLinearDamping(BodyId id, double damping);   // [1/s] ≥ 0, BodyDef::linear_damping
  void setAngularDamping(BodyId id, double damping);  // [1/s] ≥ 0
  void setGravityScale(BodyId id, double scale);      // finite
  void setFixedRotation(BodyId id, bool on);          // on also stops its rotation
  void setBullet(BodyId id, bool on);
  void setEnabled(BodyId id, bool on);                // BodyDef::enabled
  // Kinematic bodies: sets the velocity that takes the body from where it is to `position`, `angle`
  // in `time` [s] > 0 (b2Body_SetTargetTransform): v = Δc / t, ω = Δθ / t, with the centre of mass
  // moved as the origin moves to `position`. The body keeps that velocity until changed.
  void setTarget(BodyId id, const Vec2& position, double angle, double time);
  // Instant change of momentum by the impulse J at a world point (docs/design/thesis.md §1, J = Δp).
  void applyImpulse(BodyId id, const Vec2& impulse, const Vec2& world_point);
  // Instant change of angular momentum: Δω = j / I [N·m·s].
  void applyAngularImpulse(BodyId id, double impulse);
  // BodyDef::gravity: the body's own gravity, or nullopt for the world's.
  void setBodyGravity(BodyId id, std::optional<Vec2> gravity);
  void setSleepingAllowed(BodyId id, bool on);  // BodyDef::sleeping_allowed; off wakes the body
  // The moment of inertia about the centre of mass [kg·m²] > 0, in place of the shapes' (the mass
  // and centre stay). Kept until the shapes or their densities change (or resetMass).
  void setInertia(BodyId id, double inertia);
  void resetMass(BodyId id);  // mass, centre and inertia from the shapes again
  // Wakes a sleeping body and the bodies of its island. Every edit above wakes its body too.
  void wake(BodyId id);

  // --- shapes. A body's mass, centre of mass and inertia are the sums over its shapes; adding or
  // removing a shape recomputes them (the body's origin stays where it is).
  ShapeId createShape(BodyId body, const ShapeDef& def);  // InputError names the bad field
  void destroyShape(ShapeId id);
  bool isValid(ShapeId id) const;
  const BodyShape& shape(ShapeId id) const;  // InputError("shape", ...) for a stale handle
  void setShapeMaterial(ShapeId id, const Material& material);
  void setShapeFilter(ShapeId id, const Filter& filter);
  void setShapeDensity(ShapeId id, double density);  // recomputes the body's mass
  void setShapeSensor(ShapeId id, bool sensor);
  // setShapeSensor for every shape of the body, with one mass update (linear in the shapes; one
  // call per shape costs their square: a 65 536-segment chain took 36 s).
  void setBodySensor(BodyId id, bool sensor);
  void setShapeEvents(ShapeId id, bool contact_events, bool hit_events, double hit_speed);  // ShapeDef
  void setShapeOneWay(ShapeId id, std::optional<Vec2> normal);  // ShapeDef::one_way
  void setShapePreSolve(ShapeId id, bool on);
  // ShapeDef::tangent_speed (finite) and rolling_resistance (≥ 0); wakes what touches the shape.
  void setShapeSurface(ShapeId id, double tangent_speed, double rolling_resistance);
  // New geometry for the shape, of the same kind (body coordinates, validated as createShape
  // does): the body's mass is computed again and what touches it wakes.
  void setShapeGeometry(ShapeId id, const Shape& geometry);
  // The shape alone: the first point where the segment from → to enters it (a ray starting inside
  // does not hit it; a chain segment is hit from its front only).
  std::optional<RayHit> shapeRayCast(ShapeId id, const Vec2& from, const Vec2& to) const;
  // Distance between two shapes' surfaces (0 when they overlap) and the closest points on each.
  double distanceBetween(ShapeId a, ShapeId b, Vec2* on_a = nullptr, Vec2* on_b = nullptr) const;
  // A chain on a static body (docs/physics.md "Chains"): one chain segment per pair of consecutive
  // points, each knowing its neighbours so that bodies slide over the joints without catching.
  // One-sided: the surface faces the right of the direction from a point to the next, so ground
  // is listed from right to left and a counter-clockwise loop is solid inside. An open chain needs
  // at least 2 points, a loop 3.
  struct ChainDef {
    std::vector<Vec2> points;  // body coordinates
    bool loop = false;
    Material material;
    Filter filter;
    bool sensor = false;  // every segment a sensor
  };
  // Linear in the number of points.
  std::vector<ShapeId> createChain(BodyId body, const ChainDef& def);

  // --- joints (joint.h). A joint is removed with either of its bodies (and a gear with either of
  // its joints); a broken one is removed at the end of the step in which it broke.
  JointId createJoint(const JointDef& def);  // InputError names the bad field and value
  void destroyJoint(JointId id);
  bool isValid(JointId id) const;
  // The joint's definition: anchors and axis in world coordinates at creation, the rest as set.
  const JointDef& joint(JointId id) const;
  // Changes what may change after creation: limits, motor, spring, offsets, forces, break
  // thresholds, name, collide_connected (not the type, bodies, anchors or axis).
  void updateJoint(JointId id, const JointDef& def);
  JointState jointState(JointId id) const;
  std::vector<JointId> jointIds() const;  // live joints in creation order of their slots
  std::optional<JointId> findJoint(std::string_view name) const;
  std::vector<JointId> jointsOf(BodyId body) const;
  // The joints that broke in the last step: their definitions and the force and torque that broke them.
  struct JointBreakInfo {
    JointId id;
    JointDef def;
    Vec2 force = Vec2::Zero();
    double torque = 0.0;
  };
  std::vector<JointBreakInfo> jointBreaks() const;

  // --- forces. `duration` [s]: the force acts for that much simulated time from now and is removed
  // at the end of the step in which it runs out (docs/design/thesis.md §6); infinity = permanent. A step that
  // straddles the end is split there, so the force acts for exactly `duration`. kNextStep: the
  // force acts during the next step only, whatever its length.
  static constexpr double kForever = std::numeric_limits<double>::infinity();
  static constexpr double kNextStep = 0.0;
  ForceId addForce(std::unique_ptr<Force> force, BodyId a, BodyId b = {}, double duration = kForever);
  ForceId addSpring(const SpringDef& def, double duration = kForever);
  ForceId addDamper(const DamperDef& def, double duration = kForever);
  void removeForce(ForceId id);
  bool isValid(ForceId id) const;
  Force& force(ForceId id);
  const Force& force(ForceId id) const;
  BodyId forceBodyA(ForceId id) const;
  BodyId forceBodyB(ForceId id) const;
  double forceTimeLeft(ForceId id) const;  // [s], infinity for permanent forces
  std::vector<ForceId> forceIds() const;   // live forces in creation order
  // State of a body as forces see it.
  BodyState bodyState(BodyId id) const;

  // --- simulation
  // Advances by dt [s] > 0: integrate → find pairs → narrow phase → solve contacts → correct
  // positions → expire forces. Edits requested while a step runs (from inside a force) throw.
  // If a force throws (e.g. a script error) or the broad phase reaches its cap (WorldDef::pair_cap),
  // the bodies are restored to their state before the step and the exception propagates: the
  // world is as if the step had not been called.
  void step(double dt);
  bool isStepping() const;         // true while step() runs (inside a force): edits are refused
  double time() const;             // simulated time [s]
  long stepCount() const;
  const StepStats& stats() const;  // of the last step
  // Bodies the NaN firewall froze so far, oldest first (World::step: a body whose state becomes
  // non-finite is put back where the step began and made static, and reported here).
  const std::vector<Incident>& incidents() const;

  // Energies [J] (docs/design/thesis.md §12 experiment 2): kinetic Σ ½ m v² + ½ I ω²; potential of gravity
  // −m g·c (zero at the world origin) plus what the forces store (springs ½ k x²).
  double kineticEnergy() const;
  double potentialEnergy() const;
  double gravityPotentialEnergy() const;

  // Topmost body with a shape that contains the world point (docs/design/thesis.md §7 point-in-shape), for picking.
  std::optional<BodyId> bodyAt(const Vec2& point) const;

  // --- queries (world_query.cpp): exact on every shape kind, served by a bounding-volume tree kept
  // between calls (built on the first query). Disabled bodies are never found.
  // The closest hit of the segment from → to (a ray starting inside a shape does not hit it; a chain
  // is hit from its front side only).
  std::optional<RayHit> rayCast(const Vec2& from, const Vec2& to, const QueryFilter& filter = {}) const;
  std::vector<RayHit> rayCastAll(const Vec2& from, const Vec2& to, const QueryFilter& filter = {}) const;  // by fraction
  std::vector<ShapeId> queryBox(const Aabb& box, const QueryFilter& filter = {}) const;  // shapes overlapping it
  std::vector<ShapeId> queryPoint(const Vec2& point, const QueryFilter& filter = {}) const;  // shapes containing it
  // Shapes overlapping `shape` placed by `xf` (circle, box, polygon, capsule).
  std::vector<ShapeId> overlap(const Shape& shape, const Transform& xf, const QueryFilter& filter = {}) const;
  // `shape` placed by `xf` moved by `translation`: the first shape it touches, at which fraction.
  std::optional<RayHit> shapeCast(const Shape& shape, const Transform& xf, const Vec2& translation,
                                  const QueryFilter& filter = {}) const;
  // An explosion at `position` (ExplosionDef above); returns the bodies pushed, each once, in slot order.
  std::vector<BodyId> explode(const ExplosionDef& def);
  std::vector<ContactInfo> contacts() const;  // manifolds of the last step
  std::vector<ContactInfo> touchingContacts() const;  // those touching (ContactInfo::touching)
  std::vector<ContactInfo> contactsOf(BodyId body) const;  // its touching contacts (separation ≤ 0 at some point since they began)

  // --- events of the last step (contact_events.cpp, sensor.cpp), in a deterministic order (by
  // shape pair; sensors by sensor, then visitor). Contact events are kept for shapes flagged with
  // contact_events / hit_events, or for every contact after setContactEvents(true); nothing is kept
  // (or computed) otherwise.
  struct ContactEvent {
    enum class Kind : uint8_t { Begin, End, Hit };
    Kind kind = Kind::Begin;
    ShapeId shape_a, shape_b;
    BodyId a, b;
    Vec2 normal = Vec2::Zero();  // unit, from a to b
    int count = 0;
    Vec2 points[2] = {Vec2::Zero(), Vec2::Zero()};
    Vec2 point = Vec2::Zero();   // the points' middle
    double separations[2] = {0, 0};  // of each point [m] (< 0: overlap)
    // The contact's surface: as ContactInfo's, of the step (a pre-solve callback's changes included).
    double friction = 0.0, static_friction = 0.0, restitution = 0.0, tangent_speed = 0.0, rolling_resistance = 0.0;
    // Begin and hit: each point's normal and tangent impulses from the contact solver [N·s]; an
    // impact located inside the step adds its impulse to the totals below only.
    double normal_impulses[2] = {0, 0}, tangent_impulses[2] = {0, 0};
    // Begin and hit: the closing speed along the normal at the start of the step [m/s] (> 0:
    // approaching); for a bounce located inside the step (ImpactHandling::Located), whose begin, hit
    // and end come together, the closing speed at the impact.
    double approach_speed = 0.0;
    // Begin and hit: the normal and tangent impulse the step applied in all [N·s] (a located
    // bounce's: the impact's).
    double normal_impulse = 0.0, tangent_impulse = 0.0;
  };
  const std::vector<ContactEvent>& contactEvents() const;
  // The impacts located inside the last step (ImpactHandling::Located), in the order they were
  // resolved (by time; simultaneous ones by shape pair).
  struct Impact {
    ShapeId shape_a, shape_b;
    BodyId a, b;
    double time = 0.0;           // simulation time of the impact [s]
    Vec2 normal = Vec2::Zero();  // unit, from a to b
    int count = 0;               // contact points
    Vec2 points[2] = {Vec2::Zero(), Vec2::Zero()};
    double approach_speed = 0.0;   // closing speed along the normal just before it [m/s]
    double normal_impulse = 0.0, tangent_impulse = 0.0;  // [N·s]
    bool separating = false;     // the shapes part after it (a bounce), else they stay in contact
  };
  std::vector<Impact> impacts() const;
  void setContactEvents(bool every_contact);
  struct SensorEvent {
    bool begin = true;  // false: end
    ShapeId sensor, visitor;
    BodyId sensor_body, visitor_body;
  };
  const std::vector<SensorEvent>& sensorEvents() const;
  std::vector<ShapeId> sensorOverlaps(ShapeId sensor) const;  // the shapes in it now (sorted by slot)
  // Pre-solve: called during the step, after the contacts are found and before they are solved, for
  // every contact of a shape flagged pre_solve; returning false disables the contact for this step.
  // It must not edit the world. An exception it throws undoes the step and propagates.
  // The callback may change the contact's friction, static_friction, restitution and
  // tangent_speed for this step (ContactInfo).
  using PreSolveFn = std::function<bool(ContactInfo&)>;
  void setPreSolve(PreSolveFn callback);
  // Collision filter (broad_phase.cpp): called once for each pair of shapes whose boxes begin to
  // overlap and that the filters (Filter, sensors, joints) let collide; false keeps the pair from
  // colliding until their boxes part. Kept with the world through snapshots, like pre-solve; the
  // decisions of the pairs overlapping now are part of the state. Nullptr: none (the default).
  using ShouldCollideFn = std::function<bool(ShapeId, ShapeId)>;
  void setShouldCollide(ShouldCollideFn callback);
  void draw(DebugDraw& dd, const DrawOptions& options = {}) const;

  // --- snapshots (world_snapshot.h): the whole state, to come back to bit-exactly. Not allowed
  // while stepping. restore() throws SnapshotError, leaving the world as it was, for an empty
  // snapshot or one from a file naming a force (by id and kind) this world does not have.
  WorldSnapshot snapshot() const;
  void restore(const WorldSnapshot& snapshot);

 private:
  std::unique_ptr<WorldImpl> impl_;
};

}  // namespace rigidlab

// Internal state of a World, shared by the step stages (one file per stage). Not installed: user
// code sees only world.h. Tests may include it (white-box).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <memory>
#include <vector>

#include "energy_watch.h"
#include "aabb_tree.h"
#include "broad_phase.h"
#include "contact.h"
#include "impact.h"
#include "joint.h"
#include "contact_exact.h"
#include "joint_direct.h"
#include "task_pool.h"
#include "manifold.h"
#include "rigidlab/error.h"
#include "rigidlab/world.h"

namespace rigidlab {

struct ForceEntry {
  // Shared, so that a copy of the world (World::snapshot) can keep a force it cannot clone (a
  // script's, Force::clone) as the same object; forces it can clone are copied (world_snapshot.cpp).
  std::shared_ptr<Force> force;
  BodyId a, b;
  double expires_at = World::kForever;  // simulation time at which the force stops acting [s]
  bool next_step_only = false;          // World::kNextStep: removed after the next step
  uint32_t generation = 0;
  bool alive = false;
};

// Kahan-compensated clock: after a million steps of 1/60 s the time is still the nearest double
// to N/60, so "run until t = T" loops and trace timestamps do not drift.
struct SimClock {
  double t = 0.0;
  double carry = 0.0;
  void advance(double dt) {
    const double y = dt - carry;
    const double s = t + y;
    carry = (s - t) - y;
    t = s;
  }
};

// The broad phase object holds only scratch rebuilt every step (broad_phase.h), so a copy of the
// world (World::snapshot) gets a fresh object of the same kind; WorldImpl stays copyable.
struct BroadPhaseHolder {
  std::unique_ptr<BroadPhase> p;
  BroadPhaseHolder() = default;
  BroadPhaseHolder(const BroadPhaseHolder& o) { *this = o; }
  BroadPhaseHolder(BroadPhaseHolder&&) noexcept = default;
  BroadPhaseHolder& operator=(const BroadPhaseHolder& o) {
    if (this == &o) return *this;
    if (!o.p) p.reset();
    else if (dynamic_cast<const AllPairsBroadPhase*>(o.p.get())) p = std::make_unique<AllPairsBroadPhase>();
    else p = std::make_unique<GridBroadPhase>();
    return *this;
  }
  BroadPhaseHolder& operator=(BroadPhaseHolder&&) noexcept = default;
  BroadPhaseHolder& operator=(std::unique_ptr<BroadPhase> q) {
    p = std::move(q);
    return *this;
  }
  BroadPhase* operator->() const { return p.get(); }
  explicit operator bool() const { return p != nullptr; }
};

// A flag that a copy of the world does not inherit (World::snapshot copies WorldImpl): what it
// vouches for points into the original's vectors.
struct UncopiedFlag {
  bool value = false;
  UncopiedFlag() = default;
  UncopiedFlag(const UncopiedFlag&) {}
  UncopiedFlag& operator=(const UncopiedFlag&) {
    value = false;
    return *this;
  }
};

// Scratch that one stage owns: its type is declared in that stage's own file, so the other stages
// cannot reach into it; it is made by the stage's first use, and a copy of the world
// (World::snapshot) starts without one (scratch is never simulation state).
template <typename T>
class StageScratch {
 public:
  StageScratch() = default;
  StageScratch(const StageScratch&) {}
  StageScratch& operator=(const StageScratch&) {
    p_.reset();
    return *this;
  }
  StageScratch(StageScratch&&) noexcept = default;
  StageScratch& operator=(StageScratch&&) noexcept = default;
  T& get() {
    if (!p_) p_ = std::make_shared<T>();
    return *p_;
  }
  T* find() const { return p_.get(); }

 private:
  std::shared_ptr<T> p_;  // shared_ptr: destroyed where T is not known
};

struct MechanismStage;   // mechanism_step.cpp
struct SoftStepScratch;  // soft_step.cpp
struct ContactSolverScratch;  // contact_solver.cpp
struct IntegratorScratch;     // integrator.cpp
struct ImplicitScratch;       // implicit_solve.cpp
struct PositionCorrectionScratch;  // position_correction.cpp

struct WorldImpl {
  WorldDef def;
  // The worker threads WorldDef::threads asks for (task_pool.h): made by the first step that uses
  // them, never copied with the world.
  TaskPoolHolder pool;
  TaskPool* taskPool();  // world.cpp: the pool for def.threads, or nullptr for one thread

  // Bodies by slot (BodyId::index). Destroyed slots are reused, most recent first.
  std::vector<Body> bodies;
  std::vector<char> alive;
  std::vector<uint32_t> free_bodies;
  // Shapes by slot (ShapeId::index), reused the same way: a world of one-shape bodies has each
  // shape in its body's slot. The broad phase, the pairs and the contacts are per shape.
  std::vector<BodyShape> shapes;
  std::vector<char> shape_alive;
  std::vector<uint32_t> free_shapes;
  uint32_t chains = 0;  // chains made so far (BodyShape::chain)

  std::vector<ForceEntry> forces;
  std::vector<uint32_t> free_forces;

  // Joints by slot (JointId::index), reused like bodies. Each body slot lists its joints.
  std::vector<Joint> joints;
  std::vector<uint32_t> free_joints;
  std::vector<std::vector<uint32_t>> body_joints;  // per body slot: joint slots
  std::vector<uint32_t> si_joints, soft_joints;    // this step's, by solver (contact_solver.cpp)
  std::vector<char> joint_displaced;               // per slot: scratch of joint_solver.cpp
  struct JointRotation {  // an angle and its sine and cosine
    double angle, s, c;
  };
  std::vector<JointRotation> joint_rotation;       // per slot: the last rotation a joint view took (joint_solver.cpp)
  struct JointBreak {  // a joint that broke in the last step (removed at its end)
    JointId id;
    JointDef def;
    Vec2 force = Vec2::Zero();
    double torque = 0.0;
  };
  std::vector<JointBreak> joint_breaks;
  // Do the bodies in slots a and b share a joint that keeps them from colliding?
  bool jointBlocksCollision(uint32_t a, uint32_t b) const;

  SimClock clock;
  // The last step's dt [s]. No stage reads it (they read StepContext::dt, step_context.h); it is
  // kept only because the saved-world format has carried it since version 1 (snapshot_format.cpp),
  // so files stay byte for byte what they were.
  double last_dt = 0.0;
  long step_count = 0;
  // Per body slot: step_count + 1 if the body was created asleep (BodyDef::awake = false) since the
  // last step, else older. Shapes added to such a body before it is stepped do not wake it: the
  // caller said it starts at rest, as Box2D does (createShape).
  std::vector<long> created_asleep_before;
  uint32_t next_uid = 1;
  bool locked = false;  // true while step() runs
  StepStats stats;
  std::vector<Incident> incidents;  // NaN firewall reports (nan_guard.cpp), blow-ups (energy_watch.cpp)
  EnergyWatch energy;               // the energy balance of each step (energy_watch.h)
  uint64_t joint_edits = 0;         // joints created, destroyed, updated; bodies retyped or destroyed
  double kineticEnergy() const;     // World::kineticEnergy, potentialEnergy (world.cpp)
  double potentialEnergy() const;
  double gravityPotentialEnergy() const;
  double forcePotentialEnergy() const;  // what forces store (springs)

  // Scratch reused by every step, so a step in steady state allocates nothing.
  std::vector<BodyState> states;      // per slot: state seen by forces
  std::vector<Wrench> wrenches;       // per slot: force accumulator
  std::vector<Wrench> const_wrenches; // per slot: state-independent forces, once per interval
  std::vector<Vec2> start_velocity;   // per slot: velocity at the start of the step (friction choice)
  std::vector<double> start_angular_velocity;
  std::vector<Vec2> start_center;     // per slot: state at the start of the step, to undo a failed step
  std::vector<double> start_angle;
  std::vector<double> breakpoints;    // force expiry times inside the current step
  StageScratch<IntegratorScratch> integrator;  // RK4's stage sums, the dampers' rates (integrator.cpp)
  std::vector<int32_t> force_fault;   // per slot: index of a force that returned a non-finite value, or −1
  StageScratch<ImplicitScratch> implicit;  // the linearly implicit solve's system (implicit_solve.cpp)
  ImpactScratch impact;  // located impacts (impact.h)
  StageScratch<MechanismStage> mechanisms;  // exact mechanisms (mechanism_step.cpp)

  StageScratch<ContactSolverScratch> contact_solver;  // the contact solver's working copies (contact_solver.cpp)
  // Per entry of `solved`: the contact prepared for the solve (contact_solver.cpp), which position
  // correction reads after it (the points fixed to their bodies, the overlap time): passed from one
  // stage to the next within a step, so not one stage's scratch.
  std::vector<SolverPrepared> solver_prepared;
  StageScratch<SoftStepScratch> soft_step;  // the soft step's (soft_step.cpp)
  std::vector<Vec2> solve_start_velocity;  // per slot: velocity before the contact solve
  std::vector<double> solve_start_angular_velocity;
  StageScratch<PositionCorrectionScratch> position_correction;  // position_correction.cpp
  // Kinematic bodies' velocity changes between steps (integrator.cpp moveKinematicBodies), which the
  // contact displacement of what they carry takes as impulsive (position_correction.cpp).
  std::vector<Vec2> kinematic_velocity;          // per slot: the velocity it moved with this step
  std::vector<double> kinematic_angular_velocity;
  std::vector<uint32_t> kinematic_uid;           // per slot: the body those are of (0: none yet)
  std::vector<Vec2> kinematic_jump;              // per slot: velocity now minus the previous step's
  std::vector<double> kinematic_angular_jump;
  bool kinematic_jumped = false;                 // some kinematic body's velocity changed this step
  // Alive kinematic bodies (createBody, setType, destroyBody), and whether moveKinematicBodies
  // recorded one last step: without either, it has nothing to move or forget and makes no pass.
  uint32_t kinematic_bodies = 0;
  bool kinematic_recorded = false;
  void countKinematicBodies() {
    kinematic_bodies = 0;
    for (size_t i = 0; i < bodies.size(); ++i) kinematic_bodies += alive[i] && bodies[i].isKinematic();
    kinematic_recorded = std::any_of(kinematic_uid.begin(), kinematic_uid.end(), [](uint32_t u) { return u != 0; });
  }
  // The kinematic body's velocity now counts as the one it moved with (created kinematic with a
  // velocity, or made kinematic): no jump at the next step.
  void recordKinematicVelocity(uint32_t slot) {
    const size_t n = std::max<size_t>(bodies.size(), slot + 1);
    kinematic_velocity.resize(n, Vec2::Zero());
    kinematic_angular_velocity.resize(n, 0.0);
    kinematic_uid.resize(n, 0);
    kinematic_jump.resize(n, Vec2::Zero());
    kinematic_angular_jump.resize(n, 0.0);
    kinematic_velocity[slot] = bodies[slot].velocity;
    kinematic_angular_velocity[slot] = bodies[slot].angular_velocity;
    kinematic_uid[slot] = bodies[slot].uid;
  }

  BroadPhaseHolder broad_phase;
  std::vector<Proxy> proxies;
  // Events (contact_events.cpp, sensor.cpp, pre_solve.cpp). The counters say whether any shape asks
  // for them, so that a world without events does none of this work.
  bool every_contact_event = false;
  uint32_t event_shapes = 0, presolve_shapes = 0, sensor_shapes = 0;
  uint32_t surface_shapes = 0;  // shapes with a tangent speed or rolling resistance
  // This step's contacts' surface effects (pre_solve.cpp), index for index with `contacts`, when
  // some shape has them or a pre-solve callback gave some; empty otherwise (the solvers then look
  // no further).
  std::vector<ContactSurface> contact_surfaces;
  // The surface effects of a contact as its shapes give them: the tangent speeds add; rolling
  // resistance is the larger coefficient times the larger radius (Box2D v3's rule).
  ContactSurface surfaceOf(const Contact& c) const {
    const BodyShape &a = shapes[c.shape_a], &b = shapes[c.shape_b];
    ContactSurface s;
    s.tangent_speed = a.tangent_speed + b.tangent_speed;
    const double coefficient = std::max(a.rolling_resistance, b.rolling_resistance);
    if (coefficient > 0.0) s.rolling_resistance = coefficient * std::max(a.geometry.radius, b.geometry.radius);
    return s;
  }
  // Collision filter (World::setShouldCollide, broad_phase.cpp): the decisions for the pairs whose
  // boxes overlapped at the last step, ascending, so a pair is asked once while it overlaps.
  World::ShouldCollideFn should_collide;
  struct FilterDecision {
    uint32_t a, b;                    // shape slots, a < b
    uint32_t generation_a, generation_b;  // of the shapes asked about (a slot reused is a new pair)
    bool collide;
  };
  std::vector<FilterDecision> filter_decisions, filter_scratch;
  std::vector<World::ContactEvent> contact_events;
  std::vector<uint32_t> event_contacts;  // per event: its contact's index (begin and hit: impulses after the solve)
  std::vector<char> previous_matched;    // per previous contact: it continues (narrow_phase.cpp)
  std::vector<World::SensorEvent> sensor_events;
  std::vector<std::vector<ShapeId>> sensor_overlaps;  // per shape slot, for sensors: what is in it
  World::PreSolveFn pre_solve;
  void countShape(const BodyShape& s, int sign);  // the counters above, as a shape comes or goes
  bool wantsEvents(uint32_t shape_a, uint32_t shape_b) const {
    return every_contact_event || shapes[shape_a].contact_events || shapes[shape_b].contact_events ||
           shapes[shape_a].hit_events || shapes[shape_b].hit_events;
  }

  // The queries' tree (world_query.cpp): a leaf per shape slot, synced with the shapes' boxes when
  // a query comes after anything moved (layout_version counts steps and edits).
  AabbTree tree;
  std::vector<int32_t> tree_leaf;  // per shape slot, AabbTree::kNull when not in the tree
  // Per shape slot, what the queries' filter reads, copied at each sync: a query reads these few
  // bytes of the shapes it meets instead of their whole BodyShape (a cache miss each).
  struct QueryShape {
    ShapeId id;
    bool sensor = false;
    uint64_t category = 0, mask = 0;
  };
  std::vector<QueryShape> tree_shapes;
  // layout_version counts steps and edits (setShapeFilter and setShapeSensor too, for tree_shapes);
  // static shapes are refitted only when static_version says one may have moved.
  uint64_t layout_version = 1, tree_version = 0, tree_static_version = 0;
  void syncTree();
  // Static shapes for continuous collision (continuous.cpp): a tree rebuilt only after an edit that
  // can add or move a static shape (static_version: shape added, body moved, retyped, enabled).
  AabbTree static_tree;
  uint64_t static_version = 1, static_tree_version = 0;
  std::vector<uint32_t> fast_bodies;  // body slots that moved more than their inner radius this step
  std::vector<uint32_t> ccd_movers;  // shape slots of moving bodies that bullets are swept against
  std::vector<char> ccd_hit;      // per slot: stopped by continuous collision detection this step
  std::vector<Vec2> world_vertices, world_normals;  // every polygon placed in the world this step
  std::vector<uint32_t> polygon_offset;             // per shape slot: where its polygon starts in them
  // Per shape slot, what the narrow phase reads of a shape for every pair it is in, so a pair reads
  // two of these instead of two BodyShapes and their bodies. Only the placed geometry (centre,
  // world polygon) changes with a step; the rest is gathered again after an edit (shapesEdited).
  struct ShapeView {
    // What the narrow phase reads for every pair first (the placed polygon, then these up to the
    // material), so that a pair's two views take two cache lines each, mostly.
    PlacedShape placed;  // the world polygon (its corners set each step), the geometry, its body's transform
    uint32_t body;       // slot
    ShapeType type;
    bool special;        // a sensor, a filter other than the default, or a jointed body: the narrow phase looks closer
    // Set each step by the broad phase, for the narrow phase that follows it: the body moves
    // (isMoving) or is dynamic and asleep. A body can only wake in between.
    bool moving, asleep;
    double extent;       // maxExtent of the geometry: bounds the contact's slop
    Material material;
    const Vec2* local_vertices;  // polygons: Shape::vertices and normals, so that placing them
    const Vec2* local_normals;   // reads this view and not the BodyShape too (one cache line fewer)
    double radius;       // Shape::radius
    Vec2 center;         // circles: the centre in the world (manifold.h collideCircleCentres); set each step
    Vec2 local_center;   // circles: Shape::center
  };
  std::vector<ShapeView> shape_views;
  size_t active_shapes = 0;          // shapes of enabled bodies, counted with the views
  UncopiedFlag shape_views_current;  // the views' edit-only fields and the proxies' flags hold
  // Every edit that changes what a view or proxy flag copies (a shape added or removed, material,
  // filter, sensor, a body's type or enabled flag, a joint, a body added) calls this.
  void shapesEdited() { shape_views_current.value = false; }
  std::vector<BodyPair> pairs;             // shape slots
  std::vector<Manifold> pair_manifolds;    // per pair, with several threads (narrow_phase.cpp); count −1: not computed
  PairCache pair_cache;  // broad_phase.cpp
  std::vector<Contact> contacts;           // this step's, sorted by (shape_a, shape_b)
  std::vector<ContactKey> contact_keys;    // the same contacts' bodies (contact.h)
  std::vector<uint32_t> solved;            // indices of the contacts sequential impulses work on
  std::vector<uint32_t> soft_solved;       // indices of the contacts the soft step works on
  std::vector<SolvedRef> solved_refs;      // per entry of solved: its bodies (contact_solver.cpp)
  std::vector<SolvedRef> soft_refs;        // per entry of soft_solved
  std::vector<uint32_t> island_order;      // the solver's constraints grouped by island
  std::vector<Contact> previous_contacts;  // narrow_phase.cpp: last step's contacts moved out of the way
  // narrow_phase.cpp: written in place, the last step's contacts would have had to move out of the
  // way of new ones (contacts begin more than end), so this step writes them anew.
  bool contacts_displaced = false;

  // Sleeping (sleep.cpp): island of each body slot at the last update, and the wake-up call that
  // every edit, contact and force makes.
  std::vector<uint32_t> island;
  // wakeIsland's: the slots of `island` grouped by island, those of root r being
  // island_members[island_first[r] .. island_first[r + 1]); made at the first wake after `island`
  // changed (updateSleep clears the flag).
  std::vector<uint32_t> island_members, island_first;
  UncopiedFlag island_members_current;
  std::vector<uint32_t> island_parent;  // union–find scratch
  std::vector<char> island_dynamic;     // per slot: alive and not static (sleep.cpp)
  // The direct joint solve's islands (joint_direct.cpp): joint indices grouped by island, island i
  // being joint_island_joints[joint_island_start[i] .. joint_island_start[i + 1]).
  std::vector<uint32_t> joint_island_joints, joint_island_start;
  std::vector<uint32_t> joint_island_of, joint_island_index, joint_island_fill;  // its scratch
  DirectJointScratch direct_joints;     // the islands' rows and matrices (joint_direct.h)
  ContactExactScratch exact_contacts;   // the exact contact islands' rows and matrices (contact_exact.h)
  std::vector<double> island_sleep;     // per island root: the shortest sleep time of its members
  std::vector<char> keep_awake;         // per slot: a force that forbids sleep acts on it
  void wakeIsland(uint32_t slot);
  // Dynamic and awake (a disabled body is never awake): integrated, solved.
  bool isActive(uint32_t slot) const { return alive[slot] && bodies[slot].isDynamic() && bodies[slot].awake; }
  // A kinematic body that moves this step: it pushes and carries what it touches.
  bool isMovingKinematic(uint32_t slot) const {
    const Body& b = bodies[slot];
    return alive[slot] && b.isKinematic() && b.enabled && (b.velocity != Vec2::Zero() || b.angular_velocity != 0.0);
  }
  bool isMoving(uint32_t slot) const { return isActive(slot) || isMovingKinematic(slot); }
  bool isAsleep(uint32_t slot) const { return bodies[slot].isDynamic() && !bodies[slot].awake; }

  bool isLive(BodyId id) const {
    return id.index < bodies.size() && alive[id.index] && bodies[id.index].id.generation == id.generation;
  }
  Body& get(BodyId id);              // throws InputError("body", ...) for a stale handle
  const Body& get(BodyId id) const;
  bool isLive(ShapeId id) const {
    return id.index < shapes.size() && shape_alive[id.index] && shapes[id.index].id.generation == id.generation;
  }
  BodyShape& get(ShapeId id);        // throws InputError("shape", ...) for a stale handle
  Joint& get(JointId id);            // throws InputError("joint", ...) for a stale handle
  void releaseJoint(uint32_t index);  // removes the joint (and gears that use it), waking its bodies
  // Recomputes the body's mass, centre of mass and inertia from its shapes (world_shape.cpp);
  // `field`, `value`: what the densities came from, for the error message.
  void updateMass(Body& b, const char* field, double value);
  // Validates and attaches a shape to the body in `body` (world_shape.cpp); returns its slot.
  // `update_mass` false: the caller calls updateMass once after attaching several (a chain: one
  // call per segment would make a chain of n points cost n²).
  uint32_t attachShape(uint32_t body, const ShapeDef& def, const char* field, double value, bool update_mass = true);
  void releaseShape(uint32_t index);  // frees the slot (the caller fixes the body's list)
  static Shape validatedShape(const Shape& s);
  // "mass and moment of inertia must be finite with finite inverses, got ..." naming `field`.
  static InputError massError(const char* field, double mass, double inertia, double value);
  static Material validatedMaterial(double restitution, double friction, double static_friction);
  // InputError("<what> is not allowed while the world is stepping ...") during a step.
  void requireUnlocked(const char* what) const;
  const Body& bodyOf(uint32_t shape) const { return bodies[shapes[shape].body.index]; }

  // Recomputes the origin transform from the centre of mass and angle.
  static void syncTransform(Body& b) {
    b.xf.q = Rot::fromAngle(b.angle);
    b.xf.p = b.center - b.xf.q.apply(b.local_center);
  }
  static BodyState stateOf(const Body& b);
};

}  // namespace rigidlab

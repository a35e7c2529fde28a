// The world and its step (origin.md §6, Algorithm 4).
//
// Why the stages are in this order: the thesis integrates first and handles collisions once per
// step afterwards (Millington's scheme, origin.md §5): RK4 runs over the smooth forces without
// contacts in its sub-stages, then the contacts found at the new positions correct the velocities
// (restitution, friction) and finally the positions (penetration). Forces run out last, so a force
// with a duration acts during the whole step in which it expires (the integrator splits that step at
// the exact end time).
#include "rigidlab/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rigidlab/error.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

// ---------------------------------------------------------------------------------------------
// The step: integrate → find pairs → narrow phase → solve contacts → correct positions → expire.

namespace {

// Undoes a step that failed before the contacts (a force threw, or the broad phase reached its
// cap): the bodies the NaN firewall froze in it are unfrozen and forgotten, and every dynamic body
// is put back to its state at the start of the step.
void undoStep(WorldImpl& w, size_t incidents_before) {
  for (size_t k = incidents_before; k < w.incidents.size(); ++k) {
    for (size_t i = 0; i < w.bodies.size(); ++i) {
      Body& b = w.bodies[i];
      if (!w.alive[i] || b.uid != w.incidents[k].uid || !b.frozen) continue;
      b.type = BodyType::Dynamic;
      b.frozen = false;
      b.inv_mass = 1.0 / b.mass;
      b.inv_inertia = 1.0 / b.inertia;
    }
  }
  w.incidents.resize(incidents_before);
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.alive[i] || w.bodies[i].isStatic()) continue;
    Body& b = w.bodies[i];
    b.center = w.start_center[i];
    b.angle = w.start_angle[i];
    b.velocity = w.start_velocity[i];
    b.angular_velocity = w.start_angular_velocity[i];
    WorldImpl::syncTransform(b);
  }
  w.locked = false;
}

}  // namespace

void World::step(double dt) {
  WorldImpl& w = *impl_;
  if (w.locked) throw InputError("step", "step called while the world is stepping");
  requirePositive("dt", dt);

  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  w.stats = StepStats{};
  w.dt = dt;
  w.locked = true;
  const size_t incidents_before = w.incidents.size();
  const auto t0 = Clock::now();
  try {
    integrate(w, dt);  // origin.md §5: all non-contact forces, RK4 stages included
  } catch (...) {
    undoStep(w, incidents_before);  // forces run only here
    throw;
  }
  guardNonFinite(w, "integrate");  // before contacts: a non-finite body must not touch others
  w.ccd_hit.assign(w.bodies.size(), 0);
  if (w.def.continuous) sweepFastBodies(w);  // origin.md §13: no tunnelling through static bodies
  const auto t1 = Clock::now();
  try {
    findPairs(w);  // origin.md §7: all pairs, skipping static–static; throws at WorldDef::pair_cap
  } catch (...) {
    undoStep(w, incidents_before);
    throw;
  }
  const auto t2 = Clock::now();
  narrowPhase(w);  // origin.md §7: manifolds with feature ids
  const auto t3 = Clock::now();
  solveContacts(w);  // origin.md §8–10: sequential impulses; large islands by the soft step
  const auto t4 = Clock::now();
  correctPositions(w);  // origin.md §9: penetration removal (the soft step's islands need none)
  guardNonFinite(w, "the contact solve");
  const auto t5 = Clock::now();
  w.clock.advance(dt);
  updateSleep(w);  // islands whose bodies stayed still long enough stop being simulated
  ++w.step_count;
  expireForces(w);  // origin.md §6: forces whose time ran out are removed
  w.locked = false;
  const auto t6 = Clock::now();

  StepStats& s = w.stats;
  s.integrate_ms = ms(t0, t1);
  s.broad_phase_ms = ms(t1, t2);
  s.narrow_phase_ms = ms(t2, t3);
  s.solve_ms = ms(t3, t4);
  s.correct_ms = ms(t4, t5);
  s.finish_ms = ms(t5, t6);
  s.pairs = static_cast<int>(w.pairs.size());
  s.contacts = static_cast<int>(w.contacts.size());
  for (const Contact& c : w.contacts) s.contact_points += c.count;
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.alive[i]) continue;
    ++s.bodies;
    if (!w.bodies[i].isStatic()) ++s.dynamic_bodies;
    if (w.isActive(static_cast<uint32_t>(i))) ++s.awake_bodies;
  }
  for (const ForceEntry& f : w.forces) s.forces += f.alive ? 1 : 0;
}

void expireForces(WorldImpl& w) {
  const double now = w.clock.t;
  for (uint32_t i = 0; i < w.forces.size(); ++i) {
    ForceEntry& f = w.forces[i];
    // The tolerance absorbs the rounding of the clock: a force of duration 0.5 s added at t = 0
    // expires after the 30th step of 1/60 s even if the sum of the steps is 0.49999999999999994.
    if (f.alive && (f.next_step_only || f.expires_at <= now + 1e-9 * std::max(1.0, std::abs(now)))) {
      f.alive = false;
      f.force.reset();
      ++f.generation;
      w.free_forces.push_back(i);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Construction and settings

World::World(const WorldDef& def) : impl_(std::make_unique<WorldImpl>()) {
  setBroadPhase(def.broad_phase);
  setGravity(def.gravity);
  setIntegrator(def.integrator);
  setContactSolver(def.contact_solver);
  setSubsteps(def.substeps);
  if (def.soft_step_points < 1)
    throw InputError("soft_step_points", "soft_step_points must be at least 1, got " + std::to_string(def.soft_step_points));
  impl_->def.soft_step_points = def.soft_step_points;
  setIterations(def.iterations);
  impl_->def.contact_hertz = requirePositive("contact_hertz", def.contact_hertz);
  impl_->def.contact_damping_ratio = requirePositive("contact_damping_ratio", def.contact_damping_ratio);
  impl_->def.contact_push_speed = requirePositive("contact_push_speed", def.contact_push_speed);
  setWarmStarting(def.warm_starting);
  setContactDisplacement(def.contact_displacement);
  setPositionCorrection(def.position_correction);
  setPositionIterations(def.position_iterations);
  impl_->def.allowed_penetration = requireNonNegative("allowed_penetration", def.allowed_penetration);
  if (!(def.position_correction_rate > 0.0 && def.position_correction_rate <= 1.0))
    throw InputError("position_correction_rate",
                     "position_correction_rate must be in (0, 1], got " + formatNumber(def.position_correction_rate));
  impl_->def.position_correction_rate = def.position_correction_rate;
  setRestitutionThreshold(def.restitution_threshold);
  setStaticFrictionSpeed(def.static_friction_speed);
  setContactMargin(def.contact_margin);
  setSleeping(def.sleeping);
  setContinuous(def.continuous);
  if (def.pair_cap < 1) throw InputError("pair_cap", "pair_cap must be at least 1, got 0");
  if (def.pair_cap_per_body < 1)
    throw InputError("pair_cap_per_body", "pair_cap_per_body must be at least 1, got " + std::to_string(def.pair_cap_per_body));
  if (def.pair_cap_max < def.pair_cap)
    throw InputError("pair_cap_max", "pair_cap_max must be at least pair_cap (" + std::to_string(def.pair_cap) + "), got " +
                                         std::to_string(def.pair_cap_max));
  impl_->def.pair_cap = def.pair_cap;
  impl_->def.pair_cap_per_body = def.pair_cap_per_body;
  impl_->def.pair_cap_max = def.pair_cap_max;
  impl_->def.sleep_linear_speed = requireNonNegative("sleep_linear_speed", def.sleep_linear_speed);
  impl_->def.sleep_angular_speed = requireNonNegative("sleep_angular_speed", def.sleep_angular_speed);
  impl_->def.time_to_sleep = requireNonNegative("time_to_sleep", def.time_to_sleep);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

const WorldDef& World::settings() const { return impl_->def; }
void World::setGravity(const Vec2& g) {
  impl_->def.gravity = requireFinite("gravity", g);
  for (Body& b : impl_->bodies) {  // everything may start to move
    b.awake = true;
    b.sleep_time = 0.0;
  }
}
void World::setIntegrator(Integrator integrator) {
  if (!integratorName(integrator).size()) throw InputError("integrator", "unknown integrator");
  impl_->def.integrator = integrator;
}
void World::setIterations(int iterations) {
  if (iterations < 1 || iterations > 10000)
    throw InputError("iterations", "iterations must be between 1 and 10000, got " + std::to_string(iterations));
  impl_->def.iterations = iterations;
}
void World::setContactSolver(ContactSolver solver) {
  if (contactSolverName(solver).empty()) throw InputError("contact_solver", "unknown contact solver");
  impl_->def.contact_solver = solver;
}
void World::setSubsteps(int substeps) {
  if (substeps < 1 || substeps > 64)
    throw InputError("substeps", "substeps must be between 1 and 64, got " + std::to_string(substeps));
  impl_->def.substeps = substeps;
}
void World::setWarmStarting(bool on) { impl_->def.warm_starting = on; }
void World::setContactDisplacement(bool on) { impl_->def.contact_displacement = on; }
void World::setPositionCorrection(PositionCorrection pc) { impl_->def.position_correction = pc; }
void World::setPositionIterations(int iterations) {
  if (iterations < 1 || iterations > 1000)
    throw InputError("position_iterations",
                     "position_iterations must be between 1 and 1000, got " + std::to_string(iterations));
  impl_->def.position_iterations = iterations;
}
void World::setRestitutionThreshold(double speed) {
  impl_->def.restitution_threshold = requireNonNegative("restitution_threshold", speed);
}
void World::setSleeping(bool on) {
  impl_->def.sleeping = on;
  if (!on)
    for (Body& b : impl_->bodies) {
      b.awake = true;
      b.sleep_time = 0.0;
    }
}

void World::setContinuous(bool on) { impl_->def.continuous = on; }

void World::wake(BodyId id) {
  WorldImpl& w = *impl_;
  w.get(id);
  w.wakeIsland(id.index);
}

void World::setBroadPhase(BroadPhaseKind kind) {
  impl_->def.broad_phase = kind;
  if (kind == BroadPhaseKind::AllPairs) {
    impl_->broad_phase = std::make_unique<AllPairsBroadPhase>();
  } else {
    impl_->broad_phase = std::make_unique<GridBroadPhase>();
  }
}

void World::setContactMargin(double distance) {
  impl_->def.contact_margin = requireNonNegative("contact_margin", distance);
}
void World::setStaticFrictionSpeed(double speed) {
  impl_->def.static_friction_speed = requireNonNegative("static_friction_speed", speed);
}

std::string_view contactSolverName(ContactSolver s) {
  switch (s) {
    case ContactSolver::Auto: return "auto";
    case ContactSolver::SoftStep: return "soft_step";
    case ContactSolver::SequentialImpulses: return "sequential_impulses";
  }
  return {};
}
std::optional<ContactSolver> parseContactSolver(std::string_view name) {
  for (ContactSolver s : {ContactSolver::Auto, ContactSolver::SoftStep, ContactSolver::SequentialImpulses})
    if (contactSolverName(s) == name) return s;
  return std::nullopt;
}

std::string contactSolverNames() { return "auto, sequential_impulses, soft_step"; }

std::string_view integratorName(Integrator i) {
  switch (i) {
    case Integrator::ExplicitEuler: return "euler";
    case Integrator::SemiImplicitEuler: return "semi_implicit_euler";
    case Integrator::RungeKutta4: return "rk4";
    case Integrator::ImplicitEuler: return "implicit_euler";
  }
  return "";
}

std::optional<Integrator> parseIntegrator(std::string_view name) {
  for (Integrator i : {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::RungeKutta4,
                       Integrator::ImplicitEuler})
    if (integratorName(i) == name) return i;
  return std::nullopt;
}

std::string integratorNames() { return "euler, semi_implicit_euler, rk4, implicit_euler"; }

std::string_view positionCorrectionName(PositionCorrection pc) {
  switch (pc) {
    case PositionCorrection::LinearProjection: return "linear_projection";
    case PositionCorrection::NonlinearGaussSeidel: return "nonlinear_gauss_seidel";
  }
  return "";
}

std::optional<PositionCorrection> parsePositionCorrection(std::string_view name) {
  for (PositionCorrection pc : {PositionCorrection::LinearProjection, PositionCorrection::NonlinearGaussSeidel})
    if (positionCorrectionName(pc) == name) return pc;
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Bodies

namespace {

void requireUnlocked(const WorldImpl& w, const char* what) {
  if (w.locked)
    throw InputError(what, std::string(what) + " is not allowed while the world is stepping (e.g. from inside a force)");
}

Shape validatedShape(const Shape& s) {
  if (s.type == ShapeType::Circle) return makeCircle(s.radius, s.center);
  return makePolygon(s.vertices);  // re-validates and normalises a hand-built polygon
}

// `field` and `value`: the input the density came from, for the error message.
void setMassData(Body& b, double density, const char* field, double value) {
  const MassData md = computeMass(b.shape, density);
  // A mass or inertia whose inverse is not finite (a denormal mass: 1/4.9e-324 = inf) or that
  // overflowed (density 1e308 on a large shape) would reach the solver as ∞ or 0·∞ = NaN.
  const auto usable = [](double x) { return std::isfinite(x) && x > 0.0 && std::isfinite(1.0 / x); };
  if (!usable(md.mass) || !usable(md.inertia))
    throw InputError(field, "mass and moment of inertia must be finite with finite inverses, got " +
                                formatNumber(md.mass) + " kg and " + formatNumber(md.inertia) + " kg·m² (from " + field +
                                " " + formatNumber(value) + " and the shape's size)");
  b.density = density;
  b.area = md.area;
  b.mass = md.mass;
  b.inertia = md.inertia;
  b.local_center = md.center;
  b.inv_mass = b.isStatic() ? 0.0 : 1.0 / b.mass;
  b.inv_inertia = b.isStatic() ? 0.0 : 1.0 / b.inertia;
}

// Sets the body's transform and centre of mass from its origin and angle. A finite position near
// the largest double can still put the centre of mass (position + the rotated centre offset) out
// of range: refused naming position, so that no body starts with a non-finite state (fuzz_world).
void place(Body& b, const Vec2& position, double angle) {
  const Transform xf{position, Rot::fromAngle(angle)};
  const Vec2 center = xf.apply(b.local_center);
  if (!isFinite(center))
    throw InputError("position", "position " + formatVec(position) + " puts the centre of mass out of range, at " + formatVec(center));
  b.angle = angle;
  b.xf = xf;
  b.center = center;
}

Material validatedMaterial(double restitution, double friction, double static_friction) {
  requireNonNegative("restitution", restitution);
  if (restitution > 1.0)
    throw InputError("restitution", "restitution must be between 0 and 1, got " + formatNumber(restitution));
  return {restitution, requireNonNegative("friction", friction), requireNonNegative("static_friction", static_friction)};
}

}  // namespace

Body& WorldImpl::get(BodyId id) {
  if (!isLive(id)) throw InputError("body", "body handle is not valid (the body was removed or never existed)");
  return bodies[id.index];
}
const Body& WorldImpl::get(BodyId id) const { return const_cast<WorldImpl*>(this)->get(id); }

BodyState WorldImpl::stateOf(const Body& b) {
  BodyState s;
  s.position = b.xf.p;
  s.center = b.center;
  s.angle = b.angle;
  s.q = b.xf.q;
  s.velocity = b.velocity;
  s.angular_velocity = b.angular_velocity;
  s.mass = b.mass;
  s.inertia = b.inertia;
  s.is_static = b.isStatic();
  s.id = b.id;
  s.uid = b.uid;
  return s;
}

BodyId World::createBody(const BodyDef& def) {
  WorldImpl& w = *impl_;
  requireUnlocked(w, "createBody");
  Body b;
  b.uid = w.next_uid++;
  b.name = def.name;
  b.type = def.type;
  b.shape = validatedShape(def.shape);
  const Vec2 position = requireFinite("position", def.position);
  const double angle = requireFinite("angle", def.angle);
  b.material = validatedMaterial(def.restitution, def.friction, def.static_friction.value_or(def.friction));
  double density = def.density;
  if (def.mass) {
    requirePositive("mass", *def.mass);
    density = *def.mass / computeMass(b.shape, 1.0).area;
    setMassData(b, density, "mass", *def.mass);
  } else {
    requirePositive("density", density);
    setMassData(b, density, "density", density);
  }
  place(b, position, angle);
  if (!b.isStatic()) {
    b.velocity = requireFinite("velocity", def.velocity);
    b.angular_velocity = requireFinite("angular_velocity", def.angular_velocity);
  }

  uint32_t index;
  if (!w.free_bodies.empty()) {
    index = w.free_bodies.back();
    w.free_bodies.pop_back();
    b.id = {index, w.bodies[index].id.generation + 1};
    w.bodies[index] = std::move(b);
    w.alive[index] = 1;
  } else {
    index = static_cast<uint32_t>(w.bodies.size());
    b.id = {index, 0};
    w.bodies.push_back(std::move(b));
    w.alive.push_back(1);
  }
  return w.bodies[index].id;
}

void World::destroyBody(BodyId id) {
  WorldImpl& w = *impl_;
  requireUnlocked(w, "destroyBody");
  w.get(id);
  for (uint32_t i = 0; i < w.forces.size(); ++i) {
    const ForceEntry& f = w.forces[i];
    if (f.alive && (f.a == id || f.b == id)) removeForce({i, f.generation});
  }
  for (const Contact& c : w.contacts) {  // what rested on it may now fall
    if (c.a == id.index) w.wakeIsland(c.b);
    if (c.b == id.index) w.wakeIsland(c.a);
  }
  Body& b = w.bodies[id.index];
  const BodyId old = b.id;
  b = Body{};
  b.id = old;  // keeps the generation, so the next body in this slot gets a new one
  b.uid = 0;
  w.alive[id.index] = 0;
  w.free_bodies.push_back(id.index);
  // Drop contacts (and their keys, which stay index for index with them) that refer to the slot,
  // so contacts() never names a dead body.
  const auto refersToSlot = [&](const auto& c) { return c.a == id.index || c.b == id.index; };
  std::erase_if(w.contacts, refersToSlot);
  std::erase_if(w.previous_contacts, refersToSlot);
  std::erase_if(w.contact_keys, refersToSlot);
}

bool World::isValid(BodyId id) const { return impl_->isLive(id); }
const Body& World::body(BodyId id) const { return impl_->get(id); }

std::vector<BodyId> World::bodyIds() const {
  std::vector<BodyId> ids;
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->alive[i]) ids.push_back(impl_->bodies[i].id);
  return ids;
}

int World::bodyCount() const { return static_cast<int>(std::count(impl_->alive.begin(), impl_->alive.end(), 1)); }

std::optional<BodyId> World::findBody(std::string_view name) const {
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->alive[i] && impl_->bodies[i].name == name) return impl_->bodies[i].id;
  return std::nullopt;
}

std::optional<BodyId> World::findBody(uint32_t uid) const {
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->alive[i] && impl_->bodies[i].uid == uid) return impl_->bodies[i].id;
  return std::nullopt;
}

void World::setTransform(BodyId id, const Vec2& position, double angle) {
  requireUnlocked(*impl_, "setTransform");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("position", position);
  requireFinite("angle", angle);
  place(b, position, angle);
}

void World::setVelocity(BodyId id, const Vec2& velocity) {
  requireUnlocked(*impl_, "setVelocity");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("velocity", velocity);
  if (!b.isStatic()) b.velocity = velocity;
}

void World::setAngularVelocity(BodyId id, double angular_velocity) {
  requireUnlocked(*impl_, "setAngularVelocity");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("angular_velocity", angular_velocity);
  if (!b.isStatic()) b.angular_velocity = angular_velocity;
}

void World::setType(BodyId id, BodyType type) {
  requireUnlocked(*impl_, "setType");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  b.type = type;
  if (type == BodyType::Dynamic) b.frozen = false;
  if (b.isStatic()) {
    b.velocity = Vec2::Zero();
    b.angular_velocity = 0.0;
  }
  setMassData(b, b.density, "density", b.density);  // valid when the body was made
}

void World::setMass(BodyId id, double mass) {
  requireUnlocked(*impl_, "setMass");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requirePositive("mass", mass);
  setMassData(b, mass / b.area, "mass", mass);  // refuses before changing anything
}

void World::setMaterial(BodyId id, const Material& m) {
  requireUnlocked(*impl_, "setMaterial");
  impl_->get(id).material = validatedMaterial(m.restitution, m.friction, m.static_friction);
}

void World::setName(BodyId id, std::string name) {
  requireUnlocked(*impl_, "setName");
  impl_->get(id).name = std::move(name);
}

void World::applyImpulse(BodyId id, const Vec2& impulse, const Vec2& world_point) {
  requireUnlocked(*impl_, "applyImpulse");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("impulse", impulse);
  requireFinite("point", world_point);
  // Δv = J / m, Δω = (p − c) × J / I.
  b.velocity += b.inv_mass * impulse;
  b.angular_velocity += b.inv_inertia * cross(world_point - b.center, impulse);
}

BodyState World::bodyState(BodyId id) const { return WorldImpl::stateOf(impl_->get(id)); }

// ---------------------------------------------------------------------------------------------
// Forces

namespace {
ForceEntry& liveForce(WorldImpl& w, ForceId id) {
  if (id.index >= w.forces.size() || !w.forces[id.index].alive || w.forces[id.index].generation != id.generation)
    throw InputError("force", "force handle is not valid (the force was removed or has expired)");
  return w.forces[id.index];
}
}  // namespace

ForceId World::addForce(std::unique_ptr<Force> force, BodyId a, BodyId b, double duration) {
  WorldImpl& w = *impl_;
  requireUnlocked(w, "addForce");
  if (!force) throw InputError("force", "force is null");
  w.get(a);
  if (!b.isNull()) {
    w.get(b);
    if (a == b) throw InputError("b", "a two-body force needs two different bodies");
  }
  if (!(duration > 0.0) && duration != kNextStep)
    throw InputError("duration", "duration must be > 0, got " + formatNumber(duration));
  ForceEntry e;
  e.force = std::move(force);
  e.a = a;
  e.b = b;
  e.next_step_only = duration == kNextStep;
  e.expires_at = duration == kForever || e.next_step_only ? kForever : w.clock.t + duration;
  w.wakeIsland(a.index);
  if (!b.isNull()) w.wakeIsland(b.index);
  e.alive = true;
  uint32_t index;
  if (!w.free_forces.empty()) {
    index = w.free_forces.back();
    w.free_forces.pop_back();
    e.generation = w.forces[index].generation;
    w.forces[index] = std::move(e);
  } else {
    index = static_cast<uint32_t>(w.forces.size());
    w.forces.push_back(std::move(e));
  }
  return {index, w.forces[index].generation};
}

ForceId World::addSpring(const SpringDef& def, double duration) {
  WorldImpl& w = *impl_;
  SpringDef d = def;
  const BodyState a = WorldImpl::stateOf(w.get(def.a));
  if (!d.rest_length) {
    // Default rest length: the distance between the ends now.
    const Vec2 pa = a.worldPoint(requireFinite("local_a", d.local_a));
    const Vec2 pb = d.b.isNull() ? requireFinite("anchor", d.anchor)
                                 : WorldImpl::stateOf(w.get(d.b)).worldPoint(requireFinite("local_b", d.local_b));
    d.rest_length = (pb - pa).norm();
  }
  return addForce(std::make_unique<SpringForce>(d), d.a, d.b, duration);
}

ForceId World::addDamper(const DamperDef& def, double duration) {
  return addForce(std::make_unique<DamperForce>(def), def.body, {}, duration);
}

void World::removeForce(ForceId id) {
  WorldImpl& w = *impl_;
  requireUnlocked(w, "removeForce");
  ForceEntry& f = liveForce(w, id);
  w.wakeIsland(f.a.index);  // what the force held may now move
  if (!f.b.isNull()) w.wakeIsland(f.b.index);
  f.alive = false;
  f.force.reset();
  ++f.generation;
  w.free_forces.push_back(id.index);
}

bool World::isValid(ForceId id) const {
  const WorldImpl& w = *impl_;
  return id.index < w.forces.size() && w.forces[id.index].alive && w.forces[id.index].generation == id.generation;
}
Force& World::force(ForceId id) { return *liveForce(*impl_, id).force; }
const Force& World::force(ForceId id) const { return *liveForce(*impl_, id).force; }
BodyId World::forceBodyA(ForceId id) const { return liveForce(*impl_, id).a; }
BodyId World::forceBodyB(ForceId id) const { return liveForce(*impl_, id).b; }
double World::forceTimeLeft(ForceId id) const { return liveForce(*impl_, id).expires_at - impl_->clock.t; }

std::vector<ForceId> World::forceIds() const {
  std::vector<ForceId> ids;
  for (uint32_t i = 0; i < impl_->forces.size(); ++i)
    if (impl_->forces[i].alive) ids.push_back({i, impl_->forces[i].generation});
  return ids;
}

// ---------------------------------------------------------------------------------------------
// Queries

bool World::isStepping() const { return impl_->locked; }
double World::time() const { return impl_->clock.t; }
long World::stepCount() const { return impl_->step_count; }
const StepStats& World::stats() const { return impl_->stats; }
const std::vector<Incident>& World::incidents() const { return impl_->incidents; }

double World::kineticEnergy() const {
  double e = 0.0;
  for (size_t i = 0; i < impl_->bodies.size(); ++i) {
    const Body& b = impl_->bodies[i];
    if (!impl_->alive[i] || b.isStatic()) continue;
    e += 0.5 * b.mass * b.velocity.squaredNorm() + 0.5 * b.inertia * b.angular_velocity * b.angular_velocity;
  }
  return e;
}

double World::gravityPotentialEnergy() const {
  double e = 0.0;
  for (size_t i = 0; i < impl_->bodies.size(); ++i) {
    const Body& b = impl_->bodies[i];
    if (impl_->alive[i] && !b.isStatic()) e -= b.mass * impl_->def.gravity.dot(b.center);
  }
  return e;
}

double World::potentialEnergy() const {
  const WorldImpl& w = *impl_;
  double e = gravityPotentialEnergy();
  for (const ForceEntry& f : w.forces) {
    if (!f.alive) continue;
    const BodyState a = WorldImpl::stateOf(w.bodies[f.a.index]);
    if (f.b.isNull()) {
      e += f.force->potentialEnergy(a, nullptr);
    } else {
      const BodyState b = WorldImpl::stateOf(w.bodies[f.b.index]);
      e += f.force->potentialEnergy(a, &b);
    }
  }
  return e;
}

std::optional<BodyId> World::bodyAt(const Vec2& point) const {
  // Later slots are drawn on top, so search from the back.
  for (size_t i = impl_->bodies.size(); i-- > 0;) {
    const Body& b = impl_->bodies[i];
    if (impl_->alive[i] && containsPoint(b.shape, b.xf, point)) return b.id;
  }
  return std::nullopt;
}

std::vector<ContactInfo> World::contacts() const {
  std::vector<ContactInfo> out;
  for (const Contact& c : impl_->contacts) {
    ContactInfo info;
    info.a = impl_->bodies[c.a].id;
    info.b = impl_->bodies[c.b].id;
    info.normal = c.normal;
    info.count = c.count;
    for (int i = 0; i < c.count; ++i) {
      info.points[i] = c.points[i].point;
      info.separations[i] = c.points[i].separation;
      info.normal_impulses[i] = c.points[i].step_normal_impulse;
      info.tangent_impulses[i] = c.points[i].step_tangent_impulse;
      info.ids[i] = c.points[i].id;
    }
    out.push_back(info);
  }
  return out;
}

}  // namespace rigidlab

// The world and its step (docs/design/thesis.md §6, Algorithm 4).
//
// Why the stages are in this order: the thesis integrates first and handles collisions once per
// step afterwards (Millington's scheme, docs/design/thesis.md §5): RK4 runs over the smooth forces without
// contacts in its sub-stages, then the contacts found at the new positions correct the velocities
// (restitution, friction) and finally the positions (penetration). Forces run out last, so a force
// with a duration acts during the whole step in which it expires (the integration splits that step
// at the exact end time). Going beyond the thesis, impacts of the few bodies in free flight are
// located inside the integration (event_location.cpp): integrated to the moment of contact,
// resolved there, and integrated on, so they never reach the contact stages as overlaps; resting
// and persistent contacts, piles and stacks are still found and solved once per step.
#include "rigidlab/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rigidlab/error.h"
#include "mechanism_step.h"
#include "stages.h"
#include "step_context.h"
#include "world_impl.h"

namespace rigidlab {

// ---------------------------------------------------------------------------------------------
// The step: integrate (and locate impacts) → find pairs → narrow phase → pre-solve → solve contacts and
// joints → correct positions → break joints → events and sensors → sleep → expire forces.

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
      w.shapesEdited();
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
  const StepContext ctx{dt, w.def};
  w.last_dt = dt;
  w.locked = true;
  const size_t incidents_before = w.incidents.size();
  const auto t0 = Clock::now();
  beginEnergyWatch(w);  // the energy at the start: a blow-up is energy from nowhere (energy_watch.h)
  try {
    integrate(w, ctx);  // docs/design/thesis.md §5: all non-contact forces, RK4 stages included; located impacts
  } catch (...) {
    undoStep(w, incidents_before);  // forces run only here
    throw;
  }
  guardNonFinite(w, "integrate");  // before contacts: a non-finite body must not touch others
  w.ccd_hit.assign(w.bodies.size(), 0);
  if (w.def.continuous) sweepFastBodies(w);  // docs/design/thesis.md §13: no tunnelling through static bodies
  const auto t1 = Clock::now();
  try {
    findPairs(w);  // candidate pairs (the grid; thesis §7 tested all), no static–static; throws at pair_cap
  } catch (...) {
    undoStep(w, incidents_before);
    throw;
  }
  const auto t2 = Clock::now();
  narrowPhase(w);  // docs/design/thesis.md §7: manifolds with feature ids; contact begin and end events
  settleLocatedContacts(w);  // located impacts: pairs not touching wait for the next step; their events
  try {
    preSolve(w);  // one-way platforms and the pre-solve callback disable contacts for this step
  } catch (...) {
    undoStep(w, incidents_before);
    throw;
  }
  const auto t3 = Clock::now();
  settleMechanisms(w, ctx);  // exact mechanisms still touching nothing keep their joints out of the contact solve
  solveContacts(w, ctx);  // docs/design/thesis.md §8–10: contacts and joints; large islands by the soft step
  const auto t4 = Clock::now();
  correctPositions(w, ctx);  // docs/design/thesis.md §9: penetration and joint errors (the soft step's islands need none)
  finishMechanisms(w, ctx);  // the joints of exact mechanisms that met something: their impulses
  guardNonFinite(w, "the contact solve");
  breakJoints(w);  // joints over their break force or torque go, reported (jointBreaks)
  finishContactEvents(w);  // the events' impulses, now that they are known
  updateSensors(w);  // what is in each sensor now: begin and end events
  const auto t5 = Clock::now();
  w.clock.advance(dt);
  ++w.layout_version;
  updateSleep(w, ctx);  // islands whose bodies stayed still long enough stop being simulated
  ++w.step_count;
  endEnergyWatch(w, ctx);  // more energy gained than the sources can give: a blow-up incident
  expireForces(w);  // docs/design/thesis.md §6: forces whose time ran out are removed
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
  s.exact_joints = exactJointCount(w);
  s.joints = static_cast<int>(w.si_joints.size() + w.soft_joints.size()) + s.exact_joints;
  for (const Contact& c : w.contacts) s.contact_points += c.count;
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.alive[i]) continue;
    ++s.bodies;
    if (w.bodies[i].isDynamic()) ++s.dynamic_bodies;
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
  impl_->def.joint_hertz = requirePositive("joint_hertz", def.joint_hertz);
  impl_->def.joint_damping_ratio = requireNonNegative("joint_damping_ratio", def.joint_damping_ratio);
  setExactJoints(def.exact_joints);
  setStaticFrictionSpeed(def.static_friction_speed);
  setContactMargin(def.contact_margin);
  setSleeping(def.sleeping);
  setContinuous(def.continuous);
  setImpacts(def.impacts);
  setThreads(def.threads);
  if (def.impact_island_bodies < 1)
    throw InputError("impact_island_bodies", "impact_island_bodies must be at least 1, got " + std::to_string(def.impact_island_bodies));
  if (def.impact_max_bodies < 0)
    throw InputError("impact_max_bodies", "impact_max_bodies must be at least 0, got " + std::to_string(def.impact_max_bodies));
  impl_->def.impact_island_bodies = def.impact_island_bodies;
  impl_->def.impact_max_bodies = def.impact_max_bodies;
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
    b.awake = b.enabled;
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
void World::setExactJoints(bool on) { impl_->def.exact_joints = on; }
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
      b.awake = b.enabled;
      b.sleep_time = 0.0;
    }
}

void World::setContinuous(bool on) { impl_->def.continuous = on; }
void World::setThreads(int threads) {
  if (threads < 0 || threads > 64)
    throw InputError("threads", "threads must be between 0 (the machine's cores) and 64, got " + std::to_string(threads));
  impl_->def.threads = threads;
}

// The pool is made when a step first asks for more than one thread, and made again when the
// setting changed; a world on one thread has none.
TaskPool* WorldImpl::taskPool() {
  const int want = resolvedThreads(def.threads);
  if (want <= 1) return nullptr;
  if (!pool.pool || pool.pool->threads() != want) {
    pool.pool.reset();
    pool.pool = std::make_unique<TaskPool>(want);
  }
  return pool.pool.get();
}
void World::setImpacts(ImpactHandling impacts) {
  if (impactHandlingName(impacts).empty()) throw InputError("impacts", "unknown impact handling");
  impl_->def.impacts = impacts;
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

std::string_view impactHandlingName(ImpactHandling h) {
  switch (h) {
    case ImpactHandling::Located: return "located";
    case ImpactHandling::PerStep: return "per_step";
  }
  return {};
}
std::optional<ImpactHandling> parseImpactHandling(std::string_view name) {
  for (ImpactHandling h : {ImpactHandling::Located, ImpactHandling::PerStep})
    if (impactHandlingName(h) == name) return h;
  return std::nullopt;
}
std::string impactHandlingNames() { return "located, per_step"; }

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
// Queries

bool World::isStepping() const { return impl_->locked; }
double World::time() const { return impl_->clock.t; }
long World::stepCount() const { return impl_->step_count; }
const StepStats& World::stats() const { return impl_->stats; }
const std::vector<Incident>& World::incidents() const { return impl_->incidents; }

double World::kineticEnergy() const { return impl_->kineticEnergy(); }

double WorldImpl::kineticEnergy() const {
  double e = 0.0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    if (!alive[i] || !b.isDynamic()) continue;
    e += 0.5 * b.mass * b.velocity.squaredNorm() + 0.5 * b.inertia * b.angular_velocity * b.angular_velocity;
  }
  return e;
}

double World::gravityPotentialEnergy() const { return impl_->gravityPotentialEnergy(); }

double WorldImpl::gravityPotentialEnergy() const {
  double e = 0.0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    if (alive[i] && b.isDynamic()) e -= b.mass * b.gravity_scale * b.gravityOr(def.gravity).dot(b.center);
  }
  return e;
}

double World::potentialEnergy() const { return impl_->potentialEnergy(); }

double WorldImpl::potentialEnergy() const { return gravityPotentialEnergy() + forcePotentialEnergy(); }

double WorldImpl::forcePotentialEnergy() const {
  double e = 0.0;
  for (const ForceEntry& f : forces) {
    if (!f.alive) continue;
    const BodyState a = stateOf(bodies[f.a.index]);
    if (f.b.isNull()) {
      e += f.force->potentialEnergy(a, nullptr);
    } else {
      const BodyState b = stateOf(bodies[f.b.index]);
      e += f.force->potentialEnergy(a, &b);
    }
  }
  return e;
}

std::optional<BodyId> World::bodyAt(const Vec2& point) const {
  // Later slots are drawn on top, so search from the back.
  for (size_t i = impl_->bodies.size(); i-- > 0;) {
    const Body& b = impl_->bodies[i];
    if (!impl_->alive[i]) continue;
    for (ShapeId s : b.shapes)
      if (containsPoint(impl_->shapes[s.index].geometry, b.xf, point)) return b.id;
  }
  return std::nullopt;
}

namespace {

ContactInfo infoOf(const WorldImpl& w, const Contact& c, size_t k) {
  ContactInfo info;
  info.friction = c.friction;
  info.static_friction = c.static_friction;
  info.restitution = c.restitution;
  // The step's surface (a pre-solve callback's tangent speed included) while the step's list is
  // there; the shapes' otherwise.
  const ContactSurface surface = w.contact_surfaces.size() == w.contacts.size() ? w.contact_surfaces[k] : w.surfaceOf(c);
  info.tangent_speed = surface.tangent_speed;
  info.rolling_resistance = surface.rolling_resistance;
  info.a = w.bodies[c.a].id;
  info.b = w.bodies[c.b].id;
  info.shape_a = w.shapes[c.shape_a].id;
  info.shape_b = w.shapes[c.shape_b].id;
  info.normal = c.normal;
  info.count = c.count;
  info.touching = c.touching;
  for (int i = 0; i < c.count; ++i) {
    info.points[i] = c.points[i].point;
    info.separations[i] = c.points[i].separation;
    info.normal_impulses[i] = c.points[i].step_normal_impulse;
    info.tangent_impulses[i] = c.points[i].step_tangent_impulse;
    info.ids[i] = c.points[i].id;
  }
  return info;
}

}  // namespace

std::vector<ContactInfo> World::contactsOf(BodyId body) const {
  impl_->get(body);
  std::vector<ContactInfo> out;
  for (size_t k = 0; k < impl_->contacts.size(); ++k) {
    const Contact& c = impl_->contacts[k];
    if (c.touching && (c.a == body.index || c.b == body.index)) out.push_back(infoOf(*impl_, c, k));
  }
  return out;
}

std::vector<ContactInfo> World::contacts() const {
  std::vector<ContactInfo> out;
  for (size_t k = 0; k < impl_->contacts.size(); ++k) out.push_back(infoOf(*impl_, impl_->contacts[k], k));
  return out;
}

std::vector<ContactInfo> World::touchingContacts() const {
  std::vector<ContactInfo> out;
  for (size_t k = 0; k < impl_->contacts.size(); ++k)
    if (impl_->contacts[k].touching) out.push_back(infoOf(*impl_, impl_->contacts[k], k));
  return out;
}

}  // namespace rigidlab

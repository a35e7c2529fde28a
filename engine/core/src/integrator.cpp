// Stage 1 of the step: integrate every dynamic body under gravity and the non-contact forces
// (docs/design/thesis.md §5, §6). The state of body i is y_i = (c_i, θ_i, v_i, ω_i), centre of mass, angle,
// linear and angular velocity; its derivative is f(t, y) = (v, ω, F/m + g, τ/I).
//
//   explicit Euler        c += h v_n,  θ += h ω_n,  v += h a(t_n, y_n),  ω += h α(t_n, y_n)
//   semi-implicit Euler   v += h a(t_n, y_n), ω += h α(...),  then  c += h v_{n+1},  θ += h ω_{n+1}
//   implicit Euler        (M − h D − h² K) Δv = h (Q₀ + h K v₀), v += Δv, c += h v_{n+1}: springs and
//                         dampers linearly implicit (implicit_solve.cpp), stable at any stiffness
//   RK4                   k1 = f(t, y), k2 = f(t + h/2, y + h k1/2), k3 = f(t + h/2, y + h k2/2),
//                         k4 = f(t + h, y + h k3),  y += h/6 (k1 + 2 k2 + 2 k3 + k4)
//
// RK4 evaluates every state-dependent force at each of its four stages on the stage state of *all*
// bodies at once (a spring between two bodies sees both ends at the same stage), as the thesis's
// GetDerivative does (Algorithm 6). Forces that do not depend on the state (gravity, a constant push
// through the centre of mass) are evaluated once per interval; with only such forces RK4 reduces to
// the exact constant-acceleration update c += h v + ½ h² a, v += h a.
//
// In the Euler methods the damping of springs and dampers is linearly implicit, so a damper never
// flips a velocity's sign (implicit_solve.cpp).
//
// The step's time line (event_location.cpp) calls integrateInterval for each piece of the step:
// the step is split at the end times of time-limited forces and at located impacts. An interval may
// be integrated for some bodies only (`only`): the bodies of one island, which no force links to
// the others, integrated again up to an impact.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "body_acceleration.h"
#include "mechanism_step.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

// The integrator's scratch (WorldImpl::integrator holds it, opaque to the other stages), written in
// each interval before it is read.
struct IntegratorScratch {
  // RK4's: the staged bodies' state at the interval's start and the weighted sum of the stages'
  // derivatives.
  std::vector<Vec2> c0, v0, dc, dv;
  std::vector<double> a0, w0, da, dw;
  struct DampingSum {  // a body's Force::dampingRate summed over its forces
    double linear = 0.0, angular = 0.0;
  };
  std::vector<DampingSum> damping_sum;  // per slot (dampingTooStiffForRk4)
};

namespace {

using Clock = std::chrono::steady_clock;

bool isActive(const ForceEntry& f, double t0) { return f.alive && f.expires_at > t0; }

// Is the force among those of the bodies marked in `only` (nullptr: every force)?
bool selected(const ForceEntry& f, const char* only) {
  return !only || only[f.a.index] || (!f.b.isNull() && only[f.b.index]);
}

// Adds the wrenches of the active forces of one class (state-dependent or not), evaluated at time t
// on w.states, into `out`.
void evaluateForces(WorldImpl& w, double t0, double t, bool state_dependent, std::vector<Wrench>& out, const char* only) {
  const auto start = Clock::now();
  const bool watch = !w.energy.push.empty();
  for (ForceEntry& f : w.forces) {
    if (!isActive(f, t0) || f.force->dependsOnState() != state_dependent || !selected(f, only)) continue;
    const BodyState& a = w.states[f.a.index];
    const BodyState* b = f.b.isNull() ? nullptr : &w.states[f.b.index];
    ForceOutput result;
    f.force->evaluate(ForceInput{a, b, t}, result);
    ++w.stats.force_evaluations;
    // The NaN firewall names the force (nan_guard.cpp); the value still goes through, so the body's
    // state shows the fault and is frozen after this stage.
    const auto finite = [](const Wrench& x) { return isFinite(x.force) && std::isfinite(x.torque); };
    const int32_t index = static_cast<int32_t>(&f - w.forces.data());
    if (!finite(result.a) && w.force_fault[f.a.index] < 0) w.force_fault[f.a.index] = index;
    if (b && !finite(result.b) && w.force_fault[f.b.index] < 0) w.force_fault[f.b.index] = index;
    out[f.a.index] += result.a;
    if (b) out[f.b.index] += result.b;
    if (watch && f.force->putsEnergyIn()) {  // its work bounds the energy it may put in (energy_watch.h)
      w.energy.noteForce(f.a.index, result.a);
      if (b) w.energy.noteForce(f.b.index, result.b);
    }
  }
  w.stats.forces_ms += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

[[gnu::always_inline]] inline Accel accelerationOf(const WorldImpl& w, uint32_t i, const Wrench& wr) {
  return bodyAcceleration(w.bodies[i], w.def.gravity, wr);
}

void setStageState(WorldImpl& w, uint32_t i, const Vec2& c, double angle, const Vec2& v, double omega) {
  BodyState& s = w.states[i];
  s.center = c;
  s.angle = angle;
  s.q = Rot::fromAngle(angle);
  s.position = c - s.q.apply(w.bodies[i].local_center);
  s.velocity = v;
  s.angular_velocity = omega;
}

// Dynamic and awake, and among the bodies integrated (`only`, nullptr: all).
bool isMoving(const WorldImpl& w, uint32_t i, const char* only) { return w.isActive(i) && (!only || only[i]); }

// True if some body's dampers (Force::dampingRate, summed per body) reach h·c/m > 2.5 or
// h·c_ω/I > 2.5 in this interval.
bool dampingTooStiffForRk4(WorldImpl& w, double t0, double h, const char* only) {
  constexpr double kLimit = 2.5;
  auto& rate = w.integrator.get().damping_sum;
  rate.assign(w.bodies.size(), IntegratorScratch::DampingSum{});
  bool any = false;
  for (const ForceEntry& f : w.forces) {
    if (!isActive(f, t0) || !selected(f, only)) continue;
    const Force::DampingRate d = f.force->dampingRate();
    if (d.linear == 0.0 && d.angular_a == 0.0 && d.angular_b == 0.0) continue;
    any = true;
    rate[f.a.index].linear += d.linear;
    rate[f.a.index].angular += d.angular_a;
    if (f.b.isNull()) continue;
    rate[f.b.index].linear += d.linear;
    rate[f.b.index].angular += d.angular_b;
  }
  if (!any) return false;
  for (uint32_t i = 0; i < rate.size(); ++i) {
    if (!isMoving(w, i, only)) continue;
    const Body& b = w.bodies[i];
    if (h * rate[i].linear * b.inv_mass > kLimit || h * rate[i].angular * b.inv_inertia > kLimit) return true;
  }
  return false;
}


// One integrator step of length h from t0 (integrateInterval splits an interval into these).
void integrateStep(WorldImpl& w, double t0, double h, const char* only) {
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  bool any_force = false, any_dependent = false;
  for (const ForceEntry& f : w.forces) {
    if (!selected(f, only)) continue;
    any_force |= isActive(f, t0);
    any_dependent |= isActive(f, t0) && f.force->dependsOnState();
  }
  // RK4 is explicit: a damper with h·c/m above 2.785 multiplies the velocity by more than 1 each
  // step (RK4's factor is the degree-4 Taylor polynomial of e^(−hc/m): 291 at hc/m = 10) and blows
  // up (docs/design/accuracy.md S5). Above 2.5 the interval is integrated as semi-implicit Euler with implicit
  // damping instead, which never flips or grows a velocity; counted in StepStats::rk4_handovers.
  Integrator method = w.def.integrator;
  if (method == Integrator::RungeKutta4 && any_dependent && dampingTooStiffForRk4(w, t0, h, only)) {
    method = Integrator::SemiImplicitEuler;
    ++w.stats.rk4_handovers;
  }
  const bool rk4 = method == Integrator::RungeKutta4;
  // Exact mechanisms (mechanism_step.cpp): the moving bodies of islands of jointed bodies that touch
  // nothing (per slot: kStagedMechanism, whose joints' forces are computed at every stage, or
  // kStiffMechanism, stepped by stepStiffMechanisms). Their bodies are never located, so an
  // interval for some bodies only (`only`) never holds one.
  const char* mechanism = only ? nullptr : mechanismBodies(w);
  const auto stiff = [&](uint32_t i) { return mechanism && mechanism[i] == kStiffMechanism; };
  if (mechanism) beginMechanismStep(w, t0, h);
  // Body damping (BodyDef::linear_damping, angular_damping): with RK4 a force −c m v, −c_ω I ω
  // evaluated at every stage (body_acceleration.h), so a damped body keeps order 4; with the Euler
  // methods, and with RK4 where h c > 2.5, implicit over the interval on the velocity the interval
  // starts with, before the integrator adds what the forces and gravity give (for semi-implicit
  // Euler v ← v / (1 + h c) + h a, as Box2D v3 does):
  //   v ← v / (1 + h c)
  // which shrinks a velocity towards zero for any h c ≥ 0 and never flips it. Damping after the
  // integrator, v ← (v + h g) / (1 + h c), would also shrink the velocity gravity gave in this
  // step, before the joints and contacts take it away: a damped body held still would then weigh
  // m g / (1 + h c) on its pin or its floor, and a resting one sink by the contact slop.
  const auto staged_damping = [&](const Body& b) { return rk4 && dampingInStages(b, h); };
  // Forces read the damped velocity, so with forces the damping is a pass of its own; without,
  // each integrator's loop damps the body it is at (one pass over the bodies instead of two).
  const auto damp = [&](Body& b) {
    if (staged_damping(b)) return;
    if (b.linear_damping > 0.0) b.velocity *= 1.0 / (1.0 + h * b.linear_damping);
    if (b.angular_damping > 0.0) b.angular_velocity *= 1.0 / (1.0 + h * b.angular_damping);
  };
  const bool damp_in_loop = !any_force;
  if (any_force)
    for (uint32_t i = 0; i < n; ++i)
      if (isMoving(w, i, only)) damp(w.bodies[i]);
  // RK4's stages run for the bodies whose acceleration changes within the interval: every body when
  // a force depends on the state, else those of exact mechanisms and those damped in the stages.
  // The others move under a constant acceleration, for which RK4 is exact and equals its closed
  // form.
  bool any_staged = any_dependent || mechanism;
  if (rk4 && !any_staged)
    for (uint32_t i = 0; i < n && !any_staged; ++i) any_staged = isMoving(w, i, only) && staged_damping(w.bodies[i]);
  const auto staged = [&](uint32_t i) {
    return !stiff(i) && (any_dependent || (mechanism && mechanism[i]) || staged_damping(w.bodies[i]));
  };
  // The states are what forces and the stages read (ForceInput); gravity alone needs none, and
  // filling them costs a sine and a cosine per body (a tenth of the step's integration in a pile
  // of boxes).
  if (any_force || any_staged)
    for (uint32_t i = 0; i < n; ++i)
      if (w.alive[i]) w.states[i] = WorldImpl::stateOf(w.bodies[i]);

  std::fill(w.const_wrenches.begin(), w.const_wrenches.end(), Wrench{});
  evaluateForces(w, t0, t0, false, w.const_wrenches, only);

  // All forces at time t on the current w.states → w.wrenches; the mechanisms' forces added, with
  // the stage's weight in the update (their joints' impulses).
  const auto derivative = [&](double t, double weight) {
    std::copy(w.const_wrenches.begin(), w.const_wrenches.end(), w.wrenches.begin());
    if (any_dependent) evaluateForces(w, t0, t, true, w.wrenches, only);
    if (mechanism) addMechanismForces(w, t, weight, h, rk4);
  };
  // The acceleration of body i at the current stage.
  const auto stageAcceleration = [&](uint32_t i) {
    const Body& b = w.bodies[i];
    if (!staged_damping(b)) return accelerationOf(w, i, w.wrenches[i]);
    const BodyState& st = w.states[i];
    return dampedAcceleration(b, w.def.gravity, w.wrenches[i], st.velocity, st.angular_velocity);
  };

  switch (method) {
    case Integrator::ExplicitEuler:
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitEuler: {
      derivative(t0, 1.0);
      if (mechanism) stepStiffMechanisms(w, t0, h);
      const bool semi = method != Integrator::ExplicitEuler;
      // Damping (and for implicit_euler stiffness) of springs and dampers is linearly implicit
      // (implicit_solve.cpp); without such forces Δv = h a(t_n, y_n), and without any force nothing
      // to linearise (no pass over the bodies to look).
      ImplicitVelocities change;
      const bool implicit = any_force && implicitVelocityChange(w, t0, h, method == Integrator::ImplicitEuler, only, change);
      for (uint32_t i = 0; i < n; ++i) {
        if (!isMoving(w, i, only) || stiff(i)) continue;
        Body& b = w.bodies[i];
        if (damp_in_loop) damp(b);
        Vec2 dv;
        double dw;
        if (implicit) {
          const int r = change.row[i];
          dv = Vec2(change.dv[3 * r], change.dv[3 * r + 1]);
          dw = b.fixed_rotation ? 0.0 : change.dv[3 * r + 2];  // the solve treats the angle as free
        } else {
          const Accel acc = accelerationOf(w, i, w.wrenches[i]);
          dv = h * acc.a;
          dw = h * acc.alpha;
        }
        if (semi) {
          b.velocity += dv;
          b.angular_velocity += dw;
          b.center += h * b.velocity;
          b.angle += h * b.angular_velocity;
        } else {
          b.center += h * b.velocity;
          b.angle += h * b.angular_velocity;
          b.velocity += dv;
          b.angular_velocity += dw;
        }
      }
      break;
    }
    case Integrator::RungeKutta4: {
      // Constant acceleration over the interval: RK4 is exact, and equals this closed form.
      for (uint32_t i = 0; i < n; ++i) {
        if (!isMoving(w, i, only) || stiff(i) || (any_staged && staged(i))) continue;
        Body& b = w.bodies[i];
        if (damp_in_loop) damp(b);
        const Accel acc = accelerationOf(w, i, w.const_wrenches[i]);
        b.center += h * b.velocity + 0.5 * h * h * acc.a;
        b.angle += h * b.angular_velocity + 0.5 * h * h * acc.alpha;
        b.velocity += h * acc.a;
        b.angular_velocity += h * acc.alpha;
      }
      if (!any_staged) break;
      auto& s = w.integrator.get();
      for (uint32_t i = 0; i < n; ++i) {
        if (!isMoving(w, i, only) || !staged(i)) continue;
        const Body& b = w.bodies[i];
        s.c0[i] = b.center;
        s.a0[i] = b.angle;
        s.v0[i] = b.velocity;
        s.w0[i] = b.angular_velocity;
        s.dc[i] = Vec2::Zero();
        s.dv[i] = Vec2::Zero();
        s.da[i] = 0.0;
        s.dw[i] = 0.0;
      }
      // Stage k: derivative at (t0 + c_k h) on the current stage states, accumulated with weight
      // b_k; then the next stage state y0 + a_{k+1} h k.
      static constexpr double kTime[4] = {0.0, 0.5, 0.5, 1.0};
      static constexpr double kWeight[4] = {1.0, 2.0, 2.0, 1.0};
      static constexpr double kNext[3] = {0.5, 0.5, 1.0};
      for (int k = 0; k < 4; ++k) {
        derivative(t0 + kTime[k] * h, kWeight[k] / 6.0);
        if (k == 0 && mechanism) stepStiffMechanisms(w, t0, h);
        for (uint32_t i = 0; i < n; ++i) {
          if (!isMoving(w, i, only) || !staged(i)) continue;
          const BodyState& st = w.states[i];
          const Accel acc = stageAcceleration(i);
          const Vec2 kc = st.velocity;
          const double ka = st.angular_velocity;
          s.dc[i] += kWeight[k] * kc;
          s.da[i] += kWeight[k] * ka;
          s.dv[i] += kWeight[k] * acc.a;
          s.dw[i] += kWeight[k] * acc.alpha;
          if (k < 3) {
            const double f = kNext[k] * h;
            setStageState(w, i, s.c0[i] + f * kc, s.a0[i] + f * ka, s.v0[i] + f * acc.a, s.w0[i] + f * acc.alpha);
          }
        }
      }
      for (uint32_t i = 0; i < n; ++i) {
        if (!isMoving(w, i, only) || !staged(i)) continue;
        Body& b = w.bodies[i];
        b.center = s.c0[i] + (h / 6.0) * s.dc[i];
        b.angle = s.a0[i] + (h / 6.0) * s.da[i];
        b.velocity = s.v0[i] + (h / 6.0) * s.dv[i];
        b.angular_velocity = s.w0[i] + (h / 6.0) * s.dw[i];
      }
      break;
    }
  }
  // The mechanisms' bodies back onto their joints (mechanism.h): what keeps the integrator's order.
  if (mechanism) projectMechanisms(w, t0 + h);
  for (uint32_t i = 0; i < n; ++i)
    if (isMoving(w, i, only)) WorldImpl::syncTransform(w.bodies[i]);
}

}  // namespace

void integrateInterval(WorldImpl& w, double t0, double h, const char* only) {
  // An exact mechanism is integrated by an explicit method, stable and accurate only while h times
  // its fastest rate (a body's turning, a joint spring's frequency) stays small (RK4: below 2.8 on
  // an oscillation); a chain's free end whipping round turns at hundreds of rad/s. Such an interval
  // is split into steps that turn at most kMechanismTurn each, and split again while a step drifts
  // off the joints by more than kMaxMechanismDrift (mechanism_step.h). Every body takes the same
  // steps, so that forces between bodies still see one state. Worlds without a mechanism, and
  // mechanisms slow enough, take the interval whole.
  const bool mechanisms = !only && mechanismBodies(w);
  if (!mechanisms) {
    integrateStep(w, t0, h, only);
    return;
  }
  for (int steps = mechanismSteps(w, h);;) {
    beginMechanismAttempt(w);
    const double part = h / steps;
    for (int k = 0; k < steps; ++k) integrateStep(w, t0 + k * part, k + 1 == steps ? h - k * part : part, only);
    if (!mechanismAttemptFailed(w)) return;
    if (steps < kMaxMechanismSteps) {
      restoreMechanismAttempt(w);
      steps *= 2;
      continue;
    }
    // Past kMaxMechanismSteps the islands that still drift are stiff (a long chain under tension:
    // its fastest waves turn faster than any affordable step): stepped as stiff mechanisms instead
    // (stable at any step), the others with the steps they need. Each round makes at least one
    // more island stiff, so this ends; an island that fails although stiff (hostile inputs: no
    // projection converges) keeps this attempt, its residual in StepStats::mechanism_residual.
    if (!stiffenDriftingMechanisms(w)) return;
    restoreMechanismAttempt(w);
    steps = mechanismSteps(w, h);
  }
}

void beginIntegration(WorldImpl& w) {
  const size_t n = w.bodies.size();
  w.states.resize(n);
  w.wrenches.resize(n);
  w.const_wrenches.resize(n);
  w.start_velocity.resize(n);
  w.start_angular_velocity.resize(n);
  w.start_center.resize(n);
  w.start_angle.resize(n);
  w.force_fault.assign(n, -1);
  IntegratorScratch& rk4 = w.integrator.get();
  for (auto* v : {&rk4.c0, &rk4.v0, &rk4.dc, &rk4.dv}) v->resize(n);
  for (auto* v : {&rk4.a0, &rk4.w0, &rk4.da, &rk4.dw}) v->resize(n);
  for (size_t i = 0; i < n; ++i) {
    w.start_velocity[i] = w.bodies[i].velocity;
    w.start_angular_velocity[i] = w.bodies[i].angular_velocity;
    w.start_center[i] = w.bodies[i].center;
    w.start_angle[i] = w.bodies[i].angle;
  }
}

void moveKinematicBodies(WorldImpl& w, double dt) {
  // Kinematic bodies move by their velocity alone: exact for a constant velocity. A velocity set
  // between steps is a jump at the start of this one; it is kept (kinematic_jump) for the contact
  // displacement of the bodies the kinematic body carries (position_correction.cpp).
  w.kinematic_jumped = false;
  if (w.kinematic_bodies == 0 && !w.kinematic_recorded) return;
  w.kinematic_recorded = w.kinematic_bodies > 0;
  const size_t n = w.bodies.size();
  w.kinematic_velocity.resize(n, Vec2::Zero());
  w.kinematic_angular_velocity.resize(n, 0.0);
  w.kinematic_uid.resize(n, 0);
  w.kinematic_jump.resize(n, Vec2::Zero());
  w.kinematic_angular_jump.resize(n, 0.0);
  for (size_t k = 0; k < n; ++k) {
    Body& b = w.bodies[k];
    if (!w.alive[k] || !b.isKinematic() || !b.enabled) {
      w.kinematic_uid[k] = 0;
      continue;
    }
    const bool known = w.kinematic_uid[k] == b.uid;  // else it was made kinematic (or created) just now
    w.kinematic_jump[k] = known ? Vec2(b.velocity - w.kinematic_velocity[k]) : Vec2::Zero();
    w.kinematic_angular_jump[k] = known ? b.angular_velocity - w.kinematic_angular_velocity[k] : 0.0;
    w.kinematic_jumped |= w.kinematic_jump[k] != Vec2::Zero() || w.kinematic_angular_jump[k] != 0.0;
    w.kinematic_velocity[k] = b.velocity;
    w.kinematic_angular_velocity[k] = b.angular_velocity;
    w.kinematic_uid[k] = b.uid;
    if (b.velocity == Vec2::Zero() && b.angular_velocity == 0.0) continue;
    b.center += dt * b.velocity;
    b.angle += dt * b.angular_velocity;
    WorldImpl::syncTransform(b);
  }
}

}  // namespace rigidlab

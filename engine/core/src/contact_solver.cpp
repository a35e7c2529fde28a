// Stage 4 of the step: sequential impulses on the contact velocities (origin.md §8–10; E. Catto,
// "Iterative Dynamics with Temporal Coherence", GDC 2005; box2d-lite Arbiter::ApplyImpulse).
//
// For each contact point with normal n (A → B) and tangent t = n × 1:
//   relative velocity     v_r = (v_B + ω_B × r_B) − (v_A + ω_A × r_A)
//   effective mass        m_n = 1 / (1/m_A + 1/m_B + (r_A × n)²/I_A + (r_B × n)²/I_B)
//   restitution target    v_target = −e (v_r·n) if v_r·n < −threshold, else 0; computed once before
//                         the iterations so restitution is not re-applied each pass (origin.md §9),
//                         and taken at the moment the overlap began (prepare() below)
//   normal impulse        λ = −m_n (v_r·n − v_target); accumulated P_n = max(P_n + λ, 0)
//   friction impulse      λ_t = −m_t (v_r·t); accumulated P_t clamped to ±f P_n, using the
//                         accumulated normal impulse, not the last increment (origin.md §10, Catto)
// With warm starting (WorldDef::warm_starting) each point starts from the impulses it had in the
// previous step (matched by feature id); without it, from zero as in the thesis.
// f is the static coefficient f_s when the tangential slip at the start of the step is below
// WorldDef::static_friction_speed, else the dynamic f_d (origin.md §10). Normal impulses are solved
// before friction in each pass, so a single pass already gives the thesis's experiment 1 result.
#include <algorithm>
#include <cmath>

#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

void applyImpulse(Body& a, Body& b, const ContactPoint& cp, const Vec2& impulse) {
  a.velocity -= a.inv_mass * impulse;
  a.angular_velocity -= a.inv_inertia * cross(cp.ra, impulse);
  b.velocity += b.inv_mass * impulse;
  b.angular_velocity += b.inv_inertia * cross(cp.rb, impulse);
}

Vec2 relativeVelocity(const Body& a, const Body& b, const ContactPoint& cp) {
  return b.velocity + cross(b.angular_velocity, cp.rb) - a.velocity - cross(a.angular_velocity, cp.ra);
}

// κ: the weight an integrator's position update gives to the velocity gained during the step:
// 1 for semi-implicit and implicit Euler (c += h v_{n+1}), ½ for RK4 (c += h v_n + ½ h² a, exact for a constant
// force), 0 for explicit Euler (c += h v_n).
double restingWeight(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return 0.0;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitEuler: return 1.0;
    case Integrator::RungeKutta4: return 0.5;
  }
  return 0.0;
}

void prepare(WorldImpl& w, Contact& c) {
  const double resting_weight = restingWeight(w.def.integrator);
  const Body& a = w.bodies[c.a];
  const Body& b = w.bodies[c.b];
  const Vec2 n = c.normal;
  const Vec2 t = cross(n, 1.0);
  for (int i = 0; i < c.count; ++i) {
    ContactPoint& cp = c.points[i];
    cp.ra = cp.point - a.center;
    cp.rb = cp.point - b.center;
    const double rna = cross(cp.ra, n), rnb = cross(cp.rb, n);
    const double kn = a.inv_mass + b.inv_mass + a.inv_inertia * rna * rna + b.inv_inertia * rnb * rnb;
    const double rta = cross(cp.ra, t), rtb = cross(cp.rb, t);
    const double kt = a.inv_mass + b.inv_mass + a.inv_inertia * rta * rta + b.inv_inertia * rtb * rtb;
    cp.normal_mass = kn > 0.0 ? 1.0 / kn : 0.0;
    cp.tangent_mass = kt > 0.0 ? 1.0 / kt : 0.0;

    const double vn = relativeVelocity(a, b, cp).dot(n);
    // How long the point has been overlapping within this step: a new contact since depth / speed
    // before the end; a persisting one all step long, under a force spread over the step, whose
    // position effect is the integrator's weight κ of the velocity gained (position_correction.cpp).
    if (cp.persisted) {
      cp.overlap_time = resting_weight * w.dt;
    } else {
      cp.overlap_time = (vn < 0.0 && cp.separation < 0.0) ? std::min(w.dt, cp.separation / vn) : 0.0;
    }
    // Relative velocity of the point at the start of the step.
    const Vec2 v_start = w.start_velocity[c.b] + cross(w.start_angular_velocity[c.b], cp.rb) - w.start_velocity[c.a] -
                         cross(w.start_angular_velocity[c.a], cp.ra);
    cp.friction = std::abs(v_start.dot(t)) < w.def.static_friction_speed ? c.static_friction : c.friction;
    if (!w.def.warm_starting) {
      cp.normal_impulse = 0.0;
      cp.tangent_impulse = 0.0;
    }
    cp.target_velocity = 0.0;
    if (cp.separation > 0.0) {
      // Speculative point: the bodies may close the gap during the next step, not more.
      cp.target_velocity = -cp.separation / w.dt;
      if (vn < -w.def.restitution_threshold && c.restitution > 0.0 && vn * w.dt < -cp.separation) {
        // A bouncing impact: let it happen next step, where restitution is taken at the moment of
        // contact, instead of stopping the body at the surface here.
        cp.normal_mass = cp.tangent_mass = 0.0;
        cp.normal_impulse = cp.tangent_impulse = 0.0;
      }
    } else if (vn < -w.def.restitution_threshold) {
      // Restitution at the moment the overlap began, τ before the end of the step: the approach
      // speed then was v_n − a τ, with a the normal acceleration over the step (from the velocity
      // at its start); after the bounce the same acceleration acts for τ:
      //   v_target = −e (v_n − a τ) + a τ = −e v_n + (1 + e) a τ        (accuracy.md §3.12)
      const double accel = (vn - v_start.dot(n)) / w.dt;
      cp.target_velocity = std::max(0.0, -c.restitution * vn + (1.0 + c.restitution) * accel * cp.overlap_time);
    }
  }
}

// Applies the impulses carried over from the previous step (narrow_phase.cpp).
void warmStart(WorldImpl& w, Contact& c) {
  Body& a = w.bodies[c.a];
  Body& b = w.bodies[c.b];
  const Vec2 t = cross(c.normal, 1.0);
  for (int i = 0; i < c.count; ++i) {
    const ContactPoint& cp = c.points[i];
    applyImpulse(a, b, cp, cp.normal_impulse * c.normal + cp.tangent_impulse * t);
  }
}

void solve(WorldImpl& w, Contact& c) {
  Body& a = w.bodies[c.a];
  Body& b = w.bodies[c.b];
  const Vec2 n = c.normal;
  const Vec2 t = cross(n, 1.0);
  for (int i = 0; i < c.count; ++i) {
    ContactPoint& cp = c.points[i];
    const double vn = relativeVelocity(a, b, cp).dot(n);
    double lambda = -cp.normal_mass * (vn - cp.target_velocity);
    const double total = std::max(cp.normal_impulse + lambda, 0.0);
    lambda = total - cp.normal_impulse;
    cp.normal_impulse = total;
    applyImpulse(a, b, cp, lambda * n);
  }
  for (int i = 0; i < c.count; ++i) {
    ContactPoint& cp = c.points[i];
    const double vt = relativeVelocity(a, b, cp).dot(t);
    double lambda = -cp.tangent_mass * vt;
    const double limit = cp.friction * cp.normal_impulse;
    const double total = std::clamp(cp.tangent_impulse + lambda, -limit, limit);
    lambda = total - cp.tangent_impulse;
    cp.tangent_impulse = total;
    applyImpulse(a, b, cp, lambda * t);
  }
}

}  // namespace

void solveContacts(WorldImpl& w) {
  // Velocities before the solve, for the contact displacement (position_correction.cpp).
  const size_t n = w.bodies.size();
  w.solve_start_velocity.resize(n);
  w.solve_start_angular_velocity.resize(n);
  for (size_t i = 0; i < n; ++i) {
    w.solve_start_velocity[i] = w.bodies[i].velocity;
    w.solve_start_angular_velocity[i] = w.bodies[i].angular_velocity;
  }
  for (Contact& c : w.contacts) prepare(w, c);
  if (w.def.warm_starting)
    for (Contact& c : w.contacts) warmStart(w, c);
  for (int it = 0; it < w.def.iterations; ++it)
    for (Contact& c : w.contacts) solve(w, c);
}

}  // namespace rigidlab

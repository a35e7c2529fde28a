// The impulses of a located impact (event_location.cpp): at the moment two shapes touch, every
// point where the bodies involved touch gets a normal and a friction impulse, all at once, so that
// simultaneous impacts in one island (a ball landing on two others, a box landing flat) are
// resolved together.
//
// For each point with normal n (A → B), tangent t = n × 1 and lever arms r_A, r_B (docs/design/thesis.md §8):
//   relative velocity   v_r = (v_B + ω_B × r_B) − (v_A + ω_A × r_A)
//   effective masses    m_n = 1 / (1/m_A + 1/m_B + (r_A × n)²/I_A + (r_B × n)²/I_B), m_t likewise with t
//   Newton's law        v_n' = −e v_n if the approach −v_n is faster than the restitution threshold,
//                       else v_n' = 0: below it a bounce ends in resting contact, so a decaying
//                       bounce stops instead of bouncing ever more often (no Zeno cascade)
//   normal impulse      P_n ≥ 0 with v_n' ≥ target and P_n (v_n' − target) = 0
//   friction impulse    |P_t| ≤ μ P_n (Coulomb), opposing the slip; μ the static coefficient if the
//                       slip before the impact is below WorldDef::static_friction_speed
// solved by sequential impulses (normal, then friction, point by point) repeated until no impulse
// changes by more than 1e-13 of the largest: the iteration converges to the impulses that satisfy
// every point's conditions together. One circle point needs a single pass: its normal impulse
// does not turn the body (r ∥ n), and the friction impulse then sticks or slides exactly as the
// Poisson–Coulomb impact does (docs/design/accuracy.md §3.11: thesis experiment 1 to round-off).
#include <algorithm>
#include <cmath>

#include "impact.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

constexpr int kMaxPasses = 1000;
constexpr double kConverged = 1e-13;

Vec2 relativeVelocity(const Body& a, const Body& b, const ImpactPoint& p) {
  return b.velocity + cross(b.angular_velocity, p.rb) - a.velocity - cross(a.angular_velocity, p.ra);
}

void apply(Body& a, Body& b, const ImpactPoint& p, const Vec2& impulse) {
  a.velocity -= a.inv_mass * impulse;
  a.angular_velocity -= a.inv_inertia * cross(p.ra, impulse);
  b.velocity += b.inv_mass * impulse;
  b.angular_velocity += b.inv_inertia * cross(p.rb, impulse);
}

double effectiveMass(const Body& a, const Body& b, const ImpactPoint& p, const Vec2& d) {
  const double ra = cross(p.ra, d), rb = cross(p.rb, d);
  const double k = a.inv_mass + b.inv_mass + a.inv_inertia * ra * ra + b.inv_inertia * rb * rb;
  return k > 0.0 ? 1.0 / k : 0.0;
}

}  // namespace

void resolveImpact(WorldImpl& w, std::vector<ImpactPoint>& points) {
  for (ImpactPoint& p : points) {
    const Body& a = w.bodies[p.a];
    const Body& b = w.bodies[p.b];
    const Vec2 t = cross(p.normal, 1.0);
    const Vec2 v = relativeVelocity(a, b, p);
    const double vn = v.dot(p.normal);
    p.approach = -vn;
    p.normal_mass = effectiveMass(a, b, p, p.normal);
    p.tangent_mass = effectiveMass(a, b, p, t);
    p.target = vn < -w.def.restitution_threshold ? -p.restitution * vn : 0.0;
    p.mu = std::abs(v.dot(t)) < w.def.static_friction_speed ? p.static_friction : p.friction;
    p.normal_impulse = p.tangent_impulse = 0.0;
  }
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    double change = 0.0, size = 0.0;
    for (ImpactPoint& p : points) {
      Body& a = w.bodies[p.a];
      Body& b = w.bodies[p.b];
      const Vec2 t = cross(p.normal, 1.0);
      const double vn = relativeVelocity(a, b, p).dot(p.normal);
      const double pn = std::max(p.normal_impulse - p.normal_mass * (vn - p.target), 0.0);
      apply(a, b, p, (pn - p.normal_impulse) * p.normal);
      change = std::max(change, std::abs(pn - p.normal_impulse));
      p.normal_impulse = pn;
      const double limit = p.mu * p.normal_impulse;
      const double vt = relativeVelocity(a, b, p).dot(t);
      const double pt = std::clamp(p.tangent_impulse - p.tangent_mass * vt, -limit, limit);
      apply(a, b, p, (pt - p.tangent_impulse) * t);
      change = std::max(change, std::abs(pt - p.tangent_impulse));
      p.tangent_impulse = pt;
      size = std::max({size, p.normal_impulse, std::abs(p.tangent_impulse)});
    }
    if (change <= kConverged * size) break;
  }
}

}  // namespace rigidlab

// Stage 5 of the step: make positions agree with the contact-corrected velocities, then remove the
// penetration that is left (origin.md §9).
//
// Contact displacement (WorldDef::contact_displacement): the step integrates positions before the
// contacts are found (world.cpp), so a contact impulse Δv changes the velocity but not the distance
// the body already travelled under gravity during the step. Without a correction a block held by
// static friction on an incline creeps downhill by ½ g sin θ h² every step (8 cm in 2 s at 60 Hz),
// and a resting box sinks by its gravity travel each step until projection lifts it. So each body is
// moved by the displacement its contact impulses would have caused had they acted during the step:
//   Δc = κ h Δv,   Δθ = κ h Δω,
// where κ is the weight the integrator's position update gives to the velocity gained during the
// step: 1 for semi-implicit Euler (c += h v_{n+1}), ½ for RK4 (c += h v_n + ½ h² a, exact for a
// constant force), 0 for explicit Euler (c += h v_n, which already used the corrected velocity of
// the previous step). A body resting on the ground or held on an incline then stays exactly put.
// Off, the stage is the thesis's: linear projection only.
//
// Linear projection (the thesis's RemovePenetration): move the two bodies apart along the contact
// normal by the penetration depth d, shared by inverse mass, without rotating them:
//   Δc_A = −n d (1/m_A) / (1/m_A + 1/m_B),   Δc_B = +n d (1/m_B) / (1/m_A + 1/m_B)
// Contacts are processed in order; the depth of each is reduced by what earlier contacts already
// moved its bodies along its normal, so a body is not pushed twice for the same overlap. It is
// simple and exact for a single contact but imprecise for stacks (bodies creep, origin.md §9).
#include <algorithm>

#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

void linearProjection(WorldImpl& w) {
  for (const Contact& c : w.contacts) {
    Body& a = w.bodies[c.a];
    Body& b = w.bodies[c.b];
    const double inv_sum = a.inv_mass + b.inv_mass;
    if (inv_sum == 0.0) continue;
    double deepest = 0.0;  // most negative separation at detection
    for (int i = 0; i < c.count; ++i) deepest = std::min(deepest, c.points[i].separation);
    // Subtract what this stage already moved the pair apart along the normal (the contact
    // displacement and earlier contacts), so no overlap is removed twice.
    const double moved = (b.center - w.correction_start[c.b] - (a.center - w.correction_start[c.a])).dot(c.normal);
    const double depth = -deepest - moved;
    if (depth <= 0.0) continue;
    a.center -= c.normal * (depth * a.inv_mass / inv_sum);
    b.center += c.normal * (depth * b.inv_mass / inv_sum);
  }
}

// κ of the integrator (see above).
double displacementWeight(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return 0.0;
    case Integrator::SemiImplicitEuler: return 1.0;
    case Integrator::RungeKutta4: return 0.5;
  }
  return 0.0;
}

void applyContactDisplacement(WorldImpl& w) {
  const double kh = displacementWeight(w.def.integrator) * w.dt;
  if (kh == 0.0) return;
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.alive[i] || !w.in_contact[i]) continue;
    Body& b = w.bodies[i];
    b.center += kh * (b.velocity - w.solve_start_velocity[i]);
    b.angle += kh * (b.angular_velocity - w.solve_start_angular_velocity[i]);
  }
}

}  // namespace

void correctPositions(WorldImpl& w) {
  const size_t n = w.bodies.size();
  w.correction_start.resize(n);
  w.correction_start_angle.resize(n);
  for (size_t i = 0; i < n; ++i) {
    w.correction_start[i] = w.bodies[i].center;
    w.correction_start_angle[i] = w.bodies[i].angle;
  }
  if (w.def.contact_displacement && !w.contacts.empty()) applyContactDisplacement(w);
  switch (w.def.position_correction) {
    case PositionCorrection::LinearProjection:
      linearProjection(w);
      break;
  }
  for (size_t i = 0; i < n; ++i) {
    const Body& b = w.bodies[i];
    if (w.alive[i] && (b.center != w.correction_start[i] || b.angle != w.correction_start_angle[i]))
      WorldImpl::syncTransform(w.bodies[i]);
  }
}

}  // namespace rigidlab

// Stage 5 of the step: make positions agree with the contact-corrected velocities, then remove the
// penetration that is left (docs/design/thesis.md §9).
//
// Contact displacement (WorldDef::contact_displacement): the step integrates positions before the
// contacts are found (world.cpp), so a contact impulse Δv changes the velocity but not the distance
// the body travelled while it was already overlapping. Without a correction a block held by static
// friction on an incline creeps downhill by its gravity travel every step (8 cm in 2 s at 60 Hz),
// and an elastic bounce ends pressed into the floor, to be lifted by projection (which adds
// energy). So each body is moved by the displacement its contact impulses would have caused had
// they acted from the moment the overlap began:
//   Δc = τ Δv,   Δθ = τ Δω,   τ = Σ P_i τ_i / Σ P_i   (P_i: normal impulse of point i)
// τ_i is how long point i has been overlapping within the step (contact_solver.cpp):
// - a new contact (an impact): τ_i = min(h, depth_i / |v_n,i|), depth over approach speed. The
//   body ends where a bounce at the moment of contact would have put it, which keeps an elastic
//   bounce's energy (with the restitution target taken at that moment).
// - a persisting contact: the contact force acts through the whole step, and its position effect
//   is the weight κ the integrator's position update gives to the velocity gained in the step:
//   τ_i = κ h, κ = 1 for semi-implicit Euler (travel g h²), ½ for RK4 (½ g h²), 0 for explicit
//   Euler (its position update used the previous, already corrected velocity). Resting and held
//   bodies then stay exactly put.
// Off, the stage is the thesis's: linear projection only.
//
// Then the penetration left is removed by one of two strategies (WorldDef::position_correction):
// Linear projection (the thesis's RemovePenetration): move the two bodies apart along the contact
// normal by the penetration depth d, shared by inverse mass, without rotating them:
//   Δc_A = −n d (1/m_A) / (1/m_A + 1/m_B),   Δc_B = +n d (1/m_B) / (1/m_A + 1/m_B)
// Contacts are processed in order; the depth of each is reduced by what earlier contacts already
// moved its bodies along its normal, so a body is not pushed twice for the same overlap. It is
// simple and exact for a single contact but imprecise for stacks (bodies creep, docs/design/thesis.md §9).
//
// Nonlinear Gauss–Seidel (the default; E. Catto, Box2D 2.4 b2ContactSolver::SolvePositionConstraints):
// a few passes over the contact points; each recomputes the point's current separation s from its
// two surface points fixed in the bodies, and applies a position-level impulse that removes a
// fraction β of the depth beyond the allowed penetration, moving and rotating both bodies:
//   C = clamp(β (s + slop), −0.2 m, 0),  P = −C / (1/m_A + 1/m_B + (r_A × n)²/I_A + (r_B × n)²/I_B)
//   c_A −= P n / m_A,  θ_A −= (r_A × P n) / I_A,   c_B += P n / m_B,  θ_B += (r_B × P n) / I_B
// Because every point sees the corrections of the others, a stack is straightened as a whole
// instead of contacts pushing against each other; velocities are not touched.
#include <algorithm>
#include <cmath>
#include <utility>

#include "contact_exact.h"
#include "joint_solver.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

// Position correction's scratch (WorldImpl::position_correction holds it, opaque to the other
// stages), written in each step before it is read.
struct PositionCorrectionScratch {
  std::vector<double> overlap_time;    // per slot: Σ P τ over its contact points (applyContactDisplacement)
  std::vector<double> overlap_weight;  // per slot: Σ P
  std::vector<Vec2> start;             // per slot: centre before position correction
  std::vector<double> start_angle;
  std::vector<uint32_t> carrier;       // per slot: the jumping kinematic body it presses most
  std::vector<double> carrier_weight;  // per slot: Σ P of its contacts with that body
};

namespace {

// Inverse masses as the correction sees them: a sleeping body does not move.
double invMass(const WorldImpl& w, uint32_t i) { return w.isActive(i) ? w.bodies[i].inv_mass : 0.0; }
double invInertia(const WorldImpl& w, uint32_t i) { return w.isActive(i) ? w.bodies[i].inv_inertia : 0.0; }

void linearProjection(WorldImpl& w, const PositionCorrectionScratch& own) {
  for (uint32_t k : w.solved) {
    const Contact& c = w.contacts[k];
    Body& a = w.bodies[c.a];
    Body& b = w.bodies[c.b];
    const double ima = invMass(w, c.a), imb = invMass(w, c.b);
    const double inv_sum = ima + imb;
    if (inv_sum == 0.0) continue;
    double deepest = 0.0;  // most negative separation at detection
    for (int i = 0; i < c.count; ++i) deepest = std::min(deepest, c.points[i].separation);
    // Subtract what this stage already moved the pair apart along the normal (the contact
    // displacement and earlier contacts), so no overlap is removed twice.
    const double moved = (b.center - own.start[c.b] - (a.center - own.start[c.a])).dot(c.normal);
    const double depth = -deepest - moved;
    if (depth <= 0.0) continue;
    a.center -= c.normal * (depth * ima / inv_sum);
    b.center += c.normal * (depth * imb / inv_sum);
  }
}

// Moves a body's transform along with a correction of its centre and a small rotation dθ: the
// rotation is advanced by q ← normalize(q + dθ perp(q)) instead of a sine and cosine per point
// (the transforms are recomputed exactly from the angles at the end of the stage).
void rotate(Body& b, double d_angle) {
  if (d_angle != 0.0) {
    b.angle += d_angle;
    const double c = b.xf.q.c - d_angle * b.xf.q.s, s = b.xf.q.s + d_angle * b.xf.q.c;
    const double inv = 1.0 / std::sqrt(c * c + s * s);
    b.xf.q = {c * inv, s * inv};
  }
  b.xf.p = b.center - b.xf.q.apply(b.local_center);
}

void nonlinearGaussSeidel(WorldImpl& w) {
  const double beta = w.def.position_correction_rate;
  constexpr double kMaxCorrection = 0.2;  // m per point and pass, so a deep overlap separates gradually
  for (int it = 0; it < w.def.position_iterations; ++it) {
    double deepest = 0.0;
    for (size_t j = 0; j < w.solved.size(); ++j) {
      const Contact& c = w.contacts[w.solved[j]];
      if (w.exact_contacts.exact[j]) continue;  // solved with its island (exactContactPositions)
      const SolverPrepared& local = w.solver_prepared[j];  // the points fixed to their bodies (contact_solver.cpp)
      Body& a = w.bodies[c.a];
      Body& b = w.bodies[c.b];
      const double ima = invMass(w, c.a), imb = invMass(w, c.b), iia = invInertia(w, c.a), iib = invInertia(w, c.b);
      if (ima + imb == 0.0) continue;
      for (int i = 0; i < c.count; ++i) {
        const Vec2 n = a.xf.q.apply(local.local_normal);
        const Vec2 pa = a.xf.apply(local.local_a[i]), pb = b.xf.apply(local.local_b[i]);
        const double separation = (pb - pa).dot(n);
        deepest = std::min(deepest, separation);
        const double correction = std::clamp(beta * (separation + c.slop), -kMaxCorrection, 0.0);
        if (correction == 0.0) continue;
        const Vec2 p = 0.5 * (pa + pb);
        const Vec2 ra = p - a.center, rb = p - b.center;
        const double rna = cross(ra, n), rnb = cross(rb, n);
        const double k = ima + imb + iia * rna * rna + iib * rnb * rnb;
        const Vec2 impulse = (-correction / k) * n;
        a.center -= ima * impulse;
        b.center += imb * impulse;
        rotate(a, -iia * cross(ra, impulse));
        rotate(b, iib * cross(rb, impulse));
      }
    }
    if (deepest >= -3.0 * w.def.allowed_penetration) break;  // close enough: stop early
  }
}

// A kinematic body whose velocity was set between steps jumps to it at the start of the step and
// moves by h v_new (integrator.cpp). What it carries by friction follows the jump at once, by an
// impulse, not by a force spread over the step: that part of the body's velocity change moves it
// for the whole step (τ = h), and only the rest by the contact's τ. Otherwise, under RK4 (κ = ½), a
// crate on an accelerating platform trails it by h v / 2. The part is the jump of the carrying body
// at the carried one's centre, ΔV = Δv_k + Δω_k × (c − c_k), scaled by how much of it the body took,
// s = clamp(Δv·ΔV / |ΔV|², 0, 1) (1 when held by static friction, less when it slides):
//   Δc = τ Δv + (h − τ) s ΔV,   Δθ = τ Δω + (h − τ) s Δω_k
// The carrier is the jumping kinematic body the body presses hardest (Σ P of their contact points).
void applyContactDisplacement(WorldImpl& w, PositionCorrectionScratch& own, double dt) {
  const size_t n = w.bodies.size();
  // Impulse-weighted overlap time per body.
  own.overlap_time.assign(n, 0.0);
  own.overlap_weight.assign(n, 0.0);
  const bool carrying = w.kinematic_jumped && w.kinematic_uid.size() == n;
  if (carrying) {
    own.carrier.assign(n, UINT32_MAX);
    own.carrier_weight.assign(n, 0.0);
  }
  const auto jumped = [&](uint32_t k) {
    const Body& b = w.bodies[k];
    return b.isKinematic() && w.kinematic_uid[k] == b.uid &&
           (w.kinematic_jump[k] != Vec2::Zero() || w.kinematic_angular_jump[k] != 0.0);
  };
  for (size_t j = 0; j < w.solved.size(); ++j) {
    const Contact& c = w.contacts[w.solved[j]];
    const SolverPrepared& prepared = w.solver_prepared[j];
    double total = 0.0;
    for (int i = 0; i < c.count; ++i) {
      const double p = c.points[i].normal_impulse;
      total += p;
      own.overlap_time[c.a] += p * prepared.overlap_time[i];
      own.overlap_time[c.b] += p * prepared.overlap_time[i];
      own.overlap_weight[c.a] += p;
      own.overlap_weight[c.b] += p;
    }
    if (!carrying) continue;
    for (auto [carried, by] : {std::pair{c.a, c.b}, std::pair{c.b, c.a}}) {
      if (total > own.carrier_weight[carried] && jumped(by)) {
        own.carrier_weight[carried] = total;
        own.carrier[carried] = by;
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (!w.alive[i] || own.overlap_weight[i] <= 0.0) continue;
    Body& b = w.bodies[i];
    if (!w.isActive(static_cast<uint32_t>(i))) continue;
    const double tau = own.overlap_time[i] / own.overlap_weight[i];
    const Vec2 dv = b.velocity - w.solve_start_velocity[i];
    const double dw = b.angular_velocity - w.solve_start_angular_velocity[i];
    const Vec2 center = b.center;
    b.center += tau * dv;
    b.angle += tau * dw;
    if (!carrying || own.carrier[i] == UINT32_MAX || tau >= dt) continue;
    const uint32_t k = own.carrier[i];
    const Vec2 jump = w.kinematic_jump[k] + cross(w.kinematic_angular_jump[k], center - w.bodies[k].center);
    const double size = jump.squaredNorm();
    if (!(size > 0.0)) continue;
    const double s = std::clamp(dv.dot(jump) / size, 0.0, 1.0);
    b.center += ((dt - tau) * s) * jump;
    b.angle += ((dt - tau) * s) * w.kinematic_angular_jump[k];
  }
}

}  // namespace

void correctPositions(WorldImpl& w, const StepContext& ctx) {
  PositionCorrectionScratch& own = w.position_correction.get();
  const size_t n = w.bodies.size();
  own.start.resize(n);
  own.start_angle.resize(n);
  for (size_t i = 0; i < n; ++i) {
    own.start[i] = w.bodies[i].center;
    own.start_angle[i] = w.bodies[i].angle;
  }
  const std::vector<double> none;  // no contact displaced a body this step
  if (w.solved.empty()) {  // no contacts, or all of them solved by the soft step
    correctJointPositions(w, ctx.dt, none);
    return;
  }
  const bool displaced = ctx.settings.contact_displacement;
  if (displaced) applyContactDisplacement(w, own, ctx.dt);
  switch (ctx.settings.position_correction) {
    case PositionCorrection::LinearProjection:
      linearProjection(w, own);
      break;
    case PositionCorrection::NonlinearGaussSeidel:
      for (size_t i = 0; i < n; ++i)  // the pass reads the transforms the displacement moved
        if (w.alive[i] && (w.bodies[i].center != own.start[i] || w.bodies[i].angle != own.start_angle[i]))
          WorldImpl::syncTransform(w.bodies[i]);
      nonlinearGaussSeidel(w);
      exactContactPositions(w);
      break;
  }
  for (size_t i = 0; i < n; ++i) {
    const Body& b = w.bodies[i];
    if (w.alive[i] && (b.center != own.start[i] || b.angle != own.start_angle[i]))
      WorldImpl::syncTransform(w.bodies[i]);
  }
  correctJointPositions(w, ctx.dt, displaced ? own.overlap_weight : none);  // the joints' errors, at the positions the contacts were corrected to
}

}  // namespace rigidlab

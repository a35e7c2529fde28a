// Stage 4 of the step, default solver: the soft step (WorldDef::contact_solver = SoftStep).
// E. Catto, "Solver2D" (2024) and Box2D v3's solver: sub-stepping with soft contact constraints
// and relaxation. Why: sequential impulses with a separate position pass (contact_solver.cpp,
// position_correction.cpp) cannot carry the weight of a hundred rows of boxes to the ground within
// one step, so tall piles sink and spread (a pyramid of base 100 collapses within 5 s at 10
// iterations, measured); cutting the step into sub-steps, each of which applies its share of
// gravity and solves the contacts right after, makes each sub-step's problem small and lets the
// solver see the positions move.
//
// How it fits the pipeline. Integration has already moved every body by the step's forces (RK4 by
// default), and the contacts were found at those positions. Bodies that take part in a contact are
// put back at the start of the step; their velocity change from the integrator, Δv, is handed out
// in n equal kicks (Δv/n per sub-step). Each sub-step of h = dt/n then:
//   1. kick:       v += Δv/n, plus the warm start: each point's impulse of the previous sub-step
//                  (or the previous step)
//   2. solve:      soft contact impulses with a push out of overlap
//   3. move:       c += h v, θ += h ω
//   4. relax:      the same without the push, so that the push moves positions but leaves no
//                  velocity behind (no bounce from resolving an overlap)
// and after the last sub-step, restitution. Bodies that no impulse touched keep the integrator's
// result exactly, so free flight near a surface is as accurate as free flight anywhere.
//
// Separation without collision detection: the normal n is held fixed and the contact anchors r_A,
// r_B (from the centres at detection) turn with their bodies:
//   s = s₀ + (Δc_B + q_B r_B − Δc_A − q_A r_A)·n − (r_B − r_A)·n        (Box2D v3 contact_solver.c)
// where Δc, q are the displacement and rotation since detection.
//
// Soft constraint (Catto, "Soft Step", GDC 2011; Solver2D): a contact behaves like a spring of
// frequency f and damping ratio ζ integrated with the implicit sub-step h. With ω = 2πf,
//   a₁ = 2ζ + hω,  a₂ = hω a₁,  a₃ = 1/(1 + a₂),  bias rate β = ω/a₁
// and for each point the complementarity problem
//   w = v_n + b + γ P ≥ 0,  P ≥ 0,  w·P = 0
// with b = β s and γ = K/a₂ (K = 1/m_n) while overlapping (s ≤ 0) in the solve; b = s/h, γ = 0
// for a gap (speculative: the points may close it in this sub-step, not more); b = γ = 0 in the
// relax pass. One point's update is λ = −w/(K + γ); written with Box2D's mass and impulse scales
// a₂a₃ and a₃ it is λ = −m_n (a₂a₃ v_n + a₂a₃ β s) − a₃ P. The push −β s is capped at
// WorldDef::contact_push_speed; contacts with a static or sleeping body are twice as stiff.
//
// Stiffness and sub-steps (measured on the bench scenes, see README "Performance"): the contacts
// are springs, so a column of boxes buckles if they are too soft (a 20-box stack with boxes
// staggered by 1 cm topples at 30 Hz and stands from about 55 Hz), and with one pass per sub-step
// the iteration stops converging once f·h exceeds about 1/8 (pyramids creep sideways). Hence the
// defaults 60 Hz and 8 sub-steps, and the hertz is capped at 1/8 of the sub-step rate as in Box2D
// v3.2.
#include <algorithm>
#include <cmath>

#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

struct Softness {
  double bias_rate, mass_scale, impulse_scale;
};

Softness makeSoft(double hertz, double zeta, double h) {
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * zeta + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

inline void apply(SoftBody& a, SoftBody& b, const SoftPoint& p, double px, double py) {
  a.vx -= a.im * px;
  a.vy -= a.im * py;
  a.w -= a.ii * (p.rax * py - p.ray * px);
  b.vx += b.im * px;
  b.vy += b.im * py;
  b.w += b.ii * (p.rbx * py - p.rby * px);
}

// ((v_B + ω_B × r_B) − (v_A + ω_A × r_A))·d
inline double relative(const SoftBody& a, const SoftBody& b, const SoftPoint& p, double dx, double dy) {
  const double rvx = b.vx - b.w * p.rby - a.vx + a.w * p.ray;
  const double rvy = b.vy + b.w * p.rbx - a.vy - a.w * p.rax;
  return rvx * dx + rvy * dy;
}

// The normal impulses of a two-point contact together, as a 2×2 linear complementarity problem
// (as contact_solver.cpp's block solver, with the compliances on the diagonal): find P ≥ 0 with
// w = (K + diag γ) P + r ≥ 0, w·P = 0, trying both points pushing, one, the other, none. Solving
// the two points one after the other instead leaves the first with a residual in every pass, which
// turns the bodies: pyramids walk sideways (measured).
inline void solveBlock(SoftBody& a, SoftBody& b, SoftContact& c, const double vn[2], const double bias[2], const double g[2]) {
  SoftPoint &p1 = c.p[0], &p2 = c.p[1];
  const double a1 = p1.pn, a2 = p2.pn;
  const double k11 = p1.k, k22 = p2.k, k12 = c.k12;
  const double r1 = vn[0] + bias[0] - (k11 * a1 + k12 * a2);
  const double r2 = vn[1] + bias[1] - (k12 * a1 + k22 * a2);
  const double m11 = k11 + g[0], m22 = k22 + g[1];
  const double inv_det = 1.0 / (m11 * m22 - k12 * k12);
  double x1 = (k12 * r2 - m22 * r1) * inv_det;  // both points push
  double x2 = (k12 * r1 - m11 * r2) * inv_det;
  if (!(x1 >= 0.0 && x2 >= 0.0)) {
    x1 = -r1 / m11;  // only the first
    x2 = 0.0;
    if (!(x1 >= 0.0 && k12 * x1 + r2 >= 0.0)) {
      x1 = 0.0;  // only the second
      x2 = -r2 / m22;
      if (!(x2 >= 0.0 && k12 * x2 + r1 >= 0.0)) {
        x1 = x2 = 0.0;  // none: both separating
        if (!(r1 >= 0.0 && r2 >= 0.0)) return;  // no case fits (round-off)
      }
    }
  }
  const double d1 = x1 - a1, d2 = x2 - a2;
  p1.pn = x1;
  p2.pn = x2;
  apply(a, b, p1, d1 * c.nx, d1 * c.ny);
  apply(a, b, p2, d2 * c.nx, d2 * c.ny);
}

// One pass over a contact: normal impulses first, then friction against the new normal impulses
// (Box2D v3's order: the normal impulse is this sub-step's load, which friction should see).
template <bool kSoft>
inline void solve(std::vector<SoftBody>& bodies, SoftContact& c, double inv_h) {
  SoftBody& a = bodies[c.a];
  SoftBody& b = bodies[c.b];
  const double nx = c.nx, ny = c.ny;
  const double dx = b.dx - a.dx, dy = b.dy - a.dy;
  double vn[2], bias[2], g[2];
  for (int i = 0; i < c.count; ++i) {
    const SoftPoint& p = c.p[i];
    const double sx = dx + (b.qc * p.rbx - b.qs * p.rby) - (a.qc * p.rax - a.qs * p.ray);
    const double sy = dy + (b.qs * p.rbx + b.qc * p.rby) - (a.qs * p.rax + a.qc * p.ray);
    const double s = p.base + sx * nx + sy * ny;
    if (s > 0.0) {
      bias[i] = s * inv_h;
      g[i] = 0.0;
    } else if (kSoft) {
      bias[i] = std::max(c.bias_rate * s, c.bias_floor);
      g[i] = c.g[i];
    } else {
      bias[i] = g[i] = 0.0;
    }
    vn[i] = relative(a, b, p, nx, ny);
  }
  if (c.block) {
    solveBlock(a, b, c, vn, bias, g);
  } else {
    for (int i = 0; i < c.count; ++i) {
      SoftPoint& p = c.p[i];
      const double v = i == 0 ? vn[0] : relative(a, b, p, nx, ny);
      const double total = std::max(p.pn - (v + bias[i] + g[i] * p.pn) / (p.k + g[i]), 0.0);
      const double lambda = total - p.pn;
      p.pn = total;
      apply(a, b, p, lambda * nx, lambda * ny);
    }
  }
  const double tx = ny, ty = -nx;  // t = n × 1
  bool acted = false;
  for (int i = 0; i < c.count; ++i) {
    SoftPoint& p = c.p[i];
    const double limit = p.friction * p.pn;
    const double total = std::clamp(p.pt - p.tangent_mass * relative(a, b, p, tx, ty), -limit, limit);
    const double lambda = total - p.pt;
    p.pt = total;
    apply(a, b, p, lambda * tx, lambda * ty);
    acted |= (p.pn != 0.0) | (p.pt != 0.0);
  }
  c.acted |= acted;
}

// The warm start of the next sub-step: the velocity change the contact's final impulses cause,
// added up per body and applied with the next kick (velocity changes add, so this is the same as
// applying the impulses again at the start of the next sub-step, without another pass).
inline void addWarmStart(std::vector<SoftBody>& bodies, std::vector<SoftKick>& warm, const SoftContact& c) {
  const SoftBody& a = bodies[c.a];
  const SoftBody& b = bodies[c.b];
  SoftKick& wa = warm[c.a];
  SoftKick& wb = warm[c.b];
  const double tx = c.ny, ty = -c.nx;
  for (int i = 0; i < c.count; ++i) {
    const SoftPoint& p = c.p[i];
    const double px = p.pn * c.nx + p.pt * tx, py = p.pn * c.ny + p.pt * ty;
    wa.vx -= a.im * px;
    wa.vy -= a.im * py;
    wa.w -= a.ii * (p.rax * py - p.ray * px);
    wb.vx += b.im * px;
    wb.vy += b.im * py;
    wb.w += b.ii * (p.rbx * py - p.rby * px);
  }
}

// Restitution after the sub-steps (Box2D v3's b2ApplyRestitution), for points that pushed and
// were approaching faster than the threshold when they first did. The target is the bounce of the
// impact speed less what the step's forces took away after the impact (they kept pressing the
// bodies together for the remaining sub-steps):
//   v_target = −e v_impact + (n − 1 − k) · kick      (kick: the forces' normal velocity per sub-step)
// Friction acts on the restitution impulse too (Coulomb over the whole collision, origin.md §10;
// accuracy.md §3.11: experiment 1's friction impulse is f times the full normal impulse).
void restitute(std::vector<SoftBody>& bodies, const SoftContact& c, SoftTally& t, double threshold, int substeps) {
  SoftBody& a = bodies[c.a];
  SoftBody& b = bodies[c.b];
  const double nx = c.nx, ny = c.ny, tx = ny, ty = -nx;
  for (int i = 0; i < c.count; ++i) {
    const SoftPoint& p = c.p[i];
    if (t.impact[i] < 0 || t.approach[i] > -threshold) continue;
    const double target = -t.restitution * t.approach[i] + (substeps - 1 - t.impact[i]) * t.kick[i];
    const double vn = relative(a, b, p, nx, ny);
    const double normal = std::max(-(vn - target) / p.k, -p.pn);
    if (normal <= 0.0) continue;
    apply(a, b, p, normal * nx, normal * ny);
    t.total_n[i] += normal;
    const double limit = p.friction * normal;
    const double tangent = std::clamp(-p.tangent_mass * relative(a, b, p, tx, ty), -limit, limit);
    apply(a, b, p, tangent * tx, tangent * ty);
    t.total_t[i] += tangent;
  }
}

// Impact speeds for restitution: the normal velocity of each point before the first solve that
// gives it an impulse.
void recordImpacts(const SoftContact& c, SoftTally& t, const double before[2], int substep) {
  for (int i = 0; i < c.count; ++i)
    if (t.impact[i] < 0 && c.p[i].pn > 0.0) {
      t.impact[i] = substep;
      t.approach[i] = before[i];
    }
}

}  // namespace

void softStep(WorldImpl& w) {
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  const int substeps = w.def.substeps;
  const double h = w.dt / substeps, inv_h = 1.0 / h;

  const auto& solved = w.soft_solved;  // chosen by solveContacts (contact_solver.cpp)
  if (solved.empty()) return;

  // Bodies: the moving ones of those contacts go back to the start of the step.
  auto& bodies = w.soft_bodies;
  auto& kick = w.soft_kick;
  auto& warm = w.soft_warm;
  auto& moved = w.soft_moved;
  auto& angle = w.soft_angle;
  auto& list = w.soft_list;
  bodies.resize(n);
  kick.resize(n);
  angle.resize(n);
  warm.assign(n, SoftKick{0.0, 0.0, 0.0});
  moved.assign(n, 0);
  for (uint32_t k : solved) {
    const Contact& c = w.contacts[k];
    if (w.isActive(c.a)) moved[c.a] = 1;
    if (w.isActive(c.b)) moved[c.b] = 1;
  }
  list.clear();
  for (uint32_t i = 0; i < n; ++i) {
    if (!moved[i]) {
      bodies[i] = {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};  // static, asleep or not in contact
      kick[i] = {0.0, 0.0, 0.0};
      continue;
    }
    list.push_back(i);
    const Body& b = w.bodies[i];
    const Vec2 v0 = w.start_velocity[i];
    const double w0 = w.start_angular_velocity[i];
    const Vec2 d = w.start_center[i] - b.center;
    angle[i] = w.start_angle[i] - b.angle;
    bodies[i] = {v0.x(), v0.y(), w0, d.x(), d.y(), std::cos(angle[i]), std::sin(angle[i]), b.inv_mass, b.inv_inertia};
    kick[i] = {(b.velocity.x() - v0.x()) / substeps, (b.velocity.y() - v0.y()) / substeps,
               (b.angular_velocity - w0) / substeps};
  }

  // Constraints.
  const double hertz = std::min(w.def.contact_hertz, 0.125 * inv_h);
  const Softness soft = makeSoft(hertz, w.def.contact_damping_ratio, h);
  const Softness stiff = makeSoft(2.0 * hertz, w.def.contact_damping_ratio, h);
  auto& constraints = w.soft_contacts;
  auto& tallies = w.soft_tally;
  constraints.resize(solved.size());
  tallies.resize(solved.size());
  for (size_t k = 0; k < solved.size(); ++k) {
    const Contact& c = w.contacts[solved[k]];
    const SoftBody& a = bodies[c.a];
    const SoftBody& b = bodies[c.b];
    const bool fixed = (a.im == 0.0 && a.ii == 0.0) || (b.im == 0.0 && b.ii == 0.0);
    const Softness& s = fixed ? stiff : soft;
    SoftContact& sc = constraints[k];
    SoftTally& t = tallies[k];
    sc.a = c.a;
    sc.b = c.b;
    sc.count = static_cast<uint8_t>(c.count);
    sc.acted = false;
    sc.bounce = c.restitution > 0.0;
    sc.nx = c.normal.x();
    sc.ny = c.normal.y();
    sc.bias_rate = s.bias_rate;
    sc.bias_floor = -w.def.contact_push_speed / s.mass_scale;  // the push, −β s ≤ push speed
    t.restitution = c.restitution;
    const Vec2 nrm = c.normal, tan = cross(c.normal, 1.0);
    const Vec2 ca = w.bodies[c.a].center, cb = w.bodies[c.b].center;
    const SoftKick ka = kick[c.a], kb = kick[c.b];
    for (int i = 0; i < c.count; ++i) {
      const ContactPoint& cp = c.points[i];
      SoftPoint& p = sc.p[i];
      const Vec2 ra = cp.point - ca, rb = cp.point - cb;
      p.rax = ra.x();
      p.ray = ra.y();
      p.rbx = rb.x();
      p.rby = rb.y();
      p.base = cp.separation - (rb - ra).dot(nrm);
      const double rna = cross(ra, nrm), rnb = cross(rb, nrm), rta = cross(ra, tan), rtb = cross(rb, tan);
      p.k = a.im + b.im + a.ii * rna * rna + b.ii * rnb * rnb;
      const double kt = a.im + b.im + a.ii * rta * rta + b.ii * rtb * rtb;
      p.tangent_mass = kt > 0.0 ? 1.0 / kt : 0.0;
      sc.g[i] = p.k * s.impulse_scale / s.mass_scale;  // γ = K/a₂
      // f_s or f_d from the slip at the start of the step (origin.md §10).
      const double slip = relative(a, b, p, tan.x(), tan.y());  // bodies hold the start velocities
      p.friction = std::abs(slip) < w.def.static_friction_speed ? c.static_friction : c.friction;
      p.pn = w.def.warm_starting ? cp.normal_impulse : 0.0;
      p.pt = w.def.warm_starting ? cp.tangent_impulse : 0.0;
      t.total_n[i] = t.total_t[i] = 0.0;
      t.approach[i] = 0.0;
      t.impact[i] = -1;
      t.kick[i] = (kb.vx - kb.w * rb.y() - ka.vx + ka.w * ra.y()) * nrm.x() +
                  (kb.vy + kb.w * rb.x() - ka.vy - ka.w * ra.x()) * nrm.y();
    }
    // Two points: k12 = 1/m_A + 1/m_B + (r_A1×n)(r_A2×n)/I_A + (r_B1×n)(r_B2×n)/I_B; solved together
    // when K is well conditioned (Box2D 2.4's rule, as contact_solver.cpp).
    sc.block = false;
    if (c.count == 2) {
      const SoftPoint &p1 = sc.p[0], &p2 = sc.p[1];
      const double rn1a = p1.rax * nrm.y() - p1.ray * nrm.x(), rn1b = p1.rbx * nrm.y() - p1.rby * nrm.x();
      const double rn2a = p2.rax * nrm.y() - p2.ray * nrm.x(), rn2b = p2.rbx * nrm.y() - p2.rby * nrm.x();
      sc.k12 = a.im + b.im + a.ii * rn1a * rn2a + b.ii * rn1b * rn2b;
      sc.block = p1.k * p1.k < 1000.0 * (p1.k * p2.k - sc.k12 * sc.k12);
    }
    // The first sub-step's warm start: the impulses carried over from the previous step.
    for (int i = 0; i < c.count; ++i) sc.acted |= (sc.p[i].pn != 0.0) | (sc.p[i].pt != 0.0);
    addWarmStart(bodies, warm, sc);
  }

  // Sub-steps.
  for (int step = 0; step < substeps; ++step) {
    for (uint32_t i : list) {  // kick and warm start
      SoftBody& b = bodies[i];
      b.vx += kick[i].vx + warm[i].vx;
      b.vy += kick[i].vy + warm[i].vy;
      b.w += kick[i].w + warm[i].w;
      warm[i] = {0.0, 0.0, 0.0};
    }
    for (size_t k = 0; k < constraints.size(); ++k) {
      SoftContact& c = constraints[k];
      if (c.bounce) {
        double before[2];
        for (int i = 0; i < c.count; ++i) before[i] = relative(bodies[c.a], bodies[c.b], c.p[i], c.nx, c.ny);
        solve<true>(bodies, c, inv_h);
        recordImpacts(c, tallies[k], before, step);
      } else {
        solve<true>(bodies, c, inv_h);
      }
    }
    for (uint32_t i : list) {  // move
      SoftBody& b = bodies[i];
      b.dx += h * b.vx;
      b.dy += h * b.vy;
      angle[i] += h * b.w;
      // q ← normalise(q + hω q⊥): the rotation by hω to second order (Box2D v3 b2IntegrateRotation).
      const double c = b.qc - h * b.w * b.qs, s = b.qs + h * b.w * b.qc;
      const double inv = 1.0 / std::sqrt(c * c + s * s);
      b.qc = c * inv;
      b.qs = s * inv;
    }
    const bool last = step + 1 == substeps;
    for (size_t k = 0; k < constraints.size(); ++k) {  // relax
      SoftContact& c = constraints[k];
      solve<false>(bodies, c, inv_h);
      if (!last) addWarmStart(bodies, warm, c);
      SoftTally& t = tallies[k];
      for (int i = 0; i < c.count; ++i) {  // each sub-step applies its final impulses in all
        t.total_n[i] += c.p[i].pn;
        t.total_t[i] += c.p[i].pt;
      }
    }
  }
  for (size_t k = 0; k < constraints.size(); ++k)
    if (constraints[k].bounce) restitute(bodies, constraints[k], tallies[k], w.def.restitution_threshold, substeps);

  // Write back: impulses for warm starting and reports; bodies that some impulse acted on take the
  // sub-stepped state, the others keep the integrator's.
  for (size_t k = 0; k < constraints.size(); ++k) {
    const SoftContact& sc = constraints[k];
    const SoftTally& t = tallies[k];
    Contact& c = w.contacts[solved[k]];
    for (int i = 0; i < c.count; ++i) {
      ContactPoint& cp = c.points[i];
      cp.normal_impulse = sc.p[i].pn;
      cp.tangent_impulse = sc.p[i].pt;
      cp.step_normal_impulse = t.total_n[i];
      cp.step_tangent_impulse = t.total_t[i];
    }
    if (!sc.acted) continue;
    if (moved[c.a]) moved[c.a] = 2;
    if (moved[c.b]) moved[c.b] = 2;
  }
  for (uint32_t i : list) {
    if (moved[i] != 2) continue;
    Body& b = w.bodies[i];
    const SoftBody& s = bodies[i];
    b.center += Vec2(s.dx, s.dy);
    b.angle += angle[i];
    b.velocity = Vec2(s.vx, s.vy);
    b.angular_velocity = s.w;
    WorldImpl::syncTransform(b);
  }
}

}  // namespace rigidlab

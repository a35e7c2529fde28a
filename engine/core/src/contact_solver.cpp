// Stage 4 of the step: sequential impulses on the contact velocities (docs/design/thesis.md §8–10; E. Catto,
// "Iterative Dynamics with Temporal Coherence", GDC 2005; box2d-lite Arbiter::ApplyImpulse).
//
// For each contact point with normal n (A → B) and tangent t = n × 1:
//   relative velocity     v_r = (v_B + ω_B × r_B) − (v_A + ω_A × r_A)
//   effective mass        m_n = 1 / (1/m_A + 1/m_B + (r_A × n)²/I_A + (r_B × n)²/I_B)
//   restitution target    v_target = −e (v_r·n) if v_r·n < −threshold, else 0; computed once before
//                         the iterations so restitution is not re-applied each pass (docs/design/thesis.md §9),
//                         and taken at the moment the overlap began (prepare() below)
//   normal impulse        λ = −m_n (v_r·n − v_target); accumulated P_n = max(P_n + λ, 0)
//   friction impulse      λ_t = −m_t (v_r·t); accumulated P_t clamped to ±f P_n, using the
//                         accumulated normal impulse, not the last increment (docs/design/thesis.md §10, Catto)
// With warm starting (WorldDef::warm_starting) each point starts from the impulses it had in the
// previous step (matched by feature id); without it, from zero as in the thesis.
// f is the static coefficient f_s when the tangential slip at the start of the step is below
// WorldDef::static_friction_speed, else the dynamic f_d (docs/design/thesis.md §10). In each pass friction comes
// first and the normal impulses last (non-penetration matters most); a contact with two points
// solves its normal impulses together as a 2×2 problem (solveBlock).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "contact_exact.h"
#include "joint_solver.h"
#include "mechanism_step.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

// The contact solver's scratch (WorldImpl::contact_solver holds it, opaque to the other stages):
// compact working copies written anew in each step before they are read.
struct ContactSolverScratch {
  std::vector<SolverBody> velocities;  // per body slot
  std::vector<SolverContact> contacts;  // per solved contact
  std::vector<SolverSurface> surfaces;  // the solved contacts with surface effects (SolverContact::surface)
  std::vector<double> island_joint_sizes;  // per constraint of an island: its joint's impulse size
  std::vector<uint32_t> island_points;  // per island root: contact points (chooseSolvers)
};

namespace {

inline Vec2 relativeVelocity(const Body& a, const Body& b, const Vec2& ra, const Vec2& rb) {
  return b.velocity + cross(b.angular_velocity, rb) - a.velocity - cross(a.angular_velocity, ra);
}

}  // namespace

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

namespace {

void prepare(WorldImpl& w, double dt, Contact& c, SolverPrepared& out, double tangent_speed) {
  const double resting_weight = restingWeight(w.def.integrator);
  const Body& a = w.bodies[c.a];
  const Body& b = w.bodies[c.b];
  const Vec2 n = c.normal;
  const Vec2 t = cross(n, 1.0);
  if (w.def.position_correction == PositionCorrection::NonlinearGaussSeidel) {
    out.local_normal = a.xf.q.applyInverse(n);
    for (int i = 0; i < c.count; ++i) {
      const ContactPoint& cp = c.points[i];
      out.local_a[i] = a.xf.applyInverse(cp.point - 0.5 * cp.separation * n);
      out.local_b[i] = b.xf.applyInverse(cp.point + 0.5 * cp.separation * n);
    }
  }
  for (int i = 0; i < c.count; ++i) {
    ContactPoint& cp = c.points[i];
    const Vec2 ra = cp.point - a.center, rb = cp.point - b.center;
    out.ra[i] = ra;
    out.rb[i] = rb;
    const double rna = cross(ra, n), rnb = cross(rb, n);
    const double kn = a.inv_mass + b.inv_mass + a.inv_inertia * rna * rna + b.inv_inertia * rnb * rnb;
    const double rta = cross(ra, t), rtb = cross(rb, t);
    const double kt = a.inv_mass + b.inv_mass + a.inv_inertia * rta * rta + b.inv_inertia * rtb * rtb;
    out.normal_mass[i] = kn > 0.0 ? 1.0 / kn : 0.0;
    out.tangent_mass[i] = kt > 0.0 ? 1.0 / kt : 0.0;

    const double vn = relativeVelocity(a, b, ra, rb).dot(n);
    // How long the point has been overlapping within this step: a new contact since depth / speed
    // before the end; a persisting one all step long, under a force spread over the step, whose
    // position effect is the integrator's weight κ of the velocity gained (position_correction.cpp).
    if (cp.persisted) {
      out.overlap_time[i] = resting_weight * dt;
    } else {
      out.overlap_time[i] = (vn < 0.0 && cp.separation < 0.0) ? std::min(dt, cp.separation / vn) : 0.0;
    }
    // Relative velocity of the point at the start of the step.
    const Vec2 v_start = w.start_velocity[c.b] + cross(w.start_angular_velocity[c.b], rb) - w.start_velocity[c.a] -
                         cross(w.start_angular_velocity[c.a], ra);
    // The slip is measured against the surface's own motion (ContactSurface::tangent_speed, else 0).
    out.friction[i] = std::abs(v_start.dot(t) - tangent_speed) < w.def.static_friction_speed ? c.static_friction : c.friction;
    if (!w.def.warm_starting) {
      cp.normal_impulse = 0.0;
      cp.tangent_impulse = 0.0;
    }
    double& target = out.target_velocity[i];
    target = 0.0;
    if (cp.separation > 0.0) {
      // Speculative point: the bodies may close the gap during the next step, not more.
      target = -cp.separation / dt;
      // A body that would travel more than its inner radius into the other bounces now (from the
      // gap), so it cannot pass through; so does one that continuous detection put at the wall.
      const bool fast = w.ccd_hit[c.a] || w.ccd_hit[c.b] ||
                        -vn * dt > std::min(w.shapes[c.shape_a].geometry.inradius, w.shapes[c.shape_b].geometry.inradius);
      if (fast && vn < -w.def.restitution_threshold) target = -c.restitution * vn;
      if (!fast && vn < -w.def.restitution_threshold && c.restitution > 0.0 && vn * dt < -cp.separation) {
        // A bouncing impact: let it happen next step, where restitution is taken at the moment of
        // contact, instead of stopping the body at the surface here.
        out.normal_mass[i] = out.tangent_mass[i] = 0.0;
        cp.normal_impulse = cp.tangent_impulse = 0.0;
      }
    } else if (vn < -w.def.restitution_threshold) {
      // Restitution at the moment the overlap began, τ before the end of the step: the approach
      // speed then was v_n − a τ, with a the normal acceleration over the step (from the velocity
      // at its start); after the bounce the same acceleration acts for τ:
      //   v_target = −e (v_n − a τ) + a τ = −e v_n + (1 + e) a τ        (docs/design/accuracy.md §3.12)
      const double accel = (vn - v_start.dot(n)) / dt;
      target = std::max(0.0, -c.restitution * vn + (1.0 + c.restitution) * accel * out.overlap_time[i]);
    }
    cp.bounced = !(target <= 0.0);
  }
  // Two points: K = [[k11, k12], [k12, k22]], k_ij = 1/m_A + 1/m_B + (r_Ai×n)(r_Aj×n)/I_A + (r_Bi×n)(r_Bj×n)/I_B.
  // Solved together when K is well conditioned; two nearly identical points make it singular, and
  // then the points are solved one by one (Box2D 2.4's rule, condition number ≤ 1000).
  c.block = false;
  if (c.count == 2 && out.normal_mass[0] != 0.0 && out.normal_mass[1] != 0.0) {
    const double rn1a = cross(out.ra[0], n), rn1b = cross(out.rb[0], n), rn2a = cross(out.ra[1], n),
                 rn2b = cross(out.rb[1], n);
    const double k11 = a.inv_mass + b.inv_mass + a.inv_inertia * rn1a * rn1a + b.inv_inertia * rn1b * rn1b;
    const double k22 = a.inv_mass + b.inv_mass + a.inv_inertia * rn2a * rn2a + b.inv_inertia * rn2b * rn2b;
    const double k12 = a.inv_mass + b.inv_mass + a.inv_inertia * rn1a * rn2a + b.inv_inertia * rn1b * rn2b;
    const double det = k11 * k22 - k12 * k12;
    if (k11 * k11 < 1000.0 * det) {
      c.block = true;
      const Mat22 k = (Mat22() << k11, k12, k12, k22).finished();
      const Mat22 k_inverse = k.inverse();
      out.k11 = k(0, 0);
      out.k12 = k(0, 1);
      out.k22 = k(1, 1);
      out.i11 = k_inverse(0, 0);
      out.i12 = k_inverse(0, 1);
      out.i22 = k_inverse(1, 1);
    }
  }
}

// The iterations run on compact copies in plain doubles (contact.h: SolverBody, SolverContact).
inline void apply(SolverBody& a, SolverBody& b, const SolverPoint& p, double px, double py) {
  a.vx -= a.im * px;
  a.vy -= a.im * py;
  a.w -= a.ii * (p.rax * py - p.ray * px);
  b.vx += b.im * px;
  b.vy += b.im * py;
  b.w += b.ii * (p.rbx * py - p.rby * px);
}

// Relative velocity of the point along (dx, dy): ((v_B + ω_B × r_B) − (v_A + ω_A × r_A))·d.
inline double relative(const SolverBody& a, const SolverBody& b, const SolverPoint& p, double dx, double dy) {
  const double rvx = b.vx - b.w * p.rby - a.vx + a.w * p.ray;
  const double rvy = b.vy + b.w * p.rbx - a.vy - a.w * p.rax;
  return rvx * dx + rvy * dy;
}

// The normal impulses of a two-point contact as one 2×2 linear complementarity problem
// (E. Catto, Box2D 2.4 b2ContactSolver, block solver): find x ≥ 0 with v_n = K (x − a) + v_n0 ≥ 0
// and x_i v_n,i = 0, trying the four cases (both points pushing, one, the other, none).
[[gnu::always_inline]] inline void solveBlock(SolverBody& a, SolverBody& b, SolverContact& c) {
  SolverPoint &p1 = c.p[0], &p2 = c.p[1];
  const double a1 = p1.pn, a2 = p2.pn;
  // v_n = K x + r
  const double r1 = relative(a, b, p1, c.nx, c.ny) - p1.target - (c.k11 * a1 + c.k12 * a2);
  const double r2 = relative(a, b, p2, c.nx, c.ny) - p2.target - (c.k12 * a1 + c.k22 * a2);
  double x1, x2;
  x1 = -(c.i11 * r1 + c.i12 * r2);  // both points active
  x2 = -(c.i12 * r1 + c.i22 * r2);
  if (!(x1 >= 0.0 && x2 >= 0.0)) {
    x1 = -r1 / c.k11;  // only the first
    x2 = 0.0;
    if (!(x1 >= 0.0 && c.k12 * x1 + r2 >= 0.0)) {
      x1 = 0.0;  // only the second
      x2 = -r2 / c.k22;
      if (!(x2 >= 0.0 && c.k12 * x2 + r1 >= 0.0)) {
        x1 = x2 = 0.0;  // none: both separating
        if (!(r1 >= 0.0 && r2 >= 0.0)) return;  // no case fits (round-off, degenerate K)
      }
    }
  }
  const double d1 = x1 - a1, d2 = x2 - a2;
  p1.pn = x1;
  p2.pn = x2;
  apply(a, b, p1, d1 * c.nx, d1 * c.ny);
  apply(a, b, p2, d2 * c.nx, d2 * c.ny);
}

// Rolling resistance (Box2D v3's): an angular impulse on the relative turning, bounded by the
// resistance times the contact's total normal impulse.
inline void solveRolling(SolverBody& a, SolverBody& b, const SolverContact& c, SolverSurface& s) {
  if (!(s.rolling > 0.0)) return;
  const double limit = s.rolling * (c.p[0].pn + (c.count == 2 ? c.p[1].pn : 0.0));
  const double old = s.rolling_impulse;
  s.rolling_impulse = std::clamp(old - s.rolling_mass * (b.w - a.w), -limit, limit);
  const double lambda = s.rolling_impulse - old;
  a.w -= a.ii * lambda;
  b.w += b.ii * lambda;
}

// One pass over a contact: friction first, then the normal impulses, so non-penetration has the
// last word (Box2D's order); with the accumulated normal impulse of the previous pass bounding
// friction, a new contact gets its friction from the second pass on. kSurface: a contact with
// surface effects (ContactSurface): friction aims at the tangent speed instead of 0, and rolling
// resistance comes last.
template <bool kSurface>
[[gnu::noinline]] void solveContact(std::vector<SolverBody>& bodies, SolverContact& c, SolverSurface* surface) {
  SolverBody& a = bodies[c.a];
  SolverBody& b = bodies[c.b];
  const double tx = c.ny, ty = -c.nx;  // t = n × 1
  for (int i = 0; i < c.count; ++i) {
    SolverPoint& p = c.p[i];
    const double limit = p.friction * p.pn;
    if (limit == 0.0 && p.pt == 0.0) continue;  // no load, no friction: nothing to do (side contacts)
    double slip = relative(a, b, p, tx, ty);
    if constexpr (kSurface) slip -= surface->tangent_speed;
    const double total = std::clamp(p.pt - p.tangent_mass * slip, -limit, limit);
    const double lambda = total - p.pt;
    p.pt = total;
    apply(a, b, p, lambda * tx, lambda * ty);
  }
  if (c.block) {
    solveBlock(a, b, c);
  } else {
    for (int i = 0; i < c.count; ++i) {
      SolverPoint& p = c.p[i];
      const double total = std::max(p.pn - p.normal_mass * (relative(a, b, p, c.nx, c.ny) - p.target), 0.0);
      const double lambda = total - p.pn;
      p.pn = total;
      apply(a, b, p, lambda * c.nx, lambda * c.ny);
    }
  }
  if constexpr (kSurface) solveRolling(a, b, c, *surface);
}

// One pass over a contact with or without surface effects. Loops over many contacts test once
// whether any has them (WorldImpl::solver_surfaces empty), so that the plain pass runs as it is.
inline void solve(std::vector<SolverBody>& bodies, SolverContact& c, std::vector<SolverSurface>& surfaces) {
  if (c.surface == kNoSurface) {
    solveContact<false>(bodies, c, nullptr);
  } else {
    solveContact<true>(bodies, c, &surfaces[c.surface]);
  }
}

// Sequential impulses converge slowly when masses differ a lot: a 100 kg box on a 1 kg box needs
// ~50 passes to stop sinking, 1000:1 ~500 (measured). Small islands are cheap, so after the
// configured passes each island of at most kSmallIsland contact points keeps iterating until its
// normal impulses change by less than 1e-9 of their size, up to kMoreIterations times the
// configured count. Large islands (piles, pyramids) use the configured count only. Islands are
// independent, so the extra passes on one do not change another.
constexpr int kSmallIsland = 64;
// What a joint weighs in the choice of solver and the size of an island, in contact points: its
// rows, at most three. An island that sequential impulses take has fewer than soft_step_points
// (256) points, so at most 85 joints and kMaxDirectRows rows for their direct solve.
constexpr uint32_t kJointPoints = 3;
constexpr int kMoreIterations = 50;
// Islands with joints: their equalities are solved exactly (joint_direct.cpp) before and after the
// passes, and what the passes add (limits, motors, springs) converges slowly without being exact
// at the end anyway (a ragdoll's island took 320 to 490 extra passes, or all 490): a few more only.
constexpr int kMoreJointIterations = 3;

SoftBody viewOf(const SolverBody& s) { return {s.vx, s.vy, s.w, 0.0, 0.0, 1.0, 0.0, s.im, s.ii}; }
void storeView(SolverBody& s, const SoftBody& v) {
  if (s.im == 0.0 && s.ii == 0.0) return;  // immovable: unchanged (kinematic velocities too)
  s.vx = v.vx;
  s.vy = v.vy;
  s.w = v.w;
}

// One joint on the solver's velocities: its warm start, or a pass without position bias.
void solveJointVelocity(std::vector<SolverBody>& bodies, Joint& j, const JointStep& step, bool warm_start) {
  const auto solve = [&](const JointBodies& views) {
    if (warm_start) {
      warmStartJoint(j, views);
    } else {
      solveJoint(j, views, step, false);
    }
  };
  if (j.a != kWorldSlot && j.a != j.b && j.c == kWorldSlot && j.d == kWorldSlot) {
    // Every joint but a gear: body a, and b or the world; the views JointViews would make.
    SoftBody world{0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    SoftBody a = viewOf(bodies[j.a]), b = j.b == kWorldSlot ? world : viewOf(bodies[j.b]);
    solve({&a, j.b == kWorldSlot ? &world : &b, &world, &world});
    storeView(bodies[j.a], a);
    if (j.b != kWorldSlot) storeView(bodies[j.b], b);
    return;
  }
  JointViews<SolverBody> v(bodies, j, viewOf);
  solve(v.bodies);
  v.writeBack(bodies, storeView);
}

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The sum of a joint's accumulated impulses' sizes, to see whether more passes change them.
double impulseSize(const JointImpulses& p) {
  return std::abs(p.linear_x) + std::abs(p.linear_y) + std::abs(p.angular) + std::abs(p.perpendicular) +
         std::abs(p.axial) + std::abs(p.spring) + std::abs(p.motor) + std::abs(p.lower) + std::abs(p.upper) +
         std::abs(p.spring_x) + std::abs(p.spring_y);
}

void convergeSmallIslands(WorldImpl& w, ContactSolverScratch& own, std::vector<SolverBody>& bodies, std::vector<SolverContact>& constraints,
                          const JointStep& step) {
  const auto& joints = w.si_joints;
  if (constraints.empty() && joints.empty()) return;
  auto& parent = w.island_parent;  // scratch, also used by sleep.cpp at the end of the step
  parent.resize(w.bodies.size());
  for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto moves = [&](uint32_t slot) { return slot != kWorldSlot && (bodies[slot].im > 0.0 || bodies[slot].ii > 0.0); };
  const auto unite = [&](uint32_t a, uint32_t b) {
    parent[std::max(findRoot(parent, a), findRoot(parent, b))] = std::min(findRoot(parent, a), findRoot(parent, b));
  };
  for (const SolverContact& c : constraints)
    if (bodies[c.a].im > 0.0 && bodies[c.b].im > 0.0) unite(c.a, c.b);
  for (uint32_t k : joints) {
    const Joint& j = w.joints[k];
    uint32_t first = kWorldSlot;
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (moves(s)) first == kWorldSlot ? void(first = s) : unite(first, s);
  }
  // Constraint indices grouped by island (stable: each island keeps the solver's order). Joints
  // are the entries past the contacts.
  const uint32_t nc = static_cast<uint32_t>(constraints.size());
  auto& order = w.island_order;
  order.resize(nc + joints.size());
  const auto islandOf = [&](uint32_t x) {
    if (x < nc) return findRoot(parent, bodies[constraints[x].a].im > 0.0 ? constraints[x].a : constraints[x].b);
    const Joint& j = w.joints[joints[x - nc]];
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (moves(s)) return findRoot(parent, s);
    return uint32_t{0};
  };
  for (uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return islandOf(x) < islandOf(y); });
  for (size_t start = 0; start < order.size();) {
    const uint32_t island = islandOf(order[start]);
    size_t end = start;
    uint32_t points = 0;
    bool jointed = false;
    while (end < order.size() && islandOf(order[end]) == island) {
      points += order[end] < nc ? static_cast<uint32_t>(constraints[order[end]].count) : kJointPoints;
      jointed |= order[end] >= nc;
      ++end;
    }
    if (!jointed && takesExactPath(w, !own.surfaces.empty(), bodies, constraints, std::span<const uint32_t>(order.data() + start, end - start))) {
      // Masses too far apart for the passes (contact_exact.cpp): the island's problem solved at once.
      solveExactContactIsland(w, bodies, constraints, std::span<const uint32_t>(order.data() + start, end - start));
    } else if (points <= static_cast<uint32_t>(kSmallIsland)) {
      const int passes = (jointed ? kMoreJointIterations : kMoreIterations) * w.def.iterations;
      const bool plain = own.surfaces.empty();  // no contact with surface effects
      // Per joint of the island, the size of its impulses after its last solve (only its own solve
      // changes them).
      auto& sizes = own.island_joint_sizes;
      sizes.assign(end - start, -1.0);
      for (int it = w.def.iterations; it < passes; ++it) {
        double change = 0.0, size = 0.0;
        for (size_t k = jointed ? start : end; k < end; ++k) {  // the joints first, as in the passes above
          if (order[k] < nc) continue;
          Joint& j = w.joints[joints[order[k] - nc]];
          double& last = sizes[k - start];
          const double p0 = last >= 0.0 ? last : impulseSize(j.impulses);
          solveJointVelocity(bodies, j, step, false);
          const double p1 = last = impulseSize(j.impulses);
          change = std::max(change, std::abs(p1 - p0));
          size = std::max(size, p1);
        }
        const auto contactPass = [&](auto solveOne) {
          for (size_t k = start; k < end; ++k) {
            if (jointed && order[k] >= nc) continue;
            SolverContact& c = constraints[order[k]];
            const double p0 = c.p[0].pn, p1 = c.p[1].pn;
            solveOne(c);
            change = std::max({change, std::abs(c.p[0].pn - p0), std::abs(c.p[1].pn - p1)});
            size = std::max({size, c.p[0].pn, c.p[1].pn});
          }
        };
        if (plain) {
          contactPass([&](SolverContact& c) { solveContact<false>(bodies, c, nullptr); });
        } else {
          contactPass([&](SolverContact& c) { solve(bodies, c, own.surfaces); });
        }
        if (change <= 1e-9 * size) break;
      }
    }
    start = end;
  }
}

// Which contacts each solver takes. Only contacts that touch an awake dynamic body are solved (the
// others keep their impulses). With ContactSolver::Auto, islands (awake bodies joined by those
// contacts; static and sleeping bodies do not join them) of at least soft_step_points contact
// points go to the soft step: sequential impulses cannot carry a pile of more than about 50 rows,
// while small islands are solved exactly by them (mass ratios, impacts, Newton's cradle).
void chooseSolvers(WorldImpl& w, ContactSolverScratch& own) {
  w.solved.clear();
  w.soft_solved.clear();
  auto& refs = w.solved_refs;
  auto& soft_refs = w.soft_refs;
  refs.clear();
  soft_refs.clear();
  const ContactSolver mode = w.def.contact_solver;
  auto& parent = w.island_parent;
  auto& points = own.island_points;
  if (mode == ContactSolver::Auto) {
    parent.resize(w.bodies.size());
    for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
    points.assign(w.bodies.size(), 0);
  }
  // The contacts' keys (narrow_phase.cpp), not the contacts: a large pile's contacts are far beyond
  // the cache. Its bodies are too, and this loop waited on them (41 % of solveContacts' own time in
  // one load, perf): ask for the bodies of the contact 8 ahead (the flags isActive reads).
  const size_t count = w.contact_keys.size();
  const auto prefetchBody = [&](uint32_t slot) {
    __builtin_prefetch(&w.bodies[slot].type);
    __builtin_prefetch(&w.bodies[slot].awake);
  };
  for (uint32_t k = 0; k < count; ++k) {
    if (k + 8 < count) {
      prefetchBody(w.contact_keys[k + 8].a);
      prefetchBody(w.contact_keys[k + 8].b);
    }
    const ContactKey& c = w.contact_keys[k];
    if (c.disabled) continue;  // pre_solve.cpp
    const bool a = w.isActive(c.a), b = w.isActive(c.b);
    if (!a && !b) continue;
    w.solved.push_back(k);
    refs.push_back({c.a, c.b, static_cast<uint8_t>(c.count), static_cast<uint8_t>(a | b << 1)});
    if (mode != ContactSolver::Auto) continue;
    if (a && b) {
      const uint32_t ra = findRoot(parent, c.a), rb = findRoot(parent, c.b);
      parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  // Joints: solved where one of their bodies is awake and dynamic; in auto mode they join the
  // islands of their bodies, and count as kJointPoints contact points each.
  w.si_joints.clear();
  w.soft_joints.clear();
  const auto active = [&](uint32_t slot) { return slot != kWorldSlot && w.isActive(slot); };
  for (uint32_t k = 0; k < w.joints.size(); ++k) {
    const Joint& j = w.joints[k];
    if (!j.alive || mechanismSettled(w, k)) continue;  // integrated exactly (mechanism_step.cpp)
    const uint32_t slots[4] = {j.a, j.b, j.c, j.d};
    uint32_t first = kWorldSlot;
    for (uint32_t s : slots) {
      if (!active(s)) continue;
      if (first == kWorldSlot) {
        first = s;
      } else if (mode == ContactSolver::Auto) {
        const uint32_t ra = findRoot(parent, first), rb = findRoot(parent, s);
        parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
    if (first != kWorldSlot) w.si_joints.push_back(k);
  }
  if (mode == ContactSolver::SequentialImpulses) return;
  if (mode == ContactSolver::SoftStep) {
    w.soft_solved.swap(w.solved);
    soft_refs.swap(refs);
    w.soft_joints.swap(w.si_joints);
    return;
  }
  const auto islandOf = [&](const SolvedRef& r) { return findRoot(parent, r.active & 1 ? r.a : r.b); };
  const auto jointIsland = [&](const Joint& j) {
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (active(s)) return findRoot(parent, s);
    return uint32_t{0};
  };
  for (const SolvedRef& r : refs) points[islandOf(r)] += r.count;
  for (uint32_t k : w.si_joints) points[jointIsland(w.joints[k])] += kJointPoints;
  const uint32_t threshold = static_cast<uint32_t>(w.def.soft_step_points);
  size_t kept = 0;
  for (size_t j = 0; j < refs.size(); ++j) {
    if (points[islandOf(refs[j])] >= threshold) {
      w.soft_solved.push_back(w.solved[j]);
      soft_refs.push_back(refs[j]);
    } else {
      w.solved[kept] = w.solved[j];
      refs[kept++] = refs[j];
    }
  }
  w.solved.resize(kept);
  refs.resize(kept);
  kept = 0;
  for (uint32_t k : w.si_joints) {
    if (points[jointIsland(w.joints[k])] >= threshold) {
      w.soft_joints.push_back(k);
    } else {
      w.si_joints[kept++] = k;
    }
  }
  w.si_joints.resize(kept);
}

// A contact's surface effects as the solver's (SolverSurface): its index, or kNoSurface.
uint32_t addSurface(const ContactSurface& cs, const SolverBody& a, const SolverBody& b, std::vector<SolverSurface>& surfaces) {
  if (!cs.any()) return kNoSurface;
  const double k_roll = a.ii + b.ii;
  surfaces.push_back({cs.tangent_speed, cs.rolling_resistance, k_roll > 0.0 ? 1.0 / k_roll : 0.0, 0.0});
  return static_cast<uint32_t>(surfaces.size() - 1);
}

SolverContact compact(const Contact& c, const SolverPrepared& prep, uint32_t surface) {
  // Zeroed first: a one-point contact's second point is read by convergeSmallIslands's
  // convergence test (its impulse, zero) and must not be whatever the stack held (it decided
  // the number of passes, so the results differed between builds, machines and thread counts).
  SolverContact s{};
  s.a = c.a;
  s.b = c.b;
  s.count = static_cast<uint8_t>(c.count);
  s.block = c.block;
  s.surface = surface;
  s.nx = c.normal.x();
  s.ny = c.normal.y();
  s.k11 = prep.k11;
  s.k12 = prep.k12;
  s.k22 = prep.k22;
  s.i11 = prep.i11;
  s.i12 = prep.i12;
  s.i22 = prep.i22;
  for (int i = 0; i < c.count; ++i) {
    const ContactPoint& cp = c.points[i];
    s.p[i] = {prep.ra[i].x(), prep.ra[i].y(), prep.rb[i].x(), prep.rb[i].y(), prep.normal_mass[i], prep.tangent_mass[i],
              prep.target_velocity[i], prep.friction[i], cp.normal_impulse, cp.tangent_impulse};
  }
  return s;
}

}  // namespace

void solveContacts(WorldImpl& w, const StepContext& ctx) {
  // Velocities before the solve, for the contact displacement (position_correction.cpp).
  const size_t n = w.bodies.size();
  w.solve_start_velocity.resize(n);
  w.solve_start_angular_velocity.resize(n);
  for (size_t i = 0; i < n; ++i) {
    w.solve_start_velocity[i] = w.bodies[i].velocity;
    w.solve_start_angular_velocity[i] = w.bodies[i].angular_velocity;
  }
  ContactSolverScratch& own = w.contact_solver.get();
  chooseSolvers(w, own);
  beginExactContacts(w, w.solved.size());
  softStep(w, ctx);
  if (w.solved.empty() && w.si_joints.empty()) return;
  auto& prepared = w.solver_prepared;
  prepared.assign(w.solved.size(), SolverPrepared{});
  const bool any_surface = !w.contact_surfaces.empty();  // some contact has surface effects (pre_solve.cpp)
  for (size_t k = 0; k < w.solved.size(); ++k)
    prepare(w, ctx.dt, w.contacts[w.solved[k]], prepared[k], any_surface ? w.contact_surfaces[w.solved[k]].tangent_speed : 0.0);

  auto& bodies = own.velocities;
  bodies.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Body& b = w.bodies[i];
    if (w.isActive(static_cast<uint32_t>(i))) {
      bodies[i] = {b.velocity.x(), b.velocity.y(), b.angular_velocity, b.inv_mass, b.inv_inertia};
    } else if (w.isMovingKinematic(static_cast<uint32_t>(i))) {
      bodies[i] = {b.velocity.x(), b.velocity.y(), b.angular_velocity, 0.0, 0.0};  // moves, but no impulse moves it
    } else {
      bodies[i] = {0.0, 0.0, 0.0, 0.0, 0.0};  // static or asleep: immovable
    }
  }
  auto& constraints = own.contacts;
  constraints.clear();
  // Surface effects (pre_solve.cpp) for the contacts that have them; the rolling impulse starts
  // from zero each step.
  auto& surfaces = own.surfaces;
  surfaces.clear();
  for (size_t k = 0; k < w.solved.size(); ++k) {
    const Contact& c = w.contacts[w.solved[k]];
    const uint32_t surface = any_surface ? addSurface(w.contact_surfaces[w.solved[k]], bodies[c.a], bodies[c.b], surfaces) : kNoSurface;
    constraints.push_back(compact(c, prepared[k], surface));
  }
  // Joints: on the velocities only (joint.h); their position error is removed afterwards
  // (position_correction.cpp).
  JointStep step;
  step.h = ctx.dt;
  step.inv_h = 1.0 / ctx.dt;
  step.warm_starting = ctx.settings.warm_starting;
  for (uint32_t k : w.si_joints) prepareJointAt(w, w.joints[k], step);
  if (ctx.settings.warm_starting) {
    for (uint32_t k : w.si_joints) solveJointVelocity(bodies, w.joints[k], step, true);
    // Start from the impulses carried over from the previous step (narrow_phase.cpp).
    for (SolverContact& c : constraints) {
      const double tx = c.ny, ty = -c.nx;
      for (int i = 0; i < c.count; ++i) {
        const SolverPoint& p = c.p[i];
        apply(bodies[c.a], bodies[c.b], p, p.pn * c.nx + p.pt * tx, p.pn * c.ny + p.pt * ty);
      }
    }
  }
  // Joints' equalities solved exactly first (joint_direct.cpp), then everything by Gauss–Seidel,
  // then the equalities exactly again (the passes for contacts, limits and motors moved them).
  findJointIslands(w);
  directJointVelocities(w, bodies);
  const bool plain = own.surfaces.empty();  // no contact with surface effects
  for (int it = 0; it < ctx.settings.iterations; ++it) {
    for (uint32_t k : w.si_joints) solveJointVelocity(bodies, w.joints[k], step, false);
    if (plain) {
      for (SolverContact& c : constraints) solveContact<false>(bodies, c, nullptr);
    } else {
      for (SolverContact& c : constraints) solve(bodies, c, own.surfaces);
    }
  }
  convergeSmallIslands(w, own, bodies, constraints, step);
  directJointVelocities(w, bodies);

  for (size_t k = 0; k < constraints.size(); ++k) {
    Contact& c = w.contacts[w.solved[k]];
    for (int i = 0; i < c.count; ++i) {
      c.points[i].normal_impulse = c.points[i].step_normal_impulse = constraints[k].p[i].pn;
      c.points[i].tangent_impulse = c.points[i].step_tangent_impulse = constraints[k].p[i].pt;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    Body& b = w.bodies[i];
    if (!w.isActive(static_cast<uint32_t>(i))) continue;
    b.velocity = Vec2(bodies[i].vx, bodies[i].vy);
    b.angular_velocity = bodies[i].w;
  }
}

}  // namespace rigidlab

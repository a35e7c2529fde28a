// The exact solve of small contact islands with extreme mass ratios (contact_exact.h).
//
// Why: sequential impulses pass the weight of a heavy body to the ground one contact at a time, and
// each pass moves only about m_light / m_heavy of it through a light body between them: a 100 kg box
// on a 1 kg box needs ~50 passes, 1000:1 ~500 (contact_solver.cpp), 1e6:1 would need ~5e5, and the
// nonlinear Gauss–Seidel position pass has the same ratio (a 1e6 kg box on a 1 kg box sank its full
// height, 494 mm, in 5 s, measured). Solved together, the island's contacts are one small problem
// whatever the masses.
//
// Velocities. For the island's points, rows n (normal) and t = n × 1 (friction), Jacobian J over the
// movable bodies' (v_x, v_y, ω), W = J M⁻¹ Jᵀ (dense), and the impulses P sought in total (the
// passes' impulses p₀ are only the first guess):
//   w = W P + q,   q = J v − v_target − W p₀   (v: velocities after the passes, which include p₀)
//   normal rows:   P_n ≥ 0, w_n ≥ 0, P_n w_n = 0                      (v_target: restitution, gaps)
//   friction rows: |P_t| ≤ μ P_n, w_t = 0 inside, w_t ≥ 0 at −μ P_n, w_t ≤ 0 at +μ P_n
// a boxed linear complementarity problem once the friction bounds are fixed. It is solved by block
// principal pivoting (J. Júdice, F. Pires, "A block principal pivoting algorithm for large-scale
// strictly monotone linear complementarity problems", Comput. Oper. Res. 21, 1994), falling back to
// Murty's least-index rule (one flip at a time, finite for a positive definite W) when a block flip
// does not reduce the violations; each active set is an LDLT solve of its free rows. The friction
// bounds μ P_n come from the previous round's P_n, a fixed point repeated until P_n stands still
// (kFrictionRounds at most) — the usual treatment of the Coulomb box (ODE's dxSolveLCP "findex").
// W is rigid: its only regularisation is kRegularisation on the diagonal, round-off level, because
// two points of one face give equal friction rows (W singular), which then share the load evenly.
//
// Positions. The same island's overlaps are removed together, as a linearised complementarity
// problem at the current positions (Newton steps, as joint_direct.cpp does for joints):
//   normal rows only,  λ ≥ 0,  s + W λ + slop ≥ 0  with complementarity,
// each body moved by M⁻¹ Jᵀ λ; the whole overlap beyond the slop, up to kMaxCorrection per point and
// step, is removed in each of WorldDef::position_iterations steps, until it is at most 1e-9 m.
#include "contact_exact.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

#include "world_impl.h"

namespace rigidlab {
namespace {

// Which islands (docs/physics.md, "Extreme mass ratios"; measured on a 1 kg box under a heavy one,
// 5 s at 1/60, whole steps): up to 100:1 the passes converge (sink 1.372 mm against the exact 1.362)
// and are cheaper (1:1 3.6 against 5.0 µs per step, 10:1 2.7 against 3.6); beyond, they leave the
// heavy box lower (200:1 1.51 mm, 500:1 2.7 mm, 1000:1 6.0 mm, 1e4:1 91 mm, 1e6:1 its full height)
// and cost more (100:1 3.7 µs both, 500:1 7.4 against 3.9, 1000:1 44 against 4.1). The size: the
// islands whose passes are iterated to convergence (contact_solver.cpp kSmallIsland); a column of
// 16 boxes of 1 kg under 1e6 kg (32 points, 64 rows) takes 121 µs per step and holds (1.37 mm),
// where the passes let the heavy box through the column.
constexpr int kExactPoints = 64;
constexpr double kExactMassRatio = 100.0;
constexpr double kRegularisation = 1e-10;  // relative, on W's diagonal
constexpr int kFrictionRounds = 8;
constexpr double kMaxCorrection = 0.2;     // m per point and position step (as nonlinear Gauss–Seidel's)
constexpr double kInf = std::numeric_limits<double>::infinity();

enum : int8_t { kFree = 0, kAtLo = -1, kAtHi = 1, kFixed = 2 };

// The island's body numbering starts again.
void forgetBodies(ContactExactScratch& s) {
  for (const uint32_t slot : s.island_bodies) s.local[slot] = UINT32_MAX;
  s.island_bodies.clear();
}

// The slot's index among the island's movable bodies (numbered on first sight), or UINT32_MAX.
uint32_t islandBody(ContactExactScratch& s, uint32_t slot, bool movable) {
  if (!movable) return UINT32_MAX;
  if (s.local[slot] == UINT32_MAX) {
    s.local[slot] = static_cast<uint32_t>(s.island_bodies.size());
    s.island_bodies.push_back(slot);
  }
  return s.local[slot];
}

// Row r of J for a direction d at a point with arms r_A, r_B: −(d, r_A × d) on A, +(d, r_B × d) on B.
void fillRow(Eigen::MatrixXd& jac, int r, uint32_t a, uint32_t b, double dx, double dy, double rax, double ray, double rbx,
             double rby) {
  if (a != UINT32_MAX) {
    jac(r, 3 * a) -= dx;
    jac(r, 3 * a + 1) -= dy;
    jac(r, 3 * a + 2) -= rax * dy - ray * dx;
  }
  if (b != UINT32_MAX) {
    jac(r, 3 * b) += dx;
    jac(r, 3 * b + 1) += dy;
    jac(r, 3 * b + 2) += rbx * dy - rby * dx;
  }
}

// M⁻¹ Jᵀ and W = J M⁻¹ Jᵀ from s.jac, with inverse masses im(k), ii(k) of the island's body k.
template <typename Mass>
void delassus(ContactExactScratch& s, Mass mass) {
  const Eigen::Index m = s.jac.rows(), nb = static_cast<Eigen::Index>(s.island_bodies.size());
  s.jm.resize(3 * nb, m);
  for (Eigen::Index k = 0; k < nb; ++k) {
    double im, ii;
    mass(s.island_bodies[static_cast<size_t>(k)], im, ii);
    s.jm.row(3 * k) = im * s.jac.col(3 * k).transpose();
    s.jm.row(3 * k + 1) = im * s.jac.col(3 * k + 1).transpose();
    s.jm.row(3 * k + 2) = ii * s.jac.col(3 * k + 2).transpose();
  }
  s.a.noalias() = s.jac * s.jm;
  for (Eigen::Index i = 0; i < m; ++i) s.a(i, i) = s.a(i, i) > 0.0 ? s.a(i, i) * (1.0 + kRegularisation) : 1.0;
}

}  // namespace

bool solveBoxedLcp(ContactExactScratch& s, const Eigen::MatrixXd& a, const Eigen::VectorXd& q, const Eigen::VectorXd& lo,
                   const Eigen::VectorXd& hi, Eigen::VectorXd& x) {
  const int m = static_cast<int>(a.rows());
  s.state.resize(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) {
    int8_t& st = s.state[static_cast<size_t>(i)];
    st = !(hi(i) > lo(i)) ? kFixed : x(i) <= lo(i) ? kAtLo : x(i) >= hi(i) ? kAtHi : kFree;
  }
  double scale_a = 0.0;
  for (int i = 0; i < m; ++i) scale_a = std::max(scale_a, a(i, i));
  const double scale_q = q.size() > 0 ? q.cwiseAbs().maxCoeff() : 0.0;
  int best = INT_MAX, stalls = 0;
  const int max_pivots = 10 * m + 20;
  for (int it = 0; it < max_pivots; ++it) {
    s.free_rows.clear();
    for (int i = 0; i < m; ++i) {
      switch (s.state[static_cast<size_t>(i)]) {
        case kFree: s.free_rows.push_back(i); break;
        case kAtHi: x(i) = hi(i); break;
        default: x(i) = lo(i); break;
      }
    }
    const int nf = static_cast<int>(s.free_rows.size());
    if (nf > 0) {
      // A_FF x_F = −(q_F + A_FB x_B)
      s.sub.resize(nf, nf);
      s.sub_rhs.resize(nf);
      for (int r = 0; r < nf; ++r) {
        const int i = s.free_rows[static_cast<size_t>(r)];
        double rhs = -q(i);
        for (int j = 0; j < m; ++j)
          if (s.state[static_cast<size_t>(j)] != kFree) rhs -= a(i, j) * x(j);
        s.sub_rhs(r) = rhs;
        for (int c = 0; c < nf; ++c) s.sub(r, c) = a(i, s.free_rows[static_cast<size_t>(c)]);
      }
      s.ldlt.compute(s.sub);
      s.sub_x = s.ldlt.solve(s.sub_rhs);
      if (!s.sub_x.allFinite()) return false;
      for (int r = 0; r < nf; ++r) x(s.free_rows[static_cast<size_t>(r)]) = s.sub_x(r);
    }
    s.r.noalias() = a * x;
    s.r += q;
    const double size_x = x.size() > 0 ? x.cwiseAbs().maxCoeff() : 0.0;
    const double tol_x = 1e-9 * size_x + 1e-300;
    const double tol_w = 1e-9 * (scale_q + scale_a * size_x) + 1e-300;
    int violations = 0, first = -1;
    const auto violated = [&](int i) {
      switch (s.state[static_cast<size_t>(i)]) {
        case kFree: return x(i) < lo(i) - tol_x || x(i) > hi(i) + tol_x;
        case kAtLo: return s.r(i) < -tol_w;
        case kAtHi: return s.r(i) > tol_w;
        default: return false;
      }
    };
    for (int i = 0; i < m; ++i)
      if (violated(i)) {
        ++violations;
        if (first < 0) first = i;
      }
    if (violations == 0) {
      for (int i = 0; i < m; ++i) x(i) = std::clamp(x(i), lo(i), hi(i));
      return true;
    }
    if (violations < best) {
      best = violations;
      stalls = 0;
    } else {
      ++stalls;
    }
    const auto flip = [&](int i) {
      int8_t& st = s.state[static_cast<size_t>(i)];
      st = st != kFree ? kFree : x(i) < lo(i) ? kAtLo : kAtHi;
    };
    if (stalls >= 3) {
      flip(first);  // Murty's least-index rule
    } else {
      for (int i = 0; i < m; ++i)
        if (violated(i)) flip(i);
    }
  }
  for (int i = 0; i < m; ++i) x(i) = std::clamp(x(i), lo(i), hi(i));
  return false;
}

void beginExactContacts(WorldImpl& w, size_t solved) {
  ContactExactScratch& s = w.exact_contacts;
  s.exact.assign(solved, 0);
  s.contacts.clear();
  s.start.assign(1, 0);
}

bool takesExactPath(const WorldImpl& w, bool surfaces, const std::vector<SolverBody>& bodies, const std::vector<SolverContact>& constraints,
                    std::span<const uint32_t> island) {
  if (surfaces || w.def.iterations <= 0) return false;
  int points = 0;
  double lightest = kInf, heaviest = 0.0;
  for (const uint32_t k : island) {
    const SolverContact& c = constraints[k];
    points += c.count;
    for (const uint32_t slot : {c.a, c.b}) {
      const double im = bodies[slot].im;
      if (!(im > 0.0)) continue;
      lightest = std::min(lightest, 1.0 / im);
      heaviest = std::max(heaviest, 1.0 / im);
    }
  }
  return points <= kExactPoints && heaviest > kExactMassRatio * lightest;
}

void solveExactContactIsland(WorldImpl& w, std::vector<SolverBody>& bodies, std::vector<SolverContact>& constraints,
                             std::span<const uint32_t> island) {
  ContactExactScratch& s = w.exact_contacts;
  forgetBodies(s);
  s.local.resize(w.bodies.size(), UINT32_MAX);
  int m = 0;
  for (const uint32_t k : island) {
    const SolverContact& c = constraints[k];
    islandBody(s, c.a, bodies[c.a].im > 0.0 || bodies[c.a].ii > 0.0);
    islandBody(s, c.b, bodies[c.b].im > 0.0 || bodies[c.b].ii > 0.0);
    m += 2 * c.count;
  }
  const Eigen::Index nb = static_cast<Eigen::Index>(s.island_bodies.size());
  s.jac.setZero(m, 3 * nb);
  s.q.resize(m);
  s.x.resize(m);
  s.lo.resize(m);
  s.hi.resize(m);
  s.friction.resize(m);
  // Rows: per point its normal row 2i and its friction row 2i + 1, in the island's order.
  int r = 0;
  for (const uint32_t k : island) {
    const SolverContact& c = constraints[k];
    const SolverBody &a = bodies[c.a], &b = bodies[c.b];
    const uint32_t la = s.local[c.a], lb = s.local[c.b];
    const double tx = c.ny, ty = -c.nx;
    for (int i = 0; i < c.count; ++i, r += 2) {
      const SolverPoint& p = c.p[i];
      fillRow(s.jac, r, la, lb, c.nx, c.ny, p.rax, p.ray, p.rbx, p.rby);
      fillRow(s.jac, r + 1, la, lb, tx, ty, p.rax, p.ray, p.rbx, p.rby);
      // J v of every body, kinematic ones included (their velocities are in `bodies`).
      const auto relative = [&](double dx, double dy) {
        const double rvx = b.vx - b.w * p.rby - a.vx + a.w * p.ray;
        const double rvy = b.vy + b.w * p.rbx - a.vy - a.w * p.rax;
        return rvx * dx + rvy * dy;
      };
      s.q(r) = relative(c.nx, c.ny) - p.target;
      s.q(r + 1) = relative(tx, ty);
      s.x(r) = p.pn;
      s.x(r + 1) = p.pt;
      // A point the solver leaves alone (a bounce deferred to the next step, contact_solver.cpp:
      // zero effective mass) keeps no impulse.
      const bool normal = p.normal_mass != 0.0, friction = normal && p.tangent_mass != 0.0;
      s.lo(r) = 0.0;
      s.hi(r) = normal ? kInf : 0.0;
      s.friction(r + 1) = friction ? p.friction : 0.0;
    }
  }
  delassus(s, [&](uint32_t slot, double& im, double& ii) {
    im = bodies[slot].im;
    ii = bodies[slot].ii;
  });
  const Eigen::VectorXd p0 = s.x;
  s.q.noalias() -= s.a * p0;
  bool solved = false;
  for (int round = 0; round < kFrictionRounds; ++round) {
    double largest = 0.0;
    for (int i = 0; i < m; i += 2) {
      const double bound = s.friction(i + 1) * std::max(s.x(i), 0.0);
      s.lo(i + 1) = -bound;
      s.hi(i + 1) = bound;
      largest = std::max(largest, s.x(i));
    }
    Eigen::VectorXd before = s.x;
    solved = solveBoxedLcp(s, s.a, s.q, s.lo, s.hi, s.x);
    if (!solved) break;
    double change = 0.0;
    for (int i = 0; i < m; i += 2) change = std::max(change, std::abs(s.x(i) - before(i)));
    if (change <= 1e-12 * std::max(largest, s.x.cwiseAbs().maxCoeff())) break;
  }
  if (!solved) return;  // the passes' impulses stand; the position passes stay Gauss–Seidel's
  const Eigen::VectorXd dv = s.jm * (s.x - p0);
  for (Eigen::Index k = 0; k < nb; ++k) {
    SolverBody& b = bodies[s.island_bodies[static_cast<size_t>(k)]];
    b.vx += dv(3 * k);
    b.vy += dv(3 * k + 1);
    b.w += dv(3 * k + 2);
  }
  r = 0;
  for (const uint32_t k : island) {
    SolverContact& c = constraints[k];
    for (int i = 0; i < c.count; ++i, r += 2) {
      c.p[i].pn = s.x(r);
      c.p[i].pt = s.x(r + 1);
    }
    s.exact[k] = 1;
    s.contacts.push_back(k);
  }
  s.start.push_back(static_cast<uint32_t>(s.contacts.size()));
}

void exactContactPositions(WorldImpl& w) {
  ContactExactScratch& s = w.exact_contacts;
  if (s.contacts.empty()) return;
  forgetBodies(s);
  s.local.resize(w.bodies.size(), UINT32_MAX);
  const auto mass = [&](uint32_t slot, double& im, double& ii) {
    const bool moves = w.isActive(slot);
    im = moves ? w.bodies[slot].inv_mass : 0.0;
    ii = moves ? w.bodies[slot].inv_inertia : 0.0;
  };
  constexpr double kTolerance = 1e-9;  // [m]
  for (size_t island = 0; island + 1 < s.start.size(); ++island) {
    const std::span<const uint32_t> contacts(s.contacts.data() + s.start[island], s.contacts.data() + s.start[island + 1]);
    for (int step = 0; step < w.def.position_iterations; ++step) {
      forgetBodies(s);
      int m = 0;
      for (const uint32_t j : contacts) {
        const Contact& c = w.contacts[w.solved[j]];
        islandBody(s, c.a, w.isActive(c.a));
        islandBody(s, c.b, w.isActive(c.b));
        m += c.count;
      }
      const Eigen::Index nb = static_cast<Eigen::Index>(s.island_bodies.size());
      s.jac.setZero(m, 3 * nb);
      s.q.resize(m);
      double deepest = 0.0;
      int r = 0;
      for (const uint32_t j : contacts) {
        const Contact& c = w.contacts[w.solved[j]];
        const SolverPrepared& local = w.solver_prepared[j];  // the points fixed to their bodies
        const Body &a = w.bodies[c.a], &b = w.bodies[c.b];
        for (int i = 0; i < c.count; ++i, ++r) {
          // As nonlinear Gauss–Seidel (position_correction.cpp): the normal turns with A, the
          // points with their bodies, and the row acts at their midpoint.
          const Vec2 n = a.xf.q.apply(local.local_normal);
          const Vec2 pa = a.xf.apply(local.local_a[i]), pb = b.xf.apply(local.local_b[i]);
          const double separation = (pb - pa).dot(n);
          const Vec2 p = 0.5 * (pa + pb);
          const Vec2 ra = p - a.center, rb = p - b.center;
          fillRow(s.jac, r, s.local[c.a], s.local[c.b], n.x(), n.y(), ra.x(), ra.y(), rb.x(), rb.y());
          s.q(r) = std::max(separation + c.slop, -kMaxCorrection);
          deepest = std::min(deepest, separation + c.slop);
        }
      }
      if (deepest >= -kTolerance) break;
      delassus(s, mass);
      s.lo.setZero(m);
      s.hi.setConstant(m, kInf);
      s.x.setZero(m);
      if (!solveBoxedLcp(s, s.a, s.q, s.lo, s.hi, s.x)) break;
      const Eigen::VectorXd move = s.jm * s.x;
      for (Eigen::Index k = 0; k < nb; ++k) {
        Body& b = w.bodies[s.island_bodies[static_cast<size_t>(k)]];
        b.center += Vec2(move(3 * k), move(3 * k + 1));
        b.angle += move(3 * k + 2);
        WorldImpl::syncTransform(b);
      }
    }
  }
}

}  // namespace rigidlab

// The linearly implicit velocity update of the Euler methods (integrator.cpp).
//
// With Q(q, v) the generalised forces (F_x, F_y, τ) of every dynamic body, a backward-Euler step
// v₁ = v₀ + h M⁻¹ Q(q₁, v₁), q₁ = q₀ + h v₁, linearised about the start of the step, is
//   (M − h D − s h² K) Δv = h (Q₀ + s h K v₀),     D = ∂Q/∂v,  K = ∂Q/∂q
// (Baraff & Witkin, "Large Steps in Cloth Simulation", 1998). Only forces that can linearise
// themselves (Force::linearize: springs, dampers) contribute to D and K; the others, gravity and
// Lua forces included, enter Q₀ explicitly.
//   s = 1  implicit_euler: stiffness and damping implicit. A spring of any stiffness stays stable
//          (spectral radius 1/√(1 + (ωh)²) on an undamped spring) and loses energy, never gains.
//   s = 0  explicit and semi-implicit Euler: only damping is implicit, so a damper never flips a
//          velocity's sign whatever c·h/m is (v ← v / (1 + c h / m), the Padé form Box2D uses),
//          and a critically damped spring cannot destabilise semi-implicit Euler (docs/design/accuracy.md S5,
//          S6); the spring forces themselves stay explicit, as the methods' names promise.
// Bodies coupled by two-body springs are solved together (sparse LDLT); the usual case, where
// every implicit force acts on one body, is one 3×3 solve per body.
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

// The implicit solve's scratch (WorldImpl::implicit holds it, opaque to the other stages), written
// in each call before it is read.
struct ImplicitScratch {
  std::vector<int> row;     // per slot: row of the body in the system, −1 if not an unknown
  struct Block {
    int row, col;
    Eigen::Matrix3d a;      // −h D − s h² K
    Eigen::Matrix3d kv;     // s h² K (multiplies v₀ on the right-hand side)
  };
  std::vector<Block> blocks;
  std::vector<Eigen::Vector3d> mass, v0;
  std::vector<Eigen::Matrix3d> diag;
  std::vector<char> has_block;
  Eigen::VectorXd rhs, dv;  // h Q₀ (+ s h² K v₀), and the solution Δv (3 per row)
};

bool implicitVelocityChange(WorldImpl& w, double t0, double h, bool stiffness, const char* only, ImplicitVelocities& out) {
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  auto& s = w.implicit.get();
  s.row.assign(n, -1);
  int rows = 0;
  for (uint32_t i = 0; i < n; ++i)
    if (w.alive[i] && w.bodies[i].isDynamic()) s.row[i] = rows++;

  // Blocks of the linearised forces, keyed by (row body, column body).
  s.blocks.clear();
  bool coupled = false;
  for (const ForceEntry& f : w.forces) {
    if (!f.alive || f.expires_at <= t0) continue;
    if (only && !only[f.a.index] && (f.b.isNull() || !only[f.b.index])) continue;  // another island's
    const BodyState& a = w.states[f.a.index];
    const BodyState* b = f.b.isNull() ? nullptr : &w.states[f.b.index];
    ForceJacobian j;
    if (!f.force->linearize(ForceInput{a, b, t0}, j)) continue;
    const uint32_t slots[2] = {f.a.index, b ? f.b.index : f.a.index};
    const int count = b ? 2 : 1;
    for (int p = 0; p < count; ++p) {
      for (int q = 0; q < count; ++q) {
        const int rp = s.row[slots[p]], rq = s.row[slots[q]];
        if (rp < 0 || rq < 0) continue;  // a static end is fixed: no unknowns there
        // A = M − h D − s h² K;  rhs += s h² K v₀ (the h (… + s h K v₀) term).
        Eigen::Matrix3d block = -h * j.dv[p][q];
        if (stiffness) block -= h * h * j.dq[p][q];
        s.blocks.push_back({rp, rq, block, stiffness ? Eigen::Matrix3d(h * h * j.dq[p][q]) : Eigen::Matrix3d::Zero()});
        coupled |= rp != rq;
      }
    }
  }
  if (s.blocks.empty()) return false;

  // Right-hand side h Q₀ (+ s h² K v₀) and the diagonal mass.
  s.rhs.setZero(3 * rows);
  s.mass.resize(rows);
  for (uint32_t i = 0; i < n; ++i) {
    const int r = s.row[i];
    if (r < 0) continue;
    const Body& b = w.bodies[i];
    const Wrench& q = w.wrenches[i];
    const Vec2 f = q.force + b.mass * (b.gravityOr(w.def.gravity) * b.gravity_scale);
    s.rhs.segment<3>(3 * r) << h * f.x(), h * f.y(), h * q.torque;
    s.mass[r] = Eigen::Vector3d(b.mass, b.mass, b.inertia);
  }
  s.v0.resize(rows);
  for (uint32_t i = 0; i < n; ++i)
    if (s.row[i] >= 0) s.v0[s.row[i]] = Eigen::Vector3d(w.bodies[i].velocity.x(), w.bodies[i].velocity.y(), w.bodies[i].angular_velocity);
  for (const auto& blk : s.blocks) s.rhs.segment<3>(3 * blk.row) += blk.kv * s.v0[blk.col];
  s.dv.setZero(3 * rows);
  if (!coupled) {
    // Block diagonal: one 3×3 system per body that has implicit forces; M⁻¹ h Q₀ for the others.
    s.diag.assign(rows, Eigen::Matrix3d::Zero());
    s.has_block.assign(rows, 0);
    for (const auto& blk : s.blocks) {
      s.diag[blk.row] += blk.a;
      s.has_block[blk.row] = 1;
    }
    for (int r = 0; r < rows; ++r) {
      Eigen::Matrix3d a = s.diag[r];
      a.diagonal() += s.mass[r];
      s.dv.segment<3>(3 * r) = a.ldlt().solve(s.rhs.segment<3>(3 * r));
    }
  } else {
    std::vector<Eigen::Triplet<double>> triplets;
    for (int r = 0; r < rows; ++r)
      for (int k = 0; k < 3; ++k) triplets.emplace_back(3 * r + k, 3 * r + k, s.mass[r][k]);
    for (const auto& blk : s.blocks) {
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q)
          if (blk.a(p, q) != 0.0) triplets.emplace_back(3 * blk.row + p, 3 * blk.col + q, blk.a(p, q));
    }
    Eigen::SparseMatrix<double> a(3 * rows, 3 * rows);
    a.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
    s.dv = solver.solve(s.rhs);
  }
  out = {s.row.data(), s.dv.data()};
  return true;
}

}  // namespace rigidlab

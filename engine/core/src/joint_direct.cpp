// The direct solve of sequential impulses' joints (joint_solver.h): per island of joints, the rigid
// equality rows of all its joints (joint_rows.cpp) solved together, exactly,
//   K λ = −r,   K = J M⁻¹ Jᵀ (dense, symmetric positive semi-definite),
// with r = J v on the velocities (then v += M⁻¹ Jᵀ λ), or r = C on the positions (Newton's method
// on C(x) = 0: x += M⁻¹ Jᵀ λ, repeated until |C| is at round-off).
//
// Why: Gauss–Seidel solves one joint at a time, and on a chain each pass only moves an error one
// link along it; with a heavy body on light links it barely moves it at all (a 100 kg load on ten
// 1 kg links stretched without bound at 10 passes and 1.8 % at 300, measured). The dense solve
// costs O(m³) for m rows, so it is used for islands of at most kMaxDirectRows rows (a chain of 30
// pins is 60); larger islands of joints go to the soft step (contact_solver.cpp).
#include "rigidlab/portable_math.h"
#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <span>

#include "joint_direct.h"
#include "joint_rows.h"
#include "joint_solver.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

uint32_t root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

bool movable(const WorldImpl& w, uint32_t slot) { return slot != kWorldSlot && w.isActive(slot); }

// The SI joints grouped by island (findJointIslands).
struct JointIslands {
  const std::vector<uint32_t>& joints;
  const std::vector<uint32_t>& start;
  size_t size() const { return start.empty() ? 0 : start.size() - 1; }
  std::span<const uint32_t> operator[](size_t i) const { return {joints.data() + start[i], joints.data() + start[i + 1]}; }
};

JointIslands islands(const WorldImpl& w) { return {w.joint_island_joints, w.joint_island_start}; }


// The island's body numbering starts again (DirectJointScratch::local).
void forgetBodies(DirectJointScratch& s) {
  for (const uint32_t slot : s.island_bodies) s.local[slot] = UINT32_MAX;
  s.island_bodies.clear();
  s.im.clear();
  s.ii.clear();
}

// The slot's index among the island's bodies, numbering it with its inverse masses if it is new.
template <typename Mass>
uint32_t islandBody(DirectJointScratch& s, uint32_t slot, Mass mass) {
  if (s.local[slot] == UINT32_MAX) {
    s.local[slot] = static_cast<uint32_t>(s.island_bodies.size());
    s.island_bodies.push_back(slot);
    double im, ii;
    mass(slot, im, ii);
    s.im.push_back(im);
    s.ii.push_back(ii);
  }
  return s.local[slot];
}

// The rigid rows of the island's joints at the bodies' states given by `view` (slot → SoftBody),
// into s.rows, with the island's bodies numbered in the order the rows meet them; mass gives a
// slot's inverse masses, which do not change while the rows are used.
template <typename View, typename Mass>
void gather(WorldImpl& w, std::span<const uint32_t> joints, View view, Mass mass, DirectJointScratch& s) {
  forgetBodies(s);
  s.rows.clear();
  for (const uint32_t k : joints) {
    Joint& j = w.joints[k];
    IslandRow entry;
    entry.slot[0] = j.a;
    entry.slot[1] = j.b;
    entry.slot[2] = j.c;
    entry.slot[3] = j.d;
    entry.slots = 0;
    entry.bodies = 0;
    // Made in place (a copy of a view just returned stalls on reading back its fields).
    SoftBody v[4] = {view(j, 0, j.a), view(j, 1, j.b), view(j, 2, j.c), view(j, 3, j.d)};
    for (int i = 0; i < 4; ++i) {
      const uint32_t slot = entry.slot[i];
      entry.body[i] = UINT32_MAX;
      if (slot == kWorldSlot) continue;
      const uint32_t b = entry.body[i] = islandBody(s, slot, mass);
      entry.bodies |= b < 64 ? uint64_t{1} << b : ~uint64_t{0};
      entry.slots = i + 1;
    }
    RowGroup groups[2];
    const int count = equalityGroups(j, {&v[0], &v[1], &v[2], &v[3]}, groups);
    for (int g = 0; g < count; ++g) {
      if (groups[g].spring) continue;  // a soft weld's spring is not an equality
      for (int r = 0; r < groups[g].count; ++r) {
        entry.row = groups[g].rows[r];
        s.rows.push_back(entry);
      }
    }
  }
}

// K = J M⁻¹ Jᵀ over the island's rows, into s.k. Entry (r, c) sums, in the order of the rows'
// slots, over the pairs of slots of rows r and c that are the same body (a body that is two slots
// of a joint, as a gear's grounds may be, adds each one's part); rows with no body in common have
// no such pair, and their entry is the empty sum, +0.
void effectiveMass(DirectJointScratch& s) {
  const std::vector<IslandRow>& rows = s.rows;
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd& k = s.k;
  k.resize(m, m);
  for (int r = 0; r < m; ++r) {
    const IslandRow& x = rows[r];
    for (int c = r; c < m; ++c) {
      const IslandRow& y = rows[c];
      double sum = 0.0;
      if (x.bodies & y.bodies)
        for (int p = 0; p < x.slots; ++p) {
          const uint32_t b = x.body[p];
          if (b == UINT32_MAX) continue;
          for (int q = 0; q < y.slots; ++q) {
            if (b != y.body[q]) continue;
            sum += s.im[b] * (x.row.j[p][0] * y.row.j[q][0] + x.row.j[p][1] * y.row.j[q][1]) +
                   s.ii[b] * x.row.j[p][2] * y.row.j[q][2];
          }
        }
      k(r, c) = k(c, r) = sum;
    }
  }
  // Rows that move nothing (all their bodies immovable along them) solve to zero.
  for (int r = 0; r < m; ++r)
    if (!(k(r, r) > 0.0)) k(r, r) = 1.0;
}

// λ solving K λ = rhs (s.lambda); false if it is not finite.
bool solveIsland(DirectJointScratch& s) {
  s.ldlt.compute(s.k);
  s.lambda = s.ldlt.solve(s.rhs);
  return s.lambda.allFinite();
}

// The same, with the factors kept from the island's last velocity solve when its K had the same
// bits: the step's second velocity solve has the first one's rows (the Jacobians at the prepared
// frames) and masses, so it would factor the same matrix again.
bool solveIslandVelocity(DirectJointScratch& s, size_t island) {
  Eigen::MatrixXd& kept = s.velocity_k[island];
  Eigen::LDLT<Eigen::MatrixXd>& factors = s.velocity_ldlt[island];
  const bool same = kept.rows() == s.k.rows() && kept.cols() == s.k.cols() &&
                    std::memcmp(kept.data(), s.k.data(), sizeof(double) * static_cast<size_t>(s.k.size())) == 0;
  if (!same) {
    kept = s.k;
    factors.compute(kept);
  }
  s.lambda = factors.solve(s.rhs);
  return s.lambda.allFinite();
}

// The scratch for `w`'s bodies, every slot outside any island.
DirectJointScratch& scratch(WorldImpl& w) {
  DirectJointScratch& s = w.direct_joints;
  s.island_bodies.clear();
  s.local.assign(w.bodies.size(), UINT32_MAX);
  return s;
}

}  // namespace

// Islands in the order of their first joint, each island's joints in the joints' order. Linear in
// the joints (a rain of a thousand ragdolls is a thousand islands).
void findJointIslands(WorldImpl& w) {
  w.joint_island_start.clear();
  if (w.si_joints.empty()) return;
  auto& parent = w.island_parent;
  parent.resize(w.bodies.size());
  for (const uint32_t k : w.si_joints) {
    const Joint& j = w.joints[k];
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (movable(w, s)) parent[s] = s;
  }
  for (const uint32_t k : w.si_joints) {
    const Joint& j = w.joints[k];
    uint32_t first = kWorldSlot;
    for (uint32_t s : {j.a, j.b, j.c, j.d}) {
      if (!movable(w, s)) continue;
      if (first == kWorldSlot) {
        first = s;
      } else {
        const uint32_t ra = root(parent, first), rb = root(parent, s);
        parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
  }
  // Per joint its island (UINT32_MAX: no movable body), numbered in order of first appearance;
  // then a counting sort keeps each island's joints in order.
  auto& index = w.joint_island_index;  // per root slot: its island's number
  index.assign(w.bodies.size(), UINT32_MAX);
  auto& of = w.joint_island_of;
  auto& start = w.joint_island_start;
  auto& out = w.joint_island_joints;
  of.resize(w.si_joints.size());
  start.assign(1, 0);
  for (size_t q = 0; q < w.si_joints.size(); ++q) {
    const Joint& j = w.joints[w.si_joints[q]];
    of[q] = UINT32_MAX;
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (movable(w, s)) {
        const uint32_t r = root(parent, s);
        if (index[r] == UINT32_MAX) {
          index[r] = static_cast<uint32_t>(start.size() - 1);
          start.push_back(0);
        }
        of[q] = index[r];
        ++start[index[r] + 1];
        break;
      }
  }
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  out.resize(start.back());
  auto& fill = w.joint_island_fill;  // per island: where its next joint goes
  fill.assign(start.begin(), start.end() - 1);
  for (size_t q = 0; q < w.si_joints.size(); ++q)
    if (of[q] != UINT32_MAX) out[fill[of[q]]++] = w.si_joints[q];
}

void directJointVelocities(WorldImpl& w, std::vector<SolverBody>& bodies) {
  if (w.si_joints.empty()) return;
  const auto view = [&](const Joint&, int, uint32_t slot) {
    if (slot == kWorldSlot) return SoftBody{0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    const SolverBody& s = bodies[slot];
    return SoftBody{s.vx, s.vy, s.w, 0.0, 0.0, 1.0, 0.0, s.im, s.ii};
  };
  const auto mass = [&](uint32_t slot, double& im, double& ii) {
    im = bodies[slot].im;
    ii = bodies[slot].ii;
  };
  DirectJointScratch& s = scratch(w);
  const JointIslands found = islands(w);
  s.velocity_k.resize(found.size());
  s.velocity_ldlt.resize(found.size());
  for (size_t i = 0; i < found.size(); ++i) {
    gather(w, found[i], view, mass, s);
    const std::vector<IslandRow>& rows = s.rows;
    const int m = static_cast<int>(rows.size());
    if (m == 0 || m > kMaxDirectRows) continue;
    s.rhs.resize(m);
    for (int r = 0; r < m; ++r) {
      double cdot = 0.0;
      for (int p = 0; p < 4; ++p) {
        const uint32_t slot = rows[r].slot[p];
        if (slot == kWorldSlot) continue;
        cdot += rows[r].row.j[p][0] * bodies[slot].vx + rows[r].row.j[p][1] * bodies[slot].vy + rows[r].row.j[p][2] * bodies[slot].w;
      }
      s.rhs(r) = -cdot;
    }
    effectiveMass(s);
    if (!solveIslandVelocity(s, i)) continue;
    const Eigen::VectorXd& lambda = s.lambda;
    for (int r = 0; r < m; ++r) {
      *rows[r].row.impulse += lambda(r);
      for (int p = 0; p < 4; ++p) {
        const uint32_t slot = rows[r].slot[p];
        if (slot == kWorldSlot) continue;
        SolverBody& b = bodies[slot];
        b.vx += b.im * lambda(r) * rows[r].row.j[p][0];
        b.vy += b.im * lambda(r) * rows[r].row.j[p][1];
        b.w += b.ii * lambda(r) * rows[r].row.j[p][2];
      }
    }
  }
}

namespace {

// Inverse masses as the position solve sees them: a still body (static, asleep) is immovable.
void positionMass(const WorldImpl& w, uint32_t slot, double& im, double& ii) {
  const bool moves = w.isActive(slot);
  im = moves ? w.bodies[slot].inv_mass : 0.0;
  ii = moves ? w.bodies[slot].inv_inertia : 0.0;
}

}  // namespace

void directJointVelocitiesAtPositions(WorldImpl& w) {
  if (w.si_joints.empty()) return;
  const auto view = [&](const Joint& j, int i, uint32_t slot) {
    SoftBody v = jointPositionView(w, j, i);
    if (slot != kWorldSlot) {
      const Body& b = w.bodies[slot];
      v.vx = b.velocity.x();
      v.vy = b.velocity.y();
      v.w = b.angular_velocity;
    }
    return v;
  };
  const auto mass = [&](uint32_t slot, double& im, double& ii) { positionMass(w, slot, im, ii); };
  DirectJointScratch& s = scratch(w);
  const JointIslands found = islands(w);
  for (size_t i = 0; i < found.size(); ++i) {
    gather(w, found[i], view, mass, s);
    const std::vector<IslandRow>& rows = s.rows;
    const int m = static_cast<int>(rows.size());
    if (m == 0 || m > kMaxDirectRows) continue;
    s.rhs.resize(m);
    for (int r = 0; r < m; ++r) {
      double cdot = 0.0;
      for (int p = 0; p < 4; ++p) {
        const uint32_t slot = rows[r].slot[p];
        if (slot == kWorldSlot || !w.isActive(slot)) continue;
        const Body& b = w.bodies[slot];
        cdot += rows[r].row.j[p][0] * b.velocity.x() + rows[r].row.j[p][1] * b.velocity.y() + rows[r].row.j[p][2] * b.angular_velocity;
      }
      s.rhs(r) = -cdot;
    }
    effectiveMass(s);
    if (!solveIsland(s)) continue;
    const Eigen::VectorXd& lambda = s.lambda;
    for (int r = 0; r < m; ++r) {
      *rows[r].row.impulse += lambda(r);
      for (int p = 0; p < 4; ++p) {
        const uint32_t slot = rows[r].slot[p];
        if (slot == kWorldSlot || !w.isActive(slot)) continue;
        Body& b = w.bodies[slot];
        b.velocity += b.inv_mass * lambda(r) * Vec2(rows[r].row.j[p][0], rows[r].row.j[p][1]);
        b.angular_velocity += b.inv_inertia * lambda(r) * rows[r].row.j[p][2];
      }
    }
  }
}

int directJointPositions(WorldImpl& w) {
  if (w.si_joints.empty()) return 0;
  const auto view = [&](const Joint& j, int i, uint32_t) { return jointPositionView(w, j, i); };
  const auto mass = [&](uint32_t slot, double& im, double& ii) { positionMass(w, slot, im, ii); };
  constexpr int kNewtonSteps = 6;
  constexpr double kTolerance = 1e-12;  // [m, rad]: round-off
  int steps = 0;
  DirectJointScratch& s = scratch(w);
  const JointIslands found = islands(w);
  for (size_t i = 0; i < found.size(); ++i) {
    for (int it = 0; it < kNewtonSteps; ++it) {
      gather(w, found[i], view, mass, s);
      const std::vector<IslandRow>& rows = s.rows;
      const int m = static_cast<int>(rows.size());
      if (m == 0 || m > kMaxDirectRows) break;
      s.rhs.resize(m);
      double largest = 0.0;
      for (int r = 0; r < m; ++r) {
        const JointRow& row = rows[r].row;
        s.rhs(r) = -std::clamp(row.error, -row.max_error, row.max_error);
        largest = std::max(largest, std::abs(row.error));
      }
      if (largest < kTolerance) break;
      effectiveMass(s);
      if (!solveIsland(s)) break;
      ++steps;
      const Eigen::VectorXd& lambda = s.lambda;
      // Per body of the island, the sum of its rows' corrections, in the rows' order.
      const size_t n = s.island_bodies.size();
      s.move.resize(n);
      s.moved.assign(n, 0);
      for (int r = 0; r < m; ++r)
        for (int p = 0; p < 4; ++p) {
          const uint32_t slot = rows[r].slot[p];
          if (slot == kWorldSlot || !w.isActive(slot)) continue;
          const Body& b = w.bodies[slot];
          const Eigen::Vector3d d(b.inv_mass * lambda(r) * rows[r].row.j[p][0], b.inv_mass * lambda(r) * rows[r].row.j[p][1],
                                  b.inv_inertia * lambda(r) * rows[r].row.j[p][2]);
          const uint32_t k = rows[r].body[p];
          if (s.moved[k]) {
            s.move[k] += d;
          } else {
            s.move[k] = d;
            s.moved[k] = 1;
          }
        }
      for (size_t k = 0; k < n; ++k) {
        if (!s.moved[k]) continue;
        const Eigen::Vector3d& d = s.move[k];
        moveJointBody(w, s.island_bodies[k], Vec2(d.x(), d.y()), d.z());
      }
    }
  }
  return steps;
}

}  // namespace rigidlab

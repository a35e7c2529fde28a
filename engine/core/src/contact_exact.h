// The exact solve of small contact islands with extreme mass ratios (contact_exact.cpp): the contact
// complementarity problem of an island solved directly instead of by more sequential-impulse passes,
// and its overlap removed by the same kind of solve instead of the Gauss–Seidel position passes.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <span>
#include <vector>

#include "contact.h"

namespace rigidlab {

struct WorldImpl;

// Working storage only: a copy of the world starts with an empty one and assigning keeps the
// target's own (as DirectJointScratch: nothing in it outlives a step but `exact` and the islands,
// which the next step makes anew before reading them).
struct ContactExactScratch {
  ContactExactScratch() = default;
  ContactExactScratch(const ContactExactScratch&) {}
  ContactExactScratch& operator=(const ContactExactScratch&) { return *this; }

  std::vector<char> exact;             // per solved contact (WorldImpl::solved): in an exact island
  std::vector<uint32_t> contacts;      // the exact islands' solved contacts, island by island
  std::vector<uint32_t> start;         // island i: contacts[start[i] .. start[i + 1])
  std::vector<uint32_t> local;         // per body slot: its index in the island, UINT32_MAX outside
  std::vector<uint32_t> island_bodies; // the island's body slots by index
  Eigen::MatrixXd jm;                  // M⁻¹ Jᵀ: per row, the velocity change of a unit impulse
  Eigen::MatrixXd jac;                 // J: rows × 3 per island body
  Eigen::MatrixXd a;                   // W = J M⁻¹ Jᵀ
  Eigen::VectorXd q, lo, hi, x, r, friction;
  std::vector<int8_t> state;
  std::vector<int> free_rows;
  Eigen::MatrixXd sub;
  Eigen::VectorXd sub_rhs, sub_x;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
};

// Forgets the last step's exact islands; solved: the number of contacts sequential impulses take.
void beginExactContacts(WorldImpl& w, size_t solved);
// Whether an island of sequential impulses' constraints (indices into `constraints`, all contacts,
// no joint) is one the exact solve takes: at most 64 points, no surface effects (`surfaces`: some
// solved contact of the step has them), a mass ratio
// beyond 100:1 (contact_exact.cpp: kExactPoints, kExactMassRatio; docs/physics.md).
bool takesExactPath(const WorldImpl& w, bool surfaces, const std::vector<SolverBody>& bodies, const std::vector<SolverContact>& constraints,
                    std::span<const uint32_t> island);
// Solves the island's contact impulses exactly on the solver's velocities (normal impulses ≥ 0
// with complementarity, friction within ±μ P_n) and marks its contacts for exactContactPositions.
void solveExactContactIsland(WorldImpl& w, std::vector<SolverBody>& bodies, std::vector<SolverContact>& constraints,
                             std::span<const uint32_t> island);
// The position passes for the marked islands (nonlinear Gauss–Seidel skips their contacts).
void exactContactPositions(WorldImpl& w);

// The boxed linear complementarity problem: x with lo ≤ x ≤ hi and w = A x + q such that w ≥ 0
// where x = lo, w ≤ 0 where x = hi, and w = 0 in between; A symmetric positive definite. x holds a
// guess on entry (it decides the first active set). Returns false if no solution was found in the
// pivots allowed (x then holds the last iterate, within its bounds).
bool solveBoxedLcp(ContactExactScratch& s, const Eigen::MatrixXd& a, const Eigen::VectorXd& q, const Eigen::VectorXd& lo,
                   const Eigen::VectorXd& hi, Eigen::VectorXd& x);

}  // namespace rigidlab

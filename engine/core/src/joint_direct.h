// The working storage of the direct joint solve (joint_direct.cpp), held by the world (WorldImpl)
// so that a step in steady state allocates nothing: a rain of a thousand ragdolls solves a
// thousand islands several times a step, each with its own rows, K = J M⁻¹ Jᵀ and factors.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <deque>
#include <vector>

#include "joint_rows.h"

namespace rigidlab {

// A row of an island: its Jacobian, error and impulse (joint_rows.cpp), its bodies' slots and their
// indices among the island's bodies (UINT32_MAX for the world), how many of its slots count (after
// them come only the world's), and the island's bodies it has a slot for as bits (bit i: the
// island's body i; every bit set for a body past the 64th). Two rows without a common bit share no
// body, so their entry of K = J M⁻¹ Jᵀ is an empty sum.
struct IslandRow {
  JointRow row;
  uint32_t slot[4];
  uint32_t body[4];
  int slots;
  uint64_t bodies;
};

// Working storage only: a copy of the world (World::snapshot) starts with an empty one, and
// assigning one keeps the target's own, which the next solve fills again with the same bits (kept
// factors are reused only beside the K they were computed from). Nothing is copied because a
// default-made Eigen::LDLT that was never computed holds no valid state to copy (UBSan).
struct DirectJointScratch {
  DirectJointScratch() = default;
  DirectJointScratch(const DirectJointScratch&) {}
  DirectJointScratch& operator=(const DirectJointScratch&) { return *this; }

  std::vector<IslandRow> rows;
  std::vector<uint32_t> local;         // per body slot: its index in the island, UINT32_MAX outside it
  std::vector<uint32_t> island_bodies; // the island's body slots by index
  std::vector<double> im, ii;          // per island body: its inverse mass and inertia in K
  std::vector<Eigen::Vector3d> move;   // per island body: its Newton step (Δc, Δθ)
  std::vector<char> moved;             // per island body: move holds a sum
  Eigen::MatrixXd k;
  Eigen::VectorXd rhs, lambda;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;   // reused: recomputing allocates nothing while the size holds
  // Per island (its number in this step's islands): K and its factors at the last velocity solve.
  // Deques: growing one makes its new elements in place and never copies an LDLT that an island
  // left uncomputed (one with no rows or too many).
  std::deque<Eigen::MatrixXd> velocity_k;
  std::deque<Eigen::LDLT<Eigen::MatrixXd>> velocity_ldlt;
};

}  // namespace rigidlab

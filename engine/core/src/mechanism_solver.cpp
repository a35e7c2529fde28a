// The mechanism solver (mechanism.h): A = J M⁻¹ Jᵀ assembled over the island's rows, factored once
// per stage and once per projection, and the solves the stages and the projection need.
//
// A is sparse: two rows share an entry only when they act on a common moving body, so a chain's A
// is block tridiagonal and a tree's has no fill when its leaves are eliminated first (Baraff,
// "Linear-Time Dynamics using Lagrange Multipliers", SIGGRAPH 1996). Large islands are factored as
// LDLᵀ after an approximate minimum degree ordering, which finds such an order for chains and trees
// and keeps the fill of small loops small; the ordering and the symbolic factorisation are kept
// while the island's rows act on the same bodies. Small islands (a pendulum, a ragdoll) are faster
// dense. Redundant constraints (a closed loop of welds) make A singular: then A + εI is factored,
// ε = 1e-12 of A's largest diagonal entry, which gives the dependent rows bounded multipliers and
// changes the independent ones by a relative 1e-12.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mechanism.h"

namespace rigidlab::mechanism {
namespace {

constexpr double kSingular = 1e-13;  // a pivot this small relative to A's largest diagonal: singular
constexpr double kShift = 1e-12;     // the regularisation then, relative to that diagonal
constexpr int kMaxNewton = 24;
// An iteration that does not cut the error by this factor is not converging as it should: simplified
// Newton (A and J of an earlier place) is then replaced by Newton's method, and Newton's method by
// the pins' closure where it applies (project). Simplified Newton's rate is about the drift over the
// lever arms (1e-7 for a ragdoll's step); a chain's 1e-5 m drift gave 0.24 per iteration, which the
// test of halving took as converging: 12 more iterations where one Newton step was enough.
constexpr double kContraction = 0.125;

bool isMoving(const Island& island, uint32_t body) { return body < island.moving; }

// J_r M⁻¹ J_sᵀ over one body.
double weighted(const Eigen::Vector3d& jr, const Eigen::Vector3d& js, double im, double ii) {
  return im * (jr.x() * js.x() + jr.y() * js.y()) + ii * jr.z() * js.z();
}

}  // namespace

void Solver::evaluateRows(const Island& island) {
  const size_t m = island.equalities.size(), n = m + island.motors.size();
  rows_.resize(n);
  const Rot* rot = place(island);
  const bool check = !built_ || island.shape != checked_shape_ || island.shape == 0;
  if (check) {
    pin_first_.assign(m, 0);
    for (size_t k = 0; k + 1 < m; ++k)
      if (isPinPair(island.equalities[k].coordinate, island.equalities[k + 1].coordinate)) pin_first_[k++] = 1;
  }
  for (size_t k = 0; k < n; ++k) {
    if (k < m && pin_first_[k]) {
      evaluatePin(island.equalities[k].coordinate, island.states.data(), rot, rows_[k], rows_[k + 1]);
      ++k;
      continue;
    }
    const Coordinate& c = k < m ? island.equalities[k].coordinate : island.motors[k - m].coordinate;
    rows_[k] = evaluate(c, island.states.data(), rot);
  }
  use_.resize(n, 1);
  if (!check) return;
  // The structure is each row's moving bodies, in order: when it is the one the factorisation was
  // set up for, its analysis is kept. The rows' bodies change only with the island's shape.
  checked_shape_ = island.shape;
  signature_now_.clear();
  for (size_t k = 0; k < n; ++k) {
    const Evaluated& r = rows_[k];
    const size_t at = signature_now_.size();
    signature_now_.push_back(0);
    for (int i = 0; i < r.count; ++i)
      if (isMoving(island, r.body[i])) {
        signature_now_.push_back(r.body[i]);
        ++signature_now_[at];
      }
  }
  if (signature_now_ != signature_ || !built_) {
    signature_.swap(signature_now_);
    structure(island);
  }
}

void Solver::structure(const Island& island) {
  const size_t m = rows_.size();
  built_ = true;
  analysed_ = false;
  shift_ = 0.0;
  used_.clear();
  tree_ = tree_factor_.build(island, rows_);
  if (tree_) return;
  // Per moving body, the rows that act on it (and where it is in each row's Jacobian).
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> by_body(island.moving);
  for (uint32_t r = 0; r < m; ++r)
    for (int i = 0; i < rows_[r].count; ++i)
      if (isMoving(island, rows_[r].body[i])) by_body[rows_[r].body[i]].push_back({r, static_cast<uint32_t>(i)});
  entries_.clear();
  for (uint32_t body = 0; body < island.moving; ++body) {
    const auto& list = by_body[body];
    for (size_t x = 0; x < list.size(); ++x)
      for (size_t y = 0; y <= x; ++y) {
        // Lower triangle: r ≥ s.
        auto [r, jr] = list[x];
        auto [s, js] = list[y];
        if (r < s) {
          std::swap(r, s);
          std::swap(jr, js);
        }
        entries_.push_back({r, s, jr, js, body, -1});
      }
  }
  dense_ = m <= static_cast<size_t>(kDenseRows);
  if (dense_) {
    dense_a_.setZero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
    return;
  }
  // The sparse pattern: every entry, and the diagonal (a row on fixed-rotation bodies only may
  // have none, and the shift needs it).
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(entries_.size() + m);
  for (const Entry& e : entries_) triplets.emplace_back(static_cast<int>(e.r), static_cast<int>(e.s), 0.0);
  for (uint32_t r = 0; r < m; ++r) triplets.emplace_back(static_cast<int>(r), static_cast<int>(r), 0.0);
  sparse_a_.resize(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  sparse_a_.setFromTriplets(triplets.begin(), triplets.end());
  sparse_a_.makeCompressed();
  for (Entry& e : entries_) {
    const int* inner = sparse_a_.innerIndexPtr();
    const int begin = sparse_a_.outerIndexPtr()[e.s], end = sparse_a_.outerIndexPtr()[e.s + 1];
    e.value = static_cast<int>(std::lower_bound(inner + begin, inner + end, static_cast<int>(e.r)) - inner);
  }
}

void Solver::factor(const Island& island) {
  const Eigen::Index m = static_cast<Eigen::Index>(rows_.size());
  used_ = use_;
  if (tree_) {
    tree_factor_.factor(island, rows_, use_);
    return;
  }
  double largest = 0.0;
  if (dense_) {
    compact_.resize(static_cast<size_t>(m));
    Eigen::Index n = 0;
    for (Eigen::Index r = 0; r < m; ++r) {
      compact_[r] = use_[r] ? static_cast<int>(n++) : -1;
      if (!use_[r]) largest = 1.0;  // what a row out of use stands for: an identity diagonal
    }
    dense_a_.setZero(n, n);
    for (const Entry& e : entries_)
      if (use_[e.r] && use_[e.s])
        dense_a_(compact_[e.r], compact_[e.s]) += weighted(rows_[e.r].j[e.jr], rows_[e.s].j[e.js], island.im[e.body], island.ii[e.body]);
    for (Eigen::Index k = 0; k < n; ++k) largest = std::max(largest, dense_a_(k, k));
    dense_shift_ = 0.0;
    if (n == 0) return;
    dense_ldlt_.compute(dense_a_);
    const auto d = dense_ldlt_.vectorD();
    bool singular = false;
    for (Eigen::Index k = 0; k < n; ++k) singular |= !(std::abs(d[k]) > kSingular * largest);
    if (singular && largest > 0.0) {
      dense_shift_ = kShift * largest;
      dense_a_.diagonal().array() += dense_shift_;
      dense_ldlt_.compute(dense_a_);
    }
    return;
  }
  double* values = sparse_a_.valuePtr();
  std::fill(values, values + sparse_a_.nonZeros(), 0.0);
  for (const Entry& e : entries_)
    if (use_[e.r] && use_[e.s])
      values[e.value] += weighted(rows_[e.r].j[e.jr], rows_[e.s].j[e.js], island.im[e.body], island.ii[e.body]);
  for (Eigen::Index r = 0; r < m; ++r) {
    if (!use_[r]) sparse_a_.coeffRef(r, r) = 1.0;
    largest = std::max(largest, sparse_a_.coeff(r, r));
  }
  if (!sparse_ldlt_) sparse_ldlt_ = std::make_unique<std::remove_reference_t<decltype(*sparse_ldlt_)>>();
  if (!analysed_) {
    sparse_ldlt_->analyzePattern(sparse_a_);
    analysed_ = true;
  }
  sparse_ldlt_->setShift(shift_);
  sparse_ldlt_->factorize(sparse_a_);
  const auto d = sparse_ldlt_->vectorD();
  bool singular = false;
  for (Eigen::Index r = 0; r < m; ++r) singular |= !(std::abs(d[r]) > kSingular * largest);
  if (singular && largest > 0.0) {
    shift_ = kShift * largest;
    sparse_ldlt_->setShift(shift_);
    sparse_ldlt_->factorize(sparse_a_);
  } else if (shift_ != 0.0) {
    shift_ = 0.0;  // no longer singular: factored exactly again
    sparse_ldlt_->setShift(0.0);
    sparse_ldlt_->factorize(sparse_a_);
  }
}

void Solver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (tree_) {
    tree_factor_.solve(rows_, b, x);
  } else if (dense_) {
    const Eigen::Index n = dense_a_.rows();
    compact_b_.resize(n);
    for (size_t r = 0; r < compact_.size(); ++r)
      if (compact_[r] >= 0) compact_b_[compact_[r]] = b[static_cast<Eigen::Index>(r)];
    if (n > 0) compact_x_ = dense_ldlt_.solve(compact_b_);
    x.resize(b.size());
    for (size_t r = 0; r < compact_.size(); ++r) {
      const Eigen::Index i = static_cast<Eigen::Index>(r);
      x[i] = compact_[r] >= 0 ? compact_x_[compact_[r]] : b[i] / (1.0 + dense_shift_);
    }
  } else {
    x = sparse_ldlt_->solve(b);
  }
}

void Solver::applyTranspose(const Island& island, const Eigen::VectorXd& lambda, double scale, Eigen::VectorXd& out) const {
  for (size_t r = 0; r < rows_.size(); ++r) {
    if (!use_[r]) continue;
    const double l = scale * lambda[static_cast<Eigen::Index>(r)];
    const Evaluated& row = rows_[r];
    for (int i = 0; i < row.count; ++i) {
      const uint32_t k = row.body[i];
      if (!isMoving(island, k)) continue;
      out[3 * k] += island.im[k] * l * row.j[i].x();
      out[3 * k + 1] += island.im[k] * l * row.j[i].y();
      out[3 * k + 2] += island.ii[k] * l * row.j[i].z();
    }
  }
}

void Solver::forces(const Island& island, const Eigen::Vector3d* accel, Eigen::Vector3d* force) {
  const uint32_t n = island.moving;
  for (uint32_t k = 0; k < n; ++k) force[k].setZero();
  // Springs first: their accelerations are part of what the constraints answer.
  spring_force_.assign(island.springs.size(), 0.0);
  const Rot* rot = island.springs.empty() ? nullptr : place(island);
  for (size_t q = 0; q < island.springs.size(); ++q) {
    const Spring& s = island.springs[q];
    Evaluated e[2];
    for (int i = 0; i < s.dimension; ++i) e[i] = evaluate(s.coordinate[i], island.states.data(), rot);
    // K = J M⁻¹ Jᵀ of the spring's coordinates.
    double k[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    for (int p = 0; p < s.dimension; ++p)
      for (int r = 0; r < s.dimension; ++r)
        for (int x = 0; x < e[p].count; ++x)
          for (int y = 0; y < e[r].count; ++y)
            if (e[p].body[x] == e[r].body[y] && isMoving(island, e[p].body[x]))
              k[p][r] += weighted(e[p].j[x], e[r].j[y], island.im[e[p].body[x]], island.ii[e[p].body[x]]);
    const double omega = 2.0 * std::numbers::pi * s.hertz;
    double g[2];
    for (int i = 0; i < s.dimension; ++i)
      g[i] = -(omega * omega * (e[i].x - s.rest[i]) + 2.0 * s.damping_ratio * omega * e[i].xdot);
    double f[2] = {0.0, 0.0};
    if (s.dimension == 1) {
      f[0] = k[0][0] > 0.0 ? std::clamp(g[0] / k[0][0], -s.max_force, s.max_force) : 0.0;
    } else {
      const double det = k[0][0] * k[1][1] - k[0][1] * k[1][0];
      if (det > 0.0) {
        f[0] = (k[1][1] * g[0] - k[0][1] * g[1]) / det;
        f[1] = (k[0][0] * g[1] - k[1][0] * g[0]) / det;
      }
    }
    spring_force_[q] = f[0];
    for (int i = 0; i < s.dimension; ++i)
      for (int x = 0; x < e[i].count; ++x)
        if (isMoving(island, e[i].body[x])) force[e[i].body[x]] += f[i] * e[i].j[x];
  }
  const size_t m = island.equalities.size(), rows = m + island.motors.size();
  lambda_.setZero(static_cast<Eigen::Index>(rows));
  if (rows == 0) return;
  evaluateRows(island);
  // Which rows take part: equalities always; a limit while at its bound; a motor while at its
  // speed (else it pushes with its whole force towards it).
  motor_force_.assign(island.motors.size(), 0.0);
  for (size_t r = 0; r < m; ++r) {
    const Equality& e = island.equalities[r];
    use_[r] = e.sign == 0.0 || std::abs(rows_[r].x - e.target) <= island.tolerance;
  }
  motor_mode_.resize(island.motors.size(), 0);
  for (size_t q = 0; q < island.motors.size(); ++q) {
    use_[m + q] = motor_mode_[q] == 0;
    // (0, not 0 · max: a motor of unlimited force that holds its speed pushes with nothing more.)
    motor_force_[q] = motor_mode_[q] == 0 ? 0.0 : motor_mode_[q] * island.motors[q].max_force;
  }
  rhs_.resize(static_cast<Eigen::Index>(rows));
  // J a + J̇ v with a the accelerations from every other force, the springs and the motors that push.
  const auto motorForces = [&](Eigen::Vector3d* f) {
    for (size_t q = 0; q < island.motors.size(); ++q) {
      if (motor_force_[q] == 0.0) continue;
      const Evaluated& row = rows_[m + q];
      for (int i = 0; i < row.count; ++i)
        if (isMoving(island, row.body[i])) f[row.body[i]] += motor_force_[q] * row.j[i];
    }
  };
  body_accel_.resize(n);
  for (size_t round = 0; round <= rows; ++round) {
    // Each moving body's acceleration: the other forces', the springs' and the pushing motors'.
    for (uint32_t b = 0; b < n; ++b) body_accel_[b] = force[b];
    for (size_t q = 0; q < island.motors.size(); ++q) {
      if (motor_force_[q] == 0.0) continue;
      const Evaluated& mrow = rows_[m + q];
      for (int k2 = 0; k2 < mrow.count; ++k2)
        if (isMoving(island, mrow.body[k2])) body_accel_[mrow.body[k2]] += motor_force_[q] * mrow.j[k2];
    }
    for (uint32_t b = 0; b < n; ++b) {
      const Eigen::Vector3d& f = body_accel_[b];
      body_accel_[b] = Eigen::Vector3d(accel[b].x() + island.im[b] * f.x(), accel[b].y() + island.im[b] * f.y(),
                                       accel[b].z() + island.ii[b] * f.z());
    }
    for (size_t r = 0; r < rows; ++r) {
      const Evaluated& row = rows_[r];
      double ja = row.jdotv;
      for (int i = 0; i < row.count; ++i)
        if (isMoving(island, row.body[i])) ja += row.j[i].dot(body_accel_[row.body[i]]);
      rhs_[static_cast<Eigen::Index>(r)] = use_[r] ? -ja : 0.0;
    }
    factor(island);
    solve(rhs_, lambda_);
    // A limit that pulls lets go; a motor past its force pushes with it; then again.
    bool changed = false;
    for (size_t r = 0; r < m; ++r) {
      const double sign = island.equalities[r].sign;
      if (use_[r] && sign != 0.0 && lambda_[static_cast<Eigen::Index>(r)] * sign < 0.0) {
        use_[r] = 0;
        changed = true;
      }
    }
    for (size_t q = 0; q < island.motors.size(); ++q) {
      const double l = lambda_[static_cast<Eigen::Index>(m + q)], max = island.motors[q].max_force;
      if (use_[m + q] && std::abs(l) > max) {
        use_[m + q] = 0;
        motor_force_[q] = l > 0.0 ? max : -max;
        if (q < motor_push_.size()) motor_push_[q] = l > 0.0 ? 1 : -1;
        changed = true;
      }
    }
    if (!changed) break;
  }
  for (size_t r = 0; r < rows; ++r) {
    if (!use_[r]) {
      lambda_[static_cast<Eigen::Index>(r)] = r >= m ? motor_force_[r - m] : 0.0;
      continue;
    }
    const double l = lambda_[static_cast<Eigen::Index>(r)];
    const Evaluated& row = rows_[r];
    for (int i = 0; i < row.count; ++i)
      if (isMoving(island, row.body[i])) force[row.body[i]] += l * row.j[i];
  }
  motorForces(force);
}

Residuals Solver::residuals(const Island& island) {
  const Rot* rot = place(island);
  Residuals out;
  for (const Equality& e : island.equalities) {
    const Evaluated at = evaluate(e.coordinate, island.states.data(), rot);
    const double g = at.x - e.target;
    out.position = std::max(out.position, e.sign == 0.0 ? std::abs(g) : std::max(0.0, -e.sign * g));
    if (e.sign == 0.0) out.velocity = std::max(out.velocity, std::abs(at.xdot));
  }
  return out;
}

void Solver::beginStep(Island& island, double h) {
  step_h_ = h;
  const size_t m = island.equalities.size(), rows = m + island.motors.size();
  impulse_.setZero(static_cast<Eigen::Index>(rows));
  motor_mode_.assign(island.motors.size(), 0);
  motor_push_.assign(island.motors.size(), 0);
  motor_rate_.resize(island.motors.size());
  if (island.motors.empty()) return;
  // A motor off its speed is caught there by one impulse, with the joints and limits holding, if
  // that impulse is within what its force gives in the step (|Λ| ≤ max h, Λ from the whole island:
  // a crank's motor moves its weight about the pin, not about its centre of mass); else it pushes
  // with its whole force. Motors whose catch asks too much push, and the others are caught again.
  // The motors' rows alone first: when every motor is at its speed (most steps of a ragdoll's
  // joint friction) nothing else is needed.
  std::vector<int8_t>& off_sign = off_sign_;
  off_sign.assign(island.motors.size(), 0);
  bool any_off = false;
  const Rot* rot = place(island);
  for (size_t q = 0; q < island.motors.size(); ++q) {
    const double xdot = evaluate(island.motors[q].coordinate, island.states.data(), rot).xdot;
    motor_rate_[q] = xdot - island.motors[q].speed;
    const double off = island.motors[q].speed - xdot;
    if (std::abs(off) > island.speed_tolerance) off_sign[q] = off > 0.0 ? 1 : -1;
    any_off |= off_sign[q] != 0;
  }
  if (!any_off) return;
  evaluateRows(island);
  start_.assign(island.states.begin(), island.states.end());
  for (size_t round = 0; round <= island.motors.size(); ++round) {
    bool catches = false;
    for (size_t q = 0; q < island.motors.size(); ++q) catches |= off_sign[q] != 0 && motor_mode_[q] == 0;
    if (!catches) break;
    for (size_t q = 0; q < island.motors.size(); ++q) motor_rate_[q] = rows_[m + q].xdot - island.motors[q].speed;
    velocityPasses(island, true);  // the rows were evaluated where the bodies are
    bool over = false;
    for (size_t q = 0; q < island.motors.size(); ++q) {
      if (off_sign[q] == 0 || motor_mode_[q] != 0) continue;
      if (std::abs(impulse_[static_cast<Eigen::Index>(m + q)]) > island.motors[q].max_force * h) {
        motor_mode_[q] = motor_push_[q] = off_sign[q];
        over = true;
      }
    }
    if (!over) return;  // velocityPasses left motor_rate_ at the caught rates
    std::copy(start_.begin(), start_.end(), island.states.begin());
    impulse_.setZero(static_cast<Eigen::Index>(rows));
    evaluateRows(island);
  }
  for (size_t q = 0; q < island.motors.size(); ++q) motor_rate_[q] = rows_[m + q].xdot - island.motors[q].speed;
}

Projection Solver::project(Island& island, double tolerance) {
  Projection result;
  const size_t m = island.equalities.size(), rows = m + island.motors.size();
  impulse_.setZero(static_cast<Eigen::Index>(rows));
  if (rows == 0) return result;
  // Positions: the equalities, and the limits the bodies are at or past (put back at their bound).
  evaluateRows(island);
  const auto positionRows = [&] {
    for (size_t r = 0; r < m; ++r) {
      const Equality& e = island.equalities[r];
      use_[r] = e.sign == 0.0 || e.sign * (rows_[r].x - e.target) <= island.tolerance;
    }
    for (size_t q = 0; q < island.motors.size(); ++q) use_[m + q] = 0;
  };
  positionRows();
  // A and J at the step's end, kept for the Newton iterations while they converge (simplified
  // Newton: the error after a step's drift falls by a factor of the drift per iteration); when an
  // iteration does not cut the error by kContraction (a long step's large drift; a long chain,
  // whose A is ill-conditioned, corrects a small gap with large motions), A and J are taken again
  // where the bodies are (Newton's method), or the pins closed (below). A step that would raise
  // the error is shortened (halved up to six times, a backtracking line search: far from the
  // joints the linearisation overshoots); when even that does not lower it, round-off is reached.
  factor(island);
  rhs_.resize(static_cast<Eigen::Index>(rows));
  start_.resize(island.moving);
  const auto largestError = [&](bool fill) {
    const Rot* rot = place(island);
    double largest = 0.0;
    for (size_t r = 0; r < rows; ++r) {
      if (!use_[r]) {
        if (fill) rhs_[static_cast<Eigen::Index>(r)] = 0.0;
        continue;
      }
      const double g = evaluate(island.equalities[r].coordinate, island.states.data(), rot).x - island.equalities[r].target;
      if (fill) rhs_[static_cast<Eigen::Index>(r)] = -g;
      largest = std::max(largest, std::abs(g));
    }
    return largest;
  };
  const auto refactor = [&] {
    const std::vector<char> keep = use_;
    evaluateRows(island);
    use_ = keep;
    factor(island);
  };
  double largest = largestError(true);
  result.drift = result.residual = largest;
  bool fresh = true;  // the factorisation in use was taken where the bodies are
  for (int it = 0; it < kMaxNewton && largest > tolerance; ++it) {
    solve(rhs_, lambda_);
    dq_.setZero(3 * static_cast<Eigen::Index>(island.moving));
    applyTranspose(island, lambda_, 1.0, dq_);
    for (uint32_t k = 0; k < island.moving; ++k) start_[k] = island.states[k];
    double next = largest, fraction = 1.0;
    for (int halving = 0; halving <= 6; ++halving, fraction *= 0.5) {
      for (uint32_t k = 0; k < island.moving; ++k) {
        island.states[k].c = start_[k].c + fraction * Vec2(dq_[3 * k], dq_[3 * k + 1]);
        island.states[k].angle = start_[k].angle + fraction * dq_[3 * k + 2];
      }
      next = largestError(true);
      if (next < largest) break;
    }
    if (!(next < largest)) {
      for (uint32_t k = 0; k < island.moving; ++k) island.states[k] = start_[k];
      largestError(true);
      if (fresh) break;  // Newton's own step, shortened, does not lower it: round-off
      refactor();
      fresh = true;
      continue;
    }
    ++result.iterations;
    const double previous = largest;
    const bool fast = next < kContraction * largest;
    largest = next;
    result.residual = largest;
    // Newton's own step (A and J where the bodies were) did not even halve the error: the gaps are
    // beyond the region where it converges fast. That region shrinks as ℓ / n² on a chain of n
    // links of lever ℓ (A's smallest eigenvalue, the chain sliding along itself, falls as 1/n²:
    // a gap g is closed by moving links ~ n g along the chain, which turns them by ~ n g / ℓ, and
    // the linearisation's error is ~ (n g)² / ℓ): a 10 000-link chain's 0.1–1 mm drifts took 18 to
    // 24 iterations, a third of them without converging (measured). Islands of pins alone are
    // closed exactly instead, by translations from each tree's root (TreeFactor::closePins): not
    // the projection in the mass metric, but on the joints to round-off, each body moved by the
    // sum of the gaps on its path to the root (O(g) for a given island), which keeps the
    // integrator's order as well (Hairer, Lubich, Wanner IV.4: the order needs a smooth map onto
    // the joints that moves the state by O(g), not the orthogonal one).
    if (next >= 0.5 * previous && largest > tolerance && fresh && tree_ && tree_factor_.closePins(island, use_, place(island))) {
      largest = result.residual = largestError(true);
      ++result.iterations;
      result.closed = true;
      break;
    }
    if (!fast && largest > tolerance) {
      refactor();  // not converging as simplified Newton: Newton's method from here
      fresh = true;
    } else {
      fresh = false;
    }
  }
  // Velocities tangent to the rows where the bodies now are.
  velocityPasses(island);
  return result;
}

void Solver::projectVelocities(Island& island) {
  const Eigen::Index rows = static_cast<Eigen::Index>(island.equalities.size() + island.motors.size());
  impulse_.setZero(rows);
  if (rows == 0) return;
  rhs_.resize(rows);
  velocityPasses(island);
}

void Solver::velocityPasses(Island& island, bool evaluated) {
  const size_t m = island.equalities.size(), rows = m + island.motors.size();
  impulse_.setZero(static_cast<Eigen::Index>(rows));
  rhs_.resize(static_cast<Eigen::Index>(rows));
  // Which rows: the equalities; a limit at its bound that the velocities run into (an inelastic
  // stop); a motor at its speed, or whose rate crossed it since markStart (caught at its speed).
  if (!evaluated) evaluateRows(island);
  motor_rate_.resize(island.motors.size(), 0.0);
  for (size_t r = 0; r < m; ++r) {
    const Equality& e = island.equalities[r];
    use_[r] = e.sign == 0.0 ||
              (e.sign * (rows_[r].x - e.target) <= island.tolerance && e.sign * rows_[r].xdot < 0.0);
  }
  motor_mode_.resize(island.motors.size(), 0);
  for (size_t q = 0; q < island.motors.size(); ++q) {
    const double off = rows_[m + q].xdot - island.motors[q].speed;
    use_[m + q] = motor_mode_[q] == 0 || off * motor_rate_[q] <= 0.0;
  }
  // A and J where the bodies are; a second pass takes the remainder of the first's round-off. A
  // limit whose impulse would pull lets go.
  for (int pass = 0; pass < 3; ++pass) {
    if (pass == 0 || used_ != use_) factor(island);
    for (size_t r = 0; r < rows; ++r) {
      const double target = r < m ? 0.0 : island.motors[r - m].speed;
      rhs_[static_cast<Eigen::Index>(r)] = use_[r] ? target - rows_[r].xdot : 0.0;
    }
    solve(rhs_, lambda_);
    bool released = false;
    for (size_t r = 0; r < m; ++r) {
      const double sign = island.equalities[r].sign;
      if (use_[r] && sign != 0.0 && (impulse_[static_cast<Eigen::Index>(r)] + lambda_[static_cast<Eigen::Index>(r)]) * sign < 0.0) {
        use_[r] = 0;
        released = true;
      }
    }
    // A pushing motor caught at its speed where it crossed it: only while its step's impulse,
    // the push and the catch together, stays within max · h; else it is left past its speed
    // (the next step's beginStep turns it round with its whole force or catches it there).
    for (size_t q = 0; q < island.motors.size() && q < motor_push_.size(); ++q) {
      const Eigen::Index r = static_cast<Eigen::Index>(m + q);
      if (!use_[m + q] || motor_push_[q] == 0) continue;
      const double max = island.motors[q].max_force * step_h_;
      if (std::abs(motor_push_[q] * max + impulse_[r] + lambda_[r]) > max) {
        use_[m + q] = 0;
        released = true;
      }
    }
    if (released) continue;  // solved again without it
    impulse_ += lambda_;
    dq_.setZero(3 * static_cast<Eigen::Index>(island.moving));
    applyTranspose(island, lambda_, 1.0, dq_);
    for (uint32_t k = 0; k < island.moving; ++k) {
      island.states[k].v += Vec2(dq_[3 * k], dq_[3 * k + 1]);
      island.states[k].w += dq_[3 * k + 2];
    }
    // ẋ = J v with J where the bodies are (the positions did not move): each row's rate anew.
    for (size_t r = 0; r < rows; ++r) {
      Evaluated& row = rows_[r];
      double xdot = 0.0;
      for (int i = 0; i < row.count; ++i) {
        const State& st = island.states[row.body[i]];
        xdot += row.j[i].x() * st.v.x() + row.j[i].y() * st.v.y() + row.j[i].z() * st.w;
      }
      row.xdot = xdot;
    }
  }
  for (size_t q = 0; q < island.motors.size(); ++q) motor_rate_[q] = rows_[m + q].xdot - island.motors[q].speed;
}

}  // namespace rigidlab::mechanism

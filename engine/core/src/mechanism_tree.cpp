// J M⁻¹ Jᵀ of a forest of jointed bodies factored in tree order (mechanism.h TreeFactor).
//
// The rows are grouped by the moving bodies they act on (a pin's two point rows, its limit and motor
// rows: one group). In a forest every group on two bodies is an edge between them, and groups are
// coupled (A's block between them nonzero) only through a common body. Each tree is rooted at a
// body and walked from its leaves: at body c, the groups on c alone (held to fixed bodies) go first,
// then the edge to c's parent p. When a group goes, every other group at its lower body has gone,
// so the groups it is coupled with all meet at one body, `up` (c for a group on c alone, p for the
// edge), and are coupled with each other through it already: no fill. Its block LDLᵀ step is
//   D = Σ_b J_b W̃_b J_bᵀ,   u = W̃_up J_upᵀ,   W̃_up ← W̃_up − u D⁻¹ uᵀ
// (the Schur complement of the group, which reaches the remaining groups only through up's W̃).
// A = L D Lᵀ with L's block between a later group h and g being J_h,up u D⁻¹, so
//   forward   z_g = D⁻¹ (b_g − Σ_b J_g,b s_b),  s_up += u z_g       (s_b: Σ u z of the groups whose up is b)
//   backward  λ_g = z_g − D⁻¹ uᵀ t_up,  t_b += J_g,bᵀ λ_g            (t_b: Σ Jᵀ λ of the later groups at b)
// Each costs a few 3 × 3 products per group: linear in the island's joints.
#include <algorithm>
#include <cmath>

#include "mechanism.h"

namespace rigidlab::mechanism {
namespace {

constexpr double kSingular = 1e-13;  // a pivot this small relative to D's largest diagonal: singular
constexpr double kShift = 1e-12;     // the regularisation then, relative to that diagonal
constexpr uint32_t kMaxGroupRows = 12;
constexpr uint8_t kNone = 255;

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// LDLᵀ of the n × n matrix in `l` (row-major, lower triangle read), in place: L below the diagonal
// (unit diagonal), D⁻¹ into d (the solves multiply: a division costs several multiplications).
// False when a pivot is not above `floor`. N: n when known at compile time (the loops then unroll:
// a pin's group has 2 rows), 0 for any.
template <uint32_t N>
bool ldltOf(double* l, double* d, uint32_t size, double floor) {
  const uint32_t n = N ? N : size;
  for (uint32_t j = 0; j < n; ++j) {
    double dj = l[j * n + j];
    for (uint32_t k = 0; k < j; ++k) dj -= l[j * n + k] * l[j * n + k] * d[k];
    if (!(dj > floor)) return false;
    d[j] = dj;
    const double inverse = 1.0 / dj;
    for (uint32_t i = j + 1; i < n; ++i) {
      double v = l[i * n + j];
      for (uint32_t k = 0; k < j; ++k) v -= l[i * n + k] * l[j * n + k] * d[k];
      l[i * n + j] = v * inverse;
    }
  }
  for (uint32_t j = 0; j < n; ++j) d[j] = 1.0 / d[j];
  return true;
}

// y ← (L D Lᵀ)⁻¹ y (d: D⁻¹).
template <uint32_t N>
void ldltSolveOf(const double* l, const double* d, uint32_t size, double* y) {
  const uint32_t n = N ? N : size;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = 0; k < i; ++k) y[i] -= l[i * n + k] * y[k];
  for (uint32_t i = 0; i < n; ++i) y[i] *= d[i];
  for (uint32_t i = n; i-- > 0;)
    for (uint32_t k = i + 1; k < n; ++k) y[i] -= l[k * n + i] * y[k];
}

// Inlined into their callers (a call and a dispatch per group and solve cost as much as a 2 × 2
// solve; measured with callgrind on the ragdolls).
[[gnu::always_inline]] inline bool ldlt(double* l, double* d, uint32_t n, double floor) {
  switch (n) {
    case 1: return ldltOf<1>(l, d, n, floor);
    case 2: return ldltOf<2>(l, d, n, floor);
    case 3: return ldltOf<3>(l, d, n, floor);
    case 4: return ldltOf<4>(l, d, n, floor);
    default: return ldltOf<0>(l, d, n, floor);
  }
}

[[gnu::always_inline]] inline void ldltSolve(const double* l, const double* d, uint32_t n, double* y) {
  switch (n) {
    case 1: ldltSolveOf<1>(l, d, n, y); break;
    case 2: ldltSolveOf<2>(l, d, n, y); break;
    case 3: ldltSolveOf<3>(l, d, n, y); break;
    case 4: ldltSolveOf<4>(l, d, n, y); break;
    default: ldltSolveOf<0>(l, d, n, y); break;
  }
}

}  // namespace

bool TreeFactor::build(const Island& island, const std::vector<Evaluated>& rows) {
  groups_.clear();
  members_.clear();
  const uint32_t bodies = island.moving;
  // Each row's moving bodies (at most two), as a key (lower, upper; upper == lower for one).
  struct Keyed {
    uint32_t lo, hi, row;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(rows.size());
  for (uint32_t r = 0; r < rows.size(); ++r) {
    uint32_t found[2];
    int count = 0;
    for (int i = 0; i < rows[r].count; ++i) {
      if (rows[r].body[i] >= bodies) continue;
      if (count == 2) return false;
      found[count++] = rows[r].body[i];
    }
    if (count == 0) return false;
    if (count == 1) found[1] = found[0];
    keyed.push_back({std::min(found[0], found[1]), std::max(found[0], found[1]), r});
  }
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& x, const Keyed& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.row < y.row;
  });
  // The groups, and the bodies' graph: a forest when no edge closes a loop.
  struct Proto {
    uint32_t lo, hi, first, count;
  };
  std::vector<Proto> protos;
  std::vector<uint32_t> sorted_rows;
  std::vector<uint32_t> parent(bodies);
  for (uint32_t b = 0; b < bodies; ++b) parent[b] = b;
  for (size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || keyed[k].lo != keyed[k - 1].lo || keyed[k].hi != keyed[k - 1].hi) {
      protos.push_back({keyed[k].lo, keyed[k].hi, static_cast<uint32_t>(sorted_rows.size()), 0});
      if (keyed[k].lo != keyed[k].hi) {
        const uint32_t ra = findRoot(parent, keyed[k].lo), rb = findRoot(parent, keyed[k].hi);
        if (ra == rb) return false;  // a closed loop
        parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
    sorted_rows.push_back(keyed[k].row);
    if (++protos.back().count > kMaxGroupRows) return false;
  }
  // Each body's groups; each tree walked from a root (breadth first), then taken leaves first.
  std::vector<std::vector<uint32_t>> at(bodies);
  for (uint32_t g = 0; g < protos.size(); ++g) {
    at[protos[g].lo].push_back(g);
    if (protos[g].hi != protos[g].lo) at[protos[g].hi].push_back(g);
  }
  std::vector<uint32_t> order, up_edge(bodies, UINT32_MAX), up_body(bodies, UINT32_MAX);
  std::vector<char> seen(bodies, 0);
  order.reserve(bodies);
  tree_of_.assign(bodies, 0);
  for (uint32_t root = 0; root < bodies; ++root) {
    if (seen[root]) continue;
    seen[root] = 1;
    size_t head = order.size();
    order.push_back(root);
    for (; head < order.size(); ++head) {
      const uint32_t b = order[head];
      tree_of_[b] = root;
      for (uint32_t g : at[b]) {
        const Proto& p = protos[g];
        if (p.lo == p.hi) continue;
        const uint32_t other = p.lo == b ? p.hi : p.lo;
        if (seen[other]) continue;
        seen[other] = 1;
        up_edge[other] = g;
        up_body[other] = b;
        order.push_back(other);
      }
    }
  }
  const auto indexIn = [&](uint32_t row, uint32_t body) {
    for (int i = 0; i < rows[row].count; ++i)
      if (rows[row].body[i] == body) return static_cast<uint8_t>(i);
    return kNone;
  };
  uint32_t arena = 0;
  const auto add = [&](const Proto& p, uint32_t up, uint32_t down) {
    Group g;
    g.up = up;
    g.down = down;
    g.root = up == down && up_edge[up] == UINT32_MAX;
    g.first = static_cast<uint32_t>(members_.size());
    g.count = p.count;
    g.at = arena;
    arena += p.count * p.count + 9 * p.count;
    for (uint32_t k = 0; k < p.count; ++k) {
      const uint32_t row = sorted_rows[p.first + k];
      members_.push_back(row);
      j_up_.push_back(indexIn(row, up));
      j_down_.push_back(up == down ? kNone : indexIn(row, down));
    }
    groups_.push_back(g);
  };
  j_up_.clear();
  j_down_.clear();
  for (size_t k = order.size(); k-- > 0;) {
    const uint32_t c = order[k];
    for (uint32_t g : at[c])
      if (protos[g].lo == protos[g].hi) add(protos[g], c, c);
    if (up_edge[c] != UINT32_MAX) add(protos[up_edge[c]], up_body[c], c);
  }
  arena_.assign(arena, 0.0);
  in_use_.assign(members_.size(), 0);
  w_.resize(bodies);
  s_.resize(bodies);
  held_.assign(bodies, 0);
  moved_.assign(bodies, Vec2::Zero());
  tree_mass_.assign(bodies, 0.0);
  return true;
}

void TreeFactor::factor(const Island& island, const std::vector<Evaluated>& rows, const std::vector<char>& use) {
  for (uint32_t b = 0; b < island.moving; ++b)
    w_[b] = Eigen::Vector3d(island.im[b], island.im[b], island.ii[b]).asDiagonal();
  for (Group& g : groups_) {
    uint32_t n = 0;
    for (uint32_t k = 0; k < g.count; ++k)
      if (use[members_[g.first + k]]) in_use_[g.first + n++] = g.first + k;
    g.n = n;
    if (n == 0) continue;
    double* l = arena_.data() + g.at;
    double* d = l + n * n;
    double* u = d + n;  // 3 × n, column k at u + 3k
    const Eigen::Matrix3d& wu = w_[g.up];
    // u_k = W̃_up J_up,kᵀ; D_kl = J_up,k · u_l (+ J_down,k W̃_down J_down,lᵀ).
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t m = in_use_[g.first + k];
      Eigen::Map<Eigen::Vector3d>(u + 3 * k) = wu * rows[members_[m]].j[j_up_[m]];
    }
    // The lower triangle of D, `shift` added to its diagonal; returns D's largest diagonal entry.
    const auto fill = [&](double shift) __attribute__((always_inline)) {
      double largest = 0.0;
      for (uint32_t k = 0; k < n; ++k) {
        const uint32_t mk = in_use_[g.first + k];
        const Eigen::Vector3d& jk = rows[members_[mk]].j[j_up_[mk]];
        Eigen::Vector3d wd = Eigen::Vector3d::Zero();
        if (g.down != g.up) wd = w_[g.down] * rows[members_[mk]].j[j_down_[mk]];
        for (uint32_t q = 0; q <= k; ++q) {
          const uint32_t mq = in_use_[g.first + q];
          double v = jk.dot(Eigen::Map<const Eigen::Vector3d>(u + 3 * q));
          if (g.down != g.up) v += rows[members_[mq]].j[j_down_[mq]].dot(wd);
          l[k * n + q] = shift != 0.0 && q == k ? v + shift : v;
        }
        largest = std::max(largest, l[k * n + k] - shift);
      }
      return largest;
    };
    const double largest = fill(0.0);
    if (!ldlt(l, d, n, kSingular * largest) && largest > 0.0) {
      fill(kShift * largest);  // singular: D + εI, from the matrix again (ldlt overwrote the triangle)
      ldlt(l, d, n, 0.0);
    }
    // P = D⁻¹ uᵀ (n × 3, row k at p + 3k), column by column; W̃_up ← W̃_up − u P.
    double* pk = u + 4 * n;
    double y[kMaxGroupRows];
    for (int i = 0; i < 3; ++i) {
      for (uint32_t k = 0; k < n; ++k) y[k] = u[3 * k + i];
      ldltSolve(l, d, n, y);
      for (uint32_t k = 0; k < n; ++k) pk[3 * k + i] = y[k];
    }
    Eigen::Matrix3d update = Eigen::Matrix3d::Zero();
    for (uint32_t k = 0; k < n; ++k)
      update += Eigen::Map<const Eigen::Vector3d>(u + 3 * k) * Eigen::Map<const Eigen::Vector3d>(pk + 3 * k).transpose();
    Eigen::Matrix3d& w = w_[g.up];
    w -= 0.5 * (update + update.transpose());
  }
}

void TreeFactor::solve(const std::vector<Evaluated>& rows, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x = b;  // rows out of use keep b
  for (Eigen::Vector3d& s : s_) s.setZero();
  for (const Group& g : groups_) {
    const uint32_t n = g.n;
    if (n == 0) continue;
    double* l = arena_.data() + g.at;
    const double* d = l + n * n;
    const double* u = d + n;
    double* z = l + n * n + 4 * n;
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t m = in_use_[g.first + k];
      const Evaluated& row = rows[members_[m]];
      double v = b[members_[m]] - row.j[j_up_[m]].dot(s_[g.up]);
      if (g.down != g.up) v -= row.j[j_down_[m]].dot(s_[g.down]);
      z[k] = v;
    }
    ldltSolve(l, d, n, z);
    for (uint32_t k = 0; k < n; ++k) s_[g.up] += z[k] * Eigen::Map<const Eigen::Vector3d>(u + 3 * k);
  }
  for (Eigen::Vector3d& t : s_) t.setZero();
  for (size_t q = groups_.size(); q-- > 0;) {
    const Group& g = groups_[q];
    const uint32_t n = g.n;
    if (n == 0) continue;
    const double* l = arena_.data() + g.at;
    const double* d = l + n * n;
    const double* u = d + n;
    const double* z = u + 3 * n;
    double y[kMaxGroupRows];
    for (uint32_t k = 0; k < n; ++k) y[k] = Eigen::Map<const Eigen::Vector3d>(u + 3 * k).dot(s_[g.up]);
    ldltSolve(l, d, n, y);
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t m = in_use_[g.first + k];
      const double lambda = z[k] - y[k];
      x[members_[m]] = lambda;
      const Evaluated& row = rows[members_[m]];
      s_[g.up] += lambda * row.j[j_up_[m]];
      if (g.down != g.up) s_[g.down] += lambda * row.j[j_down_[m]];
    }
  }
}

bool TreeFactor::closePins(Island& island, const std::vector<char>& use, const Rot* rotations) {
  const size_t m = island.equalities.size();
  // The pin of a group: its two rows in use, x and y of one anchor pair (single terms of weight 1).
  // (True with no terms for a group with no row in use: it holds nothing now.)
  const auto pinOf = [&](const Group& g, const Term*& tx, const Term*& ty) {
    tx = ty = nullptr;
    bool any = false;
    for (uint32_t k = 0; k < g.count; ++k) any |= use[members_[g.first + k]] != 0;
    if (!any) return true;
    for (uint32_t k = 0; k < g.count; ++k) {
      const uint32_t row = members_[g.first + k];
      if (!use[row]) continue;
      if (row >= m) return false;
      const Coordinate& c = island.equalities[row].coordinate;
      if (c.terms != 1 || c.term[0].weight != 1.0 || island.equalities[row].target != 0.0) return false;
      const Term& t = c.term[0];
      if (t.measure == Measure::PointX && !tx) {
        tx = &t;
      } else if (t.measure == Measure::PointY && !ty) {
        ty = &t;
      } else {
        return false;
      }
    }
    return tx && ty && tx->a == ty->a && tx->b == ty->b && tx->sa == ty->sa && tx->sb == ty->sb;
  };
  for (uint32_t b = 0; b < island.moving; ++b)
    if (!(island.im[b] > 0.0)) return false;  // a body the mass metric would not translate
  std::fill(held_.begin(), held_.end(), 0);
  for (const Group& g : groups_) {
    const Term *tx, *ty;
    if (!pinOf(g, tx, ty)) return false;
    if (!tx || g.up != g.down) continue;
    // On one body: only at a root, and one per tree (a second would hold it at two points).
    if (!g.root || held_[g.up]) return false;
    held_[g.up] = 1;
  }
  std::fill(moved_.begin(), moved_.end(), Vec2::Zero());
  std::fill(tree_mass_.begin(), tree_mass_.end(), 0.0);
  // Root first: each group's upper body is placed before its lower one.
  for (size_t q = groups_.size(); q-- > 0;) {
    const Group& g = groups_[q];
    const Term *tx, *ty;
    pinOf(g, tx, ty);
    if (!tx) continue;
    const Term& t = *tx;
    State& A = island.states[t.a];
    State& B = island.states[t.b];
    const Vec2 gap = (B.c + rotations[t.b].apply(t.sb)) - (A.c + rotations[t.a].apply(t.sa));
    // The body this group places: its lower one (the moving one of a root's group).
    const bool moves_b = t.b == g.down;
    const Vec2 shift = moves_b ? Vec2(-gap) : gap;
    (moves_b ? B : A).c += shift;
    moved_[tree_of_[g.down]] += shift / island.im[g.down];
  }
  // A tree held by nothing keeps its centre of mass, as the projection in the mass metric does
  // (its joints' forces are internal): each body moved by its own shift (its gap to its placed
  // parent), the tree then by −Σ m Δc / Σ m, which leaves its pins as they are.
  bool free = false;
  for (uint32_t b = 0; b < island.moving; ++b) {
    const uint32_t r = tree_of_[b];
    if (held_[r]) continue;
    free = true;
    tree_mass_[r] += 1.0 / island.im[b];
  }
  if (!free) return true;
  for (uint32_t b = 0; b < island.moving; ++b) {
    const uint32_t r = tree_of_[b];
    if (!held_[r]) island.states[b].c -= moved_[r] / tree_mass_[r];
  }
  return true;
}

}  // namespace rigidlab::mechanism

// Exact mechanisms: the room of the step that integrates islands of jointed bodies touching nothing
// as one smooth ODE (docs/integrators.md, "Joints inside the integrator").
//
// At every stage of the integrator the joints' constraint forces come from an exact solve of the
// index-1 system (acceleration-level constraints)
//   (J M⁻¹ Jᵀ) λ = −J a − J̇ v        a: the bodies' accelerations from every other force
// and the stage's acceleration is a + M⁻¹ Jᵀ λ; after the step the positions and velocities are
// projected back onto the constraints in the mass metric,
//   q ← q − M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ g(q)    (simplified Newton, until g is at round-off)
//   v ← v − M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ J v
// which moves a step's result by O(h^{p+1}) and so keeps the integrator's order p (Hairer, Lubich,
// Wanner, Geometric Numerical Integration IV.4; Hairer, Wanner, Solving ODEs II, VII.2). Joint
// springs are forces on a coordinate, evaluated at every stage: f = −k (x − x₀) − c ẋ with the
// soft constraint's k = m ω², c = 2 m ζ ω, m = 1/(J M⁻¹ Jᵀ) of that coordinate.
//
// This header is the room's whole interface: an island comes in as plain bodies (states and
// inverse masses) and coordinates between them; nothing here sees the world. mechanism_step.cpp
// makes islands from the world's joints, calls in at each stage and after each interval, and
// writes the multipliers back into the joints.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "rigidlab/math.h"

namespace rigidlab::mechanism {

// A body's state: centre of mass, angle, velocity, angular velocity.
struct State {
  Vec2 c = Vec2::Zero();
  double angle = 0.0;
  Vec2 v = Vec2::Zero();
  double w = 0.0;
};

// A scalar measure of the configuration between bodies A and B (island indices), with anchors
// s_A, s_B from the centres of mass in body coordinates: P = c + R(θ) s, d = P_B − P_A.
enum class Measure : uint8_t {
  PointX,    // d_x
  PointY,    // d_y
  Angle,     // θ_B − θ_A − offset
  Axis,      // n · d, n = R(θ_A) axis: a direction fixed in A
  Distance,  // |d|
};

struct Term {
  Measure measure = Measure::PointX;
  uint32_t a = 0, b = 0;
  Vec2 sa = Vec2::Zero(), sb = Vec2::Zero();
  Vec2 axis = Vec2(1.0, 0.0);  // Axis: unit, in A's frame
  double offset = 0.0;         // Angle: the reference angle
  double weight = 1.0;         // in a coordinate of two terms
};

// A coordinate: one term, or the weighted sum of two (a gear's coordinate_1 + ratio · coordinate_2,
// a pulley's length_a + ratio · length_b).
struct Coordinate {
  Term term[2];
  int terms = 1;
};

// A coordinate at a state: value x, rate ẋ = J v and J̇ v (so that ẍ = J a + J̇ v), with the
// Jacobian J over at most four bodies (each body once).
struct Evaluated {
  double x = 0.0, xdot = 0.0, jdotv = 0.0;
  int count = 0;
  uint32_t body[4] = {0, 0, 0, 0};
  Eigen::Vector3d j[4];
};
// `rotations`: R(θ) of each body at `states` (rotationsOf).
Evaluated evaluate(const Coordinate& c, const State* states, const Rot* rotations);
void rotationsOf(const std::vector<State>& states, std::vector<Rot>& out);
// A pin's x and y rows (isPinPair: point x then point y of one term each, weight 1, the same
// bodies and anchors) evaluated together: the same values as evaluate() on each, at half the cost.
bool isPinPair(const Coordinate& x, const Coordinate& y);
void evaluatePin(const Coordinate& x, const State* states, const Rot* rotations, Evaluated& ex, Evaluated& ey);

// A rigid constraint x = target, or with `sign` ±1 a one-sided one (a joint limit): sign (x − target)
// ≥ 0, whose force may only push, sign λ ≥ 0. A one-sided row takes part at a stage only while the
// coordinate is at its bound (within Island::tolerance) and pushed into it; a bound reached inside a
// step is met by the projection after it, as an inelastic stop (first order at that instant).
struct Equality {
  Coordinate coordinate;
  double target = 0.0;
  double sign = 0.0;
};

// A motor on a coordinate: drives ẋ towards `speed` with a force of at most `max_force`. Each
// step (Solver::beginStep) it either reaches its speed, with an impulse of at most max_force · h
// at the step's start (first order, as the contact solvers' motors), and holds it through the
// step (ẍ = 0 at every stage, |λ| ≤ max_force), or it pushes with max_force towards it the whole
// step; a speed reached inside such a step is caught by the projection after it (ẋ = speed).
struct Motor {
  Coordinate coordinate;
  double speed = 0.0;
  double max_force = 0.0;
};

// A spring on one coordinate, or on two solved as one 2-vector (a soft weld's anchors: the 2×2
// effective mass, as its soft constraint has): f = −K (ω² (x − rest) + 2 ζ ω ẋ), K = (J M⁻¹ Jᵀ)⁻¹.
struct Spring {
  Coordinate coordinate[2];
  int dimension = 1;
  double rest[2] = {0.0, 0.0};
  double hertz = 0.0, damping_ratio = 0.0;
  double max_force = std::numeric_limits<double>::infinity();  // dimension 1: |f| at most this [N]
};

// An island: its bodies (the moving ones first, then the fixed ones, whose inverse masses are
// zero and whose states the caller keeps current: static, asleep, kinematic, the world) and what
// joins them. `tolerance` [m, rad] and `speed_tolerance` [m/s, rad/s]: how close to its bound a
// limit is "at" it, and to its speed a motor.
struct Island {
  std::vector<State> states;
  std::vector<double> im, ii;  // per body
  uint32_t moving = 0;
  std::vector<Equality> equalities;
  std::vector<Motor> motors;
  std::vector<Spring> springs;
  double tolerance = 1e-9, speed_tolerance = 1e-9;
  // Changed by whoever changes the bodies or the rows (mechanism_step.cpp: each time it makes the
  // island): the solver checks its structure only then.
  uint64_t shape = 0;
};

// How a projection went: the largest |g| before it (the step's drift, an estimate of its local
// error) and left after it [m or rad], and the Newton iterations taken.
struct Projection {
  double drift = 0.0;
  double residual = 0.0;
  int iterations = 0;
  bool closed = false;  // finished by the pins' closure (TreeFactor::closePins), not Newton
};

// J M⁻¹ Jᵀ of an island whose rows act on at most two moving bodies each and join them in a forest
// (chains, trees, ragdolls: no closed loop), factored in O(n) by eliminating the rows in tree order,
// leaves to root (Baraff, "Linear-Time Dynamics using Lagrange Multipliers", SIGGRAPH 1996). The
// rows on the same bodies form a group; two groups are coupled only through a body they share, so
// eliminating a group that is the last one at its lower body changes only its upper body's
// effective inverse mass,
//   W̃_up ← W̃_up − W̃_up J_upᵀ D⁻¹ J_up W̃_up,    D = Σ_{b in the group} J_b W̃_b J_bᵀ
// (W̃_b starts as diag(1/m, 1/m, 1/I)): no fill, 3 × 3 body blocks and each group's own small D.
// A group whose D is singular (rows that depend on each other: a redundant joint) is factored as
// D + εI, ε = 1e-12 of its largest diagonal entry, as the whole-matrix path does.
class TreeFactor {
 public:
  // The elimination order for `rows` (evaluated at `island`); false when the island is not such a
  // forest (then A is factored as a whole).
  bool build(const Island& island, const std::vector<Evaluated>& rows);
  // Factors A over the rows in use (`use`).
  void factor(const Island& island, const std::vector<Evaluated>& rows, const std::vector<char>& use);
  // x = A⁻¹ b over the rows in use of the last factor; a row out of use keeps x = b.
  void solve(const std::vector<Evaluated>& rows, const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Puts the island's bodies on its pins by translations alone, in one pass from each tree's root
  // to its leaves: each body is moved by its pin's gap to its (already placed) parent, a root by
  // its pin to a fixed body; a tree held by no fixed body is then moved as a whole so that its
  // centre of mass stays where it was. Exact to round-off, whatever the gaps (a point coordinate is
  // linear in a body's position). Only for islands whose rows in use (`use`, equalities numbered as
  // in island.equalities) are pins alone: each group's two point rows of one pin, a group on one
  // body only at a tree's root; false (nothing moved) otherwise. `rotations`: R(θ) at the states.
  bool closePins(Island& island, const std::vector<char>& use, const Rot* rotations);

 private:
  struct Group {
    uint32_t up = 0, down = 0;  // its bodies (up == down: one); its elimination updates W̃_up
    uint32_t first = 0, count = 0;  // its rows: members_[first .. first + count)
    uint32_t at = 0;  // its factors in arena_: L (count²), D⁻¹, u = W̃_up J_upᵀ (3 count), z, P = D⁻¹ uᵀ (3 count)
    uint32_t n = 0;   // rows in use at the last factor (in_use_[first .. first + n))
    bool root = false;  // on one body that is its tree's root (closePins)
  };
  std::vector<Group> groups_;  // in elimination order
  std::vector<uint32_t> members_, in_use_;
  std::vector<uint8_t> j_up_, j_down_;  // per member: where up and down are in the row's Jacobian
  std::vector<Eigen::Matrix3d> w_;      // per moving body: W̃
  std::vector<Eigen::Vector3d> s_;      // per moving body: the forward and backward sums
  std::vector<uint32_t> tree_of_;       // per moving body: its tree's root
  std::vector<char> held_;              // per root (closePins): held by a fixed body
  std::vector<Vec2> moved_;             // per root (closePins): Σ m Δc, then the shift
  std::vector<double> tree_mass_;       // per root (closePins)
  std::vector<double> arena_;
};

// How far an island's states are off its equalities: the largest |g| (a limit: only past its bound)
// and the largest |J v| of its two-sided ones.
struct Residuals {
  double position = 0.0, velocity = 0.0;
};

// The island's solver: the factorisation of J M⁻¹ Jᵀ (a forest's in tree order, TreeFactor; with
// closed loops dense below kDenseRows rows, else sparse LDLᵀ with an approximate minimum degree
// ordering, whose analysis is kept while the island's structure stays the same) and its scratch.
// One per island; reusing it allocates nothing while the island keeps its shape.
class Solver {
 public:
  static constexpr int kDenseRows = 64;

  // The spring, constraint and motor forces on the moving bodies at the island's states: `accel`
  // holds each moving body's acceleration (a_x, a_y, α) from every other force; `force` receives
  // the generalised force (F_x, F_y, τ) they add. Which one-sided rows push and which motors hold
  // is found by an active set: a row whose λ has the wrong sign is let go, a motor past its force
  // pushes with its force, and the rest solved again. Afterwards multiplier(k) is row k's λ
  // (equalities, then motors) and springForce(k) spring k's force (first component).
  void forces(const Island& island, const Eigen::Vector3d* accel, Eigen::Vector3d* force);

  // Projects the moving bodies' positions, then velocities, onto the equalities (the island's
  // states are updated): the equalities, the limits the positions pass, then the velocities onto
  // the equalities, the limits they run into and the motors at or past their speed since the last
  // markStart. `tolerance`: |g| at which Newton stops [m, rad]. Afterwards impulse(k) is the impulse
  // [N·s] row k applied to the velocities: the O(h^{p+1}) remainder after a step, a limit's stop,
  // a motor's catch; after an edit between steps (an applied impulse, a velocity set), the joints'
  // answer to it, as rigid joints answer a blow.
  Projection project(Island& island, double tolerance);

  // The velocities alone onto the rows where the bodies are (impulse(k) as after project).
  void projectVelocities(Island& island);
  // At the start of a step of length h: which motors reach their speed in it (caught now, the
  // velocities changed, impulse(k) as after project) and which push; project() catches a pushing
  // motor whose rate crossed its speed during the step.
  void beginStep(Island& island, double h);

  double multiplier(size_t k) const { return lambda_[static_cast<Eigen::Index>(k)]; }
  double impulse(size_t k) const { return impulse_[static_cast<Eigen::Index>(k)]; }
  double springForce(size_t k) const { return spring_force_[k]; }
  // The largest |g| and |J v| of the equalities at the island's states.
  Residuals residuals(const Island& island);

 private:
  // J at the states into rows_ (and x, ẋ, J̇v): the equalities, then the motors; builds the
  // structure when it changed.
  void evaluateRows(const Island& island);
  void structure(const Island& island);
  // A = J M⁻¹ Jᵀ over the rows in use_ (a row out of use has A's row and column of the identity,
  // so its λ is its right-hand side, kept 0), factored.
  void factor(const Island& island);
  // Two passes v ← v − M⁻¹ Jᵀ A⁻¹ J v with J where the bodies are and the last factorisation.
  // `evaluated`: rows_ hold J, x and ẋ where the bodies are already.
  void velocityPasses(Island& island, bool evaluated = false);
  // x = A⁻¹ b with the last factorisation.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Adds M⁻¹ Jᵀ λ scaled by `scale` to `out` (3 per moving body).
  void applyTranspose(const Island& island, const Eigen::VectorXd& lambda, double scale, Eigen::VectorXd& out) const;

  std::vector<Evaluated> rows_;
  // Structure: per row, its moving bodies; the entries of A they make (row r, row s, body k,
  // position in the values of A). Kept while `signature_` (each row's bodies) is unchanged.
  std::vector<uint32_t> signature_, signature_now_;
  bool built_ = false;
  uint64_t checked_shape_ = 0;  // Island::shape of the last structure check
  std::vector<char> pin_first_;   // per equality: the first of a pin pair (isPinPair), checked with the shape
  std::vector<int8_t> off_sign_;  // beginStep's scratch
  struct Entry {
    uint32_t r, s, jr, js;  // rows, and the index of the body in each row's Jacobian
    uint32_t body;
    int value;  // sparse: index into A's values; dense: unused
  };
  std::vector<Entry> entries_;
  bool dense_ = true;
  bool tree_ = false;  // the island is a forest: TreeFactor
  TreeFactor tree_factor_;
  // The dense path factors the rows in use only (a released limit is out of the matrix, not a
  // row of identity in it): compact_[r] is row r's place among them, −1 out of use.
  Eigen::MatrixXd dense_a_;
  Eigen::LDLT<Eigen::MatrixXd> dense_ldlt_;
  std::vector<int> compact_;
  Eigen::VectorXd compact_b_, compact_x_;
  double dense_shift_ = 0.0;  // the shift of the last dense factorisation (0: exact)
  Eigen::SparseMatrix<double> sparse_a_;  // lower triangle
  // Held by pointer: Eigen's sparse factorisations cannot be moved, and the islands' solvers live
  // in a vector.
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>> sparse_ldlt_;
  bool analysed_ = false;
  double shift_ = 0.0;  // regularisation used when A is singular (redundant constraints)
  Eigen::VectorXd rhs_, lambda_, dq_, impulse_;
  std::vector<char> use_;            // per row: in the current factorisation
  std::vector<char> used_;           // the use_ of the last factorisation
  std::vector<double> motor_rate_;   // per motor: ẋ − speed at beginStep
  double step_h_ = 0.0;              // the step beginStep began
  std::vector<int8_t> motor_push_;   // per motor, this step: ±1 it pushed with its whole force (at some stage), 0 held
  std::vector<int8_t> motor_mode_;   // per motor, this step: 0 holds its speed, ±1 pushes that way
  std::vector<double> motor_force_;  // per motor: the force it pushes with when out of use (0: none)
  std::vector<State> start_;  // the states a Newton step starts from (its line search)
  std::vector<Rot> rot_;         // R(θ) of each body at the island's states, as last placed
  std::vector<double> rot_at_;   // the angle each of rot_ was taken at (a body whose angle did not
                                 // change since keeps its sine and cosine: most places are at the
                                 // same positions, the velocities' and the projection's)
  const Rot* place(const Island& island) {
    const size_t n = island.states.size();
    if (rot_at_.size() != n) {
      rot_at_.assign(n, std::numeric_limits<double>::quiet_NaN());
      rot_.resize(n);
    }
    for (size_t k = 0; k < n; ++k)
      if (!(island.states[k].angle == rot_at_[k])) {
        rot_at_[k] = island.states[k].angle;
        rot_[k] = Rot::fromAngle(rot_at_[k]);
      }
    return rot_.data();
  }
  std::vector<double> spring_force_;
  std::vector<Eigen::Vector3d> body_accel_;  // forces(): each moving body's acceleration in a round
};

}  // namespace rigidlab::mechanism

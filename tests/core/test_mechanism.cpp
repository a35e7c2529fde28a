// Exact joints (WorldDef::exact_joints, mechanism_step.cpp): which islands take the path, and what
// it must hold. The orders of accuracy are the accuracy lab's (tests/accuracy, the mechanism
// problems); these are the cases the lab does not sweep.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "mechanism.h"
#include "rigidlab/world.h"
#include "test_util.h"

using namespace rigidlab;

namespace {

constexpr double kDt = 1.0 / 60.0;

// A box of `mass` that collides with nothing: the island stays free of contacts.
BodyId link(World& w, double width, double height, Vec2 position, double mass) {
  BodyDef d;
  d.shape = makeBox(width, height);
  d.position = position;
  d.mass = mass;
  d.filter.mask = 0;
  return w.createBody(d);
}

// Numbers in [0, 1) from a linear congruential generator: the same sequence on every platform.
struct Uniform {
  uint32_t seed;
  double operator()() {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) * (1.0 / 16777216.0);
  }
};

using test::largestGap;
using test::revolute;

}  // namespace

TEST_CASE("exact joints: a 1000 kg load on a 30-link chain of 1 kg links keeps every pin within 1e-9 m over 5 s") {
  // 1000:1 at the chain's end, released horizontally: the contact solvers' pins tore such a chain
  // apart (17.6 m). Exact joints hold it by construction, to the projection's round-off.
  World w;
  std::vector<JointId> pins;
  BodyId previous;
  for (int i = 0; i < 30; ++i) {
    const BodyId l = link(w, 0.5, 0.1, {0.5 * i + 0.25, 0.0}, 1.0);
    pins.push_back(revolute(w, l, previous, {0.5 * i, 0.0}));
    previous = l;
  }
  const BodyId load = link(w, 1.0, 1.0, {15.5, 0.0}, 1000.0);
  pins.push_back(revolute(w, load, previous, {15.0, 0.0}));
  double worst = 0.0, lowest = 0.0;
  for (int i = 0; i < 300; ++i) {
    w.step(kDt);
    REQUIRE(w.stats().exact_joints == 31);
    worst = std::max(worst, largestGap(w, pins));
    lowest = std::min(lowest, w.body(load).center.y());
  }
  MESSAGE("largest pin gap over 5 s: " << worst << " m");
  CHECK(worst <= 1e-9);
  CHECK(lowest < -10.0);  // it swung down: the chain moved
}

TEST_CASE("exact joints: off, or an island that touches something, leaves the joints to the contact solvers") {
  for (bool exact : {true, false}) {
    CAPTURE(exact);
    WorldDef def;
    def.exact_joints = exact;
    World w(def);
    const BodyId bob = link(w, 0.2, 0.2, {1.0, 0.0}, 1.0);
    revolute(w, bob, BodyId{}, {0.0, 0.0});
    w.step(kDt);
    CHECK(w.stats().exact_joints == (exact ? 1 : 0));
  }
  // A pendulum whose bob rests on a floor: its island has a contact.
  World w;
  BodyDef floor;
  floor.type = BodyType::Static;
  floor.shape = makeBox(10.0, 1.0);
  floor.position = {0.0, -1.5};
  w.createBody(floor);
  BodyDef bob;
  bob.shape = makeBox(0.2, 0.2);
  bob.position = {0.0, -0.9};
  const BodyId b = w.createBody(bob);
  revolute(w, b, BodyId{}, {0.0, 0.0});
  for (int i = 0; i < 30; ++i) w.step(kDt);
  CHECK(w.stats().contacts > 0);
  CHECK(w.stats().exact_joints == 0);
}

TEST_CASE("exact joints: a motor of unlimited torque holds its speed; one short of torque never gives more than it has") {
  // A bar on a pin at its end (a: the bar, b: the world, so the joint's speed ω_b − ω_a is −ω_bar:
  // the falling bar's speed is positive). Unlimited: the joint turns at exactly its motor speed
  // either way (0 · ∞ once made every stage NaN). Short (τ = 1 N·m against m g L/2 = 4.9 N·m):
  // against the fall (−2 rad/s) the motor pushes with all it has, exactly τ; with the fall (+2)
  // the weight overshoots the speed and the motor brakes with at most τ (a catch at its speed is
  // bounded by its torque over the step).
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& [speed, torque] : {std::pair{-2.0, inf}, std::pair{2.0, inf}, std::pair{-2.0, 1.0}, std::pair{2.0, 1.0}}) {
    CAPTURE(speed);
    CAPTURE(torque);
    World w;
    const BodyId bar = link(w, 1.0, 0.05, {0.5, 0.0}, 1.0);
    JointDef d;
    d.type = JointType::Revolute;
    d.a = bar;
    d.anchor_a = {0.0, 0.0};
    d.enable_motor = true;
    d.motor_speed = speed;
    d.max_motor_torque = torque;
    const JointId j = w.createJoint(d);
    for (int i = 0; i < 20; ++i) {
      w.step(kDt);
      REQUIRE(w.stats().exact_joints == 1);
      REQUIRE(std::isfinite(w.body(bar).angular_velocity));
      const JointState s = w.jointState(j);
      if (std::isinf(torque)) {
        CHECK(s.speed == doctest::Approx(speed).epsilon(1e-9));
      } else if (speed < 0.0) {
        CHECK(s.speed > 0.0);  // the weight wins
        CHECK(std::abs(s.motor) == doctest::Approx(1.0).epsilon(1e-9));
      } else {
        CHECK(std::abs(s.motor) <= 1.0 + 1e-9);
      }
    }
  }
}

TEST_CASE("exact joints: the tree-ordered factorisation solves J M⁻¹ Jᵀ x = b as a dense solve does") {
  // A random tree of 60 bodies, the first pinned to a fixed body, each other one pinned to an
  // earlier one, with an angle row on some pins (a motor's or a limit's) and a second fixed body
  // holding some by their angle (a grounded group that is not the root's); some rows out of use.
  using namespace rigidlab::mechanism;
  Uniform next{12345};
  constexpr uint32_t kBodies = 60;
  Island island;
  for (uint32_t k = 0; k < kBodies + 2; ++k) {
    State s;
    s.c = Vec2(4.0 * next() - 2.0, 4.0 * next() - 2.0);
    s.angle = 6.0 * next() - 3.0;
    s.v = Vec2(next() - 0.5, next() - 0.5);
    s.w = 2.0 * next() - 1.0;
    island.states.push_back(s);
    const bool fixed = k >= kBodies;
    island.im.push_back(fixed ? 0.0 : 0.1 + 10.0 * next());
    island.ii.push_back(fixed || k == 7 ? 0.0 : 0.1 + 100.0 * next());  // body 7 does not turn
  }
  island.moving = kBodies;
  const auto add = [&](Measure m, uint32_t a, uint32_t b) {
    Equality e;
    e.coordinate.term[0].measure = m;
    e.coordinate.term[0].a = a;
    e.coordinate.term[0].b = b;
    e.coordinate.term[0].sa = Vec2(next() - 0.5, next() - 0.5);
    e.coordinate.term[0].sb = Vec2(next() - 0.5, next() - 0.5);
    island.equalities.push_back(e);
  };
  std::vector<uint32_t> parents;
  for (uint32_t k = 0; k < kBodies; ++k) {
    const uint32_t parent = k == 0 ? kBodies : static_cast<uint32_t>(next() * k);
    parents.push_back(parent);
    add(Measure::PointX, parent, k);
    add(Measure::PointY, parent, k);
    if (k != 7 && next() < 0.4) add(Measure::Angle, parent, k);
    if (k != 7 && k > 0 && next() < 0.2) add(Measure::Angle, kBodies + 1, k);
  }
  std::vector<Rot> rot;
  rotationsOf(island.states, rot);
  std::vector<Evaluated> rows;
  for (const Equality& e : island.equalities) rows.push_back(evaluate(e.coordinate, island.states.data(), rot.data()));
  const Eigen::Index n = static_cast<Eigen::Index>(rows.size());
  std::vector<char> use(rows.size(), 1);
  for (size_t r = 0; r < rows.size(); ++r)
    if (island.equalities[r].coordinate.term[0].measure == Measure::Angle && next() < 0.3) use[r] = 0;
  TreeFactor tree;
  REQUIRE(tree.build(island, rows));
  tree.factor(island, rows, use);
  Eigen::VectorXd b(n), x;
  for (Eigen::Index r = 0; r < n; ++r) b[r] = 2.0 * next() - 1.0;
  tree.solve(rows, b, x);
  // The reference: A over the rows in use, dense.
  std::vector<Eigen::Index> in;
  for (Eigen::Index r = 0; r < n; ++r)
    if (use[static_cast<size_t>(r)]) in.push_back(r);
  const Eigen::Index m = static_cast<Eigen::Index>(in.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd bin(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    bin[i] = b[in[i]];
    for (Eigen::Index j = 0; j < m; ++j) {
      const Evaluated& p = rows[static_cast<size_t>(in[i])];
      const Evaluated& q = rows[static_cast<size_t>(in[j])];
      for (int s = 0; s < p.count; ++s)
        for (int t = 0; t < q.count; ++t) {
          const uint32_t body = p.body[s];
          if (body != q.body[t] || body >= kBodies) continue;
          a(i, j) += island.im[body] * (p.j[s].x() * q.j[t].x() + p.j[s].y() * q.j[t].y()) + island.ii[body] * p.j[s].z() * q.j[t].z();
        }
    }
  }
  const Eigen::VectorXd reference = a.ldlt().solve(bin);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) worst = std::max(worst, std::abs(x[in[i]] - reference[i]));
  MESSAGE(m << " rows in use of " << n << "; largest difference from the dense solve " << worst
            << " (largest |x| " << reference.cwiseAbs().maxCoeff() << ")");
  CHECK(worst <= 1e-9 * reference.cwiseAbs().maxCoeff());
  for (Eigen::Index r = 0; r < n; ++r)
    if (!use[static_cast<size_t>(r)]) CHECK(x[r] == b[r]);
  // A pin that closes a loop (body 0 to a body not pinned to it, which the tree joins already):
  // not a forest.
  uint32_t far = 2;
  while (parents[far] == 0) ++far;
  add(Measure::PointX, 0, far);
  rows.push_back(evaluate(island.equalities.back().coordinate, island.states.data(), rot.data()));
  CHECK_FALSE(tree.build(island, rows));
}

TEST_CASE("exact joints: the pins' closure puts a tree on its pins by translations, and a free tree keeps its centre of mass") {
  // Random trees of 40 bodies far off their pins (gaps of metres, which Newton's method could not
  // close from): one held at its root by a fixed body, one held by nothing.
  using namespace rigidlab::mechanism;
  Uniform next{777};
  constexpr uint32_t kBodies = 40;
  for (const bool held : {true, false}) {
    CAPTURE(held);
    Island island;
    for (uint32_t k = 0; k < kBodies + 1; ++k) {
      State s;
      s.c = Vec2(10.0 * next() - 5.0, 10.0 * next() - 5.0);
      s.angle = 6.0 * next() - 3.0;
      island.states.push_back(s);
      island.im.push_back(k == kBodies ? 0.0 : 0.1 + 10.0 * next());
      island.ii.push_back(k == kBodies ? 0.0 : 0.1 + 100.0 * next());
    }
    island.moving = kBodies;
    const auto pin = [&](uint32_t a, uint32_t b) {
      Equality e;
      e.coordinate.term[0].a = a;
      e.coordinate.term[0].b = b;
      e.coordinate.term[0].sa = Vec2(next() - 0.5, next() - 0.5);
      e.coordinate.term[0].sb = Vec2(next() - 0.5, next() - 0.5);
      e.coordinate.term[0].measure = Measure::PointX;
      island.equalities.push_back(e);
      e.coordinate.term[0].measure = Measure::PointY;
      island.equalities.push_back(e);
    };
    if (held) pin(kBodies, 0);
    for (uint32_t k = 1; k < kBodies; ++k) pin(static_cast<uint32_t>(next() * k), k);
    std::vector<Rot> rot;
    rotationsOf(island.states, rot);
    std::vector<Evaluated> rows;
    for (size_t r = 0; r < island.equalities.size(); r += 2) {
      // A pin's two rows together are what evaluate() gives for each.
      REQUIRE(isPinPair(island.equalities[r].coordinate, island.equalities[r + 1].coordinate));
      Evaluated x, y;
      evaluatePin(island.equalities[r].coordinate, island.states.data(), rot.data(), x, y);
      for (const auto& [pair, row] : {std::pair{&x, r}, std::pair{&y, r + 1}}) {
        const Evaluated e = evaluate(island.equalities[row].coordinate, island.states.data(), rot.data());
        CHECK(pair->x == e.x);
        CHECK(pair->count == e.count);
        for (int i = 0; i < e.count; ++i) CHECK((pair->j[i] == e.j[i]));
        rows.push_back(e);
      }
    }
    TreeFactor tree;
    REQUIRE(tree.build(island, rows));
    std::vector<char> use(rows.size(), 1);
    const std::vector<State> before = island.states;
    const auto centre = [&] {
      Vec2 sum = Vec2::Zero();
      double mass = 0.0;
      for (uint32_t k = 0; k < kBodies; ++k) {
        sum += island.states[k].c / island.im[k];
        mass += 1.0 / island.im[k];
      }
      return Vec2(sum / mass);
    };
    const Vec2 c0 = centre();
    double gap0 = 0.0;
    for (const Evaluated& e : rows) gap0 = std::max(gap0, std::abs(e.x));
    REQUIRE(gap0 > 1.0);
    REQUIRE(tree.closePins(island, use, rot.data()));
    double gap = 0.0;
    for (const Equality& e : island.equalities)
      gap = std::max(gap, std::abs(evaluate(e.coordinate, island.states.data(), rot.data()).x));
    CHECK(gap < 1e-12);
    for (uint32_t k = 0; k <= kBodies; ++k) CHECK(island.states[k].angle == before[k].angle);
    CHECK(island.states[kBodies].c == before[kBodies].c);  // the fixed body stays
    if (!held) CHECK((centre() - c0).norm() < 1e-12);
    // With a row that is not a pin's in use (an angle between two bodies), nothing moves.
    Equality angle;
    angle.coordinate.term[0].measure = Measure::Angle;
    angle.coordinate.term[0].a = 0;
    angle.coordinate.term[0].b = 1;
    island.equalities.push_back(angle);
    rows.push_back(evaluate(angle.coordinate, island.states.data(), rot.data()));
    REQUIRE(tree.build(island, rows));
    use.push_back(1);
    const std::vector<State> closed = island.states;
    CHECK_FALSE(tree.closePins(island, use, rot.data()));
    for (uint32_t k = 0; k < kBodies; ++k) CHECK(island.states[k].c == closed[k].c);
  }
}

// Exact joints (WorldDef::exact_joints, mechanism_step.cpp): which islands take the path, and what
// it must hold. The orders of accuracy are the accuracy lab's (tests/accuracy, the mechanism
// problems); these are the cases the lab does not sweep.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

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

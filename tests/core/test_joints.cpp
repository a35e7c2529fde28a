// Joints: one fixture per joint type, with predictions checked every step against what the joint
// must keep (a pin's gap, a motor's speed, a gear's ratio, a pulley's length), in both solvers.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "test_util.h"

using namespace rigidlab;
using doctest::Approx;

namespace {

constexpr double kDt = 1.0 / 60.0;

BodyId box(World& w, double width, double height, Vec2 position, double mass = 1.0, double angle = 0.0) {
  BodyDef d;
  d.shape = makeBox(width, height);
  d.position = position;
  d.angle = angle;
  d.mass = mass;
  return w.createBody(d);
}

using test::revolute;

// A horizontal chain of `links` boxes of `length`, the first pinned to the world at the origin.
struct Chain {
  std::vector<BodyId> links;
  std::vector<JointId> pins;
};
Chain makeChain(World& w, int links, double length, double mass) {
  Chain c;
  for (int i = 0; i < links; ++i) {
    c.links.push_back(box(w, length, 0.1 * length, {(i + 0.5) * length, 0.0}, mass));
    c.pins.push_back(revolute(w, c.links.back(), i == 0 ? BodyId{} : c.links[i - 1], {i * length, 0.0}));
  }
  return c;
}

double largestGap(const World& w, const Chain& c) { return test::largestGap(w, c.pins); }

}  // namespace

TEST_CASE("revolute: a chain of 30 links released horizontally stays within 0.5 % of its length, pins within 1 cm") {
  // Sequential impulses (the default for an island this size) solve the pins exactly (the direct
  // solve, joint_direct.cpp); the soft step's pins are stiff springs.
  for (ContactSolver solver : {ContactSolver::Auto, ContactSolver::SequentialImpulses, ContactSolver::SoftStep}) {
    CAPTURE(contactSolverName(solver));
    WorldDef def;
    def.contact_solver = solver;
    World w(def);
    const Chain chain = makeChain(w, 30, 0.5, 1.0);
    double worst_gap = 0.0, worst_stretch = 0.0;
    for (int i = 0; i < 300; ++i) {
      w.step(kDt);
      worst_gap = std::max(worst_gap, largestGap(w, chain));
      // Length along the chain: pin to pin, plus the last half link.
      const BodyId last = chain.links.back();
      const Vec2 tip = w.body(last).xf.apply(Vec2(0.25, 0.0));
      double length = 0.0;
      Vec2 prev = Vec2::Zero();
      for (size_t k = 1; k < chain.pins.size(); ++k) {
        const Vec2 p = w.jointState(chain.pins[k]).world_anchor_a;
        length += (p - prev).norm();
        prev = p;
      }
      length += (tip - prev).norm();
      worst_stretch = std::max(worst_stretch, std::abs(length / 15.0 - 1.0));
    }
    MESSAGE(contactSolverName(solver) << ": largest pin gap " << worst_gap << " m, stretch " << worst_stretch);
    if (solver == ContactSolver::SoftStep) {
      CHECK(worst_gap < 0.01);
      CHECK(worst_stretch < 0.01);
    } else {
      CHECK(worst_gap < 1e-9);
      CHECK(worst_stretch < 1e-9);
    }
  }
}

TEST_CASE("revolute motor: a wheel driven at 2 rad/s turns at 2 rad/s to 1e-6, the torque it needs is read back") {
  for (ContactSolver solver : {ContactSolver::SequentialImpulses, ContactSolver::SoftStep}) {
    WorldDef def;
    def.contact_solver = solver;
    def.gravity = Vec2::Zero();
    World w(def);
    BodyDef d;
    d.shape = makeCircle(0.5);
    const BodyId wheel = w.createBody(d);
    JointDef j;
    j.a = wheel;
    j.enable_motor = true;
    j.motor_speed = 2.0;
    j.max_motor_torque = 100.0;
    w.setAngularDamping(wheel, 0.5);  // something to drive against
    const JointId motor = w.createJoint(j);
    for (int i = 0; i < 120; ++i) w.step(kDt);
    CHECK(w.body(wheel).angular_velocity == Approx(-2.0).epsilon(1e-6));  // b is the world: ω_world − ω_wheel = 2
    CHECK(std::abs(w.jointState(motor).speed - 2.0) < 1e-6);
    CHECK(w.body(wheel).center.norm() < 1e-9);
  }
}

TEST_CASE("revolute limits hold a loaded arm at its bound to 1e-3 rad, in both solvers") {
  for (ContactSolver solver : {ContactSolver::SequentialImpulses, ContactSolver::SoftStep}) {
    CAPTURE(contactSolverName(solver));
    WorldDef def;
    def.contact_solver = solver;
    World w(def);
    const BodyId arm = box(w, 2.0, 0.2, {1.0, 0.0}, 5.0);
    JointDef j;
    j.a = arm;
    j.anchor_a = {0, 0};
    j.enable_limit = true;
    j.lower = -0.5;
    j.upper = 0.5;
    const JointId hinge = w.createJoint(j);
    for (int i = 0; i < 240; ++i) w.step(kDt);
    // Gravity turns the arm down (clockwise): its angle is −θ_joint (b is the world).
    CHECK(w.jointState(hinge).angle == Approx(0.5).epsilon(2e-3));
    CHECK(std::abs(w.body(arm).angle + 0.5) < 1e-3);
    const JointState s = w.jointState(hinge);
    CHECK((s.world_anchor_a - s.world_anchor_b).norm() < 1e-3);
  }
}

TEST_CASE("gear: two wheels geared 2:1 keep angle_a + 2 angle_b constant to 1e-9") {
  WorldDef def;
  def.gravity = Vec2::Zero();
  World w(def);
  BodyDef d;
  d.shape = makeCircle(1.0);
  const BodyId big = w.createBody(d);
  d.shape = makeCircle(0.5);
  d.position = {1.5, 0};
  const BodyId small = w.createBody(d);
  const JointId ja = revolute(w, big, {}, {0, 0});
  const JointId jb = revolute(w, small, {}, {1.5, 0});
  JointDef g;
  g.type = JointType::Gear;
  g.joint_a = ja;
  g.joint_b = jb;
  g.ratio = 2.0;
  w.createJoint(g);
  w.setAngularVelocity(big, 3.0);
  double worst = 0.0;
  for (int i = 0; i < 240; ++i) {
    w.step(kDt);
    worst = std::max(worst, std::abs(w.jointState(ja).angle + 2.0 * w.jointState(jb).angle));
  }
  MESSAGE("gear constraint error " << worst);
  CHECK(worst < 1e-9);
  // Angular momentum about the axles is exchanged through the gear: ω_big = −2 ω_small with
  // I_big ω_big − 2 I_small ω_small... conserved in the combination the constraint allows.
  CHECK(w.body(small).angular_velocity == Approx(-0.5 * w.body(big).angular_velocity).epsilon(1e-9));
  CHECK(std::abs(w.body(big).angular_velocity) > 1.0);  // still turning
}

TEST_CASE("pulley: length_a + ratio · length_b is conserved, the heavier side goes down") {
  World w;
  const BodyId left = box(w, 0.5, 0.5, {-2, 0}, 2.0);
  const BodyId right = box(w, 0.5, 0.5, {2, 0}, 1.0);
  JointDef p;
  p.type = JointType::Pulley;
  p.a = left;
  p.b = right;
  p.anchor_a = {-2, 0.25};
  p.anchor_b = {2, 0.25};
  p.ground_a = {-2, 4};
  p.ground_b = {2, 4};
  p.ratio = 1.0;
  const JointId pulley = w.createJoint(p);
  double worst = 0.0;
  for (int i = 0; i < 120; ++i) {
    w.step(kDt);
    const JointState s = w.jointState(pulley);
    const double la = (s.world_anchor_a - p.ground_a).norm(), lb = (s.world_anchor_b - p.ground_b).norm();
    worst = std::max(worst, std::abs(la + lb - 7.5));
  }
  CHECK(worst < 1e-3);
  CHECK(w.body(left).position().y() < -0.5);
  CHECK(w.body(right).position().y() > 0.5);
}

TEST_CASE("prismatic: slides along its axis only, stops at its limit, and its motor drives it") {
  for (ContactSolver solver : {ContactSolver::SequentialImpulses, ContactSolver::SoftStep}) {
    World w(WorldDef{.contact_solver = solver});
    const BodyId slider = box(w, 0.5, 0.5, {0, 0}, 1.0);
    JointDef j;
    j.type = JointType::Prismatic;
    j.a = slider;
    j.anchor_a = {0, 0};
    j.axis = {1, -1};  // down to the right (b is the world: the axis is fixed in the world)
    j.enable_limit = true;
    j.lower = -1.0;
    j.upper = 1.0;
    const JointId rail = w.createJoint(j);
    for (int i = 0; i < 240; ++i) w.step(kDt);
    const Body& b = w.body(slider);
    CHECK(std::abs(b.position().x() + b.position().y()) < 1e-3);  // on the line y = −x
    CHECK(std::abs(b.angle) < 1e-3);
    CHECK(std::hypot(b.position().x(), b.position().y()) == Approx(1.0).epsilon(2e-3));
    JointDef m = w.joint(rail);
    m.enable_limit = false;
    m.enable_motor = true;
    m.motor_speed = 0.5;
    m.max_motor_force = 1000.0;
    w.updateJoint(rail, m);
    for (int i = 0; i < 60; ++i) w.step(kDt);
    CHECK(std::abs(w.jointState(rail).speed) == Approx(0.5).epsilon(1e-6));
  }
}

TEST_CASE("weld and distance: a welded hammer keeps its shape, a rope is slack below its length and taut at it") {
  World w;
  const BodyId handle = box(w, 0.1, 1.0, {0, 0}, 0.5);
  const BodyId head = box(w, 0.6, 0.2, {0, 0.6}, 3.0);
  JointDef weld;
  weld.type = JointType::Weld;
  weld.a = handle;
  weld.b = head;
  weld.anchor_a = {0, 0.5};
  const JointId glue = w.createJoint(weld);
  w.setAngularVelocity(handle, 5.0);
  w.setAngularVelocity(head, 5.0);
  JointDef pin;
  pin.a = handle;
  pin.anchor_a = {0, -0.5};
  w.createJoint(pin);
  for (int i = 0; i < 120; ++i) w.step(kDt);
  CHECK(std::abs(w.jointState(glue).angle) < 1e-3);
  const JointState g = w.jointState(glue);
  CHECK((g.world_anchor_a - g.world_anchor_b).norm() < 1e-3);

  World r;
  const BodyId weight = box(r, 0.2, 0.2, {1.0, 0.0}, 1.0);
  JointDef rope;
  rope.type = JointType::Distance;
  rope.a = weight;
  rope.anchor_a = {1.0, 0.0};
  rope.anchor_b = {0.0, 0.0};
  rope.enable_limit = true;
  rope.max_length = 2.0;
  const JointId line = r.createJoint(rope);
  double longest = 0.0;
  for (int i = 0; i < 180; ++i) {
    r.step(kDt);
    longest = std::max(longest, r.jointState(line).translation);
  }
  CHECK(longest <= 2.0 + 0.005);
  CHECK(r.jointState(line).translation == Approx(2.0).epsilon(5e-3));  // hangs taut
}

TEST_CASE("a heavy load on a light chain (100:1) holds, stretching under 1 %") {
  World w;
  const Chain chain = [&] {
    Chain c;
    for (int i = 0; i < 10; ++i) {
      c.links.push_back(box(w, 0.1, 0.5, {0.0, -(i + 0.5) * 0.5}, 1.0));
      c.pins.push_back(revolute(w, c.links.back(), i == 0 ? BodyId{} : c.links[i - 1], {0.0, -i * 0.5}));
    }
    return c;
  }();
  const BodyId load = box(w, 1.0, 1.0, {0.0, -5.5}, 100.0);
  revolute(w, load, chain.links.back(), {0.0, -5.0});
  for (int i = 0; i < 300; ++i) w.step(kDt);
  const double hang = -w.body(load).position().y();
  MESSAGE("load at " << hang << " m below the pin (5.5 m unstretched)");
  CHECK(hang < 5.5 * 1.01);
  CHECK(hang > 5.5 * 0.99);
}

TEST_CASE("breaking: a weld over its break force is removed and reported with the force") {
  World w;
  const BodyId shelf = box(w, 1.0, 0.1, {0.5, 0.0}, 1.0);
  JointDef j;
  j.type = JointType::Weld;
  j.a = shelf;
  j.anchor_a = {0, 0};
  j.break_force = 20.0;  // it holds 9.8 N
  const JointId bracket = w.createJoint(j);
  for (int i = 0; i < 30; ++i) w.step(kDt);
  CHECK(w.isValid(bracket));
  w.applyImpulse(shelf, {0, -5.0}, w.body(shelf).center);  // 300 N over a step
  w.step(kDt);
  CHECK_FALSE(w.isValid(bracket));
  REQUIRE(w.jointBreaks().size() == 1);
  CHECK(w.jointBreaks()[0].force.norm() > 20.0);
  w.step(kDt);
  CHECK(w.jointBreaks().empty());
}

TEST_CASE("joints: validation names the field, removed with a body, bodies joined do not collide unless asked") {
  World w;
  const BodyId a = box(w, 1, 1, {0, 0});
  const BodyId s = test::addBox(w, 1, 1, {3, 0}, true);
  JointDef d;
  d.type = JointType::Prismatic;
  d.a = a;
  d.axis = {0, 0};
  CHECK(test::errorOf([&] { w.createJoint(d); }) == "axis must not be zero, got (0, 0)");
  d.axis = {1, 0};
  d.enable_limit = true;
  d.lower = 1.0;
  d.upper = -1.0;
  CHECK(test::errorOf([&] { w.createJoint(d); }) == "lower (1) must not exceed upper (-1)");
  JointDef two_static;
  two_static.a = s;
  CHECK(test::errorOf([&] { w.createJoint(two_static); }) ==
        "at least one of the joint's bodies must be dynamic (a joint between static or kinematic bodies does nothing)");
  JointDef gear;
  gear.type = JointType::Gear;
  const JointId pin = revolute(w, a, {}, {0, 0});
  JointDef dist;
  dist.type = JointType::Distance;
  dist.a = a;
  dist.anchor_b = {0, 2};
  const JointId rope = w.createJoint(dist);
  gear.joint_a = pin;
  gear.joint_b = rope;
  CHECK(test::errorOf([&] { w.createJoint(gear); }) == "joint_b must be a revolute or prismatic joint, got a distance joint");
  w.destroyBody(a);
  CHECK_FALSE(w.isValid(pin));
  CHECK_FALSE(w.isValid(rope));

  // Two overlapping boxes pinned together: no contact between them (collide_connected false).
  World v;
  const BodyId x = box(v, 1, 1, {0, 0}), y = box(v, 1, 1, {0.5, 0});
  const JointId p = revolute(v, x, y, {0.25, 0});
  v.step(kDt);
  CHECK(v.contacts().empty());
  JointDef more = v.joint(p);
  more.collide_connected = true;
  v.updateJoint(p, more);
  v.step(kDt);
  CHECK_FALSE(v.contacts().empty());
}

TEST_CASE("revolute reference_angle: the angle the limits and the spring count from") {
  // A rod pinned to the world with reference_angle = 0.5: its joint angle reads -0.5, and a limit of
  // [0, 0.1] turns it until its angle is within [0.5, 0.6].
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId rod = test::addBox(w, 0.1, 1.0, {0.0, -0.5});
  JointDef j;
  j.type = JointType::Revolute;
  j.b = rod;  // a: the world
  j.anchor_a = Vec2(0.0, 0.0);
  j.reference_angle = 0.5;
  const JointId id = w.createJoint(j);
  CHECK(w.jointState(id).angle == Approx(-0.5).epsilon(1e-12));
  j.enable_limit = true;
  j.lower = 0.0;
  j.upper = 0.1;
  w.updateJoint(id, j);
  for (int i = 0; i < 120; ++i) w.step(1.0 / 60.0);
  const double angle = w.jointState(id).angle;
  CHECK(angle > -1e-3);
  CHECK(angle < 0.1 + 1e-3);
  CHECK(w.body(rod).angle == Approx(0.5 + angle).epsilon(1e-9));  // the world's angle is 0
  j.reference_angle = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(w.createJoint(j), InputError);
}

TEST_CASE("updateJoint checks a motor joint's new target like createJoint does") {
  // The target pose is validated before it is taken: a NaN offset once passed here and made the
  // joint's anchor NaN (found by fuzz_world).
  World w;
  const BodyId puck = test::addCircle(w, 0.2, {1.0, 0.0});
  JointDef m;
  m.type = JointType::Motor;
  m.b = puck;
  m.anchor_a = Vec2(1.0, 0.0);
  m.max_force = 10.0;
  const JointId id = w.createJoint(m);
  JointDef bad = w.joint(id);
  bad.linear_offset = Vec2(std::numeric_limits<double>::quiet_NaN(), 0.0);
  CHECK_THROWS_AS(w.updateJoint(id, bad), InputError);
  bad = w.joint(id);
  bad.angular_offset = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(w.updateJoint(id, bad), InputError);
  CHECK(w.joint(id).linear_offset == Vec2(1.0, 0.0));
  w.step(1.0 / 60.0);
  CHECK(std::isfinite(w.jointState(id).world_anchor_a.x()));
  JointDef moved = w.joint(id);
  moved.linear_offset = Vec2(2.0, 0.0);
  w.updateJoint(id, moved);
  CHECK(w.jointState(id).world_anchor_a.x() == 2.0);
}

// Body damping was once applied after the step's gravity was added, v ← (v + h g) / (1 + h c), and
// the joints solved afterwards, so a damped body held still weighed m g / (1 + h c) (8.915 N, not
// 9.807 N, at h c = 0.1). It now damps the velocity the step starts with, v ← v / (1 + h c) + h g
// (integrator.cpp).
TEST_CASE("a damped body held by a pin weighs m g") {
  World w;
  BodyDef d;
  d.shape = makeCircle(0.2);
  d.mass = 1.0;
  d.linear_damping = 6.0;
  const BodyId disc = w.createBody(d);
  JointDef j;
  j.type = JointType::Revolute;
  j.b = disc;  // a: the world
  j.anchor_a = Vec2(0.0, 0.0);
  const JointId pin = w.createJoint(j);
  for (int i = 0; i < 20; ++i) w.step(1.0 / 60.0);  // (before it could fall asleep, at 0.5 s)
  CHECK(w.jointState(pin).reaction_force.y() == Approx(-w.settings().gravity.y() * 1.0).epsilon(1e-6));
}

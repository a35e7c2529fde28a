// Bodies made of shapes: mass properties summed over shapes against closed forms, capsules,
// segments, chains, concave outlines, shapes added and removed, filtering.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "test_util.h"

using namespace rigidlab;
using doctest::Approx;

namespace {

BodyId bodyWith(World& w, BodyType type = BodyType::Dynamic, Vec2 position = Vec2::Zero(), double angle = 0.0) {
  BodyDef d;
  d.type = type;
  d.position = position;
  d.angle = angle;
  return w.createBody(d);
}

ShapeId add(World& w, BodyId b, const Shape& s, double density = 1.0) {
  ShapeDef d;
  d.shape = s;
  d.density = density;
  return w.createShape(b, d);
}

}  // namespace

TEST_CASE("compound mass: an L of two boxes against the parallel-axis theorem worked by hand") {
  // A 2 × 1 box centred at (1, 0.5) and a 1 × 2 box centred at (0.5, 2): masses 2 and 2 (density 1),
  // centre (0.75, 1.25); each box's own I = m (w² + h²)/12 = 2·5/12, plus m d² with d² = 0.25 + 0.5625.
  World w;
  const BodyId l = bodyWith(w);
  add(w, l, makeBox(2, 1, {1, 0.5}));
  add(w, l, makeBox(1, 2, {0.5, 2}));
  const Body& b = w.body(l);
  CHECK(b.mass == Approx(4.0));
  CHECK(b.area == Approx(4.0));
  CHECK(b.local_center.x() == Approx(0.75));
  CHECK(b.local_center.y() == Approx(1.25));
  CHECK(b.inertia == Approx(2 * (2.0 * 5.0 / 12.0 + 2.0 * (0.0625 + 0.5625))));
  CHECK(b.center.x() == Approx(0.75));  // the origin stays where it was
  CHECK(b.position().x() == 0.0);
}

TEST_CASE("capsule mass: rectangle plus two half discs, I about the centre in closed form") {
  const double r = 0.5, l = 2.0, rho = 3.0;
  const MassData md = computeMass(makeCapsule({-1, 0}, {1, 0}, r), rho);
  CHECK(md.area == Approx(2 * r * l + std::numbers::pi * r * r));
  CHECK(md.mass == Approx(rho * md.area));
  CHECK(md.center.norm() == Approx(0.0));
  // Independent form: a half disc's inertia about its centroid is m (r²/2 − (4r/3π)²); moved to
  // the capsule centre, distance l/2 + 4r/3π.
  const double m_rect = rho * 2 * r * l, m_half = rho * std::numbers::pi * r * r / 2, c = 4 * r / (3 * std::numbers::pi);
  const double expected = m_rect * (l * l + 4 * r * r) / 12 + 2 * (m_half * (r * r / 2 - c * c) + m_half * std::pow(l / 2 + c, 2));
  CHECK(md.inertia == Approx(expected).epsilon(1e-12));
  // A capsule of length → 0 is a disc: I → ½ m r².
  const MassData disc = computeMass(makeCapsule({0, 0}, {1e-6, 0}, r), rho);
  CHECK(disc.inertia == Approx(0.5 * disc.mass * r * r).epsilon(1e-5));
}

TEST_CASE("compound mass: a ring of eight circles, I = Σ (½ m r² + m R²)") {
  World w;
  const BodyId ring = bodyWith(w, BodyType::Dynamic, {5, 5});
  const double R = 2.0, r = 0.25;
  for (int i = 0; i < 8; ++i) {
    const double t = 2 * std::numbers::pi * i / 8;
    add(w, ring, makeCircle(r, {R * std::cos(t), R * std::sin(t)}));
  }
  const Body& b = w.body(ring);
  const double m = std::numbers::pi * r * r;
  CHECK(b.mass == Approx(8 * m));
  CHECK(b.local_center.norm() == Approx(0.0).epsilon(1e-12));
  CHECK(b.inertia == Approx(8 * (0.5 * m * r * r + m * R * R)));
}

TEST_CASE("one-shape bodies keep their values exactly, mass and density options spread over shapes") {
  World w;
  BodyDef d;
  d.shape = makeBox(2, 1, Vec2(1, 0));
  d.mass = 10.0;
  const Body& one = w.body(w.createBody(d));
  CHECK(one.mass == 10.0);
  CHECK(one.density == 5.0);
  // setMass on a compound keeps the shapes' proportions.
  const BodyId c = bodyWith(w);
  const ShapeId light = add(w, c, makeBox(1, 1, {-1, 0}), 1.0);
  const ShapeId heavy = add(w, c, makeBox(1, 1, {1, 0}), 3.0);
  CHECK(w.body(c).mass == Approx(4.0));
  CHECK(w.body(c).local_center.x() == Approx(0.5));
  w.setMass(c, 8.0);
  CHECK(w.body(c).mass == Approx(8.0));
  CHECK(w.shape(light).density == Approx(2.0));
  CHECK(w.shape(heavy).density == Approx(6.0));
  CHECK(w.body(c).local_center.x() == Approx(0.5));
}

TEST_CASE("removing a shape recomputes the mass, a shapeless dynamic body is a unit point mass") {
  World w;
  const BodyId b = bodyWith(w);
  CHECK(w.body(b).mass == 1.0);
  CHECK(w.body(b).inertia == 1.0);
  const ShapeId a = add(w, b, makeCircle(1.0, {2, 0}));
  const ShapeId c = add(w, b, makeCircle(1.0, {-2, 0}));
  CHECK(w.body(b).local_center.x() == Approx(0.0));
  w.destroyShape(a);
  CHECK_FALSE(w.isValid(a));
  CHECK(w.body(b).shapes.size() == 1);
  CHECK(w.body(b).local_center.x() == Approx(-2.0));
  CHECK(w.body(b).mass == Approx(std::numbers::pi));
  w.destroyBody(b);
  CHECK_FALSE(w.isValid(c));  // shapes go with their body
}

TEST_CASE("segments and chains: no area, so only static and kinematic bodies, chains only static") {
  World w;
  const BodyId dyn = bodyWith(w);
  CHECK(test::errorOf([&] { add(w, dyn, makeSegment({0, 0}, {1, 0})); }) ==
        "a segment has no area, so only static and kinematic bodies may have one (use a capsule or a thin box)");
  const BodyId kin = bodyWith(w, BodyType::Kinematic);
  add(w, kin, makeSegment({0, 0}, {1, 0}));
  CHECK(test::errorOf([&] { w.setType(kin, BodyType::Dynamic); }) ==
        "a body with a segment or chain shape cannot be dynamic: segments have no area (use a capsule or a thin box)");
  World::ChainDef chain;
  chain.points = {{0, 0}, {1, 0}, {2, 1}};
  CHECK(test::errorOf([&] { w.createChain(kin, chain); }) == "chains are for static bodies; this body is kinematic");
  const BodyId ground = bodyWith(w, BodyType::Static);
  const std::vector<ShapeId> segments = w.createChain(ground, chain);
  REQUIRE(segments.size() == 2);
  // Open chain: the ends have no neighbour (ghost = end point); inside, the neighbours.
  const Shape& first = w.shape(segments[0]).geometry;
  const Shape& second = w.shape(segments[1]).geometry;
  CHECK(first.ghost1 == first.vertices[0]);
  CHECK(first.ghost2 == Vec2(2, 1));
  CHECK(second.ghost1 == Vec2(0, 0));
  CHECK(second.ghost2 == second.vertices[1]);
  CHECK(w.shape(segments[0]).chain == w.shape(segments[1]).chain);
  chain.loop = true;
  const std::vector<ShapeId> loop = w.createChain(ground, chain);
  REQUIRE(loop.size() == 3);
  CHECK(w.shape(loop[0]).geometry.ghost1 == Vec2(2, 1));  // wraps round
  chain.points = {{0, 0}, {0, 0}};
  chain.loop = false;
  CHECK(test::errorOf([&] { w.createChain(ground, chain); }) == "points[2] repeats the point before it, (0, 0)");
}

TEST_CASE("filtering: categories and masks, groups that always or never collide") {
  Filter a, b;
  CHECK(shouldCollide(a, b));
  a.category = 2;
  b.mask = ~uint64_t{2};
  CHECK_FALSE(shouldCollide(a, b));
  b.mask = ~uint64_t{0};
  a.group = b.group = -3;
  CHECK_FALSE(shouldCollide(a, b));
  a.group = b.group = 4;
  a.mask = 0;  // the positive group wins over the masks
  CHECK(shouldCollide(a, b));

  // In a world: two boxes of the same negative group fall through each other onto the floor.
  World w;
  test::addBox(w, 20, 1, {0, -0.5}, true);
  BodyDef d;
  d.shape = makeBox(1, 1);
  d.filter.group = -1;
  d.position = {0, 0.5};
  const BodyId low = w.createBody(d);
  d.position = {0, 1.0};  // half inside the first
  const BodyId high = w.createBody(d);
  for (int i = 0; i < 120; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(low).position().y() == Approx(0.5).epsilon(0.01));
  CHECK(w.body(high).position().y() == Approx(0.5).epsilon(0.01));  // on the floor, inside the other
}

TEST_CASE("concave outline: split into convex pieces with the same area, a self-crossing one is refused") {
  const std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto pieces = decomposeConcave(l);
  CHECK(pieces.size() == 2);
  double area = 0;
  for (const auto& p : pieces) area += computeMass(makePolygon(p), 1.0).area;
  CHECK(area == Approx(3.0));
  // A comb of five teeth on a 9 × 1 base: area 9 + 5 · 2 = 19, every piece convex.
  const std::vector<Vec2> comb = {{0, 0}, {9, 0}, {9, 3}, {8, 3}, {8, 1}, {7, 1}, {7, 3}, {6, 3}, {6, 1}, {5, 1},
                                  {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const auto teeth = decomposeConcave(comb);
  double comb_area = 0;
  for (const auto& p : teeth) comb_area += computeMass(makePolygon(p), 1.0).area;  // makePolygon: convex
  CHECK(comb_area == Approx(19.0));
  CHECK(teeth.size() <= 11);
  const std::vector<Vec2> bow = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  CHECK(test::errorOf([&] { decomposeConcave(bow); }) == "outline crosses itself: edge 1 meets edge 3");
}

TEST_CASE("kinematic bodies: move by their velocity, push dynamic bodies, carry them by friction, are not pushed") {
  World w;
  BodyDef pd;
  pd.type = BodyType::Kinematic;
  pd.shape = makeBox(4, 0.5);
  pd.position = {0, 0};
  pd.velocity = {1.0, 0.0};
  const BodyId platform = w.createBody(pd);
  BodyDef bd;
  bd.shape = makeBox(0.5, 0.5);
  bd.position = {0, 0.5};
  bd.friction = 1.0;
  const BodyId box = w.createBody(bd);
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);  // the box slips until friction has it at 1 m/s
  const double offset = w.body(box).position().x() - w.body(platform).position().x();
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(platform).position().x() == Approx(2.0).epsilon(1e-12));  // exactly v t: not pushed, no gravity
  CHECK(w.body(platform).position().y() == 0.0);
  CHECK(std::abs(w.body(box).position().x() - w.body(platform).position().x() - offset) < 0.01);  // carried along
  CHECK(w.body(box).velocity.x() == Approx(1.0).epsilon(0.01));
  CHECK(w.body(platform).mass > 0.0);
  CHECK(w.body(platform).inv_mass == 0.0);
}

TEST_CASE("kinematic bodies push dynamic bodies in their way, in both contact solvers") {
  for (ContactSolver solver : {ContactSolver::SequentialImpulses, ContactSolver::SoftStep}) {
    WorldDef def;
    def.gravity = Vec2::Zero();
    def.contact_solver = solver;
    World w(def);
    BodyDef k;
    k.type = BodyType::Kinematic;
    k.shape = makeBox(1, 1);
    k.velocity = {2, 0};
    const BodyId pusher = w.createBody(k);
    const BodyId box = test::addBox(w, 1, 1, {2, 0});
    for (int i = 0; i < 120; ++i) w.step(1.0 / 60.0);
    CHECK(w.body(pusher).position().x() == Approx(4.0).epsilon(1e-12));
    CHECK(w.body(box).position().x() >= 4.0 + 1.0 - 0.02);
    CHECK(w.body(box).velocity.x() >= 2.0 - 1e-6);
  }
}

TEST_CASE("kinematic set_target reaches the pose in the given time, static bodies refuse velocities") {
  World w;
  BodyDef d;
  d.type = BodyType::Kinematic;
  d.shape = makeBox(1, 1, {0.5, 0});  // the centre of mass off the origin
  const BodyId k = w.createBody(d);
  w.setTarget(k, {3, 1}, 0.5, 1.0);
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(k).position().x() == Approx(3.0).epsilon(1e-12));
  CHECK(w.body(k).position().y() == Approx(1.0).epsilon(1e-12));
  CHECK(w.body(k).angle == Approx(0.5).epsilon(1e-12));
  const BodyId s = test::addBox(w, 1, 1, {5, 5}, true);
  CHECK(test::errorOf([&] { w.setVelocity(s, {1, 0}); }) ==
        "a static body cannot move: make it kinematic to give it a velocity");
  w.setVelocity(s, {0, 0});  // zero is fine
  CHECK(test::errorOf([&] { w.setTarget(s, {0, 0}, 0, 1); }) == "set_target moves kinematic bodies; this body is static");
}

TEST_CASE("body properties: gravity scale, damping that never flips, fixed rotation, disabled bodies") {
  World w;
  BodyDef d;
  d.shape = makeCircle(0.5);
  d.gravity_scale = 0.5;
  const BodyId half = w.createBody(d);
  d.gravity_scale = 1.0;
  d.position = {10, 0};
  d.linear_damping = 1e6;  // h c = 1.7e4: v shrinks, never flips
  d.velocity = {5, 0};
  const BodyId damped = w.createBody(d);
  d.linear_damping = 0.0;
  d.position = {20, 0};
  d.velocity = {0, 0};
  d.shape = makeBox(1, 1);
  d.fixed_rotation = true;
  d.angular_velocity = 3.0;
  const BodyId fixed = w.createBody(d);
  CHECK(w.body(fixed).angular_velocity == 0.0);
  w.applyImpulse(fixed, {0, 1}, w.body(fixed).center + Vec2(0.5, 0));
  d.fixed_rotation = false;
  d.angular_velocity = 0.0;
  d.position = {30, 0};
  d.enabled = false;
  const BodyId off = w.createBody(d);
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(half).position().y() == Approx(-0.25 * 9.80665).epsilon(1e-9));
  CHECK(w.body(damped).velocity.x() >= 0.0);
  CHECK(w.body(damped).velocity.x() < 1e-6);
  CHECK(w.body(fixed).angle == 0.0);
  CHECK(w.body(fixed).angular_velocity == 0.0);
  CHECK(w.body(off).position().y() == 0.0);  // out of the simulation
  w.setEnabled(off, true);
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(off).position().y() == Approx(-0.5 * 9.80665).epsilon(1e-9));  // falls from where it was
}

// (No ';' in a test name: ctest cuts the name there and its filter then runs nothing.)
TEST_CASE("bullets: a 300 m/s ball stops at a thin dynamic plank, and without bullet only when its impacts are located") {
  for (const ImpactHandling impacts : {ImpactHandling::PerStep, ImpactHandling::Located})
  for (bool bullet : {true, false}) {
    CAPTURE(impactHandlingName(impacts));
    CAPTURE(bullet);
    WorldDef def;
    def.gravity = Vec2::Zero();
    def.impacts = impacts;
    World w(def);
    BodyDef plank;
    plank.shape = makeBox(0.05, 2.0);
    plank.position = {5, 0};
    const BodyId p = w.createBody(plank);
    BodyDef ball;
    ball.shape = makeCircle(0.05);
    ball.velocity = {300, 0};
    ball.bullet = bullet;
    ball.restitution = 0.0;
    const BodyId b = w.createBody(ball);
    for (int i = 0; i < 10; ++i) w.step(1.0 / 60.0);
    if (bullet || impacts == ImpactHandling::Located) {
      // Stopped at the plank, which took the momentum: they move on together (plastic impact). Two
      // bodies in free flight are an island of located impacts: the search along their paths finds
      // the plank whether the ball is a bullet or not.
      CHECK(w.body(b).position().x() < w.body(p).position().x());
      const double mb = w.body(b).mass, mp = w.body(p).mass;
      CHECK(w.body(p).velocity.x() == Approx(300.0 * mb / (mb + mp)).epsilon(1e-6));
    } else {
      CHECK(w.body(b).position().x() > w.body(p).position().x());  // tunnelled: once per step only bullets are swept against moving bodies
    }
  }
}

// Located impacts (WorldDef::impacts = Located, event_location.cpp): impact times and bounces
// against their closed forms, energy on elastic bounces at every step size, the end of a decaying
// bounce, simultaneous impacts, the per-island rule, and contact events of a bounce inside a step.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "test_util.h"

using namespace rigidlab;
using doctest::Approx;

namespace {

constexpr double g = 9.80665;

BodyId floorBody(World& w, double restitution, double friction = 0.6) {
  BodyDef f;
  f.type = BodyType::Static;
  f.shape = makeBox(40, 1);
  f.position = {0, -0.5};
  f.restitution = restitution;
  f.friction = friction;
  return w.createBody(f);
}

BodyId ball(World& w, Vec2 position, double restitution, double radius = 0.1, Vec2 velocity = Vec2::Zero()) {
  BodyDef d;
  d.shape = makeCircle(radius);
  d.position = position;
  d.velocity = velocity;
  d.restitution = restitution;
  d.mass = 1;
  return w.createBody(d);
}

// FNV-1a over every body's state bits.
uint64_t stateHash(const World& w) {
  uint64_t h = 1469598103934665603ull;
  const auto add = [&](double x) {
    unsigned char b[8];
    std::memcpy(b, &x, 8);
    for (unsigned char c : b) h = (h ^ c) * 1099511628211ull;
  };
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    add(b.center.x()), add(b.center.y()), add(b.angle), add(b.velocity.x()), add(b.velocity.y()), add(b.angular_velocity);
  }
  return h;
}

}  // namespace

TEST_CASE("located impacts: a bouncing ball's impact times, impact speeds and apex heights over 10 bounces at 1/60 (docs/design/accuracy.md §3.12)") {
  const double h0 = 1.0, r = 0.1;
  for (double e : {1.0, 0.8}) {
    CAPTURE(e);
    World w;
    floorBody(w, e);
    const BodyId b = ball(w, {0, r + h0}, e, r);
    // First impact at t1 = √(2 h0 / g) at v1 = g t1; bounce n leaves at e^n v1, flies 2 e^n v1 / g and
    // rises to e^{2n} h0.
    const double t1 = std::sqrt(2 * h0 / g), v1 = g * t1;
    int n = 0;
    double exact_time = t1, worst_apex = 0.0;
    for (int i = 0; i < 10 * 60 && n < 10; ++i) {
      w.step(1.0 / 60.0);
      for (const World::Impact& im : w.impacts()) {
        CHECK(std::abs(im.time - exact_time) < 1e-10);
        CHECK(std::abs(im.approach_speed - std::pow(e, n) * v1) < 1e-10);
        CHECK(im.separating);
        ++n;
        exact_time += 2 * std::pow(e, n) * v1 / g;
      }
      const Body& x = w.body(b);
      if (n > 0 && x.velocity.y() > 0)  // rising: the apex of the parabola it is on
        worst_apex = std::max(worst_apex, std::abs(x.center.y() - r + x.velocity.y() * x.velocity.y() / (2 * g) - std::pow(e, 2 * n) * h0));
    }
    CHECK(n == 10);
    CHECK(worst_apex < 1e-10);
  }
}

TEST_CASE("located impacts: no integrator but explicit Euler gains energy on an elastic bounce, at any dt, either way impacts are handled") {
  for (const ImpactHandling mode : {ImpactHandling::Located, ImpactHandling::PerStep}) {
    for (const Integrator integrator : {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::RungeKutta4,
                                        Integrator::ImplicitEuler}) {
      for (double h0 : {1.0, 2.0}) {
        for (int rate : {5, 10, 20, 30, 60, 120, 240, 480}) {
          CAPTURE(impactHandlingName(mode));
          CAPTURE(integratorName(integrator));
          CAPTURE(h0);
          CAPTURE(rate);
          World w;
          w.setIntegrator(integrator);
          w.setImpacts(mode);
          floorBody(w, 1.0);
          ball(w, {0, 0.1 + h0}, 1.0);
          const double e0 = w.kineticEnergy() + w.potentialEnergy();
          double gain = 0.0;
          int impacts = 0, ccd = 0;
          for (int i = 0; i < 4 * rate; ++i) {
            w.step(1.0 / rate);
            gain = std::max(gain, (w.kineticEnergy() + w.potentialEnergy()) / e0 - 1.0);
            impacts += w.stats().impacts_located;
            ccd += w.stats().ccd_hits;
          }
          if (mode == ImpactHandling::Located) CHECK(impacts >= 2);
          if (integrator == Integrator::ExplicitEuler) {
            CHECK(gain > 0.0);  // its own flight gains ½ g² h² per step
          } else if (integrator == Integrator::RungeKutta4) {
            CHECK(gain < 1e-14);  // exact free flight: round-off
          } else {
            CHECK(gain <= 0.0);
          }
        }
      }
    }
  }
}

TEST_CASE("located impacts: the fast-body path keeps the speed the body had at the wall (elastic ball, r 0.1 m, dropped 1 m, RK4 at 1/30)") {
  // Once per step, the ball travels more than its radius in the steps near the floor, so continuous
  // collision detection puts it back at the floor: with its end-of-step speed there it gained 7 %
  // of its energy per bounce.
  World w;
  w.setImpacts(ImpactHandling::PerStep);
  floorBody(w, 1.0);
  ball(w, {0, 1.1}, 1.0);
  const double e0 = w.kineticEnergy() + w.potentialEnergy();
  int ccd = 0;
  for (int i = 0; i < 90; ++i) {
    w.step(1.0 / 30.0);
    ccd += w.stats().ccd_hits;
    CHECK((w.kineticEnergy() + w.potentialEnergy()) / e0 - 1.0 < 1e-14);
  }
  CHECK(ccd >= 1);  // the path under test was taken
}

TEST_CASE("located impacts: a decaying bounce ends in resting contact, no Zeno cascade") {
  World w;
  floorBody(w, 0.8);
  const BodyId b = ball(w, {0, 1.1}, 0.8);
  int impacts = 0, most_in_a_step = 0, located_steps_after_rest = 0;
  for (int i = 0; i < 8 * 60; ++i) {
    w.step(1.0 / 60.0);
    impacts += w.stats().impacts_located;
    most_in_a_step = std::max(most_in_a_step, w.stats().impacts_located);
    if (w.time() > 4.0) located_steps_after_rest += w.stats().impact_bodies;
  }
  // Ten bounces faster than the restitution threshold (0.5 m/s: the 10th at 0.594 m/s), the 11th at
  // 0.475 m/s stops the ball; from then on it rests, handled once per step.
  CHECK(impacts == 11);
  CHECK(most_in_a_step == 1);
  CHECK(located_steps_after_rest == 0);
  const Body& x = w.body(b);
  CHECK(x.velocity.norm() < 1e-9);
  CHECK(std::abs(x.position().y() - 0.1) < 5e-3);  // within the allowed penetration
}

TEST_CASE("located impacts: simultaneous impacts in one island resolve together") {
  SUBCASE("a box landing flat bounces flat, on both corners at once (e = 1, no friction)") {
    World w;
    floorBody(w, 1.0, 0.0);
    BodyDef d;
    d.shape = makeBox(1, 0.5);
    d.position = {0, 1.25};
    d.restitution = 1;
    d.friction = 0;
    const BodyId box = w.createBody(d);
    const double e0 = w.kineticEnergy() + w.potentialEnergy();
    int impacts = 0;
    for (int i = 0; i < 120; ++i) {
      w.step(1.0 / 60.0);
      for (const World::Impact& im : w.impacts()) CHECK(im.count == 2);
      impacts += w.stats().impacts_located;
    }
    CHECK(impacts >= 1);
    CHECK(std::abs(w.body(box).angle) < 1e-12);
    CHECK(std::abs(w.body(box).angular_velocity) < 1e-12);
    CHECK(std::abs((w.kineticEnergy() + w.potentialEnergy()) / e0 - 1) < 1e-12);
  }
  SUBCASE("two discs hit a third from both sides at the same moment") {
    World w;
    w.setGravity(Vec2::Zero());
    const BodyId a = ball(w, {-1.51, 0}, 1.0, 0.5, {1, 0});
    const BodyId b = ball(w, {0, 0}, 1.0, 0.5);
    const BodyId c = ball(w, {1.51, 0}, 1.0, 0.5, {-1, 0});
    int impacts = 0;
    for (int i = 0; i < 120; ++i) {
      w.step(1.0 / 60.0);  // they meet at t = 0.51 s, inside the 31st step
      impacts += w.stats().impacts_located;
    }
    CHECK(impacts == 2);
    // Symmetric: the middle disc stays put, the outer ones come back; momentum stays zero.
    CHECK(std::abs(w.body(b).velocity.x()) < 1e-12);
    CHECK(w.body(a).velocity.x() == Approx(-w.body(c).velocity.x()).epsilon(1e-12));
    CHECK(std::abs(w.body(a).velocity.x() + w.body(b).velocity.x() + w.body(c).velocity.x()) < 1e-12);
    CHECK(w.body(a).velocity.x() < 0.0);
  }
}

TEST_CASE("located impacts: two discs collide in flight under gravity at the closed-form time, with Newton's velocities") {
  // Under the same gravity the separation moves in a straight line: d(t) = d0 + (vB − vA) t, so they
  // touch when |d(t)| = rA + rB, a quadratic in t. Equal masses, e = 1, no friction, head-on along x:
  // the velocities' x components swap.
  for (int rate : {30, 60, 97, 240}) {
    CAPTURE(rate);
    World w;
    const BodyId a = ball(w, {-1, 5}, 1.0, 0.25, {2, 3});
    const BodyId b = ball(w, {1, 5}, 1.0, 0.25, {-1, 3});
    // d0 = (2, 0), closing at 3 m/s: touch when 2 − 3 t = 0.5, t = 0.5 s.
    bool hit = false;
    for (int i = 0; i < rate && !hit; ++i) {
      w.step(1.0 / rate);
      for (const World::Impact& im : w.impacts()) {
        hit = true;
        CHECK(std::abs(im.time - 0.5) < 1e-12);
        CHECK(std::abs(im.approach_speed - 3.0) < 1e-12);
      }
    }
    REQUIRE(hit);
    CHECK(std::abs(w.body(a).velocity.x() + 1.0) < 1e-12);
    CHECK(std::abs(w.body(b).velocity.x() - 2.0) < 1e-12);
    // After the step of the impact both are on their exact parabolas again.
    const double t = w.time(), s = t - 0.5;
    const double y = 5 + 3 * t - 0.5 * g * t * t;
    CHECK(std::abs(w.body(a).position().x() - (-1 + 2 * 0.5 - 1 * s)) < 1e-12);
    CHECK(std::abs(w.body(b).position().x() - (1 - 1 * 0.5 + 2 * s)) < 1e-12);
    CHECK(std::abs(w.body(a).position().y() - y) < 1e-12);
  }
}

TEST_CASE("located impacts: a force that ends inside the step of an impact: both events on one time line") {
  // A 2 N push along x on a 1 kg disc for 0.3 s (ending inside a step of 1/7 s) while it falls
  // 0.5 m onto an elastic floor: x(t) = t² for t ≤ 0.3, then 0.09 + 0.6 (t − 0.3); the bounce at
  // t1 = √(2 · 0.5 / g) is the free fall's.
  World w;
  floorBody(w, 1.0, 0.0);
  BodyDef d;
  d.shape = makeCircle(0.1);
  d.position = {0, 0.6};
  d.restitution = 1;
  d.friction = 0;
  d.mass = 1;
  const BodyId b = w.createBody(d);
  w.addForce(std::make_unique<ConstantForce>(Vec2(2, 0), std::nullopt), b, {}, 0.3);
  const double t1 = std::sqrt(1.0 / g);
  std::vector<double> impacts;
  for (int i = 0; i < 7; ++i) {
    w.step(1.0 / 7.0);
    for (const World::Impact& im : w.impacts()) impacts.push_back(im.time);
  }
  REQUIRE(impacts.size() == 2);  // at t1 and 3 t1
  CHECK(std::abs(impacts[0] - t1) < 1e-12);
  CHECK(std::abs(impacts[1] - 3 * t1) < 1e-12);
  const double t = w.time();
  CHECK(std::abs(w.body(b).position().x() - (0.09 + 0.6 * (t - 0.3))) < 1e-12);
  // The bounce sends it back up to where it started at t = 2 t1, and so on: y(t) on the parabola.
  const double s = std::fmod(t - t1, 2 * t1);
  const double y = 0.1 + std::sqrt(2 * g * 0.5) * s - 0.5 * g * s * s;
  CHECK(std::abs(w.body(b).position().y() - y) < 1e-12);
}

TEST_CASE("located impacts: the rule, per island") {
  SUBCASE("a few bodies in free flight: located; once at rest: once per step") {
    World w;
    floorBody(w, 0.0);
    ball(w, {0, 1}, 0.0);
    w.step(1.0 / 60.0);
    CHECK(w.stats().impact_bodies == 1);
    for (int i = 0; i < 120; ++i) w.step(1.0 / 60.0);
    CHECK(w.stats().impact_bodies == 0);  // resting on the floor: a touching contact
  }
  SUBCASE("per_step: none") {
    World w;
    w.setImpacts(ImpactHandling::PerStep);
    floorBody(w, 0.0);
    ball(w, {0, 1}, 0.0);
    w.step(1.0 / 60.0);
    CHECK(w.stats().impact_bodies == 0);
  }
  SUBCASE("a stack is once per step, the ball falling beside it is located") {
    World w;
    floorBody(w, 0.0);
    for (int i = 0; i < 3; ++i) test::addBox(w, 1, 1, {0, 0.5 + i});
    ball(w, {5, 3}, 0.5);
    for (int i = 0; i < 10; ++i) w.step(1.0 / 60.0);
    CHECK(w.stats().impact_bodies == 1);
  }
  SUBCASE("more awake bodies than impact_max_bodies: none") {
    WorldDef def;
    def.impact_max_bodies = 4;
    World w(def);
    floorBody(w, 0.0);
    for (int i = 0; i < 5; ++i) ball(w, {2.0 * i, 3}, 0.5);
    w.step(1.0 / 60.0);
    CHECK(w.stats().impact_bodies == 0);
  }
  SUBCASE("islands larger than impact_island_bodies: once per step") {
    WorldDef def;
    def.impact_island_bodies = 2;
    World w(def);
    // Three discs on springs to each other: one island of three.
    const BodyId a = ball(w, {0, 3}, 0.5), b = ball(w, {1, 3}, 0.5), c = ball(w, {2, 3}, 0.5), d = ball(w, {6, 3}, 0.5);
    (void)d;
    SpringDef s;
    s.stiffness = 10;
    s.a = a, s.b = b;
    w.addSpring(s);
    s.a = b, s.b = c;
    w.addSpring(s);
    w.step(1.0 / 60.0);
    CHECK(w.stats().impact_bodies == 1);  // d alone
  }
  SUBCASE("a jointed island: once per step") {
    World w;
    const BodyId a = ball(w, {0, 3}, 0.5);
    JointDef j;
    j.type = JointType::Revolute;
    j.a = a;
    j.anchor_a = {0, 4};
    w.createJoint(j);
    w.step(1.0 / 60.0);
    CHECK(w.stats().impact_bodies == 0);
  }
}

TEST_CASE("located impacts: piles and stacks give the same bits with located impacts and once per step") {
  std::vector<uint64_t> hashes;
  for (const ImpactHandling mode : {ImpactHandling::Located, ImpactHandling::PerStep}) {
    World w;
    w.setImpacts(mode);
    floorBody(w, 0.0);
    for (int row = 0; row < 10; ++row)
      for (int k = 0; k < 10 - row; ++k) test::addBox(w, 1, 1, {k - 0.5 * (9 - row), 0.5 + row});
    for (int i = 0; i < 180; ++i) w.step(1.0 / 60.0);
    hashes.push_back(stateHash(w));
  }
  CHECK(hashes[0] == hashes[1]);
}

TEST_CASE("located impacts: a bounce inside a step is reported as begin, hit and end with its impact speed") {
  World w;
  floorBody(w, 1.0);
  BodyDef d;
  d.position = {0, 1.1};
  const BodyId b = w.createBody(d);
  ShapeDef s;
  s.shape = makeCircle(0.1);
  s.contact_events = true;
  s.hit_events = true;
  s.hit_speed = 1.0;
  s.material.restitution = 1;
  w.createShape(b, s);
  int begins = 0, hits = 0, ends = 0;
  for (int i = 0; i < 60; ++i) {
    w.step(1.0 / 60.0);
    for (const auto& e : w.contactEvents()) {
      begins += e.kind == World::ContactEvent::Kind::Begin;
      ends += e.kind == World::ContactEvent::Kind::End;
      if (e.kind != World::ContactEvent::Kind::Hit) continue;
      ++hits;
      CHECK(e.approach_speed == Approx(std::sqrt(2 * g * 1.0)).epsilon(1e-12));
      CHECK(e.normal_impulse == Approx(2 * w.body(b).mass * std::sqrt(2 * g * 1.0)).epsilon(1e-12));
    }
  }
  CHECK(begins == 1);
  CHECK(hits == 1);
  CHECK(ends == 1);
}

TEST_CASE("located impacts: a kinematic paddle rising at v_p hits a falling ball at the closed-form time; it leaves at v_p − e (v − v_p)") {
  // In the paddle's (inertial) frame the ball falls onto a floor: from a gap h = 2.5 m at relative
  // velocity u = −v_p it lands after t1 = (u + √(u² + 2 g h)) / g at relative speed √(u² + 2 g h).
  const double r = 0.5, h = 2.5, vp = 2.0, e = 0.5;
  const double t1 = (-vp + std::sqrt(vp * vp + 2 * g * h)) / g, u1 = std::sqrt(vp * vp + 2 * g * h);
  for (double dt : {1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240}) {
    CAPTURE(dt);
    World w;
    BodyDef p;
    p.type = BodyType::Kinematic;
    p.shape = makeBox(8, 0.4);
    p.position = {0, -0.2};
    p.velocity = {0, vp};
    const BodyId paddle = w.createBody(p);
    const BodyId b = ball(w, {0, r + h}, e, r);
    int impacts = 0;
    while (w.time() < 0.9) {
      w.step(dt);
      for (const World::Impact& im : w.impacts()) {
        ++impacts;
        CHECK(std::abs(im.time - t1) < 1e-12);
        CHECK(std::abs(im.approach_speed - u1) < 1e-12);
        CHECK(im.separating);
        CHECK((im.a == paddle || im.b == paddle));
      }
      if (impacts == 0) continue;
      // After it: v = v_p + e u1 − g (t − t1), a parabola from the paddle's top at t1.
      const double s = w.time() - t1, y1 = r + vp * t1;
      CHECK(std::abs(w.body(b).velocity.y() - (vp + e * u1 - g * s)) < 1e-12);
      CHECK(std::abs(w.body(b).center.y() - (y1 + (vp + e * u1) * s - 0.5 * g * s * s)) < 1e-12);
    }
    CHECK(impacts == 1);
  }
}

TEST_CASE("located impacts: a ball carried by a rising kinematic paddle is persistent contact, not located") {
  World w;
  BodyDef p;
  p.type = BodyType::Kinematic;
  p.shape = makeBox(8, 0.4);
  p.position = {0, -0.2};
  p.velocity = {0, 1};
  w.createBody(p);
  const BodyId b = ball(w, {0, 0.5 + 0.3}, 0.0, 0.5);
  int located = 0;
  for (int i = 0; i < 60; ++i) {
    w.step(1.0 / 60.0);
    located += w.stats().impact_bodies;
  }
  // Located while it falls the 0.3 m gap and until it lands (inelastic: it stays on); carried after.
  CHECK(located > 0);
  CHECK(w.stats().impact_bodies == 0);
  CHECK(w.body(b).velocity.y() == Approx(1.0).epsilon(1e-6));
  CHECK(std::abs(w.body(b).center.y() - 0.5 - w.time() * 1.0) < 0.01);  // on the paddle's top, within the contact slop
}

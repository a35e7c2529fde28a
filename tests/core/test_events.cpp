// Events: contact begin/end/hit with their data, sensors (including fast bodies through thin ones),
// one-way platforms and the pre-solve callback.
#include <doctest/doctest.h>

#include <cmath>

#include "test_util.h"

using namespace rigidlab;
using doctest::Approx;

namespace {

constexpr double kDt = 1.0 / 60.0;

BodyId floorBody(World& w, ShapeDef extra = {}) {
  BodyDef d;
  d.type = BodyType::Static;
  d.position = {0, -0.5};
  const BodyId b = w.createBody(d);
  extra.shape = makeBox(40, 1);
  w.createShape(b, extra);
  return b;
}

}  // namespace

TEST_CASE("contact events: a falling vase begins touching with the analytic fall speed, hits, and ends when lifted") {
  World w;
  floorBody(w);
  BodyDef d;
  d.position = {0, 2.0 + 0.25};  // bottom 2 m above the floor
  const BodyId vase = w.createBody(d);
  ShapeDef s;
  s.shape = makeBox(0.5, 0.5);
  s.contact_events = true;
  s.hit_events = true;
  s.hit_speed = 3.0;
  w.createShape(vase, s);
  const double g = 9.80665;
  bool began = false;
  for (int i = 0; i < 120 && !began; ++i) {
    const double t0 = w.time();
    w.step(kDt);
    for (const auto& e : w.contactEvents()) {
      if (e.kind != World::ContactEvent::Kind::Begin) continue;
      began = true;
      // The closing speed at the start of the step it touched in: free fall from rest, v = g t.
      CHECK(e.approach_speed == Approx(g * t0).epsilon(1e-9));
      CHECK(std::abs(e.normal.y()) == Approx(1.0));
      CHECK(e.normal_impulse > 0.0);
      CHECK(e.b == vase);
    }
    if (began) {
      bool hit = false;
      for (const auto& e : w.contactEvents()) hit |= e.kind == World::ContactEvent::Kind::Hit;
      CHECK(hit);  // 6.2 m/s against a hit speed of 3
    }
  }
  REQUIRE(began);
  for (int i = 0; i < 30; ++i) {
    w.step(kDt);
    CHECK(w.contactEvents().empty());  // resting: no flicker
  }
  CHECK(w.contactsOf(vase).size() == 1);
  w.setTransform(vase, {0, 3}, 0);
  w.step(kDt);
  REQUIRE(w.contactEvents().size() == 1);
  CHECK(w.contactEvents()[0].kind == World::ContactEvent::Kind::End);
  CHECK(w.contactsOf(vase).empty());
}

TEST_CASE("contact events: nothing is kept for shapes that did not ask, everything with setContactEvents") {
  World w;
  floorBody(w);
  test::addBox(w, 1, 1, {0, 0.6});
  for (int i = 0; i < 30; ++i) {
    w.step(kDt);
    CHECK(w.contactEvents().empty());
  }
  w.setContactEvents(true);
  const BodyId second = test::addBox(w, 1, 1, {3, 0.6});
  int begins = 0;
  for (int i = 0; i < 30; ++i) {
    w.step(kDt);
    for (const auto& e : w.contactEvents()) begins += e.kind == World::ContactEvent::Kind::Begin && e.b == second;
  }
  CHECK(begins == 1);
}

TEST_CASE("sensors: begin and end as a ball passes, static and sleeping visitors count, a fast ball does not skip a thin sensor") {
  World w;
  BodyDef zone;
  zone.type = BodyType::Static;
  zone.position = {0, 5};
  const BodyId z = w.createBody(zone);
  ShapeDef s;
  s.shape = makeBox(2, 1);
  s.sensor = true;
  const ShapeId sensor = w.createShape(z, s);
  const BodyId ball = test::addCircle(w, 0.2, {0, 8});
  int begins = 0, ends = 0;
  for (int i = 0; i < 90; ++i) {
    w.step(kDt);
    for (const auto& e : w.sensorEvents()) {
      CHECK(e.sensor == sensor);
      CHECK(e.visitor_body == ball);
      (e.begin ? begins : ends) += 1;
    }
  }
  CHECK(begins == 1);
  CHECK(ends == 1);
  CHECK(w.sensorOverlaps(sensor).empty());
  // A static visitor is reported too, and the sensor collides with nothing.
  BodyDef wall;
  wall.type = BodyType::Static;
  wall.shape = makeBox(0.5, 0.5);
  wall.position = {0.5, 5};
  w.createBody(wall);
  w.step(kDt);
  CHECK(w.sensorOverlaps(sensor).size() == 1);

  // A 1 cm sensor and a ball at 60 m/s (1 m per step): swept, it begins and ends in one step.
  WorldDef def;
  def.gravity = Vec2::Zero();
  World f(def);
  BodyDef thin;
  thin.type = BodyType::Static;
  thin.position = {10.5, 0};  // between two of the ball's steps: only the sweep sees it
  const BodyId t = f.createBody(thin);
  ShapeDef ts;
  ts.shape = makeBox(0.01, 2);
  ts.sensor = true;
  f.createShape(t, ts);
  BodyDef fast;
  fast.shape = makeCircle(0.05);
  fast.velocity = {60, 0};
  f.createBody(fast);
  int fb = 0, fe = 0;
  for (int i = 0; i < 20; ++i) {
    f.step(kDt);
    for (const auto& e : f.sensorEvents()) (e.begin ? fb : fe) += 1;
  }
  CHECK(fb == 1);
  CHECK(fe == 1);
}

TEST_CASE("one-way platform: jumped through from below, stood on from above") {
  World w;
  floorBody(w);
  BodyDef p;
  p.type = BodyType::Static;
  p.position = {0, 2};
  const BodyId plat = w.createBody(p);
  ShapeDef ps;
  ps.shape = makeBox(4, 0.2);
  ps.one_way = Vec2(0, 1);
  w.createShape(plat, ps);
  BodyDef j;
  j.shape = makeBox(0.5, 0.5);
  j.position = {0, 0.25};
  j.velocity = {0, 9.0};  // rises about 4 m: through the platform and above it
  const BodyId jumper = w.createBody(j);
  double highest = 0.0;
  for (int i = 0; i < 180; ++i) {
    w.step(kDt);
    highest = std::max(highest, w.body(jumper).position().y());
  }
  CHECK(highest > 3.0);  // went through from below
  CHECK(w.body(jumper).position().y() == Approx(2.1 + 0.25).epsilon(0.01));  // landed on top and stays
}

TEST_CASE("pre-solve callback: only for flagged shapes, returning false lets a body through") {
  World w;
  BodyDef g;
  g.type = BodyType::Static;
  g.position = {0, -0.5};
  const BodyId ground = w.createBody(g);
  ShapeDef gs;
  gs.shape = makeBox(40, 1);
  gs.pre_solve = true;
  w.createShape(ground, gs);
  const BodyId ghost = test::addBox(w, 1, 1, {0, 2});
  const BodyId solid = test::addBox(w, 1, 1, {3, 2});
  int calls = 0;
  w.setPreSolve([&](const ContactInfo& c) {
    ++calls;
    return !(c.a == ghost || c.b == ghost);
  });
  for (int i = 0; i < 120; ++i) w.step(kDt);
  CHECK(calls > 0);
  CHECK(w.body(ghost).position().y() < -2.0);                       // fell through
  CHECK(w.body(solid).position().y() == Approx(0.5).epsilon(0.01));  // stands
}

// Queries: ray casts, box, point and shape overlaps, shape casts and explosions, each against
// closed-form answers on every shape kind; and the tree that serves them kept right as bodies move.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "test_util.h"

using namespace rigidlab;
using doctest::Approx;

namespace {

BodyId staticBody(World& w, const Shape& s, Vec2 position = Vec2::Zero(), double angle = 0.0) {
  BodyDef d;
  d.type = BodyType::Static;
  d.shape = s;
  d.position = position;
  d.angle = angle;
  return w.createBody(d);
}

}  // namespace

TEST_CASE("ray cast: a rotated box's face, a capsule's side, a circle's tangent, a chain from both sides") {
  World w;
  const double angle = 0.3;
  const BodyId box = staticBody(w, makeBox(2, 2), {0, 0}, angle);
  // A ray along −x from (5, 0): hits the face whose outward normal is (cos θ, sin θ) at distance 1.
  const auto h = w.rayCast({5, 0}, {-5, 0});
  REQUIRE(h);
  CHECK(h->body == box);
  const double x = 1.0 / std::cos(angle);  // the face x cos θ + y sin θ = 1 at y = 0
  CHECK(h->point.x() == Approx(x).epsilon(1e-12));
  CHECK(h->normal.x() == Approx(std::cos(angle)).epsilon(1e-12));
  CHECK(h->normal.y() == Approx(std::sin(angle)).epsilon(1e-12));
  CHECK(h->fraction == Approx((5 - x) / 10).epsilon(1e-12));

  World c;
  staticBody(c, makeCapsule({-2, 0}, {2, 0}, 0.5), {0, 10});
  const auto side = c.rayCast({1, 20}, {1, 0});
  REQUIRE(side);
  CHECK(side->point.y() == Approx(10.5).epsilon(1e-12));
  CHECK(side->normal.y() == Approx(1.0));
  const auto end = c.rayCast({10, 10}, {0, 10});  // into the rounded end at x = 2.5
  REQUIRE(end);
  CHECK(end->point.x() == Approx(2.5).epsilon(1e-12));

  World d;
  staticBody(d, makeCircle(1.0), {0, 0});
  // A ray at height y = 1 − 1e-6 grazes the circle near its top: x = ±sqrt(1 − y²).
  const double y = 1.0 - 1e-6;
  const auto t = d.rayCast({-5, y}, {5, y});
  REQUIRE(t);
  CHECK(t->point.x() == Approx(-std::sqrt(1 - y * y)).epsilon(1e-9));
  CHECK_FALSE(d.rayCast({-5, 1.0 + 1e-9}, {5, 1.0 + 1e-9}));  // above: misses
  CHECK_FALSE(d.rayCast({0, 0}, {5, 0}));                      // starting inside: no hit

  World e;
  BodyDef ground;
  ground.type = BodyType::Static;
  const BodyId g = e.createBody(ground);
  World::ChainDef chain;
  chain.points = {{5, 0}, {0, 0}, {-5, 0}};  // right to left: the surface faces up
  e.createChain(g, chain);
  const auto down = e.rayCast({1, 3}, {1, -3});
  REQUIRE(down);
  CHECK(down->point.y() == Approx(0.0));
  CHECK(down->normal.y() == Approx(1.0));
  CHECK_FALSE(e.rayCast({1, -3}, {1, 3}));  // from behind: a chain is one-sided
}

TEST_CASE("ray cast all, filters, and query box / point / overlap exact on every kind") {
  World w;
  const BodyId a = staticBody(w, makeCircle(0.5), {0, 0});
  const BodyId b = staticBody(w, makeBox(1, 1), {3, 0});
  BodyDef s;
  s.type = BodyType::Static;
  s.shape = makeCapsule({0, -1}, {0, 1}, 0.25);
  s.position = {6, 0};
  s.filter.category = 4;
  const BodyId c = w.createBody(s);
  const auto all = w.rayCastAll({-5, 0}, {10, 0});
  REQUIRE(all.size() == 3);
  CHECK(all[0].body == a);
  CHECK(all[1].body == b);
  CHECK(all[2].body == c);
  QueryFilter no_four;
  no_four.mask = ~uint64_t{4};
  CHECK(w.rayCastAll({-5, 0}, {10, 0}, no_four).size() == 2);
  // A box that meets the box's corner region but not the circle's disc (inside its bounding box).
  CHECK(w.queryBox({{0.4, 0.4}, {0.6, 0.6}}).empty());
  CHECK(w.queryBox({{0.3, 0.3}, {0.6, 0.6}}).size() == 1);  // the disc reaches (0.35, 0.35)
  CHECK(w.queryPoint({3.4, 0.4}).size() == 1);
  CHECK(w.queryPoint({3.6, 0.0}).empty());
  CHECK(w.queryPoint({6.0, 1.2}).size() == 1);  // inside the capsule's rounded end
  CHECK(w.overlap(makeCircle(0.1), {{6.3, 0.0}, Rot{}}).size() == 1);   // touches its side (6.25)
  CHECK(w.overlap(makeCircle(0.1), {{6.36, 0.0}, Rot{}}).empty());
}

TEST_CASE("shape cast: the time of impact of a moving shape") {
  World w;
  staticBody(w, makeBox(10, 1), {0, -0.5});  // top face at y = 0
  const auto h = w.shapeCast(makeCircle(0.5), {{0, 5}, Rot{}}, {0, -10});
  REQUIRE(h);
  CHECK(h->fraction == Approx(0.45).epsilon(1e-6));  // travels 4.5 of 10 m
  CHECK(h->normal.y() == Approx(1.0).epsilon(1e-6));
  CHECK(h->point.y() == Approx(0.0).epsilon(1e-6));
  CHECK_FALSE(w.shapeCast(makeCircle(0.5), {{0, 5}, Rot{}}, {0, -4}));  // stops short
}

TEST_CASE("explosion: bodies within the radius pushed away with the width they show, less beyond, none past the falloff") {
  WorldDef def;
  def.gravity = Vec2::Zero();
  World w(def);
  const BodyId near = test::addBox(w, 1, 1, {2, 0});
  const BodyId mid = test::addBox(w, 1, 1, {0, -4});
  const BodyId far = test::addBox(w, 1, 1, {-8, 0});
  ExplosionDef e;
  e.radius = 2.0;
  e.falloff = 2.0;
  e.impulse = 3.0;
  const auto pushed = w.explode(e);
  CHECK(pushed.size() == 2);
  // The near box: its face at 1.5 m, inside the radius: impulse 3 N·s/m × 1 m of width, along +x.
  CHECK(w.body(near).velocity.x() == Approx(3.0).epsilon(1e-9));
  CHECK(w.body(near).velocity.y() == Approx(0.0).epsilon(1e-9));
  // The middle box: its face at 3.5 m, three quarters into the falloff: scale 0.25.
  CHECK(w.body(mid).velocity.y() == Approx(-0.75).epsilon(1e-9));
  CHECK(w.body(far).velocity.norm() == 0.0);
}

TEST_CASE("the query tree follows moving, removed and disabled bodies") {
  World w;
  const BodyId ball = test::addCircle(w, 0.5, {0, 10});
  CHECK(w.queryPoint({0, 10}).size() == 1);  // builds the tree
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  const Vec2 now = w.body(ball).center;
  CHECK(w.queryPoint({0, 10}).empty());
  CHECK(w.queryPoint(now).size() == 1);
  w.setEnabled(ball, false);
  CHECK(w.queryPoint(now).empty());
  w.setEnabled(ball, true);
  CHECK(w.queryPoint(now).size() == 1);
  w.destroyBody(ball);
  CHECK(w.queryPoint(now).empty());
  // Many bodies: every query answer agrees with a brute-force check.
  World many;
  for (int i = 0; i < 400; ++i) test::addCircle(many, 0.3, {(i % 20) * 1.0, (i / 20) * 1.0});
  for (int i = 0; i < 30; ++i) many.step(1.0 / 60.0);
  int found = 0, expected = 0;
  for (BodyId id : many.bodyIds()) {
    const Vec2 c = many.body(id).center;
    expected += 1;
    found += static_cast<int>(many.queryPoint(c).size() >= 1);
  }
  CHECK(found == expected);
}

// Drawing between steps: poses at alpha between the previous and the current step.
#include <doctest/doctest.h>

#include <numbers>

#include "interpolation.h"
#include "world_view.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;

TEST_CASE("interpolation: halfway between two steps, about the centre of mass") {
  World world(WorldDef{.gravity = Vec2(0, 0)});
  BodyDef def;
  // An off-centre polygon, so the origin and the centre of mass differ.
  const Vec2 pts[] = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  def.shape = makePolygon(pts);
  def.velocity = Vec2(6, 0);
  def.angular_velocity = 3.0;
  const BodyId id = world.createBody(def);

  TransformHistory h;
  h.capture(world);
  const Body before = world.body(id);
  world.step(0.1);
  const Body& after = world.body(id);

  const auto at0 = h.interpolate(world, 0.0);
  CHECK(at0[id.index].p.x() == doctest::Approx(before.xf.p.x()));
  CHECK(at0[id.index].p.y() == doctest::Approx(before.xf.p.y()));
  const auto at1 = h.interpolate(world, 1.0);
  CHECK(at1[id.index].p.x() == doctest::Approx(after.xf.p.x()));
  CHECK(at1[id.index].q.s == doctest::Approx(after.xf.q.s));

  const auto half = h.interpolate(world, 0.5);
  const Transform& xf = half[id.index];
  const double mid_angle = 0.5 * (before.angle + after.angle);
  CHECK(std::atan2(xf.q.s, xf.q.c) == doctest::Approx(mid_angle));
  const Vec2 centre = xf.apply(after.local_center);  // the centre of mass moves on a straight line
  CHECK(centre.x() == doctest::Approx(0.5 * (before.center.x() + after.center.x())));
  CHECK(centre.y() == doctest::Approx(0.5 * (before.center.y() + after.center.y())));
}

TEST_CASE("interpolation: new bodies and reused slots are drawn where they are") {
  World world;
  BodyDef def;
  def.shape = makeCircle(0.5);
  const BodyId a = world.createBody(def);
  TransformHistory h;
  h.capture(world);
  world.destroyBody(a);
  def.position = Vec2(5, 5);
  const BodyId b = world.createBody(def);  // likely the same slot, a new generation
  const auto xfs = h.interpolate(world, 0.5);
  REQUIRE(xfs.size() > b.index);
  CHECK(xfs[b.index].p.x() == doctest::Approx(5));
  CHECK(xfs[b.index].p.y() == doctest::Approx(5));
}

TEST_CASE("interpolation: an angle that wraps turns the short way") {
  World world(WorldDef{.gravity = Vec2(0, 0)});
  BodyDef def;
  def.shape = makeCircle(0.5);
  def.angle = std::numbers::pi - 0.1;
  const BodyId id = world.createBody(def);
  TransformHistory h;
  h.capture(world);
  world.setTransform(id, Vec2::Zero(), -std::numbers::pi + 0.1);  // 0.2 rad further, wrapped
  const auto xfs = h.interpolate(world, 0.5);
  const double angle = std::atan2(xfs[id.index].q.s, xfs[id.index].q.c);
  CHECK(std::abs(std::abs(angle) - std::numbers::pi) < 1e-9);  // through π, not through 0
}

namespace {
struct Segments : DebugDraw {
  std::vector<std::pair<Vec2, Vec2>> segments;
  void drawPolygon(std::span<const Vec2>, const Color&, const Color&) override {}
  void drawCircle(const Vec2&, double, double, const Color&, const Color&) override {}
  void drawSegment(const Vec2& a, const Vec2& b, const Color&) override { segments.emplace_back(a, b); }
  void drawPoint(const Vec2&, float, const Color&) override {}
};
}  // namespace

TEST_CASE("interpolation: springs are drawn from the interpolated pose, not the last step's") {
  World world(WorldDef{.gravity = Vec2(0, 0)});
  BodyDef def;
  def.shape = makeCircle(0.2);
  def.position = Vec2(1, 0);
  def.velocity = Vec2(0, 30);  // fast: 0.5 m per 60 Hz step
  const BodyId bob = world.createBody(def);
  SpringDef spring;
  spring.a = bob;
  spring.anchor = Vec2(-3, 0);
  spring.stiffness = 1;
  world.addSpring(spring);
  TransformHistory h;
  h.capture(world);
  const Vec2 before = world.body(bob).xf.p;
  world.step(1.0 / 60.0);
  const Vec2 after = world.body(bob).xf.p;
  REQUIRE((after - before).norm() > 0.4);
  for (const double alpha : {0.0, 0.5, 1.0}) {
    Segments s;
    drawForces(world, h.interpolate(world, alpha), DrawToggles{}, s);
    REQUIRE_FALSE(s.segments.empty());
    const Vec2 expected = before + alpha * (after - before);
    CHECK((s.segments.front().first - expected).norm() < 1e-9);  // the spring starts at the bob
  }
  Segments none;
  DrawToggles off;
  off.springs = false;
  drawForces(world, h.interpolate(world, 0.5), off, none);
  CHECK(none.segments.empty());
}

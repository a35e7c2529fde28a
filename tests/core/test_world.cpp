// World API: bodies, handles, forces, energies, picking, drawing and input validation.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "test_util.h"

using namespace rigidlab;
using doctest::Approx;

TEST_CASE("bodies: mass from density or from a given mass, centre of mass off the origin") {
  World w;
  BodyDef d;
  d.shape = makeBox(2, 1, Vec2(1, 0));  // shape centred 1 m right of the body origin
  d.density = 2.0;
  d.position = {5, 5};
  d.angle = std::numbers::pi / 2;
  const BodyId a = w.createBody(d);
  const Body& A = w.body(a);
  CHECK(A.mass == Approx(4.0));
  CHECK(A.inertia == Approx(4.0 * 5.0 / 12.0));
  CHECK(A.center.x() == Approx(5.0));  // the offset turned by 90°
  CHECK(A.center.y() == Approx(6.0));
  CHECK(A.position().x() == Approx(5.0));
  d.mass = 10.0;
  const Body& B = w.body(w.createBody(d));
  CHECK(B.mass == Approx(10.0));
  CHECK(B.density == Approx(5.0));
  CHECK(B.inertia == Approx(10.0 * 5.0 / 12.0));
}

TEST_CASE("bodies: static ones do not move, switching type at run time") {
  World w;
  const BodyId box = test::addBox(w, 1, 1, {0, 10}, true);
  for (int i = 0; i < 30; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(box).position().y() == 10.0);
  w.setType(box, BodyType::Dynamic);
  CHECK(w.body(box).inv_mass == Approx(1.0));
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(box).position().y() == Approx(10.0 - 0.5 * 9.80665).epsilon(1e-9));
  w.setType(box, BodyType::Static);
  CHECK(w.body(box).velocity.norm() == 0.0);
  CHECK(w.body(box).inv_mass == 0.0);
  CHECK(w.body(box).mass == Approx(1.0));  // kept, for switching back
}

TEST_CASE("handles: destroyed bodies are detected, slots are reused with a new generation") {
  World w;
  const BodyId a = test::addCircle(w, 0.5, {0, 0});
  const BodyId b = test::addCircle(w, 0.5, {3, 0});
  DamperDef damper;
  damper.body = a;
  damper.coefficient = 1.0;
  const ForceId f = w.addDamper(damper);
  w.destroyBody(a);
  CHECK_FALSE(w.isValid(a));
  CHECK_FALSE(w.isValid(f));  // a body's forces go with it
  CHECK(w.bodyCount() == 1);
  CHECK(test::errorOf([&] { w.body(a); }) == "body handle is not valid (the body was removed or never existed)");
  const BodyId c = test::addCircle(w, 0.5, {0, 0});
  CHECK(c.index == a.index);
  CHECK(c.generation != a.generation);
  CHECK_FALSE(w.isValid(a));
  CHECK(w.isValid(b));
  CHECK(w.bodyIds().size() == 2);
}

TEST_CASE("names, lookup and picking (point in shape)") {
  World w;
  BodyDef d;
  d.shape = makeBox(2, 2);
  d.name = "crate";
  const BodyId crate = w.createBody(d);
  d.shape = makeCircle(0.5);
  d.position = {0.5, 0.5};
  d.name = "ball";
  const BodyId ball = w.createBody(d);
  CHECK(w.findBody("crate") == crate);
  CHECK_FALSE(w.findBody("nothing").has_value());
  CHECK(w.bodyAt({0.6, 0.6}) == ball);    // the later body is on top
  CHECK(w.bodyAt({-0.8, -0.8}) == crate);
  CHECK_FALSE(w.bodyAt({3, 3}).has_value());
}

TEST_CASE("energies: kinetic ½mv² + ½Iω², gravity −m g·c, springs ½kx²") {
  World w;
  BodyDef d;
  d.shape = makeCircle(1.0);
  d.mass = 2.0;  // I = 1
  d.position = {0, 3};
  d.velocity = {3, 4};
  d.angular_velocity = 2.0;
  const BodyId a = w.createBody(d);
  CHECK(w.kineticEnergy() == Approx(0.5 * 2 * 25 + 0.5 * 1 * 4));
  CHECK(w.gravityPotentialEnergy() == Approx(2 * 9.80665 * 3));
  SpringDef s;
  s.a = a;
  s.anchor = {0, 0};
  s.stiffness = 10.0;
  s.rest_length = 1.0;
  w.addSpring(s);
  CHECK(w.potentialEnergy() == Approx(2 * 9.80665 * 3 + 0.5 * 10.0 * 4.0));
}

TEST_CASE("springs: default rest length is the distance at creation, force F = −k (L − L0)") {
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId a = test::addCircle(w, 0.1, {0, 0});
  const BodyId b = test::addCircle(w, 0.1, {2, 0});
  SpringDef s;
  s.a = a;
  s.b = b;
  s.stiffness = 5.0;
  const ForceId id = w.addSpring(s);
  auto& spring = dynamic_cast<SpringForce&>(w.force(id));
  CHECK(*spring.def().rest_length == Approx(2.0));
  ForceOutput out;
  const BodyState sa = w.bodyState(a);
  BodyState sb = w.bodyState(b);
  sb.position = sb.center = {3, 0};  // stretched by 1 m
  spring.evaluate({sa, &sb, 0.0}, out);
  CHECK(out.a.force.x() == Approx(5.0));  // pulls a towards b
  CHECK(out.b.force.x() == Approx(-5.0));
}

TEST_CASE("the mouse force is a damped spring to the cursor with a capped magnitude") {
  World w;
  const BodyId a = test::addCircle(w, 0.5, {0, 0}, 2.0);
  MouseForceDef def = MouseForce::forBody(w.body(a), {0, 0});
  CHECK(def.stiffness == Approx(2.0 * std::pow(2 * std::numbers::pi * 5.0, 2)));
  def.target = {100, 0};
  MouseForce mouse(def);
  ForceOutput out;
  mouse.evaluate({w.bodyState(a), nullptr, 0.0}, out);
  CHECK(out.a.force.norm() == Approx(def.max_force));
  CHECK(out.a.force.x() > 0);
}

TEST_CASE("applyImpulse: Δv = J/m, Δω = (p − c) × J / I") {
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId a = test::addBox(w, 2, 2, {0, 0});  // m = 4, I = 4·8/12
  w.applyImpulse(a, {0, 2}, {1, 0});
  CHECK(w.body(a).velocity.y() == Approx(0.5));
  CHECK(w.body(a).angular_velocity == Approx(2.0 / (4.0 * 8.0 / 12.0)));
}

TEST_CASE("edits from inside a force while the world steps are refused") {
  struct Meddler final : Force {
    World* world;
    std::string error;
    void evaluate(const ForceInput& in, ForceOutput&) override {
      error = test::errorOf([&] { world->destroyBody(in.a.id); });
    }
    std::string_view kind() const override { return "meddler"; }
  };
  World w;
  const BodyId a = test::addCircle(w, 0.5, {0, 0});
  auto meddler = std::make_unique<Meddler>();
  Meddler* m = meddler.get();
  m->world = &w;
  w.addForce(std::move(meddler), a);
  w.step(1.0 / 60.0);
  CHECK(m->error == "destroyBody is not allowed while the world is stepping (e.g. from inside a force)");
  CHECK(w.isValid(a));
}

TEST_CASE("every rejected input names the field and the value") {
  World w;
  const BodyId a = test::addCircle(w, 0.5, {0, 0});
  const auto create = [&](auto edit) {
    BodyDef d;
    d.shape = makeCircle(1.0);
    edit(d);
    return test::errorOf([&] { w.createBody(d); });
  };
  CHECK(create([](BodyDef& d) { d.density = 0.0; }) == "density must be > 0, got 0");
  CHECK(create([](BodyDef& d) { d.mass = -1.0; }) == "mass must be > 0, got -1");
  CHECK(create([](BodyDef& d) { d.position = {NAN, 0}; }) == "position must be finite, got (nan, 0)");
  CHECK(create([](BodyDef& d) { d.velocity = {0, INFINITY}; }) == "velocity must be finite, got (0, inf)");
  CHECK(create([](BodyDef& d) { d.angle = NAN; }) == "angle must be finite, got nan");
  CHECK(create([](BodyDef& d) { d.angular_velocity = -INFINITY; }) == "angular_velocity must be finite, got -inf");
  CHECK(create([](BodyDef& d) { d.restitution = 1.5; }) == "restitution must be between 0 and 1, got 1.5");
  CHECK(create([](BodyDef& d) { d.friction = -0.1; }) == "friction must be >= 0, got -0.1");
  CHECK(create([](BodyDef& d) { d.static_friction = NAN; }) == "static_friction must be >= 0, got nan");
  CHECK(create([](BodyDef& d) { d.shape->radius = -2.0; }) == "radius must be > 0, got -2");
  // A shape whose points lie so far from the body's origin that their distance overflows is refused
  // as it is made, naming it (so no finite position can put a centre of mass out of range).
  CHECK(test::errorOf([] { (void)makeCircle(1.0, {1e308, 0.0}); }) ==
        "center (1e+308, 0) is too far from the body's origin: its distance overflows (a shape's points must lie "
        "within about 1e154 m of it)");
  const Vec2 before = w.body(a).center;
  CHECK(test::errorOf([&] { w.setTransform(a, {0.0, INFINITY}, 0.0); }) == "position must be finite, got (0, inf)");
  CHECK(w.body(a).center == before);

  CHECK(test::errorOf([&] { w.step(0.0); }) == "dt must be > 0, got 0");
  CHECK(test::errorOf([&] { w.step(NAN); }) == "dt must be > 0, got nan");
  CHECK(test::errorOf([&] { w.setIterations(0); }) == "iterations must be between 1 and 10000, got 0");
  CHECK(test::errorOf([&] { w.setGravity({0, NAN}); }) == "gravity must be finite, got (0, nan)");
  CHECK(test::errorOf([&] { w.setMass(a, 0.0); }) == "mass must be > 0, got 0");
  CHECK(test::errorOf([&] { w.setVelocity(a, {INFINITY, 0}); }) == "velocity must be finite, got (inf, 0)");
  CHECK(test::errorOf([&] { w.setRestitutionThreshold(-1); }) == "restitution_threshold must be >= 0, got -1");

  SpringDef s;
  s.a = a;
  s.anchor = {1, 1};
  s.stiffness = -5.0;
  CHECK(test::errorOf([&] { w.addSpring(s); }) == "stiffness must be >= 0, got -5");
  s.stiffness = 5.0;
  s.damping = NAN;
  CHECK(test::errorOf([&] { w.addSpring(s); }) == "damping must be >= 0, got nan");
  s.damping = 0.0;
  s.rest_length = -1.0;
  CHECK(test::errorOf([&] { w.addSpring(s); }) == "rest_length must be >= 0, got -1");
  s.rest_length.reset();
  s.b = a;
  CHECK(test::errorOf([&] { w.addSpring(s); }) == "a two-body force needs two different bodies");
  DamperDef damper;
  damper.body = a;
  damper.coefficient = -3.0;
  CHECK(test::errorOf([&] { w.addDamper(damper); }) == "coefficient must be >= 0, got -3");
  damper.coefficient = 1.0;
  CHECK(test::errorOf([&] { w.addDamper(damper, -1.0); }) == "duration must be > 0, got -1");
  CHECK(test::errorOf([&] { w.addForce(std::make_unique<ConstantForce>(Vec2(NAN, 0), std::nullopt), a); }) ==
        "force must be finite, got (nan, 0)");
}

TEST_CASE("debug draw: every body, spring and force goes through the interface") {
  struct Recorder final : DebugDraw {
    int polygons = 0, circles = 0, segments = 0, points = 0;
    void drawPolygon(std::span<const Vec2>, const Color&, const Color&) override { ++polygons; }
    void drawCircle(const Vec2&, double, double, const Color&, const Color&) override { ++circles; }
    void drawSegment(const Vec2&, const Vec2&, const Color&) override { ++segments; }
    void drawPoint(const Vec2&, float, const Color&) override { ++points; }
  };
  World w;
  const BodyId box = test::addBox(w, 1, 1, {0, 0});
  const BodyId ball = test::addCircle(w, 0.5, {3, 0});
  SpringDef s;
  s.a = box;
  s.b = ball;
  s.stiffness = 1.0;
  w.addSpring(s);
  Recorder r;
  w.draw(r);
  CHECK(r.polygons == 1);
  CHECK(r.circles == 1);
  CHECK(r.segments == 2 * 8 + 3);  // the zigzag: lead-in, 16 slanted strokes, 2 lead-outs
  DrawOptions opt;
  opt.shapes = false;
  opt.springs = false;
  opt.centers = true;
  Recorder centers;
  w.draw(centers, opt);
  CHECK(centers.points == 2);
  CHECK(centers.polygons + centers.circles + centers.segments == 0);
}

TEST_CASE("a force that throws leaves the world as before the step") {
  struct Failing final : Force {
    int calls = 0;
    void evaluate(const ForceInput&, ForceOutput& out) override {
      if (++calls == 3) throw std::runtime_error("script error");  // in the middle of RK4's stages
      out.a.force = {1, 0};
    }
    std::string_view kind() const override { return "failing"; }
  };
  World w;
  const BodyId a = test::addCircle(w, 0.5, {0, 0});
  const BodyId b = test::addCircle(w, 0.5, {5, 0});
  w.setVelocity(b, {1, 2});
  w.addForce(std::make_unique<Failing>(), a);
  CHECK_THROWS_WITH(w.step(0.1), "script error");
  CHECK(w.time() == 0.0);
  CHECK(w.stepCount() == 0);
  CHECK(w.body(b).position() == Vec2(5, 0));
  CHECK(w.body(b).velocity == Vec2(1, 2));
  CHECK(w.body(a).position() == Vec2(0, 0));
  w.setVelocity(a, {0, 1});  // the world is usable again (not left locked)
}

TEST_CASE("uids count bodies in creation order and are never reused, kNextStep forces last one step") {
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId a = test::addCircle(w, 0.5, {0, 0});
  const BodyId b = test::addCircle(w, 0.5, {3, 0});
  CHECK(w.body(a).uid == 1);
  CHECK(w.body(b).uid == 2);
  w.destroyBody(a);
  const BodyId c = test::addCircle(w, 0.5, {0, 0}, 2.0);
  CHECK(w.body(c).uid == 3);
  CHECK(w.findBody(3u) == c);
  const ForceId push = w.addForce(std::make_unique<ConstantForce>(Vec2(4, 0), std::nullopt), c, {}, World::kNextStep);
  w.step(0.5);
  CHECK_FALSE(w.isValid(push));
  CHECK(w.body(c).velocity.x() == Approx(1.0));  // 4 N on 2 kg for 0.5 s
  w.step(0.5);
  CHECK(w.body(c).velocity.x() == Approx(1.0));
}

TEST_CASE("NaN firewall: a body whose state becomes non-finite is frozen, reported and cannot poison others") {
  struct Overflow final : Force {
    void evaluate(const ForceInput& in, ForceOutput& out) override {
      out.a.force = {in.time > 0.05 ? NAN : 0.0, 0.0};
    }
    std::string_view kind() const override { return "overflow"; }
  };
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId bad = test::addCircle(w, 0.5, {0, 0});
  const BodyId neighbour = test::addCircle(w, 0.5, {0.99, 0});  // overlapping: in contact every step
  w.addForce(std::make_unique<Overflow>(), bad);
  for (int i = 0; i < 20; ++i) w.step(0.02);
  REQUIRE(w.incidents().size() == 1);
  const Incident& incident = w.incidents()[0];
  CHECK(incident.uid == 1);
  CHECK(incident.step == 3);  // the first step that evaluates the force after t = 0.05
  CHECK(incident.cause == "overflow returned a non-finite force or torque");
  CHECK(incident.message() == "body 1 frozen at step 3 (t = 0.04 s): overflow returned a non-finite force or torque");
  CHECK(w.body(bad).frozen);
  CHECK(w.body(bad).isStatic());
  CHECK(isFinite(w.body(bad).center));
  CHECK(isFinite(w.body(neighbour).center));
  CHECK(isFinite(w.body(neighbour).velocity));
  w.setType(bad, BodyType::Dynamic);
  CHECK_FALSE(w.body(bad).frozen);
}

TEST_CASE("NaN firewall: an overflowing spring is named") {
  World w;
  w.setGravity(Vec2::Zero());
  w.setIntegrator(Integrator::SemiImplicitEuler);
  const BodyId a = test::addCircle(w, 0.1, {1, 0}, 1e-3);
  SpringDef s;
  s.a = a;
  s.stiffness = 1e300;  // ωh ≫ 2: semi-implicit Euler overflows within a few steps
  s.rest_length = 0.0;
  w.addSpring(s);
  for (int i = 0; i < 50 && w.incidents().empty(); ++i) w.step(1.0 / 60.0);
  REQUIRE(w.incidents().size() == 1);
  // Either the spring's own force overflowed first or the state did; both name the spring.
  CHECK(w.incidents()[0].cause.find("spring") != std::string::npos);
  CHECK(isFinite(w.body(a).center));
}

TEST_CASE("sleeping: a resting island falls asleep, costs nothing, and wakes when touched or edited") {
  World w;
  test::addBox(w, 40, 1, {0, -0.5}, true);
  const BodyId low = test::addBox(w, 1, 1, {0, 0.5});
  const BodyId high = test::addBox(w, 1, 1, {0, 1.5});
  int steps_to_sleep = 0;
  while (w.body(low).awake && steps_to_sleep < 600) {
    w.step(1.0 / 60.0);
    ++steps_to_sleep;
  }
  MESSAGE("the stack fell asleep after " << steps_to_sleep << " steps");
  CHECK(steps_to_sleep >= 30);  // at least time_to_sleep = 0.5 s of stillness
  CHECK(steps_to_sleep < 120);
  CHECK_FALSE(w.body(high).awake);  // the island sleeps together
  const Vec2 p = w.body(high).position();
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  CHECK(w.stats().awake_bodies == 0);
  CHECK(w.body(high).position() == p);  // not integrated while asleep

  // A ball dropped on it wakes the whole island when it arrives.
  const BodyId ball = test::addCircle(w, 0.3, {0.0, 4.0});
  CHECK_FALSE(w.body(low).awake);
  bool woke = false;
  for (int i = 0; i < 120 && !woke; ++i) {
    w.step(1.0 / 60.0);
    woke = w.body(low).awake && w.body(high).awake;
  }
  CHECK(woke);
  CHECK(w.body(ball).awake);

  // Edits wake too.
  for (int i = 0; i < 300; ++i) w.step(1.0 / 60.0);
  REQUIRE_FALSE(w.body(low).awake);
  w.applyImpulse(high, {0, 0.1}, w.body(high).center);
  CHECK(w.body(low).awake);
}

TEST_CASE("sleeping: bodies created asleep cost nothing until touched, and only at rest in a sleeping world") {
  World w;
  w.setGravity(Vec2::Zero());
  BodyDef d;
  d.shape = makeBox(0.4, 0.4);
  d.awake = false;
  std::vector<BodyId> wall;
  for (int j = 0; j < 5; ++j) {
    d.position = {5.0, 0.4 * j};
    wall.push_back(w.createBody(d));
  }
  for (BodyId id : wall) CHECK_FALSE(w.body(id).awake);
  // Shapes added before the first step keep a body created asleep asleep (a compound at rest)...
  BodyDef bare;
  bare.awake = false;
  bare.position = {5.0, -2.0};
  const BodyId compound = w.createBody(bare);
  ShapeDef piece;
  piece.shape = makeBox(0.4, 0.4);
  w.createShape(compound, piece);
  CHECK_FALSE(w.body(compound).awake);
  w.step(1.0 / 60.0);
  CHECK(w.stats().awake_bodies == 0);
  // ...but once stepped, an added shape wakes it: it may overlap what it rests against.
  w.createShape(compound, piece);
  CHECK(w.body(compound).awake);
  w.step(1.0 / 60.0);
  w.destroyBody(compound);
  // Moving bodies and bodies of a world that does not sleep start awake whatever they ask.
  d.position = {20.0, 0.0};
  d.velocity = {1.0, 0.0};
  CHECK(w.body(w.createBody(d)).awake);
  {
    WorldDef def;
    def.sleeping = false;
    World awake_world(def);
    d.velocity = Vec2::Zero();
    CHECK(awake_world.body(awake_world.createBody(d)).awake);
  }
  // A ball thrown at the wall wakes the column it hits and pushes it.
  const BodyId ball = test::addCircle(w, 0.2, {0.0, 0.0});
  w.setVelocity(ball, {10.0, 0.0});
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
  CHECK(w.body(wall[0]).position().x() > 5.1);
}

TEST_CASE("sleeping: forces that may change keep their bodies awake, springs at rest let them sleep") {
  World w;
  const BodyId hanging = test::addCircle(w, 0.2, {0, 0});
  SpringDef s;
  s.a = hanging;
  s.anchor = {0, 2};
  s.stiffness = 100;
  s.damping = 20;
  w.addSpring(s);
  const BodyId pushed = test::addCircle(w, 0.2, {5, 0});
  w.setGravity(Vec2::Zero());
  w.addForce(std::make_unique<ConstantForce>(Vec2(0, 0), std::nullopt), pushed);  // zero, but a force
  for (int i = 0; i < 600; ++i) w.step(1.0 / 60.0);
  CHECK_FALSE(w.body(hanging).awake);
  CHECK(w.body(pushed).awake);
  w.setSleeping(false);
  CHECK(w.body(hanging).awake);
}

TEST_CASE("bodies: a mass or inertia whose inverse is not finite is refused, naming the input") {
  World w;
  BodyDef d;
  d.shape = makeBox(1.0, 1.0);
  d.mass = 4.9e-324;  // denormal: 1 / m = inf
  CHECK(test::errorOf([&] { w.createBody(d); }) ==
        "mass and moment of inertia must be finite with finite inverses, got 5e-324 kg and 0 kg·m² (from mass 5e-324 "
        "and the shape's size)");
  d.mass.reset();
  d.density = 1e308;
  d.shape = makeBox(10.0, 10.0);  // 1e310 kg overflows
  CHECK(test::errorOf([&] { w.createBody(d); }).ends_with("got inf kg and inf kg·m² (from density 1e+308 and the shape's size)"));
  d.density = 1.0;
  const BodyId b = w.createBody(d);
  CHECK(test::errorOf([&] { w.setMass(b, 1e-320); }).ends_with("(from mass 1e-320 and the shape's size)"));
  CHECK(w.body(b).mass == doctest::Approx(100.0));  // unchanged
  CHECK(w.bodyCount() == 1);
}

TEST_CASE("sleeping: joints made between bodies created asleep, before their first step, leave them asleep") {
  // A welded wall built at rest (Box2D keeps a joint between sleeping bodies asleep): the welds
  // once woke every brick, so a wall created with awake = false was awake from its first step.
  World w;
  BodyDef d;
  d.shape = makeBox(0.5, 0.25);
  d.awake = false;
  d.position = {0.0, 0.125};
  const BodyId low = w.createBody(d);
  d.position = {0.0, 0.375};
  const BodyId high = w.createBody(d);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = makeBox(10.0, 1.0);
  ground.position = {0.0, -0.5};
  const BodyId floor = w.createBody(ground);
  JointDef weld;
  weld.type = JointType::Weld;
  weld.a = low;
  weld.b = high;
  weld.anchor_a = Vec2(0.0, 0.25);
  w.createJoint(weld);
  weld.a = floor;  // a static body keeps nothing awake
  weld.b = low;
  weld.anchor_a = Vec2(0.0, 0.0);
  w.createJoint(weld);
  CHECK_FALSE(w.body(low).awake);
  CHECK_FALSE(w.body(high).awake);
  w.step(1.0 / 60.0);
  CHECK(w.stats().awake_bodies == 0);
  // Pushed, the brick wakes, and with it the one welded to it.
  w.applyImpulse(high, {0.1, 0.0}, w.body(high).center);
  CHECK(w.body(low).awake);
  // Once stepped, a new joint wakes its bodies as before.
  for (int i = 0; i < 120; ++i) w.step(1.0 / 60.0);
  REQUIRE_FALSE(w.body(high).awake);
  JointDef pin;
  pin.type = JointType::Revolute;
  pin.b = high;
  pin.anchor_a = Vec2(0.0, 0.5);
  w.createJoint(pin);
  CHECK(w.body(high).awake);
}

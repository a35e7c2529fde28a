// The energy watch (energy_watch.h, docs/stability.md "Blow-ups caught"): a run whose energy grows
// beyond what its sources can put in is a blow-up incident; sources that do put energy in are not.
#include <doctest/doctest.h>

#include <memory>
#include <string>

#include "rigidlab/forces.h"
#include "rigidlab/world.h"
#include "test_util.h"

using namespace rigidlab;
using rigidlab::test::addBox;
using rigidlab::test::addCircle;

namespace {

// The world's blow-up incidents (those the NaN firewall did not freeze).
int blowUps(const World& w) {
  int n = 0;
  for (const Incident& i : w.incidents()) n += i.frozen ? 0 : 1;
  return n;
}

// A 1 kg ball on a spring of stiffness k to a fixed anchor 0.9 m above it, rest length 1 m.
World springWorld(Integrator integrator, double k, BodyId& ball) {
  WorldDef def;
  def.integrator = integrator;
  World w(def);
  ball = addCircle(w, 0.1, Vec2(0, 1.1));
  w.setName(ball, "ball");
  SpringDef s;
  s.a = ball;
  s.anchor = Vec2(0, 2);
  s.stiffness = k;
  s.rest_length = 1.0;
  w.addSpring(s);
  return w;
}

// The same spring without gravity: the ball swings about the spring's rest length alone.
World weightlessSpring(Integrator integrator, double k) {
  BodyId ball;
  World w = springWorld(integrator, k, ball);
  w.setGravity(Vec2::Zero());
  return w;
}

long stepsUntilBlowUp(World& w, long steps) {
  for (long n = 1; n <= steps; ++n) {
    w.step(1.0 / 60.0);
    if (blowUps(w) > 0) return n;
  }
  return -1;
}

}  // namespace

TEST_CASE("energy watch: a k = 1e7 spring at 1/60 blows up within 8 steps with every explicit integrator, named") {
  for (Integrator integrator : {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::RungeKutta4}) {
    const std::string name(integratorName(integrator));
    CAPTURE(name);
    BodyId ball;
    World w = springWorld(integrator, 1e7, ball);
    const long at = stepsUntilBlowUp(w, 8);
    CHECK(at >= 1);
    REQUIRE(blowUps(w) == 1);
    const Incident& incident = w.incidents().back();
    CHECK(incident.name == "ball");
    CHECK(incident.step == at);
    CHECK_FALSE(incident.frozen);
    CHECK(incident.message().find("blew up at step") != std::string::npos);
    stepsUntilBlowUp(w, 20);  // one incident per world
    CHECK(blowUps(w) == 1);
  }
  // A slow blow-up is one too: explicit Euler on k = 1000 N/m (ωh = 0.53) gains 28 % a step, and
  // is reported in a step where the ball's kinetic energy fell (its energy went into the spring).
  {
    World w = weightlessSpring(Integrator::ExplicitEuler, 1000);
    const long at = stepsUntilBlowUp(w, 600);
    CHECK(at > 8);
    CHECK(blowUps(w) == 1);
  }
  // The slowest: explicit Euler at ωh = 0.1 (k = 36 N/m) gains 1 % a step, 100× in 7.7 s, on a
  // ball that touches nothing (no allowance for what contacts give back: energy_watch.h); the same
  // spring under semi-implicit Euler is stable and not reported.
  {
    World w = weightlessSpring(Integrator::ExplicitEuler, 36);
    const long at = stepsUntilBlowUp(w, 600);
    CHECK(at > 400);
    CHECK(blowUps(w) == 1);
    World stable = weightlessSpring(Integrator::SemiImplicitEuler, 36);
    CHECK(stepsUntilBlowUp(stable, 600) == -1);
  }
  // Implicit Euler is stable at any stiffness: 10 s, nothing reported.
  BodyId ball;
  World w = springWorld(Integrator::ImplicitEuler, 1e7, ball);
  CHECK(stepsUntilBlowUp(w, 600) == -1);
}

TEST_CASE("energy watch: stable runs are not blow-ups, whatever their energy swings") {
  // Semi-implicit Euler at ωh = 1.9 is stable; its energy swings up to 1/(1 − (ωh)²/4) ≈ 10× E0.
  const double omega = 1.9 * 60.0;
  World w = weightlessSpring(Integrator::SemiImplicitEuler, omega * omega);
  CHECK(stepsUntilBlowUp(w, 1200) == -1);
  // A pile of ten boxes settling for 10 s with the defaults.
  World pile;
  addBox(pile, 20, 1, Vec2(0, -0.5), true);
  for (int i = 0; i < 10; ++i) addBox(pile, 1, 1, Vec2(0.1 * (i % 2), 0.5 + i));
  CHECK(stepsUntilBlowUp(pile, 600) == -1);
  // Explicit Euler in free fall gains ½ m (g h)² a step (its first-order error), from the first
  // step, where the ball has not moved yet: bounded, not a blow-up, at any dt.
  for (double h : {0.1, 1.0 / 60.0}) {
    CAPTURE(h);
    WorldDef def;
    def.integrator = Integrator::ExplicitEuler;
    World fall(def);
    addCircle(fall, 0.1, Vec2(0, 0));
    for (int n = 0; n < 100; ++n) fall.step(h);
    CHECK(blowUps(fall) == 0);
  }
}

TEST_CASE("energy watch: what forces, motors, kinematic bodies, moving surfaces and edits put in is not a blow-up") {
  SUBCASE("a constant push: 5e5 J from rest in 10 s") {
    WorldDef def;
    def.gravity = Vec2::Zero();
    World w(def);
    const BodyId b = addCircle(w, 0.5, Vec2(0, 0));
    w.addForce(std::make_unique<ConstantForce>(Vec2(100, 0), std::nullopt), b);
    CHECK(stepsUntilBlowUp(w, 600) == -1);
    CHECK(w.kineticEnergy() > 4e5);
  }
  SUBCASE("a motor spins a wheel up to 200 rad/s: 1e4 J") {
    World w;
    const BodyId wheel = addCircle(w, 1.0, Vec2(0, 0));
    JointDef j;
    j.a = wheel;
    j.anchor_a = Vec2(0, 0);
    j.enable_motor = true;
    j.motor_speed = 200;
    j.max_motor_torque = 1000;
    w.createJoint(j);
    CHECK(stepsUntilBlowUp(w, 120) == -1);
    CHECK(w.kineticEnergy() > 9e3);
  }
  SUBCASE("a kinematic platform lifts a box at 20 m/s for 10 s: 2e3 J of height") {
    World w;
    BodyDef p;
    p.type = BodyType::Kinematic;
    p.shape = makeBox(4, 0.5);
    p.velocity = Vec2(0, 20);
    w.createBody(p);
    const BodyId box = addBox(w, 1, 1, Vec2(0, 0.75));
    CHECK(stepsUntilBlowUp(w, 600) == -1);
    CHECK(w.body(box).center.y() > 150);
  }
  SUBCASE("a conveyor at 100 m/s drags a box to its speed: 5e3 J") {
    World w;
    BodyDef g;
    g.type = BodyType::Static;
    const BodyId ground = w.createBody(g);
    ShapeDef belt;
    belt.shape = makeBox(20000, 1);
    belt.tangent_speed = 100;
    belt.material.friction = 1.0;
    w.createShape(ground, belt);
    const BodyId box = addBox(w, 1, 1, Vec2(0, 1.0));
    CHECK(stepsUntilBlowUp(w, 900) == -1);
    CHECK(w.body(box).velocity.norm() > 90);
  }
  SUBCASE("edits between steps: a script stretches a spring at rest by 1 m, 6.5e3 J") {
    // Semi-implicit Euler at ωh = 1.9 swings the energy up to 10× what the edit put in: within
    // 100× that, far beyond 100× what the world had before the edit.
    BodyId ball;
    World w = springWorld(Integrator::SemiImplicitEuler, 1.9 * 60.0 * 1.9 * 60.0, ball);
    w.setGravity(Vec2::Zero());
    w.setTransform(ball, Vec2(0, 1.0), 0.0);  // at rest length: no energy
    w.step(1.0 / 60.0);
    w.setTransform(ball, Vec2(0, 0.0), 0.0);
    CHECK(stepsUntilBlowUp(w, 600) == -1);
  }
}

// Integrators (docs/design/thesis.md §5, docs/design/accuracy.md §2–3): Table 4.1, energy behaviour on a spring, observed
// orders of convergence, RK4 force evaluation at every stage, time-limited forces.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "test_util.h"

using namespace rigidlab;
using std::numbers::pi;
using doctest::Approx;

namespace {

constexpr double kG = 9.80665;

double freeFallY(Integrator integrator, double dt, double duration) {
  World w;
  w.setIntegrator(integrator);
  const BodyId ball = test::addCircle(w, 0.5, Vec2::Zero());
  const long steps = std::lround(duration / dt);
  for (long i = 0; i < steps; ++i) w.step(dt);
  return w.body(ball).center.y();
}

// Undamped oscillator k = 4π² N/m, m = 1 kg, x0 = 0.1 m (docs/design/accuracy.md §3.3), spring written as a
// user-defined Force. Returns the maximum position error over the 0.1 s sample grid up to
// T = 10.1 s, relative to x0.
double oscillatorError(Integrator integrator, double dt, std::unique_ptr<Force> force) {
  World w;
  w.setGravity(Vec2::Zero());
  w.setIntegrator(integrator);
  const BodyId body = test::addCircle(w, 0.05, Vec2(0.1, 0.0));
  w.addForce(std::move(force), body);
  const double omega = 2.0 * pi;
  const long per_sample = std::lround(0.1 / dt);
  double err = 0.0;
  for (int sample = 1; sample <= 101; ++sample) {
    for (long i = 0; i < per_sample; ++i) w.step(dt);
    const double t = sample * 0.1;
    err = std::max(err, std::abs(w.body(body).center.x() - 0.1 * std::cos(omega * t)) / 0.1);
  }
  return err;
}

// Wraps a force and samples it only once per step (at the first RK4 stage), reusing that value
// for the other three stages: the mistake docs/design/accuracy.md §0.6 warns about.
class SampledOncePerStep final : public Force {
 public:
  explicit SampledOncePerStep(std::unique_ptr<Force> inner) : inner_(std::move(inner)) {}
  void evaluate(const ForceInput& in, ForceOutput& out) override {
    if (calls_++ % 4 == 0) {
      cached_ = ForceOutput{};
      inner_->evaluate(in, cached_);
    }
    out = cached_;
  }
  std::string_view kind() const override { return "stale"; }

 private:
  std::unique_ptr<Force> inner_;
  ForceOutput cached_;
  long calls_ = 0;
};

std::vector<double> sweep(int k_first, int k_last) {
  std::vector<double> dts;
  for (int k = k_first; k <= k_last; ++k) dts.push_back(1.0 / (30.0 * std::pow(2.0, k)));
  return dts;
}

double observedOrder(Integrator integrator, const std::vector<double>& dts, bool stale = false) {
  std::vector<double> errs;
  for (double dt : dts) {
    std::unique_ptr<Force> f = std::make_unique<test::HookeToOrigin>(4.0 * pi * pi);
    if (stale) f = std::make_unique<SampledOncePerStep>(std::move(f));
    errs.push_back(oscillatorError(integrator, dt, std::move(f)));
  }
  return test::fittedOrder(dts, errs);
}

}  // namespace

TEST_CASE("Table 4.1: free fall for 10 s from y0 = 0") {
  // RK4 is exact for constant acceleration; what remains is round-off.
  CHECK(std::abs(freeFallY(Integrator::RungeKutta4, 1.0, 10.0) - (-490.3325)) < 1e-9);
  CHECK(std::abs(freeFallY(Integrator::RungeKutta4, 0.1, 10.0) - (-490.3325)) < 1e-9);
  // Explicit Euler: y_N = −½ g T (T − h), the thesis's "Euler" column.
  CHECK(std::abs(freeFallY(Integrator::ExplicitEuler, 0.1, 10.0) - (-485.429175)) < 1e-6);
  CHECK(std::abs(freeFallY(Integrator::ExplicitEuler, 0.01, 10.0) - (-489.8421675)) < 1e-6);
  CHECK(std::abs(freeFallY(Integrator::ExplicitEuler, 0.001, 10.0) - (-490.28346675)) < 1e-6);
  // Semi-implicit Euler: y_N = −½ g T (T + h) (docs/design/accuracy.md §3.1).
  CHECK(std::abs(freeFallY(Integrator::SemiImplicitEuler, 0.1, 10.0) - (-0.5 * kG * 10.0 * 10.1)) < 1e-9);
}

TEST_CASE("undamped spring: semi-implicit Euler keeps energy in its band for 100 periods") {
  // Band for v0 = 0: E/E0 ∈ [1/(1 + a/2), 1/(1 − a/2)], a = ωh (docs/design/accuracy.md §2).
  const double k = 4.0 * pi * pi, h = 1.0 / 60.0, a = 2.0 * pi * h;
  World w;
  w.setGravity(Vec2::Zero());
  w.setIntegrator(Integrator::SemiImplicitEuler);
  const BodyId body = test::addCircle(w, 0.05, Vec2(0.1, 0.0));
  SpringDef spring;
  spring.a = body;
  spring.anchor = Vec2::Zero();
  spring.stiffness = k;
  spring.rest_length = 0.0;
  w.addSpring(spring);
  const double e0 = w.kineticEnergy() + w.potentialEnergy();
  CHECK(e0 == doctest::Approx(0.5 * k * 0.01).epsilon(1e-14));
  // Semi-implicit Euler conserves Q = v² + ω²x² − h ω² x v exactly (docs/design/accuracy.md §2): no drift.
  const auto invariant = [&] {
    const double x = w.body(body).center.x(), v = w.body(body).velocity.x();
    return v * v + k * x * x - h * k * x * v;
  };
  const double q0 = invariant();
  double lo = 1.0, hi = 1.0, q_err = 0.0;
  for (int i = 1; i <= 6000; ++i) {  // 100 periods of 1 s
    w.step(h);
    const double r = (w.kineticEnergy() + w.potentialEnergy()) / e0;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    q_err = std::max(q_err, std::abs(invariant() / q0 - 1.0));
  }
  CHECK(lo >= 1.0 / (1.0 + a / 2.0) - 1e-9);
  CHECK(hi <= 1.0 / (1.0 - a / 2.0) + 1e-9);
  CHECK(hi - lo > 0.05);  // it does oscillate (the band is 0.1 wide): not a trivially constant value
  CHECK(q_err < 1e-12);
}

TEST_CASE("undamped spring: explicit Euler gains exactly the factor 1 + (ωh)² per step") {
  const double k = 4.0 * pi * pi, h = 1.0 / 60.0, growth = 1.0 + (2.0 * pi * h) * (2.0 * pi * h);
  World w;
  w.setGravity(Vec2::Zero());
  w.setIntegrator(Integrator::ExplicitEuler);
  const BodyId body = test::addCircle(w, 0.05, Vec2(0.1, 0.0));
  SpringDef spring;
  spring.a = body;
  spring.stiffness = k;
  spring.rest_length = 0.0;
  w.addSpring(spring);
  double e = w.kineticEnergy() + w.potentialEnergy();
  for (int i = 0; i < 600; ++i) {
    w.step(h);
    const double next = w.kineticEnergy() + w.potentialEnergy();
    REQUIRE(next / e == doctest::Approx(growth).epsilon(1e-12));
    e = next;
  }
}

TEST_CASE("observed order of convergence on the oscillator, with a user-defined force") {
  const double euler = observedOrder(Integrator::ExplicitEuler, sweep(5, 8));
  const double semi = observedOrder(Integrator::SemiImplicitEuler, sweep(2, 6));
  const double rk4 = observedOrder(Integrator::RungeKutta4, sweep(0, 4));
  MESSAGE("observed orders: euler " << euler << ", semi-implicit " << semi << ", rk4 " << rk4);
  CHECK(euler == doctest::Approx(1.0).epsilon(0.1));
  CHECK(semi == doctest::Approx(1.0).epsilon(0.1));
  CHECK(rk4 == doctest::Approx(4.0).epsilon(0.075));
}

TEST_CASE("a force sampled once per step drops RK4 to first order (the order test catches it)") {
  const double stale = observedOrder(Integrator::RungeKutta4, sweep(2, 6), true);
  MESSAGE("RK4 with a once-per-step force: order " << stale);
  CHECK(stale < 1.5);
}

TEST_CASE("RK4 evaluates state-dependent forces four times per step, constant ones once, gravity never") {
  World w;
  w.setIntegrator(Integrator::RungeKutta4);
  const BodyId a = test::addCircle(w, 0.5, Vec2(0, 10));
  w.step(1.0 / 60.0);
  CHECK(w.stats().force_evaluations == 0);  // gravity is not a Force object
  w.addForce(std::make_unique<ConstantForce>(Vec2(1, 0), std::nullopt), a);
  w.step(1.0 / 60.0);
  CHECK(w.stats().force_evaluations == 1);
  DamperDef damper;
  damper.body = a;
  damper.coefficient = 0.1;
  w.addDamper(damper);
  w.step(1.0 / 60.0);
  CHECK(w.stats().force_evaluations == 1 + 4);
  w.setIntegrator(Integrator::SemiImplicitEuler);
  w.step(1.0 / 60.0);
  CHECK(w.stats().force_evaluations == 2);
}

TEST_CASE("damper: RK4 follows v(t) = v0 e^(−c t / m)") {
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId body = test::addCircle(w, 0.5, Vec2::Zero(), 2.0);
  w.setVelocity(body, Vec2(3.0, 0.0));
  DamperDef damper;
  damper.body = body;
  damper.coefficient = 4.0;  // c/m = 2 /s
  w.addDamper(damper);
  for (int i = 0; i < 100; ++i) w.step(0.01);
  CHECK(w.body(body).velocity.x() == doctest::Approx(3.0 * std::exp(-2.0)).epsilon(1e-9));
  // x(t) = v0 m/c (1 − e^(−ct/m))
  CHECK(w.body(body).center.x() == doctest::Approx(1.5 * (1.0 - std::exp(-2.0))).epsilon(1e-9));
}

TEST_CASE("time-limited force: acts for exactly its duration, then is removed at the end of the step") {
  // F = 10 N on 2 kg for 1.05 s; at t = 2 s: x = 7.74375 m, v = 5.25 m/s (docs/design/accuracy.md §3.7).
  // dt = 0.1 puts the cut-off inside step 11, which the integrator splits at t = 1.05.
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId body = test::addCircle(w, 0.5, Vec2::Zero(), 2.0);
  const ForceId push = w.addForce(std::make_unique<ConstantForce>(Vec2(10, 0), std::nullopt), body, {}, 1.05);
  for (int i = 0; i < 10; ++i) w.step(0.1);
  CHECK(w.isValid(push));
  CHECK(w.forceTimeLeft(push) == doctest::Approx(0.05));
  w.step(0.1);
  CHECK_FALSE(w.isValid(push));
  for (int i = 0; i < 9; ++i) w.step(0.1);
  CHECK(w.time() == doctest::Approx(2.0).epsilon(1e-15));
  CHECK(std::abs(w.body(body).center.x() - 7.74375) < 1e-12);
  CHECK(std::abs(w.body(body).velocity.x() - 5.25) < 1e-12);
}

TEST_CASE("two-body spring: momentum conserved by every integrator, RK4 matches the closed form") {
  for (Integrator integrator : {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::RungeKutta4}) {
    CAPTURE(integratorName(integrator));
    World w;
    w.setGravity(Vec2::Zero());
    w.setIntegrator(integrator);
    const BodyId a = test::addCircle(w, 0.1, Vec2(0, 0), 1.0);
    const BodyId b = test::addCircle(w, 0.1, Vec2(1.2, 0), 3.0);
    w.setVelocity(b, Vec2(0, 0.5));  // a transverse velocity exercises the direction term
    SpringDef s;
    s.a = a;
    s.b = b;
    s.stiffness = 100.0;
    s.rest_length = 1.0;
    w.addSpring(s);
    for (int i = 0; i < 600; ++i) w.step(1.0 / 600.0);
    const Vec2 p = 1.0 * w.body(a).velocity + 3.0 * w.body(b).velocity;
    CHECK(std::abs(p.x()) < 1e-12);
    CHECK(std::abs(p.y() - 1.5) < 1e-12);
  }
  // Along the axis only: s(t) = L0 + 0.2 cos ωt, ω = √(k/μ), μ = 0.75 kg (docs/design/accuracy.md §3.5).
  World w;
  w.setGravity(Vec2::Zero());
  const BodyId a = test::addCircle(w, 0.1, Vec2(0, 0), 1.0);
  const BodyId b = test::addCircle(w, 0.1, Vec2(1.2, 0), 3.0);
  SpringDef s;
  s.a = a;
  s.b = b;
  s.stiffness = 100.0;
  s.rest_length = 1.0;
  w.addSpring(s);
  for (int i = 0; i < 240; ++i) w.step(1.0 / 240.0);
  CHECK(w.body(a).center.x() == doctest::Approx(0.0714139893).epsilon(1e-6));
  CHECK(w.body(b).center.x() == doctest::Approx(1.1761953369).epsilon(1e-7));
}

TEST_CASE("implicit Euler: a 1e6 N/m spring at 60 Hz stays finite and never gains energy (docs/design/accuracy.md S1)") {
  // ω h = 16.7: semi-implicit Euler overflows after ~63 steps, RK4 after ~45.
  const auto run = [](Integrator integrator) {
    World w;
    w.setGravity(Vec2::Zero());
    w.setIntegrator(integrator);
    const BodyId body = test::addCircle(w, 0.05, Vec2(0.01, 0.0));
    SpringDef s;
    s.a = body;
    s.stiffness = 1e6;
    s.rest_length = 0.0;
    w.addSpring(s);
    double e = w.kineticEnergy() + w.potentialEnergy();
    bool increased = false;
    for (int i = 0; i < 600; ++i) {
      w.step(1.0 / 60.0);
      const double next = w.kineticEnergy() + w.potentialEnergy();
      increased |= next > e * (1 + 1e-9) + 1e-250;  // (the energy decays to subnormal numbers)
      e = next;
    }
    return std::pair{w.incidents().empty() && isFinite(w.body(body).center), !increased};
  };
  const auto [finite, monotone] = run(Integrator::ImplicitEuler);
  CHECK(finite);
  CHECK(monotone);
  CHECK_FALSE(run(Integrator::SemiImplicitEuler).first);  // the firewall froze the overflowing body
  CHECK_FALSE(run(Integrator::RungeKutta4).first);
}

TEST_CASE("implicit Euler: one step on an undamped spring matches the closed form v₁ = (v₀ − hω²x₀)/(1 + h²ω²)") {
  World w;
  w.setGravity(Vec2::Zero());
  w.setIntegrator(Integrator::ImplicitEuler);
  const BodyId body = test::addCircle(w, 0.05, Vec2(0.1, 0.0), 2.0);
  w.setVelocity(body, Vec2(0.3, 0.0));
  SpringDef s;
  s.a = body;
  s.stiffness = 800.0;  // ω² = 400
  s.rest_length = 0.0;
  w.addSpring(s);
  const double h = 0.05, w2 = 400.0;
  w.step(h);
  const double v1 = (0.3 - h * w2 * 0.1) / (1 + h * h * w2);
  CHECK(w.body(body).velocity.x() == Approx(v1).epsilon(1e-12));
  CHECK(w.body(body).center.x() == Approx(0.1 + h * v1).epsilon(1e-12));
}

TEST_CASE("dampers never flip the sign of a velocity, whatever c·h/m is (docs/design/accuracy.md S5)") {
  for (Integrator integrator : {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::ImplicitEuler,
                                Integrator::RungeKutta4}) {
    CAPTURE(integratorName(integrator));
    World w;
    w.setGravity(Vec2::Zero());
    w.setIntegrator(integrator);
    const BodyId body = test::addCircle(w, 0.5, Vec2::Zero(), 1.0);
    w.setVelocity(body, Vec2(2.0, 0.0));
    DamperDef d;
    d.body = body;
    d.coefficient = 150.0;  // c h / m = 2.5 at 60 Hz: explicit damping would multiply v by −1.5
    w.addDamper(d);
    double previous = 2.0;
    for (int i = 0; i < 30; ++i) {
      w.step(1.0 / 60.0);
      const double v = w.body(body).velocity.x();
      REQUIRE(v >= 0.0);
      REQUIRE(v <= previous);
      previous = v;
    }
    if (integrator != Integrator::RungeKutta4) CHECK(w.body(body).velocity.x() == Approx(2.0 / std::pow(3.5, 30)));
  }
}

TEST_CASE("a critically damped spring does not destabilise semi-implicit Euler (docs/design/accuracy.md S6)") {
  // k = 2916 N/m, c = 108 N·s/m on 1 kg (ζ = 1, ωh = 0.9): with explicit damping the spectral
  // radius would be 1.25 and the oscillator would blow up.
  World w;
  w.setGravity(Vec2::Zero());
  w.setIntegrator(Integrator::SemiImplicitEuler);
  const BodyId body = test::addCircle(w, 0.05, Vec2(0.1, 0.0));
  SpringDef s;
  s.a = body;
  s.stiffness = 2916.0;
  s.rest_length = 0.0;
  s.damping = 108.0;
  w.addSpring(s);
  double e = w.kineticEnergy() + w.potentialEnergy();
  for (int i = 0; i < 600; ++i) {
    w.step(1.0 / 60.0);
    const double next = w.kineticEnergy() + w.potentialEnergy();
    REQUIRE(next <= e * (1 + 1e-12));
    e = next;
  }
  CHECK(std::abs(w.body(body).center.x()) < 1e-6);
}

TEST_CASE("implicit Euler is first order on the oscillator, and couples two-body springs") {
  CHECK(observedOrder(Integrator::ImplicitEuler, sweep(4, 7)) == doctest::Approx(1.0).epsilon(0.1));
  // Two bodies on a stiff spring (solved together): momentum is conserved.
  World w;
  w.setGravity(Vec2::Zero());
  w.setIntegrator(Integrator::ImplicitEuler);
  const BodyId a = test::addCircle(w, 0.1, Vec2(0, 0), 1.0);
  const BodyId b = test::addCircle(w, 0.1, Vec2(1.2, 0), 3.0);
  w.setVelocity(b, Vec2(0, 0.5));
  SpringDef s;
  s.a = a;
  s.b = b;
  s.stiffness = 1e5;
  s.rest_length = 1.0;
  s.damping = 5.0;
  w.addSpring(s);
  for (int i = 0; i < 300; ++i) w.step(1.0 / 60.0);
  const Vec2 p = 1.0 * w.body(a).velocity + 3.0 * w.body(b).velocity;
  CHECK(std::abs(p.x()) < 1e-12);
  CHECK(p.y() == Approx(1.5).epsilon(1e-12));
  CHECK((w.body(b).center - w.body(a).center).norm() == Approx(1.0).epsilon(1e-2));
}

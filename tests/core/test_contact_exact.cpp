// The exact solve of small contact islands with extreme mass ratios (contact_exact.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "contact_exact.h"
#include "test_util.h"

using namespace rigidlab;

namespace {

constexpr double kDt = 1.0 / 60.0;

// A 1×1 m box of `mass` kg with its centre at height y.
BodyId heavyBox(World& w, double mass, double y) {
  BodyDef d;
  d.shape = makeBox(1, 1);
  d.position = {0, y};
  d.mass = mass;
  return w.createBody(d);
}

struct StackRun {
  double worst_sink = 0.0;    // largest drop of any box below its resting height over the run [m]
  double final_speed = 0.0;   // largest speed at the end [m/s]
  double worst_tilt = 0.0;    // largest |angle| [rad]
};

// Boxes of the given masses stacked from the ground up, 5 s at 1/60 with the default settings.
StackRun stack(const std::vector<double>& masses) {
  World w;
  test::addBox(w, 10, 1, {0, -0.5}, true);
  std::vector<BodyId> boxes;
  for (size_t i = 0; i < masses.size(); ++i) boxes.push_back(heavyBox(w, masses[i], 0.5 + static_cast<double>(i)));
  StackRun r;
  for (int n = 0; n < 300; ++n) {
    w.step(kDt);
    for (size_t i = 0; i < boxes.size(); ++i) {
      const Body& b = w.body(boxes[i]);
      r.worst_sink = std::max(r.worst_sink, 0.5 + static_cast<double>(i) - b.position().y());
      r.worst_tilt = std::max(r.worst_tilt, std::abs(b.angle));
    }
  }
  for (const BodyId id : boxes) r.final_speed = std::max(r.final_speed, w.body(id).velocity.norm());
  return r;
}

}  // namespace

TEST_CASE("a 1e6 kg box on a 1 kg box on the ground sinks at most 1 cm in 5 s") {
  const StackRun r = stack({1.0, 1e6});
  CHECK(r.worst_sink <= 0.01);
  CHECK(r.final_speed < 1e-3);
  CHECK(r.worst_tilt < 1e-3);
}

TEST_CASE("a 1 kg box on a 1e6 kg box, and a 1e6 kg on 1e3 kg on 1 kg stack, hold") {
  SUBCASE("light on heavy") {
    const StackRun r = stack({1e6, 1.0});
    CHECK(r.worst_sink <= 0.01);
    CHECK(r.final_speed < 1e-3);
  }
  SUBCASE("three boxes, 1 kg under 1e3 kg under 1e6 kg") {
    const StackRun r = stack({1.0, 1e3, 1e6});
    CHECK(r.worst_sink <= 0.01);
    CHECK(r.final_speed < 1e-3);
    CHECK(r.worst_tilt < 1e-3);
  }
}

TEST_CASE("an overlap under a 1e6 kg box is driven out, the heavy box lifted") {
  // Spawned 3 cm into the 1 kg box: the position solve of the island moves the heavy box up; the
  // Gauss–Seidel passes would move the light box (a millionth of each correction for the heavy one)
  // into the ground, which pushes it back, and the overlap would stay.
  World w;
  w.setSleeping(false);
  test::addBox(w, 10, 1, {0, -0.5}, true);
  const BodyId light = heavyBox(w, 1.0, 0.5);
  const BodyId top = heavyBox(w, 1e6, 1.5 - 0.03);
  for (int n = 0; n < 60; ++n) w.step(kDt);
  const double overlap = 1.0 - (w.body(top).position().y() - w.body(light).position().y());
  CHECK(overlap <= 0.006);                              // at most the allowed 5 mm and round-off
  CHECK(w.body(light).position().y() >= 0.5 - 0.006);   // the light box is not pressed into the ground
  CHECK(std::abs(w.body(top).velocity.y()) < 1e-3);     // lifted by position, not launched
}

TEST_CASE("the boxed complementarity solve meets its conditions") {
  // w = A x + q with x₀ ∈ [0, ∞) (a normal row) and x₁ ∈ [−1, 1] (a friction row): the unconstrained
  // solution x = −A⁻¹ q = (3, −2.5) puts x₁ beyond its bound, so x₁ = −1 and x₀ = (−q₀ + 1)/2 = 2.25,
  // where w₁ = 2.25 + 3·(−1) + 4.5 = 3.75 ≥ 0 holds at the lower bound.
  ContactExactScratch s;
  Eigen::MatrixXd a(2, 2);
  a << 2, 1, 1, 3;
  Eigen::VectorXd q(2), lo(2), hi(2), x = Eigen::VectorXd::Zero(2);
  q << -3.5, 4.5;
  lo << 0, -1;
  hi << std::numeric_limits<double>::infinity(), 1;
  REQUIRE(solveBoxedLcp(s, a, q, lo, hi, x));
  CHECK(x(0) == doctest::Approx(2.25));
  CHECK(x(1) == doctest::Approx(-1.0));
  const Eigen::VectorXd w = a * x + q;
  CHECK(std::abs(w(0)) < 1e-12);  // free: w = 0
  CHECK(w(1) >= 0.0);             // at the lower bound: w ≥ 0
  // A row pushed apart (q > 0) stays at 0.
  q << 1.0, 0.0;
  x.setConstant(5.0);
  REQUIRE(solveBoxedLcp(s, a, q, lo, hi, x));
  CHECK(x(0) == 0.0);
  CHECK(x(1) == doctest::Approx(0.0));
}

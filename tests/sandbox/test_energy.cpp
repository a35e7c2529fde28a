// The energy plot's history: the split of the kinetic energy, resets, the window.
#include <doctest/doctest.h>

#include "energy_plot.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;

TEST_CASE("energy history: linear + rotational is the world's kinetic energy, total includes potential") {
  World world;
  BodyDef d;
  d.shape = makeBox(1, 2);
  d.position = Vec2(0, 3);
  d.velocity = Vec2(2, -1);
  d.angular_velocity = 4;
  world.createBody(d);
  d.type = BodyType::Static;
  d.position = Vec2(0, -5);
  d.velocity = Vec2::Zero();  // a static body cannot move
  d.angular_velocity = 0.0;
  world.createBody(d);
  EnergyHistory h;
  h.sample(world);
  REQUIRE(h.samples().size() == 1);
  const EnergySample& s = h.samples().back();
  CHECK(s.linear == doctest::Approx(0.5 * 2.0 * 5.0));
  CHECK(s.kinetic() == doctest::Approx(world.kineticEnergy()));
  CHECK(s.total() == doctest::Approx(world.kineticEnergy() + world.potentialEnergy()));
}

TEST_CASE("energy history: keeps the window, restarts when time goes back, replaces a paused sample") {
  EnergyHistory h(2.0);
  for (int i = 0; i <= 300; ++i) h.add({i / 60.0, 1.0, 0.0, 2.0});
  CHECK(h.samples().front().time >= 5.0 - 2.0 - 1e-9);
  CHECK(h.samples().back().time == doctest::Approx(5.0));
  CHECK(h.totalDrift() == 0.0);
  const size_t n = h.samples().size();
  h.add({5.0, 3.0, 0.0, 2.0});  // same time (paused): replaced, not added
  CHECK(h.samples().size() == n);
  CHECK(h.totalDrift() == doctest::Approx(2.0));
  h.add({0.0, 1.0, 0.0, 0.0});  // reset
  CHECK(h.samples().size() == 1);
}

// Golden trajectories (engine/app/golden_trajectory.cpp): the file reads back bit for bit, and a
// comparison names the first difference: a value, a body that appeared or vanished, the run's
// length.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "golden_trajectory.h"

using namespace rigidlab::app;

namespace {

Trajectory twoBodies() {
  Trajectory t{"scene.lua", 0.01, 10, 5, {}};
  for (long step : {0L, 5L, 10L}) {
    const double s = static_cast<double>(step);
    t.samples.push_back({step, s * 0.01,
                         {{1, "floor", 0, 0, 0, 0, 0, 0}, {2, "ball", 0.1 * s, 1.0 / 3.0, -0.0, 1, -9.8 * s, 0}}});
  }
  return t;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("golden: a trajectory reads back bit for bit, names with spaces, tabs and backslashes too") {
  Trajectory t = twoBodies();
  t.samples[1].bodies[1].name = "a b\\c\td ";
  t.samples[2].bodies[0].name = "";
  t.samples[2].bodies[1].x = std::nan("");
  const Trajectory back = parseTrajectory(formatTrajectory(t), "g.txt");
  CHECK(back.scene == "scene.lua");
  CHECK(back.dt == 0.01);
  CHECK(back.steps == 10);
  CHECK(back.every == 5);
  REQUIRE(back.samples.size() == 3);
  CHECK(back.samples[1].bodies[1].name == "a b\\c\td ");
  CHECK(back.samples[2].bodies[0].name == "");
  CHECK(sameBits(back.samples[0].bodies[1].y, 1.0 / 3.0));
  CHECK(std::signbit(back.samples[0].bodies[1].angle));
  CHECK(std::isnan(back.samples[2].bodies[1].x));
  CHECK_FALSE(compareTrajectories(t, back, 0.0));
}

TEST_CASE("golden: the first difference names the body, the step, the value and by how much") {
  const Trajectory expected = twoBodies();
  Trajectory actual = expected;
  actual.samples[1].bodies[1].vy += 1e-3;
  actual.samples[2].bodies[0].x += 1;  // later: not the first
  const auto message = compareTrajectories(expected, actual, 0.0);
  REQUIRE(message);
  CHECK(*message == "body 2 \"ball\" diverged first at step 5 (t = 0.05 s): vy is -48.999, expected -49 (off by 0.001) "
                    "(tolerance 0: bit for bit)");
  CHECK_FALSE(compareTrajectories(expected, actual, 1.5));
  // Bit for bit: -0 is not 0, though within any tolerance it is.
  actual = expected;
  actual.samples[0].bodies[1].angle = 0.0;
  CHECK(compareTrajectories(expected, actual, 0.0));
  CHECK_FALSE(compareTrajectories(expected, actual, 1e-300));
}

TEST_CASE("golden: bodies that appear or vanish, and a run of another length, are differences") {
  const Trajectory expected = twoBodies();
  Trajectory actual = expected;
  actual.samples[2].bodies.push_back({3, "box", 0, 0, 0, 0, 0, 0});
  CHECK(*compareTrajectories(expected, actual, 0.0) ==
        "body 3 \"box\" is in this run but not in the golden trajectory at step 10 (t = 0.1 s) (tolerance 0: bit for bit)");
  actual = expected;
  actual.samples[1].bodies.erase(actual.samples[1].bodies.begin());
  actual.samples[1].bodies[0].x += 1;
  CHECK(*compareTrajectories(expected, actual, 0.0) ==
        "body 1 \"floor\" is in the golden trajectory but not in this run at step 5 (t = 0.05 s) (tolerance 0: bit for "
        "bit); 1 more bodies differ at that step");
  actual = expected;
  actual.steps = 20;
  CHECK(*compareTrajectories(expected, actual, 0.0) ==
        "the golden trajectory was recorded with dt 0.01, 10 steps, a sample every 5; this run has dt 0.01, 20 steps, a "
        "sample every 5");
}

TEST_CASE("golden: a damaged file is refused with its line") {
  CHECK_THROWS_WITH(parseTrajectory("scene s.lua\ndt 0.01\nsteps ten\n", "g.txt"),
                    "g.txt:3: steps must be a whole number >= 0, got 'ten'");
  CHECK_THROWS_WITH(parseTrajectory("scene s.lua\ndt 0.01\nsteps 1\nevery 1\n0 1 0 0 0 0 0 0\n", "g.txt"),
                    "g.txt:5: a body line before the first 'sample' line");
  CHECK_THROWS_WITH(parseTrajectory("scene s.lua\ndt 0.01\nsteps 1\nevery 1\nsample 0 0\n0 1 0 0 0 0 0\n", "g.txt"),
                    "g.txt:6: expected angular velocity");
  CHECK_THROWS_WITH(parseTrajectory("# only a comment\n", "g.txt"), "g.txt:1: ends before its 'scene' line");
}

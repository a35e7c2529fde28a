// Frame-rate independence (docs/design/accuracy.md §4 S11): the sandbox's default scene driven through the
// sandbox's own fixed-step accumulator (FrameClock::plan, engine/sandbox/src/frame_clock.cpp)
// reaches the same simulated time with the same number of steps and a bit-identical state whether
// the frames take 1/30, 1/60 or 1/144 s; the variable-step loop does not (the control that shows
// the comparison can see a difference).
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "frame_clock.h"
#include "rigidlab/lua/scene.h"

namespace {

using rigidlab::lua::Scene;
using rigidlab::sandbox::FrameClock;
using rigidlab::sandbox::LoopMode;
using rigidlab::sandbox::LoopSettings;

// FNV-1a over the bits of every body's state.
uint64_t stateHash(const rigidlab::World& w) {
  uint64_t h = 1469598103934665603ull;
  const auto add = [&](double x) {
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    for (int i = 0; i < 8; ++i) h = (h ^ ((bits >> (8 * i)) & 0xFF)) * 1099511628211ull;
  };
  for (const auto id : w.bodyIds()) {
    const rigidlab::Body& b = w.body(id);
    add(b.center.x()), add(b.center.y()), add(b.angle), add(b.velocity.x()), add(b.velocity.y()), add(b.angular_velocity);
  }
  return h;
}

struct Outcome {
  long steps = 0;
  double time = 0;
  uint64_t hash = 0;
};

// Runs `frames` frames of `frame_seconds` real time each through the loop, as the sandbox does.
Outcome drive(double frame_seconds, long frames, LoopMode mode) {
  auto scene = Scene::loadFile(rigidlab::lua::scriptsDirectory() / "scenes" / "playground.lua");
  FrameClock clock;
  LoopSettings settings;
  settings.mode = mode;
  settings.frame_cap_hz = 0;
  Outcome o;
  for (long f = 0; f < frames; ++f) {
    const auto plan = clock.plan(frame_seconds, scene->settings().dt, settings);
    for (int i = 0; i < plan.steps; ++i) {
      scene->step(plan.step_dt);
      ++o.steps;
    }
  }
  o.time = scene->world().time();
  o.hash = stateHash(scene->world());
  return o;
}

}  // namespace

TEST_CASE("frame rate: 1/30, 1/60 and 1/144 s frames give the same steps and bit-identical states") {
  // 10 s of real time at each frame rate; the scene's dt is 1/60 s.
  const Outcome a = drive(1.0 / 60.0, 600, LoopMode::Fixed);
  const Outcome b = drive(1.0 / 30.0, 300, LoopMode::Fixed);
  const Outcome c = drive(1.0 / 144.0, 1440, LoopMode::Fixed);
  CHECK(a.steps == 600);
  CHECK(b.steps == 600);
  CHECK(c.steps == 600);  // the accumulator loses no step to rounding over 1440 frames
  CHECK(a.time == b.time);
  CHECK(a.time == c.time);
  CHECK(a.hash == b.hash);
  CHECK(a.hash == c.hash);
}

TEST_CASE("frame rate: the variable-step loop depends on the frame rate (control)") {
  const Outcome a = drive(1.0 / 60.0, 600, LoopMode::Variable);
  const Outcome b = drive(1.0 / 30.0, 300, LoopMode::Variable);
  CHECK(a.time == doctest::Approx(10.0));
  CHECK(b.time == doctest::Approx(10.0));
  CHECK(a.hash != b.hash);
}

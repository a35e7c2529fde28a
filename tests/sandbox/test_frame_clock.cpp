// The loop clock: fixed step with accumulator and catch-up cap, variable step, real-time ratio.
#include <doctest/doctest.h>

#include "frame_clock.h"

using namespace rigidlab::sandbox;

TEST_CASE("frame clock: fixed step runs whole steps and carries the rest as alpha") {
  FrameClock clock;
  LoopSettings s;
  const double dt = 1.0 / 60.0;
  // 144 Hz frames: over 1 s, exactly 60 steps, whatever the frame rate.
  int steps = 0;
  for (int i = 0; i < 144; ++i) {
    const FramePlan p = clock.plan(1.0 / 144.0, dt, s);
    CHECK(p.step_dt == dt);
    CHECK(p.alpha >= 0.0);
    CHECK(p.alpha < 1.0);
    CHECK_FALSE(p.behind);
    steps += p.steps;
  }
  CHECK(steps == 60);
  // Frames of exactly dt: one step each, nothing left over (no rounding drift into an extra step).
  clock.reset();
  for (int i = 0; i < 1000; ++i) {
    const FramePlan p = clock.plan(dt, dt, s);
    REQUIRE(p.steps == 1);
  }
  CHECK(clock.accumulator() < 1e-9);
}

TEST_CASE("frame clock: a slow frame cannot spiral: steps are capped and time is dropped") {
  FrameClock clock;
  LoopSettings s;
  s.max_steps_per_frame = 4;
  const double dt = 1.0 / 60.0;
  const FramePlan p = clock.plan(0.2, dt, s);  // 12 steps owed
  CHECK(p.steps == 4);
  CHECK(p.behind);
  CHECK(clock.accumulator() < dt);  // the rest was dropped, not carried into the next frame
  const FramePlan hang = clock.plan(30.0, dt, s);  // a 30 s stall (debugger, suspend)
  CHECK(hang.steps == 4);
  CHECK(hang.behind);
  const FramePlan next = clock.plan(dt, dt, s);
  CHECK(next.steps == 1);
  CHECK_FALSE(next.behind);
}

TEST_CASE("frame clock: variable step takes the frame time, capped") {
  FrameClock clock;
  LoopSettings s;
  s.mode = LoopMode::Variable;
  FramePlan p = clock.plan(0.01, 1.0 / 60.0, s);
  CHECK(p.steps == 1);
  CHECK(p.step_dt == doctest::Approx(0.01));
  CHECK(p.alpha == 1.0);
  CHECK_FALSE(p.behind);
  p = clock.plan(0.1, 1.0 / 60.0, s);
  CHECK(p.step_dt == doctest::Approx(s.max_variable_dt));
  CHECK(p.behind);
  p = clock.plan(0.0, 1.0 / 60.0, s);
  CHECK(p.steps == 0);
}

TEST_CASE("frame clock: time scale and the real-time meter") {
  FrameClock clock;
  LoopSettings s;
  s.time_scale = 0.5;
  int steps = 0;
  for (int i = 0; i < 120; ++i) steps += clock.plan(1.0 / 60.0, 1.0 / 60.0, s).steps;
  CHECK(steps == 60);  // half speed

  RealTimeMeter m;
  for (int i = 0; i < 120; ++i) m.add(1.0 / 60.0, 1.0 / 120.0);
  CHECK(m.ratio() == doctest::Approx(0.5));
  m.reset();
  CHECK(m.ratio() == 1.0);
}

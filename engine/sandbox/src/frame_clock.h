// How many world steps a frame runs, and how far between the last two states to draw it
// (docs/design/thesis.md §3 "Game loop"; Glenn Fiedler, "Fix Your Timestep!", gafferongames.com 2004).
//
// Fixed step (the default): real time accumulates and is consumed in steps of exactly dt, so the
// simulation's results do not depend on the frame rate. What is left over (less than one step) is
// drawn by interpolating between the previous and the current state with alpha = leftover / dt.
// A frame longer than `max_frame_time` counts as that long, and at most `max_steps_per_frame` steps
// run per frame; time beyond that is dropped, so a slow frame cannot start a spiral of ever longer
// frames. Dropping time is what "slower than real time" means, and the sandbox shows it.
//
// Variable step (the thesis's default): one step per frame of the frame's real duration, capped at
// `max_variable_dt` (a long frame would otherwise take one huge, inaccurate step). With a frame cap
// the step is nearly constant on a fast machine; results depend on the machine.
#pragma once

#include <deque>

namespace rigidlab::sandbox {

enum class LoopMode { Fixed, Variable };

struct LoopSettings {
  LoopMode mode = LoopMode::Fixed;
  int max_steps_per_frame = 8;     // fixed step: catch-up cap, ≥ 1
  double max_frame_time = 0.25;    // [s] a frame counts as at most this long
  double max_variable_dt = 1.0 / 30.0;  // [s] variable step: largest step
  double frame_cap_hz = 60.0;      // frames per second at most (sleep); 0 = no cap
  double time_scale = 1.0;         // simulated seconds per real second (slow motion < 1)
};

struct FramePlan {
  int steps = 0;         // world steps to run this frame
  double step_dt = 0.0;  // [s] length of each
  double alpha = 1.0;    // draw at previous + alpha (current − previous), in [0, 1]
  bool behind = false;   // simulated time was dropped: slower than real time
};

class FrameClock {
 public:
  // Plans one frame that took `frame_seconds` of real time, for a scene of step `dt`.
  FramePlan plan(double frame_seconds, double dt, const LoopSettings& settings);
  // Forget leftover time (after a pause, a reload or a mode change).
  void reset() { accumulator_ = 0.0; }
  double accumulator() const { return accumulator_; }

 private:
  double accumulator_ = 0.0;  // [s] simulated time not yet stepped
};

// Ratio of simulated to real time over the last second or so (1 = real time), for the statistics.
class RealTimeMeter {
 public:
  void add(double real_seconds, double simulated_seconds);
  double ratio() const;
  void reset() { samples_.clear(); real_ = simulated_ = 0.0; }

 private:
  struct Sample {
    double real, simulated;
  };
  std::deque<Sample> samples_;
  double real_ = 0.0, simulated_ = 0.0;
};

}  // namespace rigidlab::sandbox

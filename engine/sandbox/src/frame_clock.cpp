// Fixed-step accumulator and variable step (frame_clock.h).
#include "frame_clock.h"

#include <algorithm>
#include <cmath>

namespace rigidlab::sandbox {

FramePlan FrameClock::plan(double frame_seconds, double dt, const LoopSettings& s) {
  FramePlan plan;
  if (!(frame_seconds > 0.0) || !std::isfinite(frame_seconds) || !(dt > 0.0)) return plan;
  const double clamped = std::min(frame_seconds, s.max_frame_time);
  plan.behind = clamped < frame_seconds;
  const double simulated = clamped * std::max(s.time_scale, 0.0);

  if (s.mode == LoopMode::Variable) {
    accumulator_ = 0.0;
    plan.steps = simulated > 0.0 ? 1 : 0;
    plan.step_dt = std::min(simulated, s.max_variable_dt);
    plan.behind = plan.behind || simulated > s.max_variable_dt;
    plan.alpha = 1.0;
    return plan;
  }

  accumulator_ += simulated;
  plan.step_dt = dt;
  // The small tolerance keeps a frame of exactly dt from leaving dt·(1 − ε) behind through rounding.
  const double tolerance = 1e-9 * dt;
  const int wanted = static_cast<int>(std::floor((accumulator_ + tolerance) / dt));
  const int cap = std::max(s.max_steps_per_frame, 1);
  plan.steps = std::min(wanted, cap);
  accumulator_ = std::max(accumulator_ - plan.steps * dt, 0.0);
  if (wanted > cap) {
    plan.behind = true;
    accumulator_ = std::fmod(accumulator_, dt);  // drop the whole steps we could not afford
  }
  plan.alpha = std::clamp(accumulator_ / dt, 0.0, 1.0);
  return plan;
}

void RealTimeMeter::add(double real_seconds, double simulated_seconds) {
  constexpr double kWindow = 1.0;  // [s] of real time averaged
  samples_.push_back({real_seconds, simulated_seconds});
  real_ += real_seconds;
  simulated_ += simulated_seconds;
  while (samples_.size() > 1 && real_ - samples_.front().real > kWindow) {
    real_ -= samples_.front().real;
    simulated_ -= samples_.front().simulated;
    samples_.pop_front();
  }
}

double RealTimeMeter::ratio() const { return real_ > 0.0 ? simulated_ / real_ : 1.0; }

}  // namespace rigidlab::sandbox

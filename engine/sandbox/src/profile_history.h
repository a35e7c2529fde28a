// The Profile panel's data (as Box2D v3's samples show a step's profile): each step stage's time
// over the last few seconds of wall time, for its average, its maximum and a graph of the step.
#pragma once

#include <array>
#include <deque>
#include <vector>

#include "rigidlab/world.h"

namespace rigidlab::sandbox {

// The stages of StepStats in the order the panel lists them; "step" is their sum (total_ms).
inline constexpr std::array<const char*, 8> kProfileStages = {
    "integrate", "  of it forces", "broad phase", "narrow phase", "solve", "correct positions", "finish", "step"};

class ProfileHistory {
 public:
  explicit ProfileHistory(double window_seconds = 2.0) : window_(window_seconds) {}

  // A step's stage times, taken at `now` [s of wall time, any origin]; steps older than the window
  // before `now` are dropped.
  void add(const StepStats& stats, double now);
  void clear() { steps_.clear(); }

  struct Figures {
    double last = 0.0, average = 0.0, maximum = 0.0;  // [ms]
  };
  // Stage `k` (an index of kProfileStages) over the steps in the window; zeros without steps.
  Figures stage(size_t k) const;
  // The step's time [ms] of each step in the window, oldest first (the graph).
  std::vector<float> stepTimes() const;
  size_t steps() const { return steps_.size(); }
  double window() const { return window_; }

 private:
  struct Step {
    double at;
    std::array<double, kProfileStages.size()> ms;
  };
  double window_;
  std::deque<Step> steps_;
};

}  // namespace rigidlab::sandbox

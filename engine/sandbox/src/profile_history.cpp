// Step stage times over a window of wall time (profile_history.h).
#include "profile_history.h"

#include <algorithm>

namespace rigidlab::sandbox {

void ProfileHistory::add(const StepStats& st, double now) {
  steps_.push_back({now, {st.integrate_ms, st.forces_ms, st.broad_phase_ms, st.narrow_phase_ms, st.solve_ms,
                          st.correct_ms, st.finish_ms, st.total_ms()}});
  while (!steps_.empty() && steps_.front().at < now - window_) steps_.pop_front();
}

ProfileHistory::Figures ProfileHistory::stage(size_t k) const {
  Figures f;
  if (steps_.empty() || k >= kProfileStages.size()) return f;
  for (const Step& s : steps_) {
    f.average += s.ms[k];
    f.maximum = std::max(f.maximum, s.ms[k]);
  }
  f.average /= static_cast<double>(steps_.size());
  f.last = steps_.back().ms[k];
  return f;
}

std::vector<float> ProfileHistory::stepTimes() const {
  std::vector<float> out;
  out.reserve(steps_.size());
  for (const Step& s : steps_) out.push_back(static_cast<float>(s.ms.back()));
  return out;
}

}  // namespace rigidlab::sandbox

// The live energy plot (docs/design/thesis.md §12, experiment 2, Fig. 5.3 as it happens): linear and rotational
// kinetic, potential and total energy against simulated time, over the last `window` seconds.
#pragma once

#include <deque>

#include "rigidlab/world.h"

namespace rigidlab::sandbox {

struct EnergySample {
  double time = 0.0;        // simulated [s]
  double linear = 0.0;      // [J]  Σ ½ m v²   (dynamic bodies)
  double rotational = 0.0;  // [J]  Σ ½ I ω²
  double potential = 0.0;   // [J]  gravity + springs (World::potentialEnergy)
  double kinetic() const { return linear + rotational; }
  double total() const { return linear + rotational + potential; }
};

class EnergyHistory {
 public:
  explicit EnergyHistory(double window_seconds = 20.0) : window_(window_seconds) {}
  // Adds the world's current energies. Time going backwards (a reset) starts a new plot.
  void sample(const World& world);
  void add(const EnergySample& s);
  void clear() { samples_.clear(); }
  const std::deque<EnergySample>& samples() const { return samples_; }
  double window() const { return window_; }
  // Drift of the total over the window, |max − min| [J]: the number experiment 2 is about.
  double totalDrift() const;

 private:
  double window_;
  std::deque<EnergySample> samples_;
};

// Draws the plot in the current ImGui window, `height` pixels tall, full width.
void drawEnergyPlot(const EnergyHistory& history, float height);

}  // namespace rigidlab::sandbox

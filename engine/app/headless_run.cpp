#include "headless_run.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "rigidlab/lua/scene_text.h"

namespace rigidlab::app {

std::optional<RunLength> runLength(const lua::Scene& scene, std::optional<double> time, std::optional<long> steps,
                                   std::string& refused) {
  const auto refuse = [&](const std::string& what) {
    refused = what + ", more than the limit of " + std::to_string(kMaxRunSteps) +
              " steps per run; use a larger dt or a shorter run";
    return std::nullopt;
  };
  RunLength length;
  if (steps) {
    if (*steps > kMaxRunSteps) return refuse("--steps " + std::to_string(*steps) + " asks for " + std::to_string(*steps) + " steps");
    length.full_steps = *steps;
    return length;
  }
  const double h = scene.settings().dt;
  const double total = time.value_or(scene.settings().duration);
  // Refused before anything is converted to an integer: total / h can be 1e300 or infinite.
  const double count = std::floor(total / h + 1e-9);
  if (!(count <= static_cast<double>(kMaxRunSteps))) {
    char what[160];
    std::snprintf(what, sizeof what, "reaching t = %g s with steps of dt = %g s takes %.3g steps", total, h, count);
    return refuse(what);
  }
  length.full_steps = static_cast<long>(count);
  length.last = total - static_cast<double>(length.full_steps) * h;
  if (length.last <= 1e-9 * h) length.last = 0.0;
  return length;
}

void stepScene(lua::Scene& scene, const RunLength& length, RunInfo& info, const std::function<void()>& after_step) {
  World& world = scene.world();
  const double h = scene.settings().dt;
  const auto start = std::chrono::steady_clock::now();
  const long total_steps = length.total();
  size_t reported = 0;
  for (long i = 0; i < total_steps; ++i) {
    scene.step(i < length.full_steps ? h : length.last);
    ++info.steps;
    for (; reported < world.incidents().size(); ++reported)
      std::fprintf(stderr, "warning: %s\n", lua::displayText(world.incidents()[reported].message(), lua::kMessageBytes).c_str());
    if (info.energy_blowup_step == 0) {
      const double kinetic = world.kineticEnergy(), potential = world.potentialEnergy();
      if (!std::isfinite(kinetic) || !std::isfinite(potential)) {
        info.energy_blowup_step = world.stepCount();
        info.energy_blowup_time = world.time();
        info.blowup_kinetic = kinetic;
        info.blowup_potential = potential;
        std::fprintf(stderr, "warning: %s\n", incidents(world, info).back().c_str());
      }
    }
    after_step();
  }
  info.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::optional<std::string> runCheck(lua::Scene& scene, RunInfo& info) {
  info.check = scene.hasCheck() ? "passed" : "none";
  try {
    scene.runCheck();
  } catch (const lua::SceneError& e) {
    info.check = "failed";
    return sceneErrorText(e);
  }
  return std::nullopt;
}

std::string sceneErrorText(const lua::SceneError& error) {
  return lua::displayText(error.what(), lua::kMessageBytes, "\n\t");
}

}  // namespace rigidlab::app

// A headless run of a scene, shared by `rigidlab run` and `rigidlab test`: how many steps it
// takes, the stepping loop, and Check.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "report.h"
#include "rigidlab/lua/scene.h"

namespace rigidlab::app {

// The most steps one run may take (docs/security.md): about 10 s of an empty world's steps, and
// 46 hours of simulated time at 1/60 s. dt = 1e-12 with --time 1 would otherwise ask for 1e12.
inline constexpr long kMaxRunSteps = 10000000;

struct RunLength {
  long full_steps = 0;  // steps of the scene's dt
  double last = 0.0;    // a final shorter step that lands exactly on the end time (0: none)
  long total() const { return full_steps + (last > 0 ? 1 : 0); }
};

// The steps that reach `time` (default: the scene's duration) with whole steps of dt and, if a
// remainder is left, one shorter step; or exactly `steps`. nullopt when that is more than
// kMaxRunSteps, with `refused` saying so.
std::optional<RunLength> runLength(const lua::Scene& scene, std::optional<double> time, std::optional<long> steps,
                                   std::string& refused);

// Takes the steps (each calls OnStep), then `after_step()` after each. Incidents are printed on
// standard error as they happen, a non-finite energy is recorded in `info` (steps, wall_ms too).
// A script error throws lua::SceneError.
void stepScene(lua::Scene& scene, const RunLength& length, RunInfo& info, const std::function<void()>& after_step);

// Runs the scene's Check, if any, and sets info.check; the error message (shown as the runner
// shows it) if Check failed.
std::optional<std::string> runCheck(lua::Scene& scene, RunInfo& info);

// A SceneError's message as the runners print it: escaped, at most lua::kMessageBytes, continued
// lines indented.
std::string sceneErrorText(const lua::SceneError& error);

}  // namespace rigidlab::app

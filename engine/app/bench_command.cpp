// rigidlab bench: time benchmark scenes. Only World::step is timed; the result is the median and
// the 95th percentile of the per-step times over all measured steps of all repetitions.
// Benchmarks, never tests: timings depend on the machine and its load; compare ratios measured
// in one run.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "bench_scenes.h"
#include "cli.h"
#include "commands.h"
#include "report.h"

namespace rigidlab::app {
namespace {

constexpr const char* kHelp = R"(usage: rigidlab bench [SCENE...] [--reps R] [--json]

Times benchmark scenes (all of them without SCENE arguments). Per scene: median and p95 ms per
step (only the step is timed), setup time, per-stage breakdown, calls into Lua, and ratios between
related scenes. --json prints one JSON object per scene, one per line.

scenes:
)";

struct Result {
  std::string name;
  double median_ms = 0, p95_ms = 0, setup_ms = 0;
  StepStats stages;  // summed over the measured steps
  long steps = 0;
  long lua_calls = 0;
};

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const size_t i = static_cast<size_t>(std::min(p * (v.size() - 1) + 0.5, static_cast<double>(v.size() - 1)));
  return v[i];
}

Result run(const BenchScene& scene, int reps) {
  using Clock = std::chrono::steady_clock;
  Result r;
  r.name = scene.name;
  std::vector<double> times;
  std::vector<double> setups;
  for (int rep = 0; rep < reps; ++rep) {
    const auto t0 = Clock::now();
    BenchWorld bw = scene.build();
    setups.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    World& w = bw.get();
    const long calls_before = bw.luaCalls();
    for (int i = 0; i < scene.steps; ++i) {
      const auto a = Clock::now();
      w.step(scene.dt);
      times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - a).count());
      const StepStats& s = w.stats();
      r.stages.integrate_ms += s.integrate_ms;
      r.stages.forces_ms += s.forces_ms;
      r.stages.broad_phase_ms += s.broad_phase_ms;
      r.stages.narrow_phase_ms += s.narrow_phase_ms;
      r.stages.solve_ms += s.solve_ms;
      r.stages.correct_ms += s.correct_ms;
      r.stages.contacts = s.contacts;
      r.stages.bodies = s.bodies;
    }
    r.lua_calls += bw.luaCalls() - calls_before;
    r.steps += scene.steps;
  }
  r.median_ms = percentile(times, 0.5);
  r.p95_ms = percentile(times, 0.95);
  r.setup_ms = percentile(setups, 0.5);
  return r;
}

void print(const Result& r, bool json) {
  const double n = static_cast<double>(r.steps);
  if (json) {
    std::printf("{\"engine\":\"rigidlab\",\"scene\":%s,\"median_ms\":%s,\"p95_ms\":%s,\"setup_ms\":%s,\"bodies\":%d,"
                "\"contacts\":%d,\"lua_calls_per_step\":%s,\"stages_ms\":{\"integrate\":%s,\"forces\":%s,"
                "\"broad_phase\":%s,\"narrow_phase\":%s,\"solve\":%s,\"position_correction\":%s}}\n",
                jsonString(r.name).c_str(), jsonNumber(r.median_ms).c_str(), jsonNumber(r.p95_ms).c_str(),
                jsonNumber(r.setup_ms).c_str(), r.stages.bodies, r.stages.contacts, jsonNumber(r.lua_calls / n).c_str(),
                jsonNumber(r.stages.integrate_ms / n).c_str(), jsonNumber(r.stages.forces_ms / n).c_str(),
                jsonNumber(r.stages.broad_phase_ms / n).c_str(), jsonNumber(r.stages.narrow_phase_ms / n).c_str(),
                jsonNumber(r.stages.solve_ms / n).c_str(), jsonNumber(r.stages.correct_ms / n).c_str());
    return;
  }
  std::printf("%-14s median %8.3f ms  p95 %8.3f ms  setup %8.1f ms  | integrate %.3f (forces %.3f) broad %.3f "
              "narrow %.3f solve %.3f correct %.3f ms | %d bodies, %d contacts, %.0f Lua calls/step\n",
              r.name.c_str(), r.median_ms, r.p95_ms, r.setup_ms, r.stages.integrate_ms / n, r.stages.forces_ms / n,
              r.stages.broad_phase_ms / n, r.stages.narrow_phase_ms / n, r.stages.solve_ms / n, r.stages.correct_ms / n,
              r.stages.bodies, r.stages.contacts, r.lua_calls / n);
}

}  // namespace

int benchCommand(const std::vector<std::string>& argv) {
  const Args args("bench", argv, {"reps"}, {"json"});
  if (args.help()) {
    std::fputs(kHelp, stdout);
    for (const BenchScene& s : benchScenes()) std::printf("  %-14s %s\n", s.name.c_str(), s.description.c_str());
    return kExitOk;
  }
  const int reps = static_cast<int>(args.integer("reps", 1).value_or(3));
  std::vector<const BenchScene*> selected;
  for (const std::string& name : args.positional()) {
    const auto it = std::find_if(benchScenes().begin(), benchScenes().end(), [&](const BenchScene& s) { return s.name == name; });
    if (it == benchScenes().end()) throw UsageError("bench: unknown scene '" + name + "' (see rigidlab bench --help)");
    selected.push_back(&*it);
  }
  if (selected.empty())
    for (const BenchScene& s : benchScenes()) selected.push_back(&s);

  std::vector<Result> results;
  for (const BenchScene* s : selected) {
    if (!args.flag("json")) std::fprintf(stderr, "bench: %s ...\n", s->name.c_str());
    results.push_back(run(*s, reps));
    print(results.back(), args.flag("json"));
  }
  // The cost of a Lua force: the same springs in Lua and built in.
  const auto find = [&](const char* n) {
    return std::find_if(results.begin(), results.end(), [&](const Result& r) { return r.name == n; });
  };
  if (const auto lua = find("lua_springs"), builtin = find("springs"); lua != results.end() && builtin != results.end()) {
    const double ratio = lua->median_ms / builtin->median_ms;
    if (args.flag("json")) {
      std::printf("{\"engine\":\"rigidlab\",\"ratio\":\"lua_springs/springs\",\"value\":%s}\n", jsonNumber(ratio).c_str());
    } else {
      std::printf("Lua spring / built-in spring: %.2f x per step (%.1f us per Lua force evaluation)\n", ratio,
                  1000.0 * (lua->median_ms - builtin->median_ms) / (4.0 * 1000.0));
    }
  }
  return kExitOk;
}

}  // namespace rigidlab::app

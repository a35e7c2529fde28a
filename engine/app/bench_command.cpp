// rigidlab bench: time benchmark scenes (bench_scenes.cpp, bench_suite.cpp), each in its own
// process (bench_run.cpp), and compare them with other engines (bench_compare.cpp).
// Benchmarks, never tests: timings depend on the machine and its load; compare ratios measured
// in one run (--compare runs the peers right after; --v3 alternates with Box2D v3).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "bench_compare.h"
#include "bench_run.h"
#include "bench_scenes.h"
#include "cli.h"
#include "commands.h"
#include "json_value.h"
#include "report.h"

namespace rigidlab::app {
namespace {

constexpr const char* kHelp = R"(usage: rigidlab bench [SCENE...] [--reps R] [--steps N] [--json] [--compare] [--peers DIR]
                      [--v3 PROGRAM] [--v3-threads T] [--solver NAME] [--substeps N] [--iterations N]
                      [--impacts NAME] [--threads N]

Times benchmark scenes (all of them without SCENE arguments), each in its own process. Per scene:
median and p95 ms per step (only World::step is timed), setup time, the per-stage breakdown,
contacts, calls into Lua, peak memory, and the peers' stability metrics.
  --reps R      repetitions, each on a fresh world (default 3)
  --steps N     steps per repetition (default: the scene's own, listed below)
  --json        one JSON line per scene, in the peer programs' format plus rigidlab's fields
  --compare     then run the peers (Box2D 2.4.1 and Chipmunk 7.0.3, DIR/run.sh, default
                ../shared/peers beside the repository) and print rigidlab/peer ratios per scene
  --peers DIR   where the peer benchmark is
  --v3 PROGRAM  compare with Box2D v3 instead: an existing build of ../shared/peers/v3/bench_v3.c
                (--compare alone uses RIGIDLAB_V3_BENCH when set), run on 1 and T threads, alternated
                with rigidlab scene by scene for R rounds (--reps); prints the medians with their
                spread [min-max], the ratios and both engines' quality figures
  --v3-threads T  Box2D v3's second configuration (default 2; 1 skips it)
  --solver NAME contact solver: auto (default), sequential_impulses or soft_step
  --substeps N  soft step sub-steps per step (default 8); with --v3 a list such as 8,5 runs
                rigidlab at each (a row each, alternated with v3 in every round), so that the
                default and the sub-steps at which rigidlab's results are as good as v3's are
                compared in one run
  --iterations N  sequential impulses velocity passes per step (default 10)
  --impacts NAME  located (default: impacts of small free islands located inside the step while
                at most 128 bodies are awake) or per_step (every impact once per step), so that
                two runs show what located impacts cost
  --threads N   threads a step runs on (WorldDef::threads): 0 the machine's cores, 1 (default) the
                serial path; the results are the same bits whatever N

scenes:
)";

// --substeps: one count, or (for --v3) a comma-separated list; each 1…64.
std::vector<int> substepList(const std::optional<std::string>& text, int fallback) {
  if (!text) return {fallback};
  std::vector<int> out;
  size_t start = 0;
  while (start <= text->size()) {
    const size_t comma = std::min(text->find(',', start), text->size());
    const std::string item = text->substr(start, comma - start);
    char* end = nullptr;
    const long value = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || value < 1 || value > 64)
      throw UsageError("bench: --substeps must be a number from 1 to 64 or a list of them such as 8,5, got '" + *text + "'");
    out.push_back(static_cast<int>(value));
    start = comma + 1;
  }
  return out;
}

}  // namespace

int benchCommand(const std::vector<std::string>& argv) {
  const Args args("bench", argv, {"reps", "steps", "peers", "v3", "v3-threads", "solver", "substeps", "iterations", "impacts", "threads"}, {"json", "compare"});
  if (args.help()) {
    std::fputs(kHelp, stdout);
    for (const BenchScene& s : benchScenes()) std::printf("  %-12s %s\n", s.name.c_str(), s.description.c_str());
    return kExitOk;
  }
  const int reps = static_cast<int>(args.integer("reps", 1).value_or(3));
  const auto steps = args.integer("steps", 1);
  if (steps && *steps > 1000000) throw UsageError("bench: --steps must be at most 1000000");
  WorldDef& settings = benchSettings();
  if (const auto name = args.value("solver")) {
    const auto solver = parseContactSolver(*name);
    if (!solver) throw UsageError("bench: --solver must be one of " + contactSolverNames() + ", got '" + *name + "'");
    settings.contact_solver = *solver;
  }
  if (const auto name = args.value("impacts")) {
    const auto impacts = parseImpactHandling(*name);
    if (!impacts) throw UsageError("bench: --impacts must be one of " + impactHandlingNames() + ", got '" + *name + "'");
    settings.impacts = *impacts;
  }
  const std::vector<int> substeps = substepList(args.value("substeps"), settings.substeps);
  settings.substeps = substeps.front();
  settings.iterations = static_cast<int>(args.integer("iterations", 1).value_or(settings.iterations));
  if (settings.iterations > 10000) throw UsageError("bench: --iterations must be at most 10000");
  settings.threads = static_cast<int>(args.integer("threads", 0).value_or(settings.threads));
  if (settings.threads > 64) throw UsageError("bench: --threads must be at most 64");
  std::vector<const BenchScene*> selected;
  for (const std::string& name : args.positional()) {
    const auto it = std::find_if(benchScenes().begin(), benchScenes().end(), [&](const BenchScene& s) { return s.name == name; });
    if (it == benchScenes().end()) throw UsageError("bench: unknown scene '" + name + "' (see rigidlab bench --help)");
    selected.push_back(&*it);
  }
  if (selected.empty())
    for (const BenchScene& s : benchScenes()) selected.push_back(&s);

  const bool json = args.flag("json");
  const int v3_threads = static_cast<int>(args.integer("v3-threads", 1).value_or(2));
  if (args.value("v3-threads") && !args.value("v3") && !args.flag("compare"))
    throw UsageError("bench: --v3-threads needs --v3 PROGRAM (or --compare with RIGIDLAB_V3_BENCH set)");
  std::optional<std::string> v3 = args.value("v3");
  if (!v3 && args.flag("compare"))
    if (const char* env = std::getenv("RIGIDLAB_V3_BENCH"); env && *env) v3 = env;
  if (v3) {
    std::vector<BenchScene> scenes;
    for (const BenchScene* s : selected) {
      scenes.push_back(*s);
      if (steps) scenes.back().steps = static_cast<int>(*steps);
    }
    return compareV3(scenes, *v3, reps, v3_threads, substeps, json);
  }
  if (substeps.size() > 1) throw UsageError("bench: a list of --substeps is for comparisons with --v3; give one number");
  std::vector<JsonValue> results;
  for (size_t i = 0; i < selected.size(); ++i) {
    const BenchScene* s = selected[i];
    std::fprintf(stderr, "bench: [%zu/%zu] %s ...\n", i + 1, selected.size(), s->name.c_str());
    BenchScene scene = *s;
    if (steps) scene.steps = static_cast<int>(*steps);
    const std::string line = runIsolated(scene, reps);
    const auto v = parseJson(line);
    if (!v || v->get("error")) {
      std::fprintf(stderr, "bench: %s: %s\n", s->name.c_str(), line.c_str());
      return kExitSceneError;
    }
    results.push_back(*v);
    if (json) {
      std::printf("%s\n", line.c_str());
    } else {
      printHuman(*v);
    }
    std::fflush(stdout);
  }
  // The cost of a Lua force: the same springs in Lua and built in.
  const auto find = [&](const char* n) {
    return std::find_if(results.begin(), results.end(), [&](const JsonValue& r) { return r.str("name") == n; });
  };
  if (const auto lua = find("lua_springs"), builtin = find("springs"); lua != results.end() && builtin != results.end()) {
    const double ratio = lua->num("ms_median").value_or(NAN) / builtin->num("ms_median").value_or(NAN);
    const double per_call_us = 1000.0 * (lua->get("stages_ms")->num("forces").value_or(0) -
                                         builtin->get("stages_ms")->num("forces").value_or(0)) /
                               std::max(1.0, lua->num("lua_calls_per_step").value_or(1));
    if (json) {
      std::printf("{\"engine\": \"rigidlab\", \"ratio\": \"lua_springs/springs\", \"value\": %s, \"lua_call_us\": %s}\n",
                  fmt(ratio).c_str(), fmt(per_call_us).c_str());
    } else {
      std::printf("Lua spring / built-in spring: %.2fx per step; %.2f us per Lua force evaluation\n", ratio, per_call_us);
    }
  }
  if (args.flag("compare")) {
    const std::filesystem::path peers =
        args.value("peers") ? std::filesystem::path(*args.value("peers")) : lua::scriptsDirectory().parent_path().parent_path() / "shared" / "peers";
    return comparePeers(results, peers);
  }
  return kExitOk;
}

}  // namespace rigidlab::app

// rigidlab bench: time benchmark scenes (bench_scenes.cpp, bench_suite.cpp), each in its own
// process (bench_run.cpp), and compare them with other engines (bench_compare.cpp).
// Benchmarks, never tests: timings depend on the machine and its load; compare ratios measured
// in one run (--compare and --v3 alternate rigidlab with the other engines, scene by scene).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>

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
                      [--v3 PROGRAM] [--v3-threads T] [--peer-timeout S] [--solver NAME]
                      [--substeps N] [--iterations N] [--impacts NAME] [--threads N]

Times benchmark scenes (all of them without SCENE arguments), each in its own process. Per scene:
median and p95 ms per step (only World::step is timed), its CPU time (all threads: below the
wall time, the step waited for a busy core; above it, the cores it used), setup time, the
per-stage breakdown, contacts, calls into Lua, peak memory, and the peers' stability metrics.
  --reps R      repetitions, each on a fresh world (default 3)
  --steps N     steps per repetition (default: the scene's own, listed below)
  --json        one JSON line per scene, in the peer programs' format plus rigidlab's fields
  --compare     against Box2D 2.4.1 and Chipmunk 7.0.3 (the Debian packages libbox2d-dev and
                libchipmunk-dev, never installed by this: it names the missing ones and the command
                that installs them; the peer programs of DIR, built first) and Box2D v3 when a program is given (--v3, or RIGIDLAB_V3_BENCH):
                every scene for R rounds (--reps), each round alternating rigidlab with every other
                engine (one five times slower than rigidlab runs in the first round only); prints
                each one's median ms per step with the spread [min-max] of the rounds, the ratios
                rigidlab/peer and every engine's quality figures side by side
  --peers DIR   the peer programs' sources (default: engine/peers of the repository)
  --v3 PROGRAM  an existing build of Box2D v3's peer program (bench_v3.c, built by hand outside the
                repository; docs/performance.md): run on 1 and T threads as above; alone, without
                --compare, against Box2D v3 only
  --v3-threads T  Box2D v3's second configuration (default 2; 1 skips it)
  --peer-timeout S  stop one run of a peer after S seconds (default 600; 0: never) and report it
                as at least S over its steps per step (Chipmunk's joint_grid comes apart and
                takes about 20 minutes)
  --solver NAME contact solver: auto (default), sequential_impulses or soft_step
  --substeps N  soft step sub-steps per step (default 8); with --compare or --v3 a list such as
                8,5 runs rigidlab at each (a row each, alternated with the peers in every round),
                so that the default and the sub-steps at which rigidlab's results are as good as a
                peer's are compared in one run
  --iterations N  sequential impulses velocity passes per step (default 10)
  --impacts NAME  located (default: impacts of small free islands located inside the step while
                at most 128 bodies are awake) or per_step (every impact once per step), so that
                two runs show what located impacts cost
  --threads N   threads a step runs on (WorldDef::threads): 0 the machine's cores, 1 (default) the
                serial path; the results are the same bits whatever N

scenes:
)";

// --substeps: one count, or (for --compare and --v3) a comma-separated list; each 1…64.
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
  const Args args("bench", argv, {"reps", "steps", "peers", "v3", "v3-threads", "peer-timeout", "solver", "substeps", "iterations", "impacts", "threads"}, {"json", "compare"});
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
    if (it == benchScenes().end()) {
      std::vector<std::string> names;
      for (const BenchScene& scene : benchScenes()) names.push_back(scene.name);
      const std::string hint = suggestion(name, names);
      throw UsageError("bench: unknown scene '" + name + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)") +
                       " (see rigidlab bench --help)");
    }
    selected.push_back(&*it);
  }
  if (selected.empty())
    for (const BenchScene& s : benchScenes()) selected.push_back(&s);

  const bool json = args.flag("json");
  const int v3_threads = static_cast<int>(args.integer("v3-threads", 1).value_or(2));
  if (args.value("v3-threads") && !args.value("v3") && !args.flag("compare"))
    throw UsageError("bench: --v3-threads needs --v3 PROGRAM (or --compare with RIGIDLAB_V3_BENCH set)");
  if (args.value("peers") && !args.flag("compare")) throw UsageError("bench: --peers DIR is for --compare");
  const int peer_timeout = static_cast<int>(args.integer("peer-timeout", 0).value_or(600));
  if (args.value("peer-timeout") && !args.value("v3") && !args.flag("compare"))
    throw UsageError("bench: --peer-timeout is for comparisons (--compare, --v3)");
  std::optional<std::string> v3 = args.value("v3");
  if (!v3 && args.flag("compare"))
    if (const char* env = std::getenv("RIGIDLAB_V3_BENCH"); env && *env) v3 = env;
  if (v3 || args.flag("compare")) {
    std::vector<PeerProgram> peers;
    if (v3) peers = v3Programs(*v3, v3_threads);
    if (args.flag("compare")) {
      // By default the repository's engine/peers: the build tree's scripts folder is a link to the
      // repository's scripts/, so the link resolved leads there.
      std::error_code error;
      const std::filesystem::path scripts = std::filesystem::canonical(lua::scriptsDirectory(), error);
      const std::filesystem::path dir =
          args.value("peers") ? std::filesystem::path(*args.value("peers")) : scripts.parent_path() / "engine" / "peers";
      // Built beside the other temporary files, in a folder of the sources' own (tests use fake peers).
      char folder[48];
      std::snprintf(folder, sizeof folder, "rigidlab-peers-%016zx", std::hash<std::string>{}(std::filesystem::absolute(dir).string()));
      for (PeerProgram& p : buildPeerPrograms(dir, std::filesystem::temp_directory_path() / folder))
        peers.push_back(std::move(p));
    }
    std::vector<BenchScene> scenes;
    for (const BenchScene* s : selected) {
      scenes.push_back(*s);
      if (steps) scenes.back().steps = static_cast<int>(*steps);
    }
    return comparePeers(scenes, peers, reps, substeps, peer_timeout, json);
  }
  if (substeps.size() > 1) throw UsageError("bench: a list of --substeps is for comparisons (--compare, --v3); give one number");
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
  // The cost of a Lua function the step calls (a pre_solve function, ShouldCollide): the same
  // scene with and without it.
  const auto perCall = [&](const std::string& with_name, const char* what) {
    const auto with = find(with_name.c_str()), without = find((with_name + "_off").c_str());
    if (with == results.end() || without == results.end()) return;
    const double ms_with = with->num("ms_median").value_or(NAN), ms_without = without->num("ms_median").value_or(NAN);
    const double per_call_us = 1000.0 * (ms_with - ms_without) / std::max(1.0, with->num("lua_calls_per_step").value_or(1));
    if (json) {
      std::printf("{\"engine\": \"rigidlab\", \"ratio\": \"%s/%s_off\", \"value\": %s, \"%s_call_us\": %s}\n", with_name.c_str(),
                  with_name.c_str(), fmt(ms_with / ms_without).c_str(), with_name.c_str(), fmt(per_call_us).c_str());
    } else {
      std::printf("%s / none: %.2fx per step; %.2f us per %s call\n", with_name.c_str(), ms_with / ms_without, per_call_us, what);
    }
  };
  perCall("pre_solve", "pre_solve");
  perCall("should_collide", "ShouldCollide");
  return kExitOk;
}

}  // namespace rigidlab::app

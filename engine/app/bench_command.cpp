// rigidlab bench: time benchmark scenes. Only World::step is timed; per scene the result is the
// median (and p95) of the per-step times of each repetition, then the median over repetitions,
// exactly as the peer programs (../shared/peers) compute theirs. Each scene runs in its own child
// process, so its peak memory (max RSS) is its own.
// Benchmarks, never tests: timings depend on the machine and its load; compare ratios measured
// in one run (--compare runs the peers right after).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <map>

#include "bench_scenes.h"
#include "cli.h"
#include "commands.h"
#include "json_value.h"
#include "report.h"

namespace rigidlab::app {
namespace {

constexpr const char* kHelp = R"(usage: rigidlab bench [SCENE...] [--reps R] [--steps N] [--json] [--compare] [--peers DIR]
                      [--solver NAME] [--substeps N] [--iterations N]

Times benchmark scenes (all of them without SCENE arguments), each in its own process. Per scene:
median and p95 ms per step (only World::step is timed), setup time, the per-stage breakdown,
contacts, calls into Lua, peak memory, and the peers' stability metrics.
  --reps R      repetitions, each on a fresh world (default 3)
  --steps N     steps per repetition (default: the scene's own, listed below)
  --json        one JSON line per scene, in the peer programs' format plus rigidlab's fields
  --compare     then run the peers (Box2D 2.4.1 and Chipmunk 7.0.3, DIR/run.sh, default
                ../shared/peers beside the repository) and print rigidlab/peer ratios per scene
  --peers DIR   where the peer benchmark is
  --solver NAME contact solver: auto (default), sequential_impulses or soft_step
  --substeps N  soft step sub-steps per step (default 8)
  --iterations N  sequential impulses velocity passes per step (default 10)

scenes:
)";

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double percentile(std::vector<double> v, double p) {  // as the peers: the ceil(p n)-th value
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t idx = static_cast<size_t>(std::ceil(p * v.size()));
  if (idx > 0) --idx;
  return v[std::min(idx, v.size() - 1)];
}

std::string fmt(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, std::isfinite(x) ? "%.6g" : "null", x);
  return buf;
}

std::string array(const std::vector<double>& v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt(v[i]);
  return s + "]";
}

// Runs one scene (in the child process) and returns its JSON line.
std::string runScene(const BenchScene& scene, int reps) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> medians, p95s, means, firsts, totals, setups;
  StepStats stages;  // summed over the measured steps of all repetitions
  long lua_calls = 0, steps = 0;
  int contacts = 0, dynamic = 0;
  std::string metrics;
  for (int rep = 0; rep < reps; ++rep) {
    const auto t0 = Clock::now();
    BenchWorld bw = scene.build();
    setups.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    World& w = bw.get();
    BenchTracker tracker;
    SuiteTracker suite;
    const bool in_suite = isSuiteScene(scene.kind);
    std::vector<double> times;
    times.reserve(scene.steps);
    const long calls_before = bw.luaCalls();
    for (int i = 0; i < scene.steps; ++i) {
      const auto a = Clock::now();
      if (bw.before_step) bw.before_step(w, i);
      w.step(scene.dt);
      times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - a).count());
      const StepStats& s = w.stats();
      stages.integrate_ms += s.integrate_ms;
      stages.forces_ms += s.forces_ms;
      stages.broad_phase_ms += s.broad_phase_ms;
      stages.narrow_phase_ms += s.narrow_phase_ms;
      stages.solve_ms += s.solve_ms;
      stages.correct_ms += s.correct_ms;
      stages.finish_ms += s.finish_ms;
      if (!bw.bodies.empty()) tracker.observe(scene.kind, bw, i, scene.dt);
      if (in_suite) suite.observe(w, i);
    }
    lua_calls += bw.luaCalls() - calls_before;
    steps += scene.steps;
    medians.push_back(median(times));
    p95s.push_back(percentile(times, 0.95));
    double total = 0;
    for (double t : times) total += t;
    totals.push_back(total);
    means.push_back(total / times.size());
    firsts.push_back(times.front());
    contacts = 0;
    for (const ContactInfo& c : w.contacts())
      for (int k = 0; k < c.count; ++k)
        if (c.separations[k] <= 0.0) {
          ++contacts;  // touching, as the peers count them (speculative points excluded)
          break;
        }
    dynamic = w.stats().dynamic_bodies;
    metrics = in_suite ? suiteMetrics(w, suite) : bw.bodies.empty() ? "{}" : benchMetrics(scene, bw, tracker);
  }
  const double n = static_cast<double>(steps);
  std::string s = "{\"engine\": \"rigidlab\", \"version\": \"0.1.0\", \"build\": \"release\", \"scene\": \"" +
                  scene.kind + "\", \"n\": " + std::to_string(scene.n) + ", \"dynamic_bodies\": " +
                  std::to_string(dynamic) + ", \"steps\": " + std::to_string(scene.steps) + ", \"reps\": " +
                  std::to_string(reps) + ", \"sleep\": false, \"settings\": {\"solver\": \"" +
                  std::string(contactSolverName(benchSettings().contact_solver)) + "\", \"substeps\": " +
                  std::to_string(benchSettings().substeps) + ", \"iterations\": " +
                  std::to_string(benchSettings().iterations) + "}, \"ms_median\": " + fmt(median(medians)) +
                  ", \"ms_median_best_rep\": " + fmt(*std::min_element(medians.begin(), medians.end())) +
                  ", \"ms_p95\": " + fmt(median(p95s)) + ", \"ms_mean\": " + fmt(median(means)) +
                  ", \"ms_first_step\": " + fmt(median(firsts)) + ", \"ms_total\": " + fmt(median(totals)) +
                  ", \"ms_setup\": " + fmt(median(setups)) + ", \"rep_medians\": " + array(medians) +
                  ", \"rep_p95\": " + array(p95s) + ", \"contacts_at_end\": " + std::to_string(contacts) +
                  ", \"metrics\": " + metrics + ", \"name\": \"" + scene.name + "\", \"stages_ms\": {\"integrate\": " +
                  fmt(stages.integrate_ms / n) + ", \"forces\": " + fmt(stages.forces_ms / n) +
                  ", \"broad_phase\": " + fmt(stages.broad_phase_ms / n) + ", \"narrow_phase\": " +
                  fmt(stages.narrow_phase_ms / n) + ", \"solve\": " + fmt(stages.solve_ms / n) +
                  ", \"position_correction\": " + fmt(stages.correct_ms / n) + ", \"finish\": " +
                  fmt(stages.finish_ms / n) + "}, \"lua_calls_per_step\": " + fmt(lua_calls / n) + "}";
  return s;
}

// Forks, runs the scene in the child, and returns its line with the child's peak memory added.
std::string runIsolated(const BenchScene& scene, int reps) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("bench: pipe failed");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("bench: fork failed");
  if (pid == 0) {
    close(fds[0]);
    std::string line;
    try {
      line = runScene(scene, reps);
    } catch (const std::exception& e) {
      line = std::string("{\"error\": ") + jsonString(e.what()) + "}";
    }
    const char* p = line.data();
    for (size_t left = line.size(); left > 0;) {
      const ssize_t k = write(fds[1], p, left);
      if (k <= 0) break;
      p += k;
      left -= static_cast<size_t>(k);
    }
    _exit(0);
  }
  close(fds[1]);
  std::string line;
  char buf[4096];
  for (ssize_t k; (k = read(fds[0], buf, sizeof buf)) > 0;) line.append(buf, static_cast<size_t>(k));
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  if (line.empty() || line.back() != '}') throw std::runtime_error("bench: " + scene.name + " failed in its process");
  line.pop_back();
  return line + ", \"peak_rss_mb\": " + fmt(usage.ru_maxrss / 1024.0) + "}";
}

void printHuman(const JsonValue& r) {
  const JsonValue* stages = r.get("stages_ms");
  const auto stage = [&](const char* k) { return stages ? stages->num(k).value_or(0) : 0.0; };
  std::printf("%-12s median %8.3f ms  p95 %8.3f ms  setup %7.1f ms  peak %6.1f MiB | forces %.3f integrate %.3f "
              "broad %.3f narrow %.3f solve %.3f correct %.3f ms | %.0f contacts, %.0f Lua calls/step\n",
              r.str("name").value_or("?").c_str(), r.num("ms_median").value_or(0), r.num("ms_p95").value_or(0),
              r.num("ms_setup").value_or(0), r.num("peak_rss_mb").value_or(0), stage("forces"), stage("integrate"),
              stage("broad_phase"), stage("narrow_phase"), stage("solve"), stage("position_correction"),
              r.num("contacts_at_end").value_or(0), r.num("lua_calls_per_step").value_or(0));
  if (const JsonValue* m = r.get("metrics"); m && !m->object.empty()) {
    std::string s;
    for (const auto& [k, v] : m->object) {
      if (k == "awake_at_end") continue;
      s += "  " + k + "=" + (v.type == JsonValue::Type::Bool ? (v.boolean ? "true" : "false") : fmt(v.number));
    }
    std::printf("             %s\n", s.c_str());
  }
}

// Key "pyramid/40" of a result line.
std::string key(const JsonValue& r) {
  return r.str("scene").value_or("?") + "/" + std::to_string(static_cast<long>(r.num("n").value_or(0)));
}

std::string stability(const JsonValue& r) {
  const JsonValue* m = r.get("metrics");
  if (!m) return "";
  const std::string scene = r.str("scene").value_or("");
  const auto b = [&](const char* k) {
    const JsonValue* v = m->get(k);
    return v && v->type == JsonValue::Type::Bool && v->boolean;
  };
  char buf[128] = "";
  if (scene == "pyramid") {
    std::snprintf(buf, sizeof buf, "%s, disp %.3f", b("top_on_top") ? "top on top" : "TOP FELL", m->num("max_disp_m").value_or(NAN));
  } else if (scene == "stack") {
    std::snprintf(buf, sizeof buf, "%s, disp %.3f", b("toppled") ? "TOPPLED" : "stands", m->num("max_disp_m").value_or(NAN));
  } else if (scene == "rain") {
    std::snprintf(buf, sizeof buf, "overlap max %.4f mean %.4f", m->num("max_overlap_m").value_or(NAN),
                  m->num("mean_overlap_m").value_or(NAN));
  } else if (scene == "massratio") {
    std::snprintf(buf, sizeof buf, "%s, pen %.4f", b("collapsed") ? "COLLAPSED" : "holds",
                  m->num("max_box_box_penetration_m").value_or(NAN));
  } else if (scene == "bullet") {
    std::snprintf(buf, sizeof buf, "%s", b("passed_through") ? "PASSES THROUGH" : "stops");
  }
  return buf;
}

int compare(const std::vector<JsonValue>& ours, const std::filesystem::path& peers) {
  const std::filesystem::path script = peers / "run.sh";
  if (!std::filesystem::exists(script)) {
    std::fprintf(stderr, "bench: no peer benchmark at %s (use --peers DIR)\n", script.c_str());
    return kExitUsage;
  }
  std::fprintf(stderr, "bench: running the peers (%s, about 3 minutes) ...\n", script.c_str());
  const std::string command = "'" + script.string() + "' /tmp/rigidlab-peers 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    std::fprintf(stderr, "bench: cannot run %s\n", script.c_str());
    return kExitSceneError;
  }
  std::map<std::string, std::map<std::string, JsonValue>> peer;  // key → engine → line
  char buf[1 << 16];
  while (std::fgets(buf, sizeof buf, pipe)) {
    if (const auto v = parseJson(std::string(buf, std::strlen(buf) - (std::strchr(buf, '\n') ? 1 : 0))))
      peer[key(*v)][v->str("engine").value_or("?")] = *v;
  }
  pclose(pipe);
  std::printf("\n%-16s %10s %10s %10s %9s %9s   %-28s %-28s %-28s\n", "scene", "rigidlab", "Box2D 2.4", "Chipmunk",
              "/Box2D", "/Chipmunk", "rigidlab", "Box2D 2.4", "Chipmunk");
  for (const JsonValue& r : ours) {
    const std::string k = key(r);
    if (!peer.count(k)) continue;
    const auto& p = peer[k];
    const double ms = r.num("ms_median").value_or(NAN);
    const auto peerMs = [&](const char* e) { return p.count(e) ? p.at(e).num("ms_median").value_or(NAN) : NAN; };
    const auto peerStab = [&](const char* e) { return p.count(e) ? stability(p.at(e)) : std::string(); };
    std::printf("%-16s %8.3fms %8.3fms %8.3fms %8.2fx %8.2fx   %-28s %-28s %-28s\n", k.c_str(), ms, peerMs("box2d"),
                peerMs("chipmunk"), ms / peerMs("box2d"), ms / peerMs("chipmunk"), stability(r).c_str(),
                peerStab("box2d").c_str(), peerStab("chipmunk").c_str());
  }
  return kExitOk;
}

}  // namespace

int benchCommand(const std::vector<std::string>& argv) {
  const Args args("bench", argv, {"reps", "steps", "peers", "solver", "substeps", "iterations"}, {"json", "compare"});
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
  settings.substeps = static_cast<int>(args.integer("substeps", 1).value_or(settings.substeps));
  settings.iterations = static_cast<int>(args.integer("iterations", 1).value_or(settings.iterations));
  if (settings.substeps > 64) throw UsageError("bench: --substeps must be at most 64");
  if (settings.iterations > 10000) throw UsageError("bench: --iterations must be at most 10000");
  std::vector<const BenchScene*> selected;
  for (const std::string& name : args.positional()) {
    const auto it = std::find_if(benchScenes().begin(), benchScenes().end(), [&](const BenchScene& s) { return s.name == name; });
    if (it == benchScenes().end()) throw UsageError("bench: unknown scene '" + name + "' (see rigidlab bench --help)");
    selected.push_back(&*it);
  }
  if (selected.empty())
    for (const BenchScene& s : benchScenes()) selected.push_back(&s);

  const bool json = args.flag("json");
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
    return compare(results, peers);
  }
  return kExitOk;
}

}  // namespace rigidlab::app

// One benchmark scene timed in its own child process (so that its peak memory is its own): only
// World::step (and the scene's own edits before it) is timed; the result is the median (and p95)
// of the per-step times of each repetition, then the median over repetitions, exactly as the peer
// programs compute theirs (docs/performance.md, "How to reproduce the figures").
#include "bench_run.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include "report.h"
#include "version.h"

namespace rigidlab::app {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fmt(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, std::isfinite(x) ? "%.6g" : "null", x);
  return buf;
}

namespace {

double percentile(std::vector<double> v, double p) {  // as the peers: the ceil(p n)-th value
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t idx = static_cast<size_t>(std::ceil(p * v.size()));
  if (idx > 0) --idx;
  return v[std::min(idx, v.size() - 1)];
}

// The probe's series (median and interquartile range, µs) and figures, as JSON members.
std::string sampleMembers(const BenchSamples& samples) {
  std::string s;
  for (const auto& [name, v] : samples.us) {
    s += ", \"" + name + "_us_median\": " + fmt(median(v)) + ", \"" + name +
         "_us_iqr\": " + fmt(percentile(v, 0.75) - percentile(v, 0.25)) + ", \"" + name +
         "_samples\": " + std::to_string(v.size());
  }
  for (const auto& [name, x] : samples.figures) s += ", \"" + name + "\": " + fmt(x);
  return s;
}

std::string array(const std::vector<double>& v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt(v[i]);
  return s + "]";
}

// CPU time of the whole process (every thread of the step's pool) [ms]. Beside the wall time of a
// step it shows what the step had: with one thread, wall above CPU is time spent waiting for a busy
// core; with several, CPU above wall is the cores used (CPU ÷ wall).
double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

// Runs one scene (in the child process) and returns its JSON line.
std::string runScene(const BenchScene& scene, int reps) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> medians, p95s, means, firsts, totals, setups, cpu_medians, cpu_means;
  StepStats stages;  // summed over the measured steps of all repetitions
  long lua_calls = 0, steps = 0;
  int contacts = 0, dynamic = 0;
  std::string metrics;
  BenchSamples samples;  // over all repetitions
  for (int rep = 0; rep < reps; ++rep) {
    const auto t0 = Clock::now();
    BenchWorld bw = scene.build();
    setups.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    World& w = bw.get();
    BenchTracker tracker;
    SuiteTracker suite;
    const bool in_suite = isSuiteScene(scene.kind);
    std::vector<double> times, cpu;
    times.reserve(scene.steps);
    cpu.reserve(scene.steps);
    const long calls_before = bw.luaCalls();
    for (int i = 0; i < scene.steps; ++i) {
      const auto a = Clock::now();
      const double cpu_start = processCpuMs();  // inside the wall time's interval
      if (bw.before_step) bw.before_step(w, i);
      if (bw.scene_steps) {
        bw.scene->step(scene.dt);
      } else {
        w.step(scene.dt);
      }
      cpu.push_back(processCpuMs() - cpu_start);
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
      if (scene.probe) scene.probe(bw, i, samples);
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
    cpu_medians.push_back(median(cpu));
    double cpu_total = 0;
    for (double t : cpu) cpu_total += t;
    cpu_means.push_back(cpu_total / cpu.size());
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
  if (const std::string members = sampleMembers(samples); !members.empty()) {  // into {…} or {}
    metrics = metrics == "{}" ? "{" + members.substr(2) + "}" : metrics.substr(0, metrics.size() - 1) + members + "}";
  }
  const double n = static_cast<double>(steps);
  std::string build = kVersion.build_type;
  std::transform(build.begin(), build.end(), build.begin(), [](unsigned char c) { return std::tolower(c); });
  std::string s = "{\"engine\": \"rigidlab\", \"version\": \"" + std::string(kVersion.version) +
                  "\", \"build\": \"" + build + "\", \"scene\": \"" +
                  scene.kind + "\", \"n\": " + std::to_string(scene.n) + ", \"dynamic_bodies\": " +
                  std::to_string(dynamic) + ", \"steps\": " + std::to_string(scene.steps) + ", \"reps\": " +
                  std::to_string(reps) + ", \"sleep\": false, \"settings\": {\"solver\": \"" +
                  std::string(contactSolverName(benchSettings().contact_solver)) + "\", \"substeps\": " +
                  std::to_string(benchSettings().substeps) + ", \"iterations\": " +
                  std::to_string(benchSettings().iterations) + ", \"threads\": " +
                  std::to_string(benchSettings().threads) + ", \"impacts\": \"" +
                  std::string(impactHandlingName(benchSettings().impacts)) + "\"}, \"ms_median\": " + fmt(median(medians)) +
                  ", \"ms_median_best_rep\": " + fmt(*std::min_element(medians.begin(), medians.end())) +
                  ", \"ms_p95\": " + fmt(median(p95s)) + ", \"ms_mean\": " + fmt(median(means)) +
                  ", \"ms_first_step\": " + fmt(median(firsts)) + ", \"ms_total\": " + fmt(median(totals)) +
                  ", \"ms_setup\": " + fmt(median(setups)) + ", \"cpu_ms_median\": " + fmt(median(cpu_medians)) +
                  ", \"cpu_ms_mean\": " + fmt(median(cpu_means)) + ", \"rep_medians\": " + array(medians) +
                  ", \"rep_p95\": " + array(p95s) + ", \"contacts_at_end\": " + std::to_string(contacts) +
                  ", \"metrics\": " + metrics + ", \"name\": \"" + scene.name + "\", \"stages_ms\": {\"integrate\": " +
                  fmt(stages.integrate_ms / n) + ", \"forces\": " + fmt(stages.forces_ms / n) +
                  ", \"broad_phase\": " + fmt(stages.broad_phase_ms / n) + ", \"narrow_phase\": " +
                  fmt(stages.narrow_phase_ms / n) + ", \"solve\": " + fmt(stages.solve_ms / n) +
                  ", \"position_correction\": " + fmt(stages.correct_ms / n) + ", \"finish\": " +
                  fmt(stages.finish_ms / n) + "}, \"lua_calls_per_step\": " + fmt(lua_calls / n) + "}";
  return s;
}

}  // namespace

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
  std::printf("%-12s median %8.3f ms  p95 %8.3f ms  cpu %8.3f ms  setup %7.1f ms  peak %6.1f MiB | forces %.3f integrate %.3f "
              "broad %.3f narrow %.3f solve %.3f correct %.3f ms | %.0f contacts, %.0f Lua calls/step\n",
              r.str("name").value_or("?").c_str(), r.num("ms_median").value_or(0), r.num("ms_p95").value_or(0),
              r.num("cpu_ms_median").value_or(0),
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

}  // namespace rigidlab::app

// rigidlab against Box2D 2.4.1, Chipmunk 7 and Box2D v3 on the same scenes (bench_compare.h).
#include "bench_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "bench_run.h"
#include "cli.h"
#include "commands.h"

namespace rigidlab::app {
namespace {

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

}  // namespace

int comparePeers(const std::vector<JsonValue>& ours, const std::filesystem::path& peers) {
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


namespace {

// The peer program's arguments for one of rigidlab's scenes, or "" if it has no such scene.
std::string v3Arguments(const BenchScene& s) {
  const std::string steps = " --steps=" + std::to_string(s.steps);
  if (isSuiteScene(s.kind)) return s.kind + steps;
  if (s.kind == "pyramid" || s.kind == "stack" || s.kind == "rain") return s.kind + " --n=" + std::to_string(s.n) + steps;
  if (s.kind == "massratio") return "massratio --top=heavy --heavy-half=0.5 --heavy-mass=100" + steps;
  if (s.kind == "bullet") return "bullet --n=1" + steps;
  return "";
}

std::optional<JsonValue> runProgram(const std::string& command) {
  FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return std::nullopt;
  std::string out;
  char buf[1 << 16];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  const size_t last = out.rfind('\n');
  return parseJson(last == std::string::npos ? out : out.substr(last + 1));
}

// Pile height loss, overlap, top on top, joint gaps: what says whether a result is as good.
std::string quality(const JsonValue& r) {
  const JsonValue* m = r.get("metrics");
  if (!m) return "";
  if (!isSuiteScene(r.str("scene").value_or(""))) return stability(r);
  // Only the figures the scene has (ragdolls have no pile, so no drop or top).
  std::string out;
  const auto add = [&](const char* label, const char* key, const char* format) {
    const std::optional<double> v = m->num(key);
    if (!v || std::isnan(*v)) return;
    char buf[48];
    std::snprintf(buf, sizeof buf, format, *v);
    out += (out.empty() ? "" : " ") + std::string(label) + " " + buf;
  };
  add("pen", "max_penetration_m", "%.3f");
  add("gap", "max_joint_gap_m", "%.4f");
  add("drop", "mean_drop_m", "%.3f");
  add("top", "top_height_loss_m", "%.3f");
  return out;
}

struct Series {
  std::vector<double> ms;
  std::optional<JsonValue> last;
  void add(const std::optional<JsonValue>& r) {
    if (!r || r->get("error")) return;
    ms.push_back(r->num("ms_median").value_or(NAN));
    last = r;
  }
  double mid() const { return ms.empty() ? NAN : median(ms); }
  double lo() const { return ms.empty() ? NAN : *std::min_element(ms.begin(), ms.end()); }
  double hi() const { return ms.empty() ? NAN : *std::max_element(ms.begin(), ms.end()); }
  std::string spread() const {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f [%.3f-%.3f]", mid(), lo(), hi());
    return buf;
  }
};

}  // namespace

int compareV3(const std::vector<BenchScene>& scenes, const std::filesystem::path& program, int rounds, int threads,
              const std::vector<int>& substeps, bool json) {
  if (!std::filesystem::exists(program)) {
    std::fprintf(stderr, "bench: no Box2D v3 peer program at %s (--v3 PATH or RIGIDLAB_V3_BENCH)\n", program.c_str());
    return kExitUsage;
  }
  const std::string quoted = "'" + program.string() + "' ";
  if (!json)
  {
    // With --v3-threads 1 there is one v3 column and one ratio.
    const std::string many_head = "v3 " + std::to_string(threads) + " threads", many_ratio = "/v3 " + std::to_string(threads) + "T";
    if (threads > 1)
      std::printf("%-14s %-26s %-26s %-26s %7s %7s   %-44s %s\n", "scene", "rigidlab ms [min-max]", "v3 1 thread",
                  many_head.c_str(), "/v3", many_ratio.c_str(), "rigidlab", "Box2D v3");
    else
      std::printf("%-14s %-26s %-26s %7s   %-44s %s\n", "scene", "rigidlab ms [min-max]", "v3 1 thread", "/v3",
                  "rigidlab", "Box2D v3");
  }
  for (const BenchScene& s : scenes) {
    const std::string args = v3Arguments(s);
    if (args.empty()) {
      if (!json) std::printf("%-14s (Box2D v3 has no such scene)\n", s.name.c_str());
      continue;
    }
    std::vector<Series> ours(substeps.size());
    Series one, many;
    WorldDef& settings = benchSettings();
    const int default_substeps = settings.substeps;
    for (int r = 0; r < rounds; ++r) {  // alternated, so that a change in load hits every configuration
      std::fprintf(stderr, "bench: %s round %d/%d ...\n", s.name.c_str(), r + 1, rounds);
      for (size_t k = 0; k < substeps.size(); ++k) {
        settings.substeps = substeps[k];
        ours[k].add(parseJson(runIsolated(s, 1)));
      }
      settings.substeps = default_substeps;
      one.add(runProgram(quoted + args + " --reps=1"));
      if (threads > 1) many.add(runProgram(quoted + args + " --reps=1 --workers=" + std::to_string(threads)));
    }
    if (!one.last) {
      std::fprintf(stderr, "bench: %s: the Box2D v3 program gave no result (%s%s)\n", s.name.c_str(), quoted.c_str(),
                   args.c_str());
      continue;
    }
    for (size_t k = 0; k < substeps.size(); ++k) {
      const Series& mine = ours[k];
      const double r1 = mine.mid() / one.mid(), r2 = mine.mid() / many.mid();
      if (json) {
        std::printf("{\"engine\": \"rigidlab\", \"compare\": \"box2d_v3\", \"name\": \"%s\", \"substeps\": %d, "
                    "\"rounds\": %d, \"ms\": %s, \"ms_min\": %s, \"ms_max\": %s, \"v3_ms\": %s, \"v3_ms_min\": %s, "
                    "\"v3_ms_max\": %s, \"v3_threads\": %d, \"v3_mt_ms\": %s, \"v3_mt_ms_min\": %s, \"v3_mt_ms_max\": %s, "
                    "\"ratio\": %s, \"ratio_mt\": %s, \"metrics\": %s, \"v3_metrics\": %s}\n",
                    s.name.c_str(), substeps[k], rounds, fmt(mine.mid()).c_str(), fmt(mine.lo()).c_str(),
                    fmt(mine.hi()).c_str(), fmt(one.mid()).c_str(), fmt(one.lo()).c_str(), fmt(one.hi()).c_str(), threads,
                    fmt(many.mid()).c_str(), fmt(many.lo()).c_str(), fmt(many.hi()).c_str(), fmt(r1).c_str(),
                    fmt(r2).c_str(), mine.last && mine.last->get("metrics") ? mine.last->get("metrics")->dump().c_str() : "{}",
                    one.last->get("metrics") ? one.last->get("metrics")->dump().c_str() : "{}");
      } else {
        const std::string label = substeps.size() > 1 ? s.name + " @" + std::to_string(substeps[k]) : s.name;
        const std::string ours_quality = mine.last ? quality(*mine.last) : "", v3_quality = quality(*one.last);
        if (threads > 1)
          std::printf("%-14s %-26s %-26s %-26s %6.2fx %6.2fx   %-44s %s\n", label.c_str(), mine.spread().c_str(),
                      one.spread().c_str(), many.spread().c_str(), r1, r2, ours_quality.c_str(), v3_quality.c_str());
        else
          std::printf("%-14s %-26s %-26s %6.2fx   %-44s %s\n", label.c_str(), mine.spread().c_str(),
                      one.spread().c_str(), r1, ours_quality.c_str(), v3_quality.c_str());
      }
    }
    std::fflush(stdout);
  }
  return kExitOk;
}

}  // namespace rigidlab::app

// rigidlab against Box2D 2.4.1, Chipmunk 7 and Box2D v3 on the same scenes (bench_compare.h).
#include "bench_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <sys/wait.h>

#include "bench_run.h"
#include "cli.h"
#include "commands.h"

namespace rigidlab::app {
namespace {

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

// The peer program's arguments for one of rigidlab's scenes, or "" if it has no such scene.
std::string peerArguments(const BenchScene& s) {
  const std::string steps = " --steps=" + std::to_string(s.steps);
  if (isSuiteScene(s.kind)) return s.kind + steps;
  if (s.kind == "pyramid" || s.kind == "stack" || s.kind == "rain") return s.kind + " --n=" + std::to_string(s.n) + steps;
  if (s.kind == "massratio") return "massratio --top=heavy --heavy-half=0.5 --heavy-mass=100" + steps;
  if (s.kind == "bullet") return "bullet --n=1" + steps;
  return "";
}

// The program's last output line as JSON; `timed_out` tells whether it was stopped after
// `timeout_s` seconds (0: no limit) by coreutils' timeout, which exits with 124 then.
std::optional<JsonValue> runProgram(const std::string& command, int timeout_s, bool& timed_out) {
  const std::string limited = timeout_s > 0 ? "timeout " + std::to_string(timeout_s) + " " + command : command;
  FILE* pipe = popen((limited + " 2>/dev/null").c_str(), "r");
  timed_out = false;
  if (!pipe) return std::nullopt;
  std::string out;
  char buf[1 << 16];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  timed_out = timeout_s > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 124;
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
  add("escaped", "escaped", "%.0f");  // compounds, junkyard, washer: bodies out of the container
  return out;
}

constexpr double kSlowPeer = 5.0;
constexpr int kPeersMissingPackages = 3;  // engine/peers/run.sh's exit status

struct Series {
  std::vector<double> ms;
  std::optional<JsonValue> last;
  bool timed_out = false;  // stopped by --peer-timeout: no result, and not run again
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

std::vector<PeerProgram> buildPeerPrograms(const std::filesystem::path& dir, const std::filesystem::path& build_dir) {
  const std::filesystem::path script = dir / "run.sh";
  if (!std::filesystem::exists(script))
    throw UsageError("bench: no peer programs at " + dir.string() + " (no run.sh there; use --peers DIR)");
  std::fprintf(stderr, "bench: building the peer programs (%s) in %s ...\n", dir.c_str(), build_dir.c_str());
  const std::string command = "'" + script.string() + "' --build-only '" + build_dir.string() + "' >&2";
  const int status = std::system(command.c_str());
  // run.sh installs nothing: without the peers' packages it has named them and the command that
  // installs them (exit status 3).
  if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == kPeersMissingPackages)
    throw std::runtime_error("bench: --compare needs the packages named above; nothing was installed");
  if (status != 0) throw std::runtime_error("bench: building the peer programs failed: " + command);
  return {{"Box2D 2.4.1", (build_dir / "box2d_bench").string(), ""},
          {"Chipmunk 7", (build_dir / "chipmunk_bench").string(), ""}};
}

std::vector<PeerProgram> v3Programs(const std::filesystem::path& program, int threads) {
  if (!std::filesystem::exists(program))
    throw UsageError("bench: no Box2D v3 peer program at " + program.string() + " (--v3 PATH or RIGIDLAB_V3_BENCH)");
  std::vector<PeerProgram> out{{"Box2D v3, 1 thread", program.string(), ""}};
  if (threads > 1)
    out.push_back({"Box2D v3, " + std::to_string(threads) + " threads", program.string(), " --workers=" + std::to_string(threads)});
  return out;
}

int comparePeers(const std::vector<BenchScene>& scenes, const std::vector<PeerProgram>& peers, int rounds,
                 const std::vector<int>& substeps, int timeout_s, bool json) {
  for (const BenchScene& s : scenes) {
    const std::string args = peerArguments(s);
    if (args.empty()) {
      if (!json) std::printf("%s: the peers have no such scene\n", s.name.c_str());
      continue;
    }
    std::vector<Series> ours(substeps.size()), theirs(peers.size());
    WorldDef& settings = benchSettings();
    const int default_substeps = settings.substeps;
    for (int r = 0; r < rounds; ++r) {  // alternated, so that a change in load hits every configuration
      std::fprintf(stderr, "bench: %s round %d/%d ...\n", s.name.c_str(), r + 1, rounds);
      for (size_t k = 0; k < substeps.size(); ++k) {
        settings.substeps = substeps[k];
        ours[k].add(parseJson(runIsolated(s, 1)));
      }
      settings.substeps = default_substeps;
      double slowest_ours = 0.0;
      for (const Series& x : ours) slowest_ours = std::max(slowest_ours, x.mid());
      for (size_t p = 0; p < peers.size(); ++p) {
        // A peer five times slower than every rigidlab row runs in the first round only: the
        // load's ±20 % cannot change what its ratio says, and its rounds would take most of the run.
        if (theirs[p].timed_out || (r > 0 && theirs[p].last && theirs[p].mid() > kSlowPeer * slowest_ours)) continue;
        bool timed_out = false;
        theirs[p].add(runProgram("'" + peers[p].program + "' " + args + " --reps=1" + peers[p].extra, timeout_s, timed_out));
        theirs[p].timed_out = timed_out;
      }
    }
    // A peer stopped by the time limit took at least the limit over the steps per step.
    const double at_least_ms = 1000.0 * timeout_s / s.steps;
    for (size_t p = 0; p < peers.size(); ++p)
      if (!theirs[p].last && !theirs[p].timed_out)
        std::fprintf(stderr, "bench: %s: %s gave no result ('%s' %s --reps=1%s)\n", s.name.c_str(), peers[p].label.c_str(),
                     peers[p].program.c_str(), args.c_str(), peers[p].extra.c_str());
    const auto metrics = [](const Series& x) {
      return x.last && x.last->get("metrics") ? x.last->get("metrics")->dump() : std::string("{}");
    };
    if (json) {
      for (size_t k = 0; k < substeps.size(); ++k) {
        std::string list;
        for (size_t p = 0; p < peers.size(); ++p) {
          const Series& x = theirs[p];
          if (x.timed_out) {
            list += std::string(p ? ", " : "") + "{\"engine\": \"" + peers[p].label + "\", \"timed_out_s\": " +
                    std::to_string(timeout_s) + ", \"ms_at_least\": " + fmt(at_least_ms) +
                    ", \"ratio_at_most\": " + fmt(ours[k].mid() / at_least_ms) + "}";
            continue;
          }
          list += std::string(p ? ", " : "") + "{\"engine\": \"" + peers[p].label + "\", \"ms\": " + fmt(x.mid()) +
                  ", \"ms_min\": " + fmt(x.lo()) + ", \"ms_max\": " + fmt(x.hi()) +
                  ", \"rounds\": " + std::to_string(x.ms.size()) +
                  ", \"ratio\": " + fmt(ours[k].mid() / x.mid()) + ", \"metrics\": " + metrics(x) + "}";
        }
        std::printf("{\"engine\": \"rigidlab\", \"name\": \"%s\", \"substeps\": %d, \"rounds\": %d, \"ms\": %s, "
                    "\"ms_min\": %s, \"ms_max\": %s, \"metrics\": %s, \"peers\": [%s]}\n",
                    s.name.c_str(), substeps[k], rounds, fmt(ours[k].mid()).c_str(), fmt(ours[k].lo()).c_str(),
                    fmt(ours[k].hi()).c_str(), metrics(ours[k]).c_str(), list.c_str());
      }
    } else {
      // A block per scene: rigidlab's rows, then each peer with rigidlab ÷ peer for each of
      // rigidlab's rows in their order.
      std::printf("\n%s (median ms per step of %d round%s [min-max])\n", s.name.c_str(), rounds, rounds == 1 ? "" : "s");
      for (size_t k = 0; k < substeps.size(); ++k) {
        const std::string label = "rigidlab, " + std::to_string(substeps[k]) + " sub-steps";
        std::printf("  %-22s %-28s %-20s %s\n", label.c_str(), ours[k].spread().c_str(), "",
                    ours[k].last ? quality(*ours[k].last).c_str() : "no result");
      }
      for (size_t p = 0; p < peers.size(); ++p) {
        const Series& x = theirs[p];
        if (x.timed_out) {
          std::string ratios = "rigidlab/peer";
          for (size_t k = 0; k < substeps.size(); ++k) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%s < %.2f", k ? "," : "", ours[k].mid() / at_least_ms);
            ratios += buf;
          }
          char took[64];
          std::snprintf(took, sizeof took, "> %.3f (stopped after %d s)", at_least_ms, timeout_s);
          std::printf("  %-22s %-28s %-20s\n", peers[p].label.c_str(), took, ratios.c_str());
          continue;
        }
        std::string ratios = "rigidlab/peer";
        for (size_t k = 0; k < substeps.size(); ++k) {
          char buf[32];
          std::snprintf(buf, sizeof buf, "%s %.2f", k ? "," : "", ours[k].mid() / x.mid());
          ratios += buf;
        }
        const std::string label = peers[p].label + (x.last && x.ms.size() == 1 && rounds > 1 ? " (1 round)" : "");
        std::printf("  %-22s %-28s %-20s %s\n", label.c_str(), x.last ? x.spread().c_str() : "no result",
                    x.last ? ratios.c_str() : "", x.last ? quality(*x.last).c_str() : "");
      }
    }
    std::fflush(stdout);
  }
  return kExitOk;
}

}  // namespace rigidlab::app

// rigidlab run / rigidlab check: headless runs of a scene (the runner of scripted regression scenes).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli.h"
#include "commands.h"
#include "headless_run.h"
#include "report.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene.h"
#include "rigidlab/lua/scene_text.h"
#include "rigidlab/world_snapshot.h"
#include "state_file.h"

namespace rigidlab::app {
namespace {

constexpr const char* kRunHelp = R"(usage: rigidlab run SCENE.lua [options]

Runs a scene headless: PopulateWorld, then steps (calling OnStep after each), then Check.

  --time T          run until the simulation time reaches T seconds (default: the scene's
                    `duration`, else 10 s). Whole steps of dt are taken while they fit; if a
                    remainder is left, one last shorter step lands exactly on T.
  --steps N         run exactly N steps of dt instead (--time 0 / --steps 0: the state right
                    after PopulateWorld)
  --dt H            step size in seconds (overrides the scene's dt)
  --integrator NAME euler | semi_implicit_euler | rk4 (overrides the scene's)
  --iterations K    contact solver iterations (overrides the scene's)
  --threads N       threads a step runs on: 0 the machine's cores, 1 serial (the default); the
                    same bits whatever N
  --json            print exactly one JSON document on stdout (logs go to stderr):
                    {"time", "steps", "bodies":[{"id","name","static","position","angle",
                    "velocity","angular_velocity"}], "energy":{"kinetic","potential"}, "check"}
  --trace FILE.csv  write time,id,name,x,y,angle,vx,vy,omega for every body ...
  --trace-every K   ... every K steps (default 1), plus the initial and the final state
  --quiet           no summary (errors and the scene's print output still appear)
  --save-state FILE write the whole simulation state at the end of the run (before Check) to
                    FILE, whose folder must exist: a snapshot naming the scene file and its dt
                    (docs/testing.md "Snapshots"), e.g. to attach to a bug report
  --load-state FILE load the scene the snapshot names (or SCENE, which must be the same file
                    unless --force), run PopulateWorld, put the world in the snapshot's state,
                    then continue: --time T runs until t = T (default: the scene's duration),
                    --steps N runs N more steps. The steps after a resume give the same bits as
                    the uninterrupted run; the scene's Lua variables start as after PopulateWorld,
                    then as its LoadState sets them from what its SaveState saved. A state file
                    is at most 256 MiB
  --force           with --load-state: accept a snapshot of another scene file

A run may take at most 10000000 steps (--steps, or --time / the scene's duration divided by
dt): a longer one is refused before it starts.

Exit status: 0 success, 1 scene error (in any hook, SaveState and LoadState included, or a dt of
the scene's that asks for too many steps) or failed Check, 2 usage error, 3 the run blew up: the
NaN firewall froze a body or the energy became non-finite (listed as "incidents" in the summary
and the JSON), unless the scene sets scene.expect_incidents = true.
)";

constexpr const char* kCheckHelp = R"(usage: rigidlab check SCENE.lua

Loads the scene and runs PopulateWorld without simulating: reports the first problem (syntax,
bad value, unknown option, ...) as file:line: function: message. Exit status 0 if the scene
loads, 1 if not, 2 for a usage error.
)";

std::unique_ptr<lua::Scene> loadOrReport(const std::string& path) {
  try {
    return lua::Scene::loadFile(path);
  } catch (const lua::SceneError& e) {
    std::fprintf(stderr, "%s\n", sceneErrorText(e).c_str());
  }
  return nullptr;
}

// Prints progress on a terminal for runs that take more than a couple of seconds.
class Progress {
 public:
  explicit Progress(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}
  void update(double t, double total) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::seconds(1)) return;
    last_ = now;
    shown_ = true;
    std::fprintf(stderr, "\rrun: t = %.3f of %.3f s (%.0f%%)   ", t, total, total > 0 ? 100.0 * t / total : 100.0);
  }
  ~Progress() {
    if (shown_) std::fprintf(stderr, "\r%60s\r", "");
  }

 private:
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

struct StateLabel {
  std::string scene;
  std::optional<double> dt;
};

// Reads Scene::snapshot's label: the scene file and its dt; any other label is taken as the file.
StateLabel parseStateLabel(const std::string& label) {
  StateLabel out;
  if (!label.starts_with("scene: ")) {
    out.scene = label;
    return out;
  }
  size_t at = 0;
  while (at < label.size()) {
    size_t end = label.find('\n', at);
    if (end == std::string::npos) end = label.size();
    const std::string line = label.substr(at, end - at);
    if (line.starts_with("scene: ")) out.scene = line.substr(7);
    if (line.starts_with("dt: ")) {
      char* stop = nullptr;
      const double dt = std::strtod(line.c_str() + 4, &stop);
      if (stop && *stop == '\0' && dt > 0 && std::isfinite(dt)) out.dt = dt;
    }
    at = end + 1;
  }
  return out;
}

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec)) return std::filesystem::equivalent(a, b, ec);
  return std::filesystem::path(a).lexically_normal() == std::filesystem::path(b).lexically_normal();
}

}  // namespace

int runCommand(const std::vector<std::string>& argv) {
  const Args args("run", argv,
                  {"time", "steps", "dt", "integrator", "iterations", "threads", "trace", "trace-every", "save-state", "load-state"},
                  {"json", "quiet", "force"});
  if (args.help()) {
    std::fputs(kRunHelp, stdout);
    return kExitOk;
  }
  const auto load_state = args.value("load-state");
  if (args.flag("force") && !load_state) throw UsageError("run: --force goes with --load-state");
  if (args.positional().size() != 1 && !(load_state && args.positional().empty()))
    throw UsageError("run: expected one scene file, got " + std::to_string(args.positional().size()));
  if (args.value("time") && args.value("steps")) throw UsageError("run: give --time or --steps, not both");
  const auto time = args.number("time");
  if (time && *time < 0) throw UsageError("run: --time must be >= 0");
  const auto steps = args.integer("steps", 0);
  const auto dt = args.number("dt");
  if (dt && !(*dt > 0)) throw UsageError("run: --dt must be > 0");
  std::optional<Integrator> integrator;
  if (const auto name = args.value("integrator")) {
    integrator = parseIntegrator(*name);
    if (!integrator) throw UsageError("run: --integrator must be one of " + integratorNames() + ", got '" + *name + "'");
  }
  const auto iterations = args.integer("iterations", 1);
  const auto threads = args.integer("threads", 0);
  if (threads && *threads > 64) throw UsageError("run: --threads must be at most 64");
  const auto trace_every = args.integer("trace-every", 1).value_or(1);
  const bool json = args.flag("json");

  // --load-state: the snapshot first, for the scene it names.
  WorldSnapshot loaded;
  StateLabel label;
  if (load_state) {
    try {
      loaded = readStateFile(*load_state);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "run: --load-state: %s\n", e.what());  // the message starts with the file
      return kExitUsage;
    }
    label = parseStateLabel(loaded.label());
    if (args.positional().empty() && label.scene.empty()) {
      std::fprintf(stderr, "run: --load-state %s names no scene file: give it\n", load_state->c_str());
      return kExitUsage;
    }
    if (!args.positional().empty() && !args.flag("force") && !sameFile(args.positional()[0], label.scene)) {
      std::fprintf(stderr, "run: --load-state %s is a snapshot of %s, not of %s (--force to load it anyway)\n",
                   load_state->c_str(), label.scene.c_str(), args.positional()[0].c_str());
      return kExitUsage;
    }
  }
  const std::string scene_path = args.positional().empty() ? label.scene : args.positional()[0];
  std::unique_ptr<lua::Scene> scene = loadOrReport(scene_path);
  if (!scene) return kExitSceneError;
  World& world = scene->world();
  if (load_state) {
    try {
      scene->restore(loaded);
    } catch (const lua::SceneError& e) {
      std::fprintf(stderr, "run: --load-state %s: %s\n", load_state->c_str(), e.what());
      return kExitSceneError;
    }
    if (label.dt) scene->setDt(*label.dt);
  }
  // Command-line settings override the scene's (applied after PopulateWorld, which may set them,
  // and after a restored state, which carries them).
  if (dt) scene->setDt(*dt);
  if (integrator) world.setIntegrator(*integrator);
  if (iterations) world.setIterations(static_cast<int>(std::min(*iterations, 10000L)));
  if (threads) world.setThreads(static_cast<int>(*threads));

  std::string refused;
  std::optional<RunLength> length = runLength(*scene, time, steps, refused);
  if (!length) {
    std::fprintf(stderr, "run: %s\n", refused.c_str());
    // Whose numbers asked for too many steps: --steps and --dt are the command line's; with the
    // scene's own dt, --time is at fault only if the scene's own length would have been allowed
    // (a dt of 1e-12 is the scene's error whatever --time says).
    std::string ignored;
    const bool command_line = steps || dt || (time && runLength(*scene, std::nullopt, std::nullopt, ignored));
    return command_line ? kExitUsage : kExitSceneError;
  }
  // Resumed: until the same end time, by the steps the uninterrupted run would still take.
  if (load_state && !steps) length->full_steps = std::max(0L, length->full_steps - world.stepCount());

  std::unique_ptr<Trace> trace;
  try {
    if (const auto path = args.value("trace")) trace = std::make_unique<Trace>(*path);
    if (trace) trace->write(world);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run: %s\n", e.what());
    return kExitUsage;
  }

  RunInfo info;
  info.expect_incidents = scene->settings().expect_incidents;
  try {
    Progress progress(!json && !args.flag("quiet"));
    const double end_time =
        world.time() + static_cast<double>(length->full_steps) * scene->settings().dt + length->last;
    stepScene(*scene, *length, info, [&] {
      if (trace && (info.steps % trace_every == 0 || info.steps == length->total())) trace->write(world);
      progress.update(world.time(), end_time);
    });
  } catch (const lua::SceneError& e) {
    std::fprintf(stderr, "%s\n", sceneErrorText(e).c_str());
    return kExitSceneError;
  }
  if (const auto path = args.value("save-state")) {
    WorldSnapshot state;
    try {
      state = scene->snapshot();  // runs the scene's SaveState: its errors are the scene's
    } catch (const lua::SceneError& e) {
      std::fprintf(stderr, "%s\n", sceneErrorText(e).c_str());
      return kExitSceneError;
    }
    try {
      writeStateFile(*path, state);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "run: --save-state: %s\n", e.what());  // the message names the file
      return kExitUsage;
    }
  }

  int status = kExitOk;
  if (const auto failure = runCheck(*scene, info)) {
    std::fprintf(stderr, "%s\n", failure->c_str());
    status = kExitSceneError;
  }
  if (status == kExitOk && !info.expect_incidents && !incidents(world, info).empty()) status = kExitIncidents;
  if (json) {
    printJson(stdout, *scene, info);
  } else if (!args.flag("quiet")) {
    printSummary(stdout, *scene, info);
  }
  return status;
}

int checkCommand(const std::vector<std::string>& argv) {
  const Args args("check", argv, {}, {});
  if (args.help()) {
    std::fputs(kCheckHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 1) throw UsageError("check: expected one scene file");
  std::unique_ptr<lua::Scene> scene = loadOrReport(args.positional()[0]);
  if (!scene) return kExitSceneError;
  const World& w = scene->world();
  std::string hooks;
  for (const auto& [name, present] : {std::pair{"OnStep", scene->hasOnStep()}, {"Check", scene->hasCheck()},
                                     {"OnKey", scene->hasOnKey()}, {"OnDraw", scene->hasOnDraw()}})
    if (present) hooks += std::string(hooks.empty() ? "" : ", ") + name;
  std::printf("%s: ok: \"%s\", %d bodies, %zu forces; hooks: %s\n", args.positional()[0].c_str(),
              lua::displayText(scene->settings().title, lua::kTitleBytes).c_str(), w.bodyCount(), w.forceIds().size(),
              hooks.empty() ? "none" : hooks.c_str());
  return kExitOk;
}

int headlessPreview(const std::string& scene_path, const std::string& reason) {
  constexpr double kSeconds = 3.0;
  std::fprintf(stderr, "rigidlab: %s; running %s headless for %g s of simulated time instead (see `rigidlab run --help`).\n",
               reason.c_str(), scene_path.c_str(), kSeconds);
  return runCommand({scene_path, "--time", std::to_string(kSeconds)});
}

}  // namespace rigidlab::app

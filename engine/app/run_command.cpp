// rigidlab run / rigidlab check: headless runs of a scene (the runner of scripted regression scenes).
#include <unistd.h>

#include <algorithm>
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
  --json            print exactly one JSON document on stdout (logs go to stderr):
                    {"time", "steps", "bodies":[{"id","name","static","position","angle",
                    "velocity","angular_velocity"}], "energy":{"kinetic","potential"}, "check"}
  --trace FILE.csv  write time,id,name,x,y,angle,vx,vy,omega for every body ...
  --trace-every K   ... every K steps (default 1), plus the initial and the final state
  --quiet           no summary (errors and the scene's print output still appear)

A run may take at most 10000000 steps (--steps, or --time / the scene's duration divided by
dt): a longer one is refused before it starts.

Exit status: 0 success, 1 scene error or failed Check, 2 usage error, 3 the run blew up: the
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

}  // namespace

int runCommand(const std::vector<std::string>& argv) {
  const Args args("run", argv, {"time", "steps", "dt", "integrator", "iterations", "trace", "trace-every"},
                  {"json", "quiet"});
  if (args.help()) {
    std::fputs(kRunHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 1) throw UsageError("run: expected one scene file, got " + std::to_string(args.positional().size()));
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
  const auto trace_every = args.integer("trace-every", 1).value_or(1);
  const bool json = args.flag("json");

  std::unique_ptr<lua::Scene> scene = loadOrReport(args.positional()[0]);
  if (!scene) return kExitSceneError;
  World& world = scene->world();
  // Command-line settings override the scene's (applied after PopulateWorld, which may set them).
  if (dt) scene->setDt(*dt);
  if (integrator) world.setIntegrator(*integrator);
  if (iterations) world.setIterations(static_cast<int>(std::min(*iterations, 10000L)));

  std::string refused;
  const std::optional<RunLength> length = runLength(*scene, time, steps, refused);
  if (!length) {
    std::fprintf(stderr, "run: %s\n", refused.c_str());
    return time || steps || dt ? kExitUsage : kExitSceneError;  // the command line's or the scene's settings
  }

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

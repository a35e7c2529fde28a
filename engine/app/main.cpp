// rigidlab: the command-line program. `rigidlab [SCENE.lua]` opens the sandbox; subcommands run
// scenes headless, benchmark, and report accuracy and stability.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "rigidlab/lua/scene.h"
#ifdef RIGIDLAB_HAS_SANDBOX
#include "rigidlab/sandbox/sandbox.h"
#endif

namespace rigidlab::app {
namespace {

constexpr const char* kHelp = R"(rigidlab: a real-time 2D rigid-body physics engine with Lua scenes

usage:
  rigidlab [SCENE.lua] [--frames N --screenshot FILE.png]
                           open the sandbox on SCENE (default: scripts/scenes/playground.lua);
                           without a display, run the scene headless for a few seconds instead
  rigidlab run SCENE.lua [--time T | --steps N] [--dt H] [--integrator NAME] [--json] ...
              [--save-state FILE] [--load-state FILE]
                           run a scene headless and print a summary or JSON; runs its Check
  rigidlab check SCENE.lua load and validate a scene without simulating
  rigidlab bench [SCENE...] [--json] [--reps R]
                           time benchmark scenes (ms per step, stages, memory)
  rigidlab accuracy [--out DIR] [--scenes ...] [--integrators ...]
                           error against run time for every integrator and step size
  rigidlab stability [--out DIR]
                           stiff and extreme cases: where the simulation stays stable
  rigidlab test [PATH...] [-j N] [--junit FILE] [--shard K/N] [--filter PATTERN] [--update]
                           run every scene that defines Check, in parallel; golden trajectories
  rigidlab help            this text; `rigidlab COMMAND --help` for a command's options

Exit status: 0 success, 1 scene error or failed check, 2 usage error, 3 a run that blew up
(`rigidlab run --help`).
)";

std::string defaultScene() { return (lua::scriptsDirectory() / "scenes" / "playground.lua").string(); }

int sandbox(const std::vector<std::string>& argv) {
  const Args args("rigidlab", argv, {"frames", "screenshot"}, {});
  if (args.help()) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() > 1) throw UsageError("expected at most one scene file");
  const std::string scene = args.positional().empty() ? defaultScene() : args.positional()[0];
  const auto frames = args.integer("frames", 1);
  const auto screenshot = args.value("screenshot");
  if (screenshot && !frames) throw UsageError("--screenshot needs --frames N (the frame to capture)");
#ifdef RIGIDLAB_HAS_SANDBOX
  sandbox::SandboxOptions options;
  if (!args.positional().empty()) options.scene = scene;
  if (frames) options.frames = static_cast<int>(*frames);
  if (screenshot) options.screenshot = *screenshot;
  const int status = sandbox::runSandbox(options);
  if (status != sandbox::kNoDisplay) return status;
  if (screenshot) {
    std::fprintf(stderr, "rigidlab: no display available, cannot take a screenshot\n");
    return kExitSceneError;
  }
  return headlessPreview(scene, "no display available");
#else
  if (screenshot) {
    std::fprintf(stderr, "rigidlab: this build has no sandbox (RIGIDLAB_SANDBOX=OFF), cannot take a screenshot\n");
    return kExitUsage;
  }
  return headlessPreview(scene, "this build has no sandbox (RIGIDLAB_SANDBOX=OFF)");
#endif
}

int dispatch(const std::vector<std::string>& argv) {
  if (argv.empty()) return sandbox(argv);
  const std::string& command = argv[0];
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (command == "help" || command == "--help" || command == "-h") {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (command == "run") return runCommand(rest);
  if (command == "check") return checkCommand(rest);
  if (command == "bench") return benchCommand(rest);
  if (command == "accuracy") return accuracyCommand(rest);
  if (command == "stability") return stabilityCommand(rest);
  if (command == "test") return testCommand(rest);
  if (command.starts_with("-") || command.ends_with(".lua")) return sandbox(argv);
  throw UsageError("unknown command '" + command + "'");
}

}  // namespace
}  // namespace rigidlab::app

int main(int argc, char** argv) {
  using namespace rigidlab::app;
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    return dispatch(args);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "rigidlab: %s\n(see `rigidlab help`)\n", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rigidlab: %s\n", e.what());
    return kExitSceneError;
  }
}

// rigidlab: the command-line program. `rigidlab [SCENE.lua]` opens the sandbox; subcommands run
// scenes headless, benchmark, and report accuracy and stability.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "rigidlab/lua/closest_name.h"
#include "rigidlab/lua/scene.h"
#include "version.h"
#ifdef RIGIDLAB_HAS_SANDBOX
#include "rigidlab/sandbox/sandbox.h"
#endif

namespace rigidlab::app {
namespace {

constexpr const char* kHelp = R"(rigidlab: a real-time 2D rigid-body physics engine with Lua scenes

usage:
  rigidlab [SCENE.lua] [--size WxH] [--frames N [--screenshot FILE.png] [--layout-file FILE]]
                           open the sandbox on SCENE (default: scripts/scenes/playground.lua) in a
                           window of W x H pixels (default 1280x720); without a display, run the
                           scene headless for a few seconds instead. --frames N: stop after N frames
                           (1/60 s of simulation each), writing the last one's picture and where
                           its panels were
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
  rigidlab --version, -V   the version, the build type and the git commit it was built from

Exit status: 0 success, 1 scene error or failed check, 2 usage error, 3 a run that blew up
(`rigidlab run --help`).
)";

std::string defaultScene() { return (lua::scriptsDirectory() / "scenes" / "playground.lua").string(); }

const std::vector<std::string> kCommands = {"run", "check", "bench", "accuracy", "stability", "test", "help"};
const std::vector<std::string> kSandboxValued = {"frames", "screenshot", "size", "layout-file"};
const std::vector<std::string> kSandboxFlags = {"version"};

int printVersion() {
  std::printf("%s\n", versionLine().c_str());
  return kExitOk;
}

// A word given where a scene file or a command was expected: "-x" or "-version" is a mistyped
// option, anything else a mistyped command (a scene is a .lua file).
[[noreturn]] void unknownWord(const std::string& word) {
  if (word.starts_with("-")) {
    const std::string name = word.substr(1);
    std::string hint;
    if (name.size() == 1) {  // -v for -V: the short options differ from it in case only
      hint = lua::closestName(name, {"V", "h"}, {.min_length = 1});
      if (!hint.empty()) hint = "-" + hint;
    } else {
      std::vector<std::string> all = kSandboxValued;
      all.insert(all.end(), kSandboxFlags.begin(), kSandboxFlags.end());
      all.push_back("help");
      hint = suggestion(name, all);
      if (!hint.empty()) hint = "--" + hint;
    }
    throw UsageError("unknown option " + word + (hint.empty() ? "" : " (did you mean " + hint + "?)"));
  }
  const std::string hint = suggestion(word, kCommands);
  throw UsageError("unknown command '" + word + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
}

int sandbox(const std::vector<std::string>& argv) {
  const Args args("", argv, kSandboxValued, kSandboxFlags);
  if (args.help()) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  const auto& words = args.positional();
  if (args.flag("version") || std::find(words.begin(), words.end(), "-V") != words.end()) return printVersion();
  for (const std::string& word : args.positional())
    if (word.starts_with("-") && word != "-") unknownWord(word);
  if (args.positional().size() > 1) throw UsageError("expected at most one scene file");
  const std::string scene = args.positional().empty() ? defaultScene() : args.positional()[0];
  const auto frames = args.integer("frames", 1);
  const auto screenshot = args.value("screenshot");
  if (screenshot && !frames) throw UsageError("--screenshot needs --frames N (the frame to capture)");
  const auto layout_file = args.value("layout-file");
  if (layout_file && !frames) throw UsageError("--layout-file needs --frames N (the frame to describe)");
  int width = 1280, height = 720;
  if (const auto size = args.value("size")) {
    char x = 0, rest = 0;
    if (std::sscanf(size->c_str(), "%d%c%d%c", &width, &x, &height, &rest) != 3 || x != 'x' || width < 64 ||
        height < 64 || width > 16384 || height > 16384)
      throw UsageError("--size must be WIDTHxHEIGHT in pixels, each 64 to 16384, got '" + *size + "'");
  }
#ifdef RIGIDLAB_HAS_SANDBOX
  sandbox::SandboxOptions options;
  if (!args.positional().empty()) options.scene = scene;
  if (frames) options.frames = static_cast<int>(*frames);
  if (screenshot) options.screenshot = *screenshot;
  if (layout_file) options.layout_file = *layout_file;
  options.width = width;
  options.height = height;
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
  if (command == "--version" || command == "-V") return printVersion();
  if (command == "run") return runCommand(rest);
  if (command == "check") return checkCommand(rest);
  if (command == "bench") return benchCommand(rest);
  if (command == "accuracy") return accuracyCommand(rest);
  if (command == "stability") return stabilityCommand(rest);
  if (command == "test") return testCommand(rest);
  if (command.starts_with("-") || command.ends_with(".lua")) return sandbox(argv);
  unknownWord(command);
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

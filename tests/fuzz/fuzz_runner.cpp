// libFuzzer target: the files and arguments `rigidlab test` and `rigidlab run` read besides scenes
// (issue 32). The first byte picks the input, the rest is it:
//   'a'  a `rigidlab test` command line, arguments separated by NUL bytes → testCommand with --list
//        over a scratch suite: option parsing, --filter globs, --shard, discovery (paths that would
//        leave the scratch folder are replaced by it)
//   's'  a scene file in the scratch suite → discovery (`rigidlab test --list`), which reads it
//   'f'  a state file → readStateFile (header first, within the size limit)
//   else a golden trajectory file → parseTrajectory, compareTrajectories with a recorded run, and
//        checkGolden of a scene beside it (within the size limit; the diff files go to the scratch
//        folder); a trajectory that parses must read back the same after formatTrajectory
// Only std::runtime_error (UsageError, SnapshotError, FileTooLarge, a parse error) may come out;
// nothing may crash, trip a sanitizer, or break the round trip.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "golden_trajectory.h"
#include "state_file.h"

using namespace rigidlab;
using namespace rigidlab::app;

namespace {

namespace fs = std::filesystem;

void write(const fs::path& file, std::string_view text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

// The scratch folder (the working directory from here on) and its suite: two scenes with Check,
// one without, one in a subfolder, one with a golden trajectory.
void makeScratch() {
  static bool made = false;
  if (made) return;
  made = true;
  char dir[] = "/tmp/rigidlab-fuzz-runner.XXXXXX";
  if (!mkdtemp(dir)) std::abort();
  fs::current_path(dir);
  fs::create_directories("suite/sub");
  fs::create_directories("suite/golden");
  write("suite/a.lua", "function PopulateWorld(world) end\nfunction Check(world) end\n");
  write("suite/none.lua", "function PopulateWorld(world) end\n");
  write("suite/sub/b.lua", "Check = function(world) end\nfunction PopulateWorld(world) end\n");
  write("suite/fz.lua", "scene = { golden = \"fz\" }\nfunction PopulateWorld(world) end\nfunction Check(world) end\n");
  // testCommand --list prints the scenes: not into libFuzzer's output.
  if (!std::freopen("/dev/null", "w", stdout)) std::abort();
}

Trajectory recorded() {
  Trajectory t{"fz.lua", 1.0 / 60, 20, 10, {}};
  for (long step : {0L, 10L, 20L}) {
    TrajectorySample s;
    s.step = step;
    s.time = static_cast<double>(step) / 60;
    s.bodies.push_back({1, "ground", 0, -0.5, 0, 0, 0, 0});
    s.bodies.push_back({2, "", 0.25, 3.0 - 0.01 * static_cast<double>(step), 0.1, 0, -1, 0.5});
    t.samples.push_back(std::move(s));
  }
  return t;
}

void commandLine(std::string_view bytes) {
  std::vector<std::string> args = {"--list"};  // first: no argument after it can stop it being a flag
  size_t start = 0;
  while (start <= bytes.size()) {
    const size_t end = std::min(bytes.find('\0', start), bytes.size());
    std::string arg(bytes.substr(start, end - start));
    if (arg.find('/') != std::string::npos || arg.find("..") != std::string::npos || arg == "~") arg = "suite";
    args.push_back(std::move(arg));
    start = end + 1;
    if (args.size() > 64) break;
  }
  (void)testCommand(args);
}

void golden(std::string_view bytes) {
  const std::string text(bytes);
  try {
    const Trajectory t = parseTrajectory(text, "fz.txt");
    const std::string once = formatTrajectory(t);
    const std::string twice = formatTrajectory(parseTrajectory(once, "fz.txt"));
    if (once != twice) {
      std::fprintf(stderr, "fuzz_runner: a golden trajectory does not read back the same after formatting\n");
      std::abort();
    }
    (void)compareTrajectories(t, recorded(), 0.0);
    (void)compareTrajectories(t, recorded(), 1e-6);
  } catch (const std::runtime_error&) {
  }
  write("suite/golden/fz.txt", bytes);
  (void)checkGolden("suite/fz.lua", "fz", recorded(), 0.0, "diff/fz");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  makeScratch();
  if (size == 0) return 0;
  const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0]) {
      case 'a':
        commandLine(bytes);
        break;
      case 's':
        write("suite/fz_scene.lua", bytes);
        (void)testCommand({"--list", "suite"});
        break;
      case 'f':
        write("state.snap", bytes);
        (void)readStateFile("state.snap");
        break;
      default:
        golden(bytes);
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}

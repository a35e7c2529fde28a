// Files the program reads, within their size limits (issue 32, docs/security.md "Files"): the size
// is checked before reading, reading stops past the limit whatever the size said (/dev/zero), a
// state file's header is read first, nothing is allocated in proportion to a hostile size field,
// and every refusal names the file, its size and the limit. Output files need their folder.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "golden_trajectory.h"
#include "rigidlab/lua/bounded_file.h"
#include "rigidlab/world.h"
#include "state_file.h"
#include "text_file.h"

using namespace rigidlab;
using namespace rigidlab::app;
namespace fs = std::filesystem;

namespace {

// A scratch folder for one test case, removed after it.
struct Scratch {
  fs::path dir;
  Scratch() {
    char name[] = "/tmp/rigidlab-files-test.XXXXXX";
    REQUIRE(mkdtemp(name));
    dir = name;
  }
  ~Scratch() { fs::remove_all(dir); }
  fs::path operator/(const std::string& name) const { return dir / name; }
};

void write(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary);
  out << bytes;
}

// A file of `bytes` bytes that takes no disk space (a hole), for sizes past the limits.
void sparse(const fs::path& file, uintmax_t bytes) {
  write(file, "");
  fs::resize_file(file, bytes);
}

// The process's peak resident memory so far [KiB] (VmHWM).
long peakKiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.starts_with("VmHWM:")) return std::stol(line.substr(6));
  return -1;
}

template <typename E, typename F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(no error)";
}

WorldSnapshot smallWorld() {
  World w;
  BodyDef ball;
  ball.shape = makeCircle(0.5);
  ball.position = {0, 3};
  w.createBody(ball);
  for (int i = 0; i < 10; ++i) w.step(1.0 / 60);
  return w.snapshot();
}

}  // namespace

TEST_CASE("files: a file over its limit is refused by its size before it is read, one at the limit is read") {
  Scratch s;
  write(s / "at.txt", std::string(1000, 'x'));
  CHECK(lua::readBoundedFile(s / "at.txt", 1000, "at.txt", "a test file").size() == 1000);
  write(s / "over.txt", std::string(1001, 'x'));
  CHECK(refusal<lua::FileTooLarge>([&] { lua::readBoundedFile(s / "over.txt", 1000, "over.txt", "a test file"); }) ==
        "over.txt: the file is 1001 bytes, more than the limit of 1000 bytes for a test file");
  // 5 GiB of hole: refused at once, nothing read.
  sparse(s / "huge.txt", uintmax_t{5} << 30);
  const long peak = peakKiB();
  CHECK(refusal<lua::FileTooLarge>([&] { lua::readBoundedFile(s / "huge.txt", size_t{4} << 20, "huge.txt", "a scene file"); }) ==
        "huge.txt: the file is 5368709120 bytes, more than the limit of 4 MiB for a scene file");
  CHECK(peakKiB() - peak < 8 * 1024);  // far below the 300 MB (the sanitizers' own allocations are a few MB)
  CHECK(refusal<lua::FileUnreadable>([&] { lua::readBoundedFile(s / "missing.txt", 10, "missing.txt", "x"); }) ==
        "missing.txt: cannot read the file (No such file or directory)");
  CHECK(refusal<lua::FileUnreadable>([&] { lua::readBoundedFile(s.dir, 10, "dir", "x"); }) ==
        "dir: cannot read the file (it is a folder)");
}

TEST_CASE("files: a device or a pipe is read no further than the limit, and a pipe without a writer does not block") {
  const long peak = peakKiB();
  CHECK(refusal<lua::FileTooLarge>([] { lua::readBoundedFile("/dev/zero", size_t{1} << 20, "/dev/zero", "a scene file"); }) ==
        "/dev/zero: the file holds more than the limit of 1 MiB for a scene file (read up to there)");
  CHECK(peakKiB() - peak < 8 * 1024);
  Scratch s;
  REQUIRE(mkfifo((s / "fifo").c_str(), 0600) == 0);
  CHECK(lua::readBoundedFile(s / "fifo", 100, "fifo", "a state file").empty());  // open() would wait for a writer
}

TEST_CASE("files: a state file is read header first: /dev/zero and an announced 300 MB are refused at once") {
  // The header (30 bytes) is all that is read of /dev/zero; it used to be read until 2.1 GB were
  // resident and the allocation failed.
  long peak = peakKiB();
  CHECK(refusal<SnapshotError>([] { readStateFile("/dev/zero"); }) ==
        "/dev/zero: snapshot: not a rigidlab snapshot (no \"RIGIDLAB-SNAPSHOT\" header)");
  CHECK(peakKiB() - peak < 8 * 1024);  // far below the 300 MB (the sanitizers' own allocations are a few MB)

  Scratch s;
  const std::string good = serializeSnapshot(smallWorld());
  // A valid header announcing 300 MB of state, with the bytes behind it: refused before they are read
  // (they used to peak at 608 MB before the checksum refused them).
  std::string header = good.substr(0, kSnapshotHeaderBytes);
  const uint64_t length = uint64_t{300} << 20;
  std::memcpy(header.data() + 22, &length, 8);  // little-endian, as the format says
  write(s / "announced.snap", header);
  fs::resize_file(s / "announced.snap", kSnapshotHeaderBytes + length + 8);
  peak = peakKiB();
  CHECK(refusal<lua::FileTooLarge>([&] { readStateFile((s / "announced.snap").string()); }) ==
        (s / "announced.snap").string() +
            ": the file is 314572838 bytes, more than the limit of 256 MiB for a state file");
  // The same header in a short file (or a pipe, whose size is not known): refused by the header.
  write(s / "header_only.snap", header);
  CHECK(refusal<lua::FileTooLarge>([&] { readStateFile((s / "header_only.snap").string()); }) ==
        (s / "header_only.snap").string() +
            ": the header announces a state of 314572838 bytes, more than the limit of 256 MiB for a state file");
  CHECK(peakKiB() - peak < 8 * 1024);  // far below the 300 MB (the sanitizers' own allocations are a few MB)
  // A state within the limit reads back; a truncated one is refused naming the file.
  write(s / "good.snap", good);
  CHECK(readStateFile((s / "good.snap").string()).stepCount() == 10);
  write(s / "cut.snap", good.substr(0, good.size() - 9));
  CHECK(refusal<SnapshotError>([&] { readStateFile((s / "cut.snap").string()); })
            .starts_with((s / "cut.snap").string() + ": snapshot: truncated or extended"));
}

TEST_CASE("files: a state is written only into a folder that exists, and read back") {
  Scratch s;
  const fs::path missing = s / "missing" / "deeper" / "x.snap";
  CHECK(refusal<std::runtime_error>([&] { writeStateFile(missing.string(), smallWorld()); }) ==
        missing.string() + ": cannot write the file: the folder " + (s / "missing" / "deeper").string() +
            " does not exist");
  CHECK_FALSE(fs::exists(s / "missing"));  // it used to make the folders, at the root too
  writeStateFile((s / "x.snap").string(), smallWorld());
  CHECK(readStateFile((s / "x.snap").string()).stepCount() == 10);
  // The folders the program owns are made.
  writeFile(s / "owned" / "a.txt", "text", Folders::Make);
  CHECK(fs::is_regular_file(s / "owned" / "a.txt"));
}

TEST_CASE("files: a golden trajectory over 64 MiB is refused before it is read, no diff is written") {
  Scratch s;
  fs::create_directories(s / "golden");
  write(s / "scene.lua", "");
  sparse(s / "golden" / "g.txt", uintmax_t{400} << 20);  // the 400 MB golden took rigidlab test past 2 GB
  Trajectory actual{"scene.lua", 0.01, 0, 1, {}};
  actual.samples.push_back({0, 0.0, {{1, "ball", 0, 1, 0, 0, 0, 0}}});
  const long peak = peakKiB();
  const auto mismatch = checkGolden(s / "scene.lua", "g", actual, 0.0, s / "diff");
  CHECK(peakKiB() - peak < 8 * 1024);  // far below the 300 MB (the sanitizers' own allocations are a few MB)
  REQUIRE(mismatch);
  CHECK(*mismatch == "cannot read the golden trajectory: " + (s / "golden" / "g.txt").string() +
                         ": the file is 419430400 bytes, more than the limit of 64 MiB for a golden trajectory");
  CHECK_FALSE(fs::exists(s / "diff"));
}

TEST_CASE("files: sampleBytesBound is at least what formatTrajectory writes, whatever the numbers and names") {
  Trajectory t{"s.lua", 0.01, 3, 1, {}};
  const double extremes[] = {-1.2345678901234567e-308, -DBL_MAX, 4.9e-324, -0.0, NAN, -INFINITY, 1.0 / 3.0};
  for (long step = 0; step < 3; ++step) {
    TrajectorySample sample{step * 1000000000000L, -1.2345678901234567e-300, {}};
    for (double x : extremes)
      sample.bodies.push_back({UINT32_MAX, std::string(256, '\x1b'), x, x, x, x, x, x});
    sample.bodies.push_back({1, "", 0, 0, 0, 0, 0, 0});
    t.samples.push_back(sample);
  }
  size_t bound = 0;
  for (const TrajectorySample& sample : t.samples) bound += sampleBytesBound(sample);
  Trajectory header_only = t;
  header_only.samples.clear();
  CHECK(formatTrajectory(t).size() - formatTrajectory(header_only).size() <= bound);
}

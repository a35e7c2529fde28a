// rigidlab test: finds the scenes that define Check, runs each in its own process (several at a
// time, each killed after a timeout) and reports them as lines, a summary and JUnit XML.
#include <fcntl.h>
#include <fnmatch.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "rigidlab/lua/bounded_file.h"
#include "rigidlab/lua/scene.h"
#include "test_case.h"
#include "test_report.h"
#include "text_file.h"

namespace rigidlab::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kTestHelp = R"(usage: rigidlab test [PATH...] [options]

Runs scenes as tests: every .lua file under each PATH (recursively) that defines a global
Check function, and every PATH that is a .lua file itself. Without PATH: scripts/scenes/,
tests/scenes/ and scenes/ of the current directory, those that exist. Files that start with
`---@meta` (editor annotations) are not scenes.

Each scene runs in its own process, as `rigidlab run SCENE` runs it: its duration and dt, the
memory cap of its Lua, the budget of every call into Lua, at most 10000000 steps; then Check;
then, if the scene sets scene.golden, the comparison with its golden trajectory. One line per
scene as it finishes (status, wall time, path; why it did not pass and the end of its output),
then a summary.

  -j N, --jobs N    scenes run at once (default: the number of cores)
  --timeout S       kill a scene still running after S seconds of wall time (default 120;
                    0: no limit); it is reported as TIMEOUT, an error
  --filter PATTERN  only the scenes whose path contains PATTERN; a PATTERN with * ? or [ is a
                    glob that must match the whole path instead (* also matches /)
  --shard K/N       only shard K of N (K from 1): the filtered scenes sorted by path, the one
                    at position i (from 0) in shard (i mod N) + 1; every scene is in one shard
  --junit FILE      also write the results as JUnit XML
  --update          record the golden trajectories (scene.golden) instead of comparing them
  --diff-dir DIR    where a scene whose golden trajectory differs writes expected.txt and
                    actual.txt: DIR/<scene path without .lua>/ (default rigidlab-test-diff)
  --list            print the scenes that would run, one per line, and run none

Statuses: PASS; FAIL: Check raised, the golden trajectory differs or is missing, or the run
blew up (NaN firewall, non-finite energy) without scene.expect_incidents; ERROR: the scene did
not load or a script error stopped it, or its process crashed; TIMEOUT: killed after --timeout;
SKIP: scene.skip = "reason". On a terminal a live line shows progress: [done/all] failures, eta.

Exit status: 0 every scene passed or was skipped, 1 a scene did not pass or no scene was found,
2 usage error. docs/testing.md has the file formats and how to run it in CI.
)";

// Far above what a scene of this repository takes (the slowest, playground: 0.13 s in a test run),
// yet a hung scene costs a CI job two minutes rather than the job's whole time limit.
constexpr double kDefaultTimeout = 120.0;
// A scene's output beyond this is dropped (a scene printing every step must not fill memory).
constexpr size_t kMaxLogBytes = size_t{1} << 20;
const std::vector<std::string> kDefaultPaths = {"scripts/scenes", "tests/scenes", "scenes"};

struct TestOptions {
  std::vector<std::string> paths;
  long jobs = 1;
  double timeout = kDefaultTimeout;  // 0: none
  std::optional<std::string> filter;
  long shard = 1, shards = 1;
  std::optional<std::string> junit;
  bool list = false;
  TestCaseOptions run;
};

long cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
}

// -j N and -jN are --jobs N (make's and ctest's spelling).
std::vector<std::string> jobsSpelledLong(const std::vector<std::string>& argv) {
  std::vector<std::string> out;
  for (const std::string& a : argv) {
    if (a == "-j") out.push_back("--jobs");
    else if (a.starts_with("-j") && a.size() > 2) out.push_back("--jobs=" + a.substr(2));
    else out.push_back(a);
  }
  return out;
}

std::pair<long, long> parseShard(const std::string& text) {
  const size_t slash = text.find('/');
  const auto whole = [](const std::string& s) -> long {
    if (s.empty() || s.size() > 9 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return 0;
    return std::stol(s);
  };
  const long k = slash == std::string::npos ? 0 : whole(text.substr(0, slash));
  const long n = slash == std::string::npos ? 0 : whole(text.substr(slash + 1));
  if (k < 1 || n < 1 || k > n) throw UsageError("test: --shard must be K/N with 1 <= K <= N, got '" + text + "'");
  return {k, n};
}

TestOptions parseOptions(const std::vector<std::string>& argv, bool& help) {
  const Args args("test", jobsSpelledLong(argv), {"jobs", "timeout", "filter", "shard", "junit", "diff-dir"},
                  {"update", "list"});
  help = args.help();
  TestOptions o;
  o.paths = args.positional();
  o.jobs = args.integer("jobs", 1).value_or(cores());
  o.timeout = args.number("timeout").value_or(kDefaultTimeout);
  if (o.timeout < 0) throw UsageError("test: --timeout must be >= 0 (0: no limit)");
  o.filter = args.value("filter");
  if (const auto shard = args.value("shard")) std::tie(o.shard, o.shards) = parseShard(*shard);
  o.junit = args.value("junit");
  o.list = args.flag("list");
  o.run.update = args.flag("update");
  o.run.diff_root = args.value("diff-dir").value_or("rigidlab-test-diff");
  return o;
}

std::string_view trimmed(std::string_view s) {
  s.remove_prefix(std::min(s.find_first_not_of(" \t"), s.size()));
  return s;
}

// A scene to test: a global Check is defined at the start of a line (`function Check(` or
// `Check = function`), as scenes write it; a file of editor annotations (---@meta) is not one. A
// file larger than a scene may be is not read: it is run, so that its refusal is reported.
bool definesCheck(const fs::path& file) {
  std::string text;
  try {
    text = readFile(file, lua::ScriptLimits{}.source_bytes, "a scene file");
  } catch (const lua::FileTooLarge&) {
    return true;
  } catch (const std::exception&) {
    return false;
  }
  if (text.starts_with("---@meta")) return false;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = trimmed(std::string_view(text).substr(start, end - start));
    start = end + 1;
    if (line.starts_with("function ") || line.starts_with("function\t")) {
      const std::string_view name = trimmed(line.substr(8));
      if (name.starts_with("Check") && trimmed(name.substr(5)).starts_with("(")) return true;
    } else if (line.starts_with("Check")) {
      const std::string_view assigned = trimmed(line.substr(5));
      if (assigned.starts_with("=") && trimmed(assigned.substr(1)).starts_with("function")) return true;
    }
  }
  return false;
}

// The scenes under the paths, sorted by path, each once.
std::vector<std::string> discover(const TestOptions& o) {
  std::vector<std::string> paths = o.paths;
  if (paths.empty()) {
    for (const std::string& p : kDefaultPaths)
      if (fs::is_directory(p)) paths.push_back(p);
    if (paths.empty()) throw UsageError("test: no PATH given and none of scripts/scenes/, tests/scenes/, scenes/ exists here");
  }
  std::set<std::string> scenes;
  for (const std::string& p : paths) {
    std::error_code error;
    if (fs::is_regular_file(p, error)) {
      scenes.insert(fs::path(p).lexically_normal().generic_string());
      continue;
    }
    if (!fs::is_directory(p, error)) throw UsageError("test: no such file or folder: " + p);
    for (auto it = fs::recursive_directory_iterator(p, fs::directory_options::skip_permission_denied, error);
         !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
      if (it->is_regular_file(error) && it->path().extension() == ".lua" && definesCheck(it->path()))
        scenes.insert(it->path().lexically_normal().generic_string());
    }
    if (error) throw std::runtime_error(p + ": " + error.message());
  }
  return {scenes.begin(), scenes.end()};
}

bool matches(const std::string& pattern, const std::string& path) {
  if (pattern.find_first_of("*?[") == std::string::npos) return path.find(pattern) != std::string::npos;
  return fnmatch(pattern.c_str(), path.c_str(), 0) == 0;
}

std::vector<std::string> filtered(const std::vector<std::string>& all, const std::optional<std::string>& pattern) {
  std::vector<std::string> out;
  for (const std::string& s : all)
    if (!pattern || matches(*pattern, s)) out.push_back(s);
  return out;
}

std::vector<std::string> shardOf(const std::vector<std::string>& scenes, long shard, long shards) {
  std::vector<std::string> out;
  for (size_t i = 0; i < scenes.size(); ++i)
    if (static_cast<long>(i % static_cast<size_t>(shards)) + 1 == shard) out.push_back(scenes[i]);
  return out;
}

// The progress line on a terminal, rewritten in place; result lines are printed above it.
class LiveLine {
 public:
  LiveLine() : enabled_(isatty(STDOUT_FILENO)) {}
  void print(const std::string& lines) {
    clear();
    std::fputs(lines.c_str(), stdout);
    std::fflush(stdout);
  }
  void show(const std::string& text) {
    if (!enabled_ || (shown_ && text == text_)) return;
    std::fprintf(stdout, "\r\033[K%s", text.c_str());
    std::fflush(stdout);
    shown_ = true;
    text_ = text;
  }
  void clear() {
    if (shown_) std::fputs("\r\033[K", stdout);
    shown_ = false;
  }

 private:
  bool enabled_;
  bool shown_ = false;
  std::string text_;  // what the line shows
};

void writeAll(int fd, const std::string& data) {
  for (size_t done = 0; done < data.size();) {
    const ssize_t n = write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

// A scene's process: its output (stdout and stderr together) and its outcome, each on a pipe.
struct Child {
  size_t index = 0;
  pid_t pid = -1;
  int log_fd = -1, result_fd = -1;
  std::string log, result;
  bool log_truncated = false;
  Clock::time_point start;
  bool killed = false;
};

// The outcome travels as one status digit and the message.
std::string encodeOutcome(const TestOutcome& outcome) {
  return std::to_string(static_cast<int>(outcome.status)) + outcome.message;
}

// Forks; the child runs the scene and never returns.
Child start(size_t index, const std::string& scene, const TestCaseOptions& options) {
  int log[2], result[2];
  if (pipe2(log, O_CLOEXEC) != 0 || pipe2(result, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("test: cannot make a pipe: ") + std::strerror(errno));
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("test: cannot start a process: ") + std::strerror(errno));
  if (pid == 0) {
    dup2(log[1], STDOUT_FILENO);
    dup2(log[1], STDERR_FILENO);
    const rlimit no_core{0, 0};
    setrlimit(RLIMIT_CORE, &no_core);  // a crashing scene is reported, not dumped
    TestOutcome outcome;
    try {
      outcome = runTestCase(scene, options);
    } catch (const std::exception& e) {
      outcome = {TestStatus::Error, e.what()};
    }
    std::fflush(stdout);
    std::fflush(stderr);
    writeAll(result[1], encodeOutcome(outcome));
    _exit(0);
  }
  close(log[1]);
  close(result[1]);
  Child c;
  c.index = index;
  c.pid = pid;
  c.log_fd = log[0];
  c.result_fd = result[0];
  c.start = Clock::now();
  return c;
}

// Reads what is there; closes the descriptor at its end.
void drain(int& fd, std::string& into, bool* truncated) {
  char buf[65536];
  const ssize_t n = read(fd, buf, sizeof buf);
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return;
  if (n <= 0) {
    close(fd);
    fd = -1;
    return;
  }
  size_t keep = static_cast<size_t>(n);
  if (truncated) {
    const size_t room = into.size() < kMaxLogBytes ? kMaxLogBytes - into.size() : 0;
    if (keep > room) {
      *truncated = true;
      keep = room;
    }
  }
  into.append(buf, keep);
}

TestResult finish(Child& c, const std::string& scene, const TestOptions& o) {
  int status = 0;
  while (waitpid(c.pid, &status, 0) < 0 && errno == EINTR) {
  }
  TestResult r;
  r.scene = scene;
  r.seconds = std::chrono::duration<double>(Clock::now() - c.start).count();
  r.log = c.log + (c.log_truncated ? "\n[output cut at 1 MiB]\n" : "");
  if (c.killed) {
    char text[96];
    std::snprintf(text, sizeof text, "killed after %g s of wall time (--timeout)", o.timeout);
    r.status = TestStatus::Timeout;
    r.message = text;
  } else if (!c.result.empty() && c.result[0] >= '0' && c.result[0] <= '4') {
    r.status = static_cast<TestStatus>(c.result[0] - '0');
    r.message = c.result.substr(1);
  } else if (WIFSIGNALED(status)) {
    r.status = TestStatus::Error;
    r.message = "its process crashed: signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  } else {
    r.status = TestStatus::Error;
    r.message = "its process exited with status " + std::to_string(WEXITSTATUS(status)) + " before reporting";
  }
  return r;
}

std::string progressText(size_t done, size_t total, int not_passed, double elapsed) {
  std::string text = "[" + std::to_string(done) + "/" + std::to_string(total) + "] " + std::to_string(not_passed) +
                     " failed, eta ";
  if (done == 0) return text + "?";
  char eta[32];
  std::snprintf(eta, sizeof eta, "%.0f s", elapsed / static_cast<double>(done) * static_cast<double>(total - done));
  return text + eta;
}

std::vector<TestResult> runAll(const std::vector<std::string>& scenes, const TestOptions& o) {
  std::vector<TestResult> results(scenes.size());
  std::vector<Child> running;
  LiveLine live;
  const auto began = Clock::now();
  size_t next = 0, done = 0;
  int not_passed = 0;
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - began).count(); };
  while (next < scenes.size() || !running.empty()) {
    while (next < scenes.size() && static_cast<long>(running.size()) < o.jobs) {
      running.push_back(start(next, scenes[next], o.run));
      ++next;
    }
    live.show(progressText(done, scenes.size(), not_passed, elapsed()));

    std::vector<pollfd> fds;
    for (const Child& c : running)
      for (int fd : {c.log_fd, c.result_fd})
        if (fd >= 0) fds.push_back({fd, POLLIN, 0});
    // Wake for the nearest timeout, and at least twice a second for the live line.
    int wait_ms = 500;
    if (o.timeout > 0)
      for (const Child& c : running) {
        if (c.killed) continue;  // its pipes close as it dies: poll wakes then
        const double left = o.timeout - std::chrono::duration<double>(Clock::now() - c.start).count();
        wait_ms = std::clamp(static_cast<int>(left * 1000.0) + 1, 0, wait_ms);
      }
    if (poll(fds.data(), fds.size(), wait_ms) < 0 && errno != EINTR)
      throw std::runtime_error(std::string("test: poll: ") + std::strerror(errno));
    for (const pollfd& p : fds) {
      if (!(p.revents & (POLLIN | POLLHUP | POLLERR))) continue;
      for (Child& c : running) {
        if (c.log_fd == p.fd) drain(c.log_fd, c.log, &c.log_truncated);
        else if (c.result_fd == p.fd) drain(c.result_fd, c.result, nullptr);
      }
    }
    for (Child& c : running)
      if (!c.killed && o.timeout > 0 && std::chrono::duration<double>(Clock::now() - c.start).count() >= o.timeout) {
        kill(c.pid, SIGKILL);  // its pipes then close, and it is reaped below
        c.killed = true;
      }
    for (auto it = running.begin(); it != running.end();) {
      if (it->log_fd >= 0 || it->result_fd >= 0) {
        ++it;
        continue;
      }
      TestResult& r = results[it->index] = finish(*it, scenes[it->index], o);
      ++done;
      if (r.status != TestStatus::Passed && r.status != TestStatus::Skipped) ++not_passed;
      live.print(resultLines(r));
      it = running.erase(it);
    }
  }
  live.clear();
  return results;
}

std::string utcTimestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  return buf;
}

}  // namespace

int testCommand(const std::vector<std::string>& argv) {
  bool help = false;
  const TestOptions o = parseOptions(argv, help);
  if (help) {
    std::fputs(kTestHelp, stdout);
    return kExitOk;
  }
  const std::vector<std::string> all = discover(o);
  if (all.empty()) {
    std::fprintf(stderr, "test: no scenes (.lua files that define Check) found\n");
    return kExitSceneError;
  }
  const std::vector<std::string> matching = filtered(all, o.filter);
  if (matching.empty()) {
    std::fprintf(stderr, "test: --filter '%s' matches none of the %zu scenes found\n", o.filter->c_str(), all.size());
    return kExitSceneError;
  }
  const std::vector<std::string> scenes = shardOf(matching, o.shard, o.shards);
  if (o.list) {
    for (const std::string& s : scenes) std::printf("%s\n", s.c_str());
    return kExitOk;
  }
  if (scenes.empty()) std::printf("shard %ld/%ld has no scenes (%zu in all)\n", o.shard, o.shards, matching.size());

  const std::string timestamp = utcTimestamp();
  const auto began = Clock::now();
  const std::vector<TestResult> results = runAll(scenes, o);
  const double seconds = std::chrono::duration<double>(Clock::now() - began).count();
  const TestCounts counts = countResults(results);

  if (!counts.ok() && results.size() > 1) {
    std::printf("\nnot passed:\n");
    for (const TestResult& r : results)
      if (r.status != TestStatus::Passed && r.status != TestStatus::Skipped)
        std::printf("  %s\n", resultHead(r).c_str());
  }
  std::printf("%s\n", summaryLine(counts, results.size(), seconds).c_str());
  if (o.junit) {
    try {
      writeFile(*o.junit, junitXml(results, seconds, timestamp), Folders::Make);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "test: %s\n", e.what());
      return kExitSceneError;
    }
  }
  return counts.ok() ? kExitOk : kExitSceneError;
}

}  // namespace rigidlab::app

// What `rigidlab test` reports: one line per scene, the summary, and JUnit XML for CI systems.
#pragma once

#include <string>
#include <vector>

namespace rigidlab::app {

enum class TestStatus {
  Passed,
  Failed,   // Check raised, the golden trajectory differs or is missing, or the run blew up
  Error,    // the scene did not run to its end: a load or script error, a crash
  Timeout,  // killed after --timeout (an error in the summary and the XML)
  Skipped,  // scene.skip
};

struct TestResult {
  std::string scene;  // the path as discovered
  TestStatus status = TestStatus::Error;
  // Why it failed, errored or was skipped; for a pass, a note (a golden file written) or empty.
  std::string message;
  std::string log;  // what the scene's process printed (print(), warnings)
  double seconds = 0.0;
};

struct TestCounts {
  int passed = 0, failed = 0, errors = 0, timeouts = 0, skipped = 0;  // timeouts are among errors
  bool ok() const { return failed == 0 && errors == 0; }
};

TestCounts countResults(const std::vector<TestResult>& results);

// "FAIL     0.02 s  tests/x.lua" (a pass with a note and a skip: ": " and the message).
std::string resultHead(const TestResult& result);
// resultHead, then the message and the end of the log of a scene that did not
// pass, indented. Ends with a newline.
std::string resultLines(const TestResult& result);
// "3 passed, 1 failed, 2 errors (1 timed out), 1 skipped: 7 scenes in 4.2 s"
std::string summaryLine(const TestCounts& counts, size_t scenes, double seconds);
// A JUnit XML document in the strict junit-4 format (tests/runner/junit-4.xsd): one testsuite, one
// testcase per scene (classname: its folder with dots, name: its file name without .lua) with
// <failure>, <error> or <skipped> (the reason as its text) and its log; each scene's file as a
// property "<classname>.<name>.file" of the suite.
std::string junitXml(const std::vector<TestResult>& results, double seconds, const std::string& timestamp);

}  // namespace rigidlab::app

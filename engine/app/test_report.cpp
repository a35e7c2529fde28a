#include "test_report.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "rigidlab/lua/scene_text.h"

namespace rigidlab::app {
namespace {

// The log lines shown under a scene that did not pass: its last ones, where the trouble is.
constexpr size_t kLogLinesShown = 20;

const char* statusWord(TestStatus status) {
  switch (status) {
    case TestStatus::Passed: return "PASS";
    case TestStatus::Failed: return "FAIL";
    case TestStatus::Error: return "ERROR";
    case TestStatus::Timeout: return "TIMEOUT";
    case TestStatus::Skipped: return "SKIP";
  }
  return "?";
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = std::min(text.find('\n', start), text.size());
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

// Text as XML 1.0 character data (or an attribute value, where line breaks and tabs must be
// character references to survive): shown as the runners show a scene's text (valid UTF-8, the
// control characters XML cannot hold as \xHH), with XML's special characters escaped.
std::string xml(const std::string& text, bool attribute = true) {
  std::string out;
  for (char c : lua::displayText(text, SIZE_MAX, "\n\t\r")) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\n': out += attribute ? "&#10;" : "\n"; break;
      case '\t': out += attribute ? "&#9;" : "\t"; break;
      case '\r': out += attribute ? "&#13;" : "\r"; break;
      default: out += c;
    }
  }
  return out;
}

std::string seconds3(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", seconds);
  return buf;
}

std::string countsAttributes(const TestCounts& c, size_t tests, double seconds) {
  return "tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(c.failed) + "\" errors=\"" +
         std::to_string(c.errors) + "\" time=\"" + seconds3(seconds) + "\"";
}

// A testcase's classname (the scene's folder with dots) and name (its file name without .lua).
std::pair<std::string, std::string> caseNames(const TestResult& r) {
  const std::filesystem::path path(r.scene);
  std::string classname = path.parent_path().generic_string();
  for (char& ch : classname)
    if (ch == '/') ch = '.';
  return {classname.empty() ? "." : classname, path.stem().string()};
}

}  // namespace

TestCounts countResults(const std::vector<TestResult>& results) {
  TestCounts c;
  for (const TestResult& r : results) {
    switch (r.status) {
      case TestStatus::Passed: ++c.passed; break;
      case TestStatus::Failed: ++c.failed; break;
      case TestStatus::Error: ++c.errors; break;
      case TestStatus::Timeout: ++c.errors, ++c.timeouts; break;
      case TestStatus::Skipped: ++c.skipped; break;
    }
  }
  return c;
}

std::string resultHead(const TestResult& r) {
  char head[64];
  if (r.status == TestStatus::Skipped) {
    std::snprintf(head, sizeof head, "%-8s %8s  ", statusWord(r.status), "");
  } else {
    std::snprintf(head, sizeof head, "%-8s %6.2f s  ", statusWord(r.status), r.seconds);
  }
  const bool noted = r.status == TestStatus::Skipped || (r.status == TestStatus::Passed && !r.message.empty());
  return head + r.scene + (noted ? ": " + r.message : "");
}

std::string resultLines(const TestResult& r) {
  std::string out = resultHead(r) + "\n";
  if (r.status == TestStatus::Passed || r.status == TestStatus::Skipped) return out;
  for (const std::string& line : splitLines(r.message)) out += "    " + line + "\n";
  const std::vector<std::string> log = splitLines(r.log);
  const size_t first = log.size() > kLogLinesShown ? log.size() - kLogLinesShown : 0;
  if (first > 0) out += "    | ... " + std::to_string(first) + " lines of its output before these\n";
  for (size_t i = first; i < log.size(); ++i) out += "    | " + log[i] + "\n";
  return out;
}

std::string summaryLine(const TestCounts& c, size_t scenes, double seconds) {
  char time[32];
  std::snprintf(time, sizeof time, "%.1f", seconds);
  std::string out = std::to_string(c.passed) + " passed, " + std::to_string(c.failed) + " failed, " +
                    std::to_string(c.errors) + (c.errors == 1 ? " error" : " errors");
  if (c.timeouts) out += " (" + std::to_string(c.timeouts) + " timed out)";
  out += ", " + std::to_string(c.skipped) + " skipped: " + std::to_string(scenes) +
         (scenes == 1 ? " scene in " : " scenes in ") + time + " s";
  return out;
}

std::string junitXml(const std::vector<TestResult>& results, double seconds, const std::string& timestamp) {
  const TestCounts c = countResults(results);
  const std::string counts = countsAttributes(c, results.size(), seconds);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites name=\"rigidlab test\" " + counts + ">\n";
  out += "  <testsuite name=\"rigidlab test\" " + counts + " skipped=\"" + std::to_string(c.skipped) +
         "\" timestamp=\"" + xml(timestamp) + "\">\n";
  // What the junit-4 format has no attribute for (tests/runner/junit-4.xsd): each scene's file.
  if (!results.empty()) {
    out += "    <properties>\n";
    for (const TestResult& r : results) {
      const auto [classname, name] = caseNames(r);
      out += "      <property name=\"" + xml(classname + "." + name + ".file") + "\" value=\"" + xml(r.scene) + "\"/>\n";
    }
    out += "    </properties>\n";
  }
  for (const TestResult& r : results) {
    const auto [classname, name] = caseNames(r);
    out += "    <testcase classname=\"" + xml(classname) + "\" name=\"" + xml(name) + "\" time=\"" +
           seconds3(r.seconds) + "\"";
    const std::string first_line = r.message.substr(0, r.message.find('\n'));
    switch (r.status) {
      case TestStatus::Passed:
        out += "/>\n";
        continue;
      case TestStatus::Skipped:  // the reason as the element's text: junit-4's <skipped> has no attributes
        out += ">\n      <skipped>" + xml(r.message, false) + "</skipped>\n    </testcase>\n";
        continue;
      case TestStatus::Failed:
        out += ">\n      <failure type=\"failure\" message=\"" + xml(first_line) + "\">" + xml(r.message, false) + "</failure>\n";
        break;
      case TestStatus::Error:
      case TestStatus::Timeout:
        out += ">\n      <error type=\"" + std::string(r.status == TestStatus::Timeout ? "timeout" : "error") +
               "\" message=\"" + xml(first_line) + "\">" + xml(r.message, false) + "</error>\n";
        break;
    }
    if (!r.log.empty()) out += "      <system-out>" + xml(r.log, false) + "</system-out>\n";
    out += "    </testcase>\n";
  }
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

}  // namespace rigidlab::app

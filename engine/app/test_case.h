// One scene as a test (`rigidlab test`): loaded and run headless as `rigidlab run` runs it, with
// its budgets, then its Check and its golden trajectory. Runs in the process the runner made for
// the scene.
#pragma once

#include <filesystem>
#include <string>

#include "test_report.h"

namespace rigidlab::app {

struct TestCaseOptions {
  bool update = false;              // --update: record the golden trajectory instead of comparing
  std::filesystem::path diff_root;  // --diff-dir: where mismatching trajectories are written
};

struct TestOutcome {
  TestStatus status = TestStatus::Error;
  std::string message;
};

TestOutcome runTestCase(const std::filesystem::path& scene, const TestCaseOptions& options);

// Where the expected and actual trajectories of `scene` go: `root` / the scene's path without
// .lua (an absolute path or `..` kept inside `root`).
std::filesystem::path diffDirectory(const std::filesystem::path& root, const std::filesystem::path& scene);

}  // namespace rigidlab::app

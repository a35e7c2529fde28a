#include "test_case.h"

#include <exception>
#include <memory>
#include <optional>
#include <vector>

#include "golden_trajectory.h"
#include "headless_run.h"
#include "report.h"
#include "rigidlab/lua/bounded_file.h"
#include "rigidlab/lua/scene.h"

namespace rigidlab::app {

std::filesystem::path diffDirectory(const std::filesystem::path& root, const std::filesystem::path& scene) {
  std::filesystem::path inside = root;
  std::filesystem::path parts = scene.lexically_normal();
  parts.replace_extension();
  for (const auto& part : parts) {
    if (part == "..") inside /= "__";
    else if (!part.empty() && part != "." && part != scene.root_path()) inside /= part;
  }
  return inside;
}

TestOutcome runTestCase(const std::filesystem::path& path, const TestCaseOptions& options) {
  std::unique_ptr<lua::Scene> scene;
  try {
    scene = lua::Scene::loadFile(path);
  } catch (const lua::SceneError& e) {
    return {TestStatus::Error, sceneErrorText(e)};
  }
  const lua::SceneSettings& settings = scene->settings();
  if (settings.skip) return {TestStatus::Skipped, *settings.skip};
  std::string refused;
  const std::optional<RunLength> length = runLength(*scene, std::nullopt, std::nullopt, refused);
  if (!length) return {TestStatus::Error, refused};

  World& world = scene->world();
  const bool golden = !settings.golden.empty();
  Trajectory trajectory{path.filename().string(), settings.dt, length->total(), settings.golden_every, {}};
  if (golden) trajectory.samples.push_back(sampleWorld(world, 0));
  RunInfo info;
  info.expect_incidents = settings.expect_incidents;
  // The trajectory's file at its longest, kept within kMaxGoldenBytes while it is recorded.
  size_t trajectory_bytes = golden ? sampleBytesBound(trajectory.samples.back()) : 0;
  struct TooLong {};
  const auto sample = [&] {
    trajectory.samples.push_back(sampleWorld(world, info.steps));
    trajectory_bytes += sampleBytesBound(trajectory.samples.back());
    if (trajectory_bytes > kMaxGoldenBytes) throw TooLong{};
  };
  try {
    stepScene(*scene, *length, info, [&] {
      if (golden && (info.steps % settings.golden_every == 0 || info.steps == length->total())) sample();
    });
  } catch (const lua::SceneError& e) {
    return {TestStatus::Error, sceneErrorText(e)};
  } catch (const TooLong&) {
    return {TestStatus::Error, "scene.golden: the golden trajectory would be larger than the limit of " +
                                   lua::formatBytes(kMaxGoldenBytes) + " (" + std::to_string(trajectory.samples.size()) +
                                   " samples by step " + std::to_string(info.steps) + " of " +
                                   std::to_string(length->total()) +
                                   "); sample less often (scene.golden_every) or fewer bodies"};
  }

  std::vector<std::string> failures;
  if (const auto failure = runCheck(*scene, info)) failures.push_back(*failure);
  if (!info.expect_incidents) {
    const std::vector<std::string> list = incidents(world, info);
    if (!list.empty())
      failures.push_back("the run blew up: " + list[0] +
                         (list.size() > 1 ? " (and " + std::to_string(list.size() - 1) + " more incidents)" : ""));
  }
  std::string note;
  if (golden) {
    try {
      if (!options.update) {
        if (const auto mismatch = checkGolden(path, settings.golden, trajectory, settings.golden_tolerance,
                                              diffDirectory(options.diff_root, path)))
          failures.push_back(*mismatch);
      } else if (failures.empty()) {
        note = "golden trajectory written to " + writeGolden(path, settings.golden, trajectory).string();
      } else {
        failures.push_back("golden trajectory not updated: the run failed");
      }
    } catch (const std::exception& e) {
      return {TestStatus::Error, e.what()};
    }
  }
  if (failures.empty()) return {TestStatus::Passed, note};
  std::string message;
  for (const std::string& f : failures) message += (message.empty() ? "" : "\n") + f;
  return {TestStatus::Failed, message};
}

}  // namespace rigidlab::app

// Building a scene beside the running one (docs/design/reliability.md §3.1, "shadow world"): the new scene is
// loaded on a worker thread from its file while the old one keeps running and drawing; the caller
// swaps it in only if the load succeeded. Each scene has its own Lua state, so the two never share
// anything. A newer request supersedes an older one still in flight (its result is dropped), so a
// script that never returns from PopulateWorld cannot block the next save's reload.
#pragma once

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "rigidlab/lua/scene.h"

namespace rigidlab::sandbox {

// Why a scene is being loaded; decides what the swap keeps (sandbox.cpp adoptScene).
enum class LoadPurpose {
  Open,    // a new scene (start, browser): camera and world settings from the scene
  Reload,  // its files changed: keep camera, pause state and settings
  Reset,   // the user asked to start over: like Reload
};

struct LoadResult {
  LoadPurpose purpose = LoadPurpose::Open;
  std::filesystem::path file;
  std::unique_ptr<lua::Scene> scene;  // null on failure
  std::string error;                  // "file:line: message" on failure
  double load_ms = 0.0;               // wall time of Scene::loadFile
};

class SceneLoader {
 public:
  // Starts loading `file` on a worker thread; supersedes any load in flight.
  void start(const std::filesystem::path& file, LoadPurpose purpose, const lua::SceneOptions& options);
  // The newest load's result once it is done (once), else nothing. Waits up to `wait` for it, so a
  // small scene started this frame is swapped in this frame rather than the next.
  std::optional<LoadResult> poll(std::chrono::milliseconds wait = std::chrono::milliseconds(0));
  bool busy() const;
  // Loads on the calling thread (the first scene, so the first frame shows it).
  static LoadResult loadNow(const std::filesystem::path& file, LoadPurpose purpose, const lua::SceneOptions& options);

 private:
  struct Job {
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    LoadResult result;
  };
  std::shared_ptr<Job> job_;  // the newest; older jobs finish on their own and are dropped
};

}  // namespace rigidlab::sandbox

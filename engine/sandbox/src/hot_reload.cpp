// Loading scenes on a worker thread (hot_reload.h).
#include "hot_reload.h"

#include <thread>

namespace rigidlab::sandbox {

LoadResult SceneLoader::loadNow(const std::filesystem::path& file, LoadPurpose purpose,
                                const lua::SceneOptions& options) {
  LoadResult r;
  r.purpose = purpose;
  r.file = file;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    r.scene = lua::Scene::loadFile(file, options);
  } catch (const std::exception& e) {  // SceneError, and anything else a broken script provokes
    r.error = e.what();
  } catch (...) {
    r.error = file.string() + ": unknown error while loading";
  }
  r.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void SceneLoader::start(const std::filesystem::path& file, LoadPurpose purpose, const lua::SceneOptions& options) {
  auto job = std::make_shared<Job>();
  job_ = job;
  // Detached: the thread owns a reference to its job; if a newer request replaced it, the result
  // (and its scene) is destroyed on the worker when the thread ends.
  std::thread([job, file, purpose, options] {
    LoadResult r = loadNow(file, purpose, options);
    {
      std::lock_guard lock(job->mutex);
      job->result = std::move(r);
      job->done = true;
    }
    job->finished.notify_all();
  }).detach();
}

std::optional<LoadResult> SceneLoader::poll(std::chrono::milliseconds wait) {
  if (!job_) return std::nullopt;
  std::unique_lock lock(job_->mutex);
  if (!job_->finished.wait_for(lock, wait, [&] { return job_->done; })) return std::nullopt;
  LoadResult r = std::move(job_->result);
  lock.unlock();
  job_.reset();
  return r;
}

bool SceneLoader::busy() const { return job_ != nullptr; }

}  // namespace rigidlab::sandbox

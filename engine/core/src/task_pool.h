// The world's worker threads (WorldDef::threads): N − 1 persistent threads that, with the calling
// thread, run the iterations of a loop split into N fixed ranges.
//
// Determinism by construction: parallelFor gives thread t the t-th of N equal ranges of [0, count)
// (static partition, no stealing), and the callers only parallelise loops whose iterations are
// independent (each writes its own slots), with every reduction done afterwards serially in index
// order. What an iteration computes is then the same whatever thread runs it and whatever N is, so
// the results are bit-identical to the serial loop (tests/core/test_threads.cpp).
//
// Waiting: a worker spins a little on the job counter after each job (the step issues jobs a few
// microseconds apart: one per colour and pass of the soft step), then sleeps on it (std::atomic
// wait, a futex on Linux), so an idle world costs no processor time.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <memory>
#include <thread>
#include <vector>

namespace rigidlab {

class TaskPool {
 public:
  explicit TaskPool(int threads);  // threads ≥ 1 in all, counting the caller
  ~TaskPool();                     // joins the workers
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  int threads() const { return threads_; }

  // Runs fn(begin, end) over [0, count) split into threads() fixed ranges, the caller taking the
  // first, and returns when all are done. Serially in the caller (fn(0, count)) when there is one
  // thread or fewer than `grain` items per thread: small loops do not pay for the hand-off.
  template <typename Fn>
  void parallelFor(size_t count, size_t grain, Fn&& fn) {
    if (threads_ <= 1 || count < grain * static_cast<size_t>(threads_)) {
      if (count > 0) fn(size_t{0}, count);
      return;
    }
    using F = std::remove_reference_t<Fn>;
    run(count, [](void* f, size_t begin, size_t end) { (*static_cast<F*>(f))(begin, end); }, static_cast<void*>(&fn));
  }

  // The range of [0, count) that part `part` of `parts` takes: the same split for every count.
  static void rangeOf(size_t count, int part, int parts, size_t& begin, size_t& end) {
    begin = count * static_cast<size_t>(part) / static_cast<size_t>(parts);
    end = count * static_cast<size_t>(part + 1) / static_cast<size_t>(parts);
  }

 private:
  using Call = void (*)(void*, size_t, size_t);  // a plain trampoline: no allocation per job
  void run(size_t count, Call call, void* fn);
  void work(int part);

  int threads_;
  std::vector<std::thread> workers_;
  Call call_ = nullptr;
  void* fn_ = nullptr;
  size_t count_ = 0;
  std::atomic<uint32_t> epoch_{0};    // incremented per job (and to stop)
  std::atomic<int> pending_{0};       // workers not yet done with the current job
  std::atomic<int> sleeping_{0};      // workers waiting on epoch_ (then a job must notify)
  std::atomic<bool> stop_{false};
};

// The pool of a world: created on the first step that wants more than one thread, never copied (a
// copy of the world, World::snapshot, starts without threads and makes its own when it steps).
struct TaskPoolHolder {
  std::unique_ptr<TaskPool> pool;
  TaskPoolHolder() = default;
  TaskPoolHolder(const TaskPoolHolder&) {}
  TaskPoolHolder& operator=(const TaskPoolHolder&) {
    pool.reset();
    return *this;
  }
  TaskPoolHolder(TaskPoolHolder&&) noexcept = default;
  TaskPoolHolder& operator=(TaskPoolHolder&&) noexcept = default;
};

// The number of threads WorldDef::threads asks for: itself, or for 0 the machine's cores.
int resolvedThreads(int threads);

}  // namespace rigidlab

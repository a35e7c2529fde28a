// The world's worker threads (WorldDef::threads): N − 1 persistent threads that, with the calling
// thread, run the iterations of a loop.
//
// Determinism by construction: the callers only parallelise loops whose iterations are
// independent (each writes its own slots), with every reduction done afterwards serially in index
// order, and an iteration computes the same whatever thread runs it. Which thread takes which
// iterations then does not matter, so the results are bit-identical to the serial loop for every
// thread count (tests/core/test_threads.cpp).
//
// Sharing: a loop is cut into a few chunks (fixed ranges of [0, count)), which the caller and the
// workers take in turn from a counter. On a shared machine a worker is often not running when a
// loop starts (descheduled, or asleep between steps); the caller then does the chunks it has not
// taken instead of waiting for it (a fixed split waited for each of its halves: with the machine
// loaded, 2 threads took 3 times as long as one on the pyramid of base 40, measured).
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

  // Runs fn(begin, end) over [0, count) in chunks, each a fixed range, and returns when all are
  // done. Serially in the caller (fn(0, count)) when there is one thread or fewer than `grain`
  // items per thread: small loops do not pay for the hand-off.
  template <typename Fn>
  void parallelFor(size_t count, size_t grain, Fn&& fn) {
    if (threads_ <= 1 || count < grain * static_cast<size_t>(threads_)) {
      if (count > 0) fn(size_t{0}, count);
      return;
    }
    using F = std::remove_reference_t<Fn>;
    const size_t most = 4 * static_cast<size_t>(threads_);  // chunks: enough to even out, few to hand out
    const size_t chunks = count / grain < most ? count / grain : most;
    run(count, chunks, [](void* f, size_t begin, size_t end) { (*static_cast<F*>(f))(begin, end); }, static_cast<void*>(&fn));
  }

  // The range of [0, count) that part `part` of `parts` takes.
  static void rangeOf(size_t count, size_t part, size_t parts, size_t& begin, size_t& end) {
    begin = count * part / parts;
    end = count * (part + 1) / parts;
  }

 private:
  using Call = void (*)(void*, size_t, size_t);  // a plain trampoline: no allocation per job
  void run(size_t count, size_t chunks, Call call, void* fn);
  void takeChunks();
  void work();

  int threads_;
  std::vector<std::thread> workers_;
  // The job: written by the caller only while no worker is inside_ one.
  Call call_ = nullptr;
  void* fn_ = nullptr;
  size_t count_ = 0, chunks_ = 0;
  std::atomic<size_t> next_{0};       // the next chunk to take
  std::atomic<size_t> done_{0};       // chunks finished
  std::atomic<uint32_t> open_{0};     // the epoch of the job that may be joined, 0 if none
  std::atomic<uint32_t> epoch_{0};    // incremented per job (and to stop)
  std::atomic<int> inside_{0};        // workers that may be reading the job
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

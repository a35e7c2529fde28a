// The world's worker threads (task_pool.h).
#include "task_pool.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace rigidlab {
namespace {

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

// About 50 µs of pause instructions: longer than the gaps between the jobs of one step, far
// shorter than the time between steps of an interactive run (16 ms).
constexpr int kSpins = 4000;

}  // namespace

int resolvedThreads(int threads) {
  if (threads > 0) return threads;
  // Asked once per process: glibc reads it from /sys, and every step asks.
  static const int cores = [] {
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : static_cast<int>(n > 64 ? 64 : n);
  }();
  return cores;
}

TaskPool::TaskPool(int threads) : threads_(threads < 1 ? 1 : threads) {
  workers_.reserve(static_cast<size_t>(threads_ - 1));
  for (int part = 1; part < threads_; ++part) workers_.emplace_back([this] { work(); });
}

TaskPool::~TaskPool() {
  stop_.store(true, std::memory_order_seq_cst);
  epoch_.fetch_add(1, std::memory_order_seq_cst);
  epoch_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void TaskPool::takeChunks() {
  for (size_t c = next_.fetch_add(1, std::memory_order_relaxed); c < chunks_; c = next_.fetch_add(1, std::memory_order_relaxed)) {
    size_t begin, end;
    rangeOf(count_, c, chunks_, begin, end);
    call_(fn_, begin, end);
    done_.fetch_add(1, std::memory_order_release);  // publishes the chunk's writes to the caller
  }
}

void TaskPool::run(size_t count, size_t chunks, Call call, void* fn) {
  // A worker that looked at the last job may still be leaving it: the job's fields are rewritten
  // only once none is inside.
  for (int spins = 0; inside_.load(std::memory_order_seq_cst) != 0; ++spins)
    if (spins < kSpins) relax();
    else std::this_thread::yield();
  call_ = call;
  fn_ = fn;
  count_ = count;
  chunks_ = chunks;
  next_.store(0, std::memory_order_relaxed);
  done_.store(0, std::memory_order_relaxed);
  // Open, then publish (sequentially consistent, as the workers' announcements of a sleep and
  // their checks are: either a worker sees the new job before it sleeps or this sees it sleeping
  // and wakes it).
  uint32_t epoch = epoch_.load(std::memory_order_relaxed) + 1;
  if (epoch == 0) epoch = 1;  // after 2³² jobs: 0 means no job is open
  open_.store(epoch, std::memory_order_seq_cst);
  epoch_.store(epoch, std::memory_order_seq_cst);
  if (sleeping_.load(std::memory_order_seq_cst) > 0) epoch_.notify_all();
  takeChunks();
  // Chunks a worker took and is still running: their writes are visible after this acquire.
  for (int spins = 0; done_.load(std::memory_order_acquire) != chunks; ++spins)
    if (spins < kSpins) relax();
    else std::this_thread::yield();
  open_.store(0, std::memory_order_seq_cst);
}

void TaskPool::work() {
  // The epoch at construction, not a fresh load: the first job may be published before this
  // thread starts running.
  uint32_t seen = 0;
  for (;;) {
    uint32_t now = epoch_.load(std::memory_order_acquire);
    for (int spins = 0; now == seen && spins < kSpins; ++spins) {
      relax();
      now = epoch_.load(std::memory_order_acquire);
    }
    while (now == seen) {
      // Announce the sleep before checking again (see run).
      sleeping_.fetch_add(1, std::memory_order_seq_cst);
      now = epoch_.load(std::memory_order_seq_cst);
      if (now == seen) epoch_.wait(seen, std::memory_order_seq_cst);
      sleeping_.fetch_sub(1, std::memory_order_seq_cst);
      now = epoch_.load(std::memory_order_acquire);
    }
    seen = now;
    if (stop_.load(std::memory_order_seq_cst)) return;
    // Inside before looking: once the job is seen open, the caller keeps its fields until this
    // worker leaves; a job already closed (the caller did it all) is left alone.
    inside_.fetch_add(1, std::memory_order_seq_cst);
    if (open_.load(std::memory_order_seq_cst) == seen) takeChunks();
    inside_.fetch_sub(1, std::memory_order_seq_cst);
  }
}

}  // namespace rigidlab

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
  for (int part = 1; part < threads_; ++part) workers_.emplace_back([this, part] { work(part); });
}

TaskPool::~TaskPool() {
  stop_.store(true, std::memory_order_relaxed);
  epoch_.fetch_add(1, std::memory_order_release);
  epoch_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void TaskPool::run(size_t count, Call call, void* fn) {
  call_ = call;
  fn_ = fn;
  count_ = count;
  pending_.store(threads_ - 1, std::memory_order_relaxed);
  // Publishes the job. Sequentially consistent with the load of sleeping_ after it, as the
  // workers' announcement of a sleep and their check of epoch_ are: either a worker sees the new
  // job before it sleeps or this sees it sleeping and wakes it.
  epoch_.fetch_add(1, std::memory_order_seq_cst);
  if (sleeping_.load(std::memory_order_seq_cst) > 0) epoch_.notify_all();
  size_t begin, end;
  rangeOf(count, 0, threads_, begin, end);
  if (begin < end) call(fn, begin, end);
  // The workers' writes are visible after this acquire (each decrement is a release).
  for (int spins = 0; pending_.load(std::memory_order_acquire) != 0; ++spins)
    if (spins < kSpins) relax();
    else std::this_thread::yield();
}

void TaskPool::work(int part) {
  // The epoch at construction, not a fresh load: the first job may be published before this
  // thread starts running, and must not be taken for the one already seen.
  uint32_t seen = 0;
  for (;;) {
    uint32_t now = epoch_.load(std::memory_order_acquire);
    for (int spins = 0; now == seen && spins < kSpins; ++spins) {
      relax();
      now = epoch_.load(std::memory_order_acquire);
    }
    while (now == seen) {
      // Announce the sleep before checking again, so a job published meanwhile either is seen here
      // or sees sleeping_ > 0 and notifies (both are sequentially consistent).
      sleeping_.fetch_add(1, std::memory_order_seq_cst);
      now = epoch_.load(std::memory_order_seq_cst);
      if (now == seen) epoch_.wait(seen, std::memory_order_seq_cst);
      sleeping_.fetch_sub(1, std::memory_order_seq_cst);
      now = epoch_.load(std::memory_order_acquire);
    }
    seen = now;
    if (stop_.load(std::memory_order_relaxed)) return;
    size_t begin, end;
    rangeOf(count_, part, threads_, begin, end);
    if (begin < end) call_(fn_, begin, end);
    pending_.fetch_sub(1, std::memory_order_release);
  }
}

}  // namespace rigidlab

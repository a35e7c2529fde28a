// Budgets for calls into Lua: the watchdog thread, the signal that installs the hook, the hook.
// Design and reasons in budget.h.
#include "budget.h"

#include "script_host.h"

#include <lua.hpp>
#include <signal.h>

#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

namespace rigidlab::lua {
namespace {

// SIGURG: ignored by default, so a stray one (after our handler was replaced) does nothing. A
// previous handler, if the host program had one, still gets the signals that are not ours.
constexpr int kBudgetSignal = SIGURG;

int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// A clock's reading in ns, or -1 if it cannot be read (the thread of a CPU clock has ended).
int64_t clockNs(clockid_t clock) {
  timespec t{};
  if (clock_gettime(clock, &t) != 0) return -1;
  return static_cast<int64_t>(t.tv_sec) * 1000000000 + t.tv_nsec;
}

// The budget armed on this thread (innermost). Read by the signal handler: static TLS, set before
// any signal can target this thread.
thread_local Budget* t_active = nullptr;

struct sigaction g_previous {};

}  // namespace

// The signal arrives on the thread that runs the expired window (pthread_kill): install the hook
// on its state. Only lua_sethook here (documented as callable from a signal handler).
void budgetSignal(int sig) {
  const int saved_errno = errno;
  Budget* b = t_active;
  const int64_t s = b ? b->state_.load(std::memory_order_acquire) : 0;
  if (b && s > 0 && s < Budget::kFirstWindow) {
    lua_sethook(b->L_, budgetHook, LUA_MASKCOUNT, 1);
  } else if (g_previous.sa_handler != SIG_IGN && g_previous.sa_handler != SIG_DFL && g_previous.sa_handler) {
    g_previous.sa_handler(sig);  // not ours: the host's handler
  }
  errno = saved_errno;
}

// Runs at every Lua instruction of an expired window (count 1): raises the budget error. A hook
// left behind by a window that has closed removes itself.
void budgetHook(lua_State* L, lua_Debug* ar) {
  Budget* b = t_active;
  if (!b || b->L_ != L || !b->expired()) {
    lua_sethook(L, nullptr, 0, 0);
    return;
  }
  (void)ar;
  const std::string text = b->locatedMessage(L);
  b->raised_ = text;
  lua_pushlstring(L, text.data(), text.size());
  lua_error(L);  // Lua is built as C++: this unwinds with an exception, destroying `text`
}

// One thread for the process: wakes every tick while any budget exists, expires the windows past
// their deadline and signals their threads. Never destroyed (a detached thread outliving static
// destructors must not touch destroyed statics).
class Watchdog {
 public:
  static Watchdog& instance() {
    static Watchdog* w = new Watchdog;
    return *w;
  }

  void add(Budget* b) {
    std::lock_guard lock(mutex_);
    budgets_.push_back(b);
    wake_.notify_one();
  }

  void remove(Budget* b) {
    std::lock_guard lock(mutex_);
    std::erase(budgets_, b);
  }

 private:
  Watchdog() {
    struct sigaction sa {};
    sa.sa_handler = budgetSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(kBudgetSignal, &sa, &g_previous);
    std::thread([this] { run(); }).detach();
  }

  void run() {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return !budgets_.empty(); });
      const int64_t now = nowNs();
      for (Budget* b : budgets_) {
        int64_t s = b->state_.load(std::memory_order_acquire);
        if (s < Budget::kFirstWindow) continue;
        // Read after the window's serial (acquire): its deadlines. If the window changes meanwhile,
        // the compare-and-swap below fails.
        const int64_t cpu = clockNs(b->cpu_clock_.load(std::memory_order_relaxed));
        const bool wall = now >= b->wall_deadline_.load(std::memory_order_relaxed);
        const bool spent = cpu >= 0 && cpu >= b->cpu_deadline_.load(std::memory_order_relaxed);
        if (!spent && !wall) continue;
        const int64_t signalling = spent ? Budget::kSignalling : Budget::kSignallingWall;
        if (b->state_.compare_exchange_strong(s, signalling, std::memory_order_acq_rel)) {
          // The owning thread waits in disarm() while signalling, so it is alive here.
          pthread_kill(b->thread_, kBudgetSignal);
          b->state_.store(spent ? Budget::kExpired : Budget::kExpiredWall, std::memory_order_release);
        }
      }
      lock.unlock();
      std::this_thread::sleep_for(Budget::kWatchdogTick);
      lock.lock();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Budget*> budgets_;
};

Budget::Budget(lua_State* L, double hook_seconds, double force_seconds)
    : L_(L),
      hook_ns_(static_cast<int64_t>(std::llround(hook_seconds * 1e9))),
      force_ns_(static_cast<int64_t>(std::llround(force_seconds * 1e9))) {
  Watchdog::instance().add(this);
}

Budget::~Budget() {
  Watchdog::instance().remove(this);
  if (t_active == this) t_active = previous_;
}

void Budget::arm(Kind kind) {
  window_kind_ = kind;
  window_per_step_ = lazy_;
  window_ns_ = kind == Kind::Hook ? hook_ns_ : force_ns_;
  by_backstop_ = false;
  raised_.clear();
  thread_ = pthread_self();
  clockid_t clock{};
  if (pthread_getcpuclockid(thread_, &clock) != 0) clock = CLOCK_MONOTONIC;  // no CPU clock: wall time
  cpu_clock_.store(clock, std::memory_order_relaxed);
  previous_ = t_active;
  t_active = this;
  std::atomic_signal_fence(std::memory_order_seq_cst);
  cpu_deadline_.store(clockNs(clock) + window_ns_, std::memory_order_relaxed);
  const int64_t backstop = window_ns_ > INT64_MAX / kBackstopFactor ? INT64_MAX / 2 : window_ns_ * kBackstopFactor;
  wall_deadline_.store(nowNs() + backstop, std::memory_order_relaxed);
  serial_ = serial_ == INT64_MAX ? kFirstWindow : serial_ + 1;
  state_.store(serial_, std::memory_order_release);
  armed_ = true;
}

void Budget::disarm() {
  if (!armed_) return;
  int64_t s = state_.exchange(0, std::memory_order_acq_rel);
  while (signalling(s)) {  // the watchdog is between its exchange and pthread_kill: let it finish
    std::this_thread::yield();
    s = state_.exchange(0, std::memory_order_acq_rel);
  }
  t_active = previous_;
  std::atomic_signal_fence(std::memory_order_seq_cst);
  // The hook (if the window expired) goes; one that a late signal installs removes itself.
  if (s == kExpired || s == kExpiredWall) lua_sethook(L_, nullptr, 0, 0);
  by_backstop_ = s == kExpiredWall;  // for message() after the window
  armed_ = false;
}

Budget::Scope::Scope(Budget& budget, Kind kind, bool lazy) : b_(budget) {
  if (b_.depth_++ == 0) {
    b_.lazy_ = lazy;
    if (!lazy) b_.arm(kind);
  } else if (b_.lazy_ && !b_.armed_ && !lazy) {
    b_.arm(kind);
  }
}

Budget::Scope::~Scope() {
  if (--b_.depth_ == 0) b_.disarm();
}

bool Budget::expired() const {
  const int64_t s = state_.load(std::memory_order_acquire);
  return s > 0 && s < kFirstWindow;
}

std::string Budget::message() const {
  const std::string limit = formatSeconds(window_ns_ * 1e-9);
  const int64_t s = state_.load(std::memory_order_acquire);
  if (s == kSignallingWall || s == kExpiredWall || by_backstop_) {
    const std::string subject = window_kind_ == Kind::Force ? "Lua forces" : "script";
    return subject + " ran longer than " + formatSeconds(window_ns_ * 1e-9 * kBackstopFactor) +
           " of wall-clock time, the backstop of a budget of " + limit +
           " of CPU time (the machine may be overloaded, or the process stalled)";
  }
  if (window_kind_ == Kind::Force)
    return "Lua forces ran longer than their budget of " + limit + (window_per_step_ ? " per step" : " per call") +
           " (infinite loop?)";
  return "script ran longer than its budget of " + limit + " (infinite loop?)";
}

std::string Budget::locatedMessage(lua_State* L) const {
  // The location of the scene's code that is running, not of the host's own chunks (the prelude's
  // pcall wrapper, the sort comparator).
  return sceneLocation(L) + message();
}

bool Budget::expiredOn(lua_State* L) {
  const Budget* b = t_active;
  return b && b->L_ == L && b->expired();
}

int Budget::check(lua_State* L) {
  Budget* b = t_active;
  if (expiredOn(L)) {
    if (b->raised_.empty()) b->raised_ = b->locatedMessage(L);  // the hook has not fired yet
    const std::string text = b->raised_;
    lua_pushlstring(L, text.data(), text.size());
    return lua_error(L);
  }
  return 0;
}

std::string formatSeconds(double seconds) {
  char text[32];
  if (seconds < 1.0) {
    std::snprintf(text, sizeof text, "%g ms", seconds * 1e3);
  } else {
    std::snprintf(text, sizeof text, "%g s", seconds);
  }
  return text;
}

}  // namespace rigidlab::lua

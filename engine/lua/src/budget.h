// CPU-time budgets for calls into a scene's Lua (docs/design/reliability.md §1.3, §1.5 item 5, test plan C).
//
// Every call from the host into Lua runs inside a budget window: the main chunk, PopulateWorld,
// OnStep, Check, OnKey, OnDraw and Exact each get ScriptLimits::hook_seconds; the Lua forces of
// one Scene::step share ScriptLimits::force_seconds (the window opens at the step's first Lua
// force evaluation and closes when the step ends; World::step called directly, as the benchmark
// does, gives each evaluation its own window). Nested calls (require inside PopulateWorld, Lua
// forces run by world:step() inside OnStep) count against the outer window.
//
// A window counts the CPU time of the thread running the scene (its POSIX CPU-time clock,
// pthread_getcpuclockid: what CLOCK_THREAD_CPUTIME_ID reads on that thread), including the C++
// calls the script makes, so a machine busy with other work does not make a good scene an
// "infinite loop". A wall-clock backstop of kBackstopFactor times the budget ends a window whose
// thread gets no CPU time at all for that long (nothing a scene can do blocks, but a host could be
// stalled or swapping).
//
// Zero cost while the budget holds: no Lua hook is installed. A watchdog thread (one per process)
// looks at every armed window every kWatchdogTick; when one has run out it marks it expired and
// signals (kBudgetSignal) the thread running that scene. The signal handler, on that thread, installs
// a count hook with count 1 on the scene's state — lua_sethook is documented as safe to call from
// a signal handler (ldebug.c; lua.c does the same for Ctrl-C). The hook raises
//     "<file>:<line>: script ran longer than its budget of 1 s (infinite loop?)"
// at the next Lua instruction, and again at every instruction after that until the window closes:
// the error is sticky, so pcall/xpcall (wrapped as well, see prelude.lua), error handlers and
// __close handlers cannot swallow it, and no script code runs after it in the same call.
// (A count hook installed permanently would cost ~2.2x on hot Lua loops in Lua 5.4, §0.5.)
//
// Not covered by the hook (it only fires while Lua code runs): long C and C++ functions. Those the
// scene can reach are capped or bounded instead (script_host.cpp: patterns, table.sort, table.move,
// string.rep; the bindings: linear-time chains, bounded outlines, Budget::check inside loops over
// a body's shapes), so a window ends at most one such call after its budget (docs/security.md
// states the bound); coroutines are not offered (a coroutine would need its own hook). __gc is
// refused.
#pragma once

#include <pthread.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

struct lua_State;
struct lua_Debug;

namespace rigidlab::lua {

void budgetHook(lua_State* L, lua_Debug* ar);
void budgetSignal(int sig);

class Budget {
 public:
  enum class Kind { Hook, Force };

  // `L` is the scene's (main) state. Limits in seconds, > 0.
  Budget(lua_State* L, double hook_seconds, double force_seconds);
  ~Budget();
  Budget(const Budget&) = delete;
  Budget& operator=(const Budget&) = delete;

  // A window, RAII. The outermost scope on a budget arms it (Hook: now; Force: now) and disarms it
  // on exit; nested scopes do nothing. A lazy Force scope (Scene::step) arms nothing by itself: the
  // first Force scope inside it arms the window, so C++ physics before the first Lua call is not
  // counted.
  class Scope {
   public:
    Scope(Budget& budget, Kind kind, bool lazy = false);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    Budget& b_;
  };

  // True once the open window has run out (until it closes).
  bool expired() const;
  // "script ran longer than its budget of 1 s (infinite loop?)" for the open (or last) window;
  // for a window ended by the wall-clock backstop, says so.
  std::string message() const;
  // The message the hook raised last, with the Lua location ("" if none yet).
  const std::string& raised() const { return raised_; }

  double hookSeconds() const { return hook_ns_ * 1e-9; }
  double forceSeconds() const { return force_ns_ * 1e-9; }

  // Raises the budget error in Lua if the running window of L's budget has expired (the pcall
  // wrappers call it). Returns 0 otherwise.
  static int check(lua_State* L);
  // True if L's budget window on this thread has expired.
  static bool expiredOn(lua_State* L);

  // How often the watchdog looks at the armed windows: the stop latency is the budget plus at
  // most about this (plus the rest of a C++ call that is running, see above).
  static constexpr std::chrono::milliseconds kWatchdogTick{2};
  // The wall-clock backstop: a window also ends after this many times its budget of wall time.
  static constexpr int kBackstopFactor = 10;

 private:
  friend class Watchdog;
  friend void budgetHook(lua_State* L, lua_Debug* ar);
  friend void budgetSignal(int sig);

  void arm(Kind kind);
  std::string locatedMessage(lua_State* L) const;  // "<file>:<line>: " of the scene's code + message()
  void disarm();

  // state_: 0 idle (or lazily open); while the watchdog signals the thread kSignalling (CPU budget
  // spent) or kSignallingWall (backstop), kExpired / kExpiredWall after; else the serial number of
  // the armed window (>= kFirstWindow), so that the watchdog's compare-and-swap cannot expire a
  // later window with an earlier one's deadlines.
  static constexpr int64_t kSignalling = 1, kExpired = 2, kSignallingWall = 3, kExpiredWall = 4, kFirstWindow = 8;
  static bool signalling(int64_t s) { return s == kSignalling || s == kSignallingWall; }
  std::atomic<int64_t> state_{0};
  int64_t serial_ = kFirstWindow;
  // The armed window's deadlines, written before state_ publishes the window: its thread's CPU
  // clock (cpu_clock_) in ns, and the steady clock in ns.
  std::atomic<int64_t> cpu_deadline_{0}, wall_deadline_{0};
  std::atomic<clockid_t> cpu_clock_{};
  bool by_backstop_ = false;  // the last closed window expired by the wall-clock backstop (owner thread)
  lua_State* L_;
  pthread_t thread_{};
  int64_t hook_ns_, force_ns_;
  int64_t window_ns_ = 0;  // limit of the open window
  Kind window_kind_ = Kind::Hook;
  bool window_per_step_ = false;  // a lazily armed Force window covers one Scene::step
  int depth_ = 0;      // open scopes
  bool lazy_ = false;  // the outermost scope was lazy (not armed yet, or armed by a later scope)
  bool armed_ = false;
  Budget* previous_ = nullptr;  // the thread's active budget before this one was armed
  std::string raised_;
};

// Long loops in C++ code that a scene's call runs (over a table's keys, a saved state's values,
// a sort's comparisons) look at the budget every this many items with Budget::check: a few ms of
// work at most between looks.
inline constexpr size_t kBudgetEvery = 4096;

// std::sort that looks at L's budget every kBudgetEvery comparisons, and once it is spent stops
// (the range is left in some order) and raises the budget error in Lua. Sorting two million keys
// takes seconds in one C call, which no hook can interrupt.
template <typename It, typename Less>
void budgetedSort(lua_State* L, It first, It last, Less less) {
  struct Spent {};
  size_t comparisons = 0;
  try {
    std::sort(first, last, [&](const auto& x, const auto& y) {
      if (++comparisons % kBudgetEvery == 0 && Budget::expiredOn(L)) throw Spent{};
      return less(x, y);
    });
  } catch (const Spent&) {
    Budget::check(L);
  }
}

// "1 s", "250 ms", "1.5 s".
std::string formatSeconds(double seconds);

}  // namespace rigidlab::lua

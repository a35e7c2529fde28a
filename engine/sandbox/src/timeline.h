// The sandbox's timeline (docs/sandbox.md "Rewind"): a ring of the world's recent states, as
// snapshot files' bytes (world_snapshot.h), for stepping backwards, scrubbing and bug reports.
//
// It keeps the states of the last `seconds` of simulated time, at most `max_bytes` in all (the
// oldest go first), one every `every` steps. A cursor says which state the world shows: at the
// end (not rewound) new states are appended; rewound, moving the cursor moves through the kept
// states both ways, and the first new state (the simulation resumed, or the user edited the world)
// first drops every state after the cursor: the future that was, is gone.
//
// States are stored as differences: every kKeyEvery-th one whole (a key state), the others as the
// 64-byte blocks that changed since the state before (most of a state, the static bodies and
// shapes, does not change from step to step: 4 to 12 times less memory for the shipped scenes,
// docs/sandbox.md "Rewind"). stateBytes() rebuilds a state from its key state.
//
// No SDL, no OpenGL: tested alone (tests/sandbox/test_timeline.cpp).
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <string>

namespace rigidlab::sandbox {

struct TimelineLimits {
  double seconds = 10.0;             // simulated time kept [s]
  size_t max_bytes = size_t{256} << 20;  // memory kept at most
  int every = 1;                     // record one state every this many steps, ≥ 1
};

class Timeline {
 public:
  static constexpr size_t kKeyEvery = 30;
  static constexpr size_t kBlock = 64;
  struct Entry {
    double time = 0.0;  // simulated time of the state [s]
    long step = 0;      // World::stepCount of the state
    bool key = true;    // `data` is the whole state, else its changes since the entry before
    size_t size = 0;    // bytes of the whole state
    std::string data;   // key: serializeSnapshot's bytes; else (u64 offset, u64 length, bytes)...
  };

  explicit Timeline(TimelineLimits limits = {}) : limits_(limits) {}
  const TimelineLimits& limits() const { return limits_; }
  void setLimits(const TimelineLimits& limits);
  void clear();

  // Whether a state at `step` is due (every `every` steps; the first state always is).
  bool due(long step) const;
  // Appends a state (the world after a step or an edit). Rewound, the states after the cursor
  // are dropped first and the cursor goes back to the end. Then the old states beyond `seconds`
  // before this one, and the oldest beyond `max_bytes`, go (at least this one stays).
  void record(double time, long step, std::string bytes);
  // Drops the states after the cursor (an edit while rewound), leaving it at the end.
  void truncate();

  // Moves the cursor by `delta` states (negative: back), clamped; the state to show, or nullptr
  // if there is none or the cursor did not move.
  const Entry* move(long delta);
  // Puts the cursor on state `index` (0 = oldest), clamped; the state to show, or nullptr.
  const Entry* seek(size_t index);

  bool empty() const { return entries_.empty(); }
  size_t size() const { return entries_.size(); }
  const Entry& at(size_t i) const { return entries_[i]; }
  std::string stateBytes(size_t i) const;  // the whole state of entry i
  size_t cursor() const { return cursor_ ? *cursor_ : entries_.size() - 1; }  // when not empty
  bool rewound() const { return cursor_.has_value(); }
  size_t bytes() const { return bytes_ + newest_.capacity(); }  // stored, and the newest state whole
  double span() const { return entries_.empty() ? 0.0 : entries_.back().time - entries_.front().time; }

 private:
  void evict();
  static std::string delta(const std::string& before, const std::string& after);
  static void apply(std::string& state, const Entry& e);
  TimelineLimits limits_;
  std::deque<Entry> entries_;
  std::optional<size_t> cursor_;  // rewound: the state shown; nullopt: the newest
  size_t bytes_ = 0;
  long last_step_ = -1;  // step of the newest state
  std::string newest_;   // the newest state whole, the base of the next difference
};

}  // namespace rigidlab::sandbox

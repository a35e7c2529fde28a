// Rewind: the session's use of the timeline (timeline.h, docs/sandbox.md "Rewind"). States are
// kept as snapshot files' bytes, so the memory shown is what they take, and every rewind goes
// through the same format a bug report's file does.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "rigidlab/world_snapshot.h"
#include "session.h"

namespace rigidlab::sandbox {

namespace {

// Shows a kept state: the world restored to it, paused, the readouts that follow the state reset.
void show(Session& s) {
  cancelGesture(s);
  try {
    s.scene->restore(deserializeSnapshot(s.timeline.stateBytes(s.timeline.cursor())));
  } catch (const std::exception& ex) {
    s.setStatus(overlayText(std::string("cannot rewind: ") + ex.what()), 6.0);
    return;
  }
  s.paused = true;
  s.alpha = 1.0;
  s.history.clear();  // interpolation between the last two steps: there are none now
  s.exact.update(*s.scene);
  s.incidents_seen = std::min(s.incidents_seen, s.world().incidents().size());
  if (!s.world().isValid(s.selected)) s.selected = {};
  if (!s.world().isValid(s.selected_joint)) s.selected_joint = {};
  s.timeline_undo_mark = s.undo.size();
}

}  // namespace

void recordState(Session& s) {
  const World& w = s.world();
  if (!s.rewind_error.empty() || !s.timeline.due(w.stepCount())) return;
  // The snapshot carries what the scene's SaveState returns: one that fails (returns what cannot be
  // saved) turns rewinding off, says why, and leaves the scene running.
  std::string bytes;
  try {
    bytes = serializeSnapshot(s.scene->snapshot());
  } catch (const std::exception& e) {
    s.rewind_error = e.what();
    std::fprintf(stderr, "rigidlab: rewind off until the scene reloads: %s\n", s.rewind_error.c_str());
    std::fflush(stderr);
    s.setStatus("rewind off: " + s.rewind_error);
    return;
  }
  // Recording costs about 8 ms per MB of state (measured: a pyramid of 820 boxes, 1.3 MB, in 10 ms;
  // docs/sandbox.md "Rewind"): one state every k steps, k from the state's size (not from a
  // clock, so runs repeat), keeps the cost near 1 ms per step on average.
  constexpr double kBytesPerStep = 128.0 * 1024;
  TimelineLimits limits = s.timeline.limits();
  limits.every = std::clamp(static_cast<int>(std::ceil(static_cast<double>(bytes.size()) / kBytesPerStep)), 1, 60);
  s.timeline.record(w.time(), w.stepCount(), std::move(bytes));
  if (limits.every != s.timeline.limits().every) s.timeline.setLimits(limits);
}

bool stepBack(Session& s) {
  setPaused(s, true);
  const Timeline::Entry* e = s.timeline.move(-1);
  if (!e) {
    s.setStatus("nothing older kept (the timeline keeps the last " + std::to_string(s.timeline.limits().seconds) + " s)");
    return false;
  }
  show(s);
  return true;
}

bool stepForward(Session& s) {
  if (!s.timeline.rewound()) return false;
  const Timeline::Entry* e = s.timeline.move(+1);
  if (!e) return false;
  show(s);
  return true;
}

void seekState(Session& s, size_t index) {
  setPaused(s, true);
  if (s.timeline.seek(index)) show(s);
}

void syncTimeline(Session& s) {
  if (s.timeline.rewound() && s.undo.size() != s.timeline_undo_mark) {
    s.timeline.truncate();  // an edit at a past state: its future is gone
    s.setStatus("edited a past state: the later states were dropped");
  }
  s.timeline_undo_mark = s.undo.size();
}

bool saveState(Session& s, const std::filesystem::path& path, std::string& message) {
  const std::string bytes = serializeSnapshot(s.scene->snapshot());
  std::FILE* f = std::fopen(path.string().c_str(), "wb");
  if (!f) {
    message = "cannot write " + path.string();
    return false;
  }
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  if (std::fclose(f) != 0 || !ok) {
    message = "cannot write " + path.string();
    return false;
  }
  message = "saved the state at t = " + std::to_string(s.world().time()) + " s to " + path.string() +
            " (rigidlab run --load-state " + path.string() + ")";
  return true;
}

std::filesystem::path suggestStatePath(const Session& s) {
  const std::filesystem::path dir = s.file.empty() ? std::filesystem::current_path() : s.file.parent_path();
  const std::string stem = s.file.empty() ? "world" : s.file.stem().string();
  std::error_code ec;
  for (int i = 1;; ++i) {
    const std::filesystem::path p = dir / (stem + (i == 1 ? "_state" : "_state_" + std::to_string(i)) + ".snap");
    if (!std::filesystem::exists(p, ec)) return p;
  }
}

}  // namespace rigidlab::sandbox

// The ring of recent states (timeline.h).
#include "timeline.h"

#include <algorithm>

namespace rigidlab::sandbox {

void Timeline::setLimits(const TimelineLimits& limits) {
  limits_ = limits;
  limits_.every = std::max(1, limits_.every);
  evict();
}

void Timeline::clear() {
  entries_.clear();
  cursor_.reset();
  bytes_ = 0;
  last_step_ = -1;
}

bool Timeline::due(long step) const {
  return entries_.empty() || cursor_ || step < last_step_ || step - last_step_ >= limits_.every;
}

void Timeline::truncate() {
  if (!cursor_) return;
  while (entries_.size() > *cursor_ + 1) {
    bytes_ -= entries_.back().bytes.size();
    entries_.pop_back();
  }
  cursor_.reset();
  last_step_ = entries_.empty() ? -1 : entries_.back().step;
}

void Timeline::record(double time, long step, std::string bytes) {
  truncate();
  bytes_ += bytes.size();
  entries_.push_back({time, step, std::move(bytes)});
  last_step_ = step;
  evict();
}

void Timeline::evict() {
  if (entries_.empty()) return;
  const double oldest = entries_.back().time - limits_.seconds;
  // Keeps one state at or before the window's start, so the whole window can be reached.
  while (entries_.size() > 1 &&
         ((entries_[1].time <= oldest) || bytes_ > limits_.max_bytes)) {
    bytes_ -= entries_.front().bytes.size();
    entries_.pop_front();
    if (cursor_ && *cursor_ > 0) --*cursor_;  // (the state shown may itself go: then the oldest kept)
  }
}

const Timeline::Entry* Timeline::move(long delta) {
  if (entries_.empty()) return nullptr;
  const long now = static_cast<long>(cursor());
  const long last = static_cast<long>(entries_.size()) - 1;
  return seek(static_cast<size_t>(std::clamp(now + delta, 0L, last)));
}

const Timeline::Entry* Timeline::seek(size_t index) {
  if (entries_.empty()) return nullptr;
  index = std::min(index, entries_.size() - 1);
  if (index == cursor()) return nullptr;
  if (index == entries_.size() - 1) cursor_.reset();
  else cursor_ = index;
  return &entries_[index];
}

}  // namespace rigidlab::sandbox

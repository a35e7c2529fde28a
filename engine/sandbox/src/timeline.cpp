// The ring of recent states (timeline.h).
#include "timeline.h"

#include <algorithm>
#include <cstring>

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
  newest_.clear();
  newest_.shrink_to_fit();
}

std::string Timeline::delta(const std::string& before, const std::string& after) {
  std::string out;
  const auto put = [&](uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
  const size_t common = std::min(before.size(), after.size());
  size_t at = 0;
  while (at < common) {
    const size_t n = std::min(kBlock, common - at);
    if (std::memcmp(before.data() + at, after.data() + at, n) == 0) {
      at += n;
      continue;
    }
    size_t end = at + n;  // a run of changed blocks, as one record
    while (end < common) {
      const size_t m = std::min(kBlock, common - end);
      if (std::memcmp(before.data() + end, after.data() + end, m) == 0) break;
      end += m;
    }
    put(at);
    put(end - at);
    out.append(after, at, end - at);
    at = end;
  }
  if (after.size() > common) {
    put(common);
    put(after.size() - common);
    out.append(after, common, std::string::npos);
  }
  return out;
}

void Timeline::apply(std::string& state, const Entry& e) {
  state.resize(e.size);
  for (size_t at = 0; at + 16 <= e.data.size();) {
    uint64_t offset, length;
    std::memcpy(&offset, e.data.data() + at, 8);
    std::memcpy(&length, e.data.data() + at + 8, 8);
    std::memcpy(state.data() + offset, e.data.data() + at + 16, length);
    at += 16 + length;
  }
}

std::string Timeline::stateBytes(size_t i) const {
  if (i + 1 == entries_.size()) return newest_;
  size_t k = i;
  while (!entries_[k].key) --k;  // entry 0 is always a key state
  std::string state = entries_[k].data;
  for (size_t j = k + 1; j <= i; ++j) apply(state, entries_[j]);
  return state;
}

bool Timeline::due(long step) const {
  return entries_.empty() || cursor_ || step < last_step_ || step - last_step_ >= limits_.every;
}

void Timeline::truncate() {
  if (!cursor_) return;
  if (entries_.size() > *cursor_ + 1) {
    newest_ = stateBytes(*cursor_);
    while (entries_.size() > *cursor_ + 1) {
      bytes_ -= entries_.back().data.size();
      entries_.pop_back();
    }
  }
  cursor_.reset();
  last_step_ = entries_.empty() ? -1 : entries_.back().step;
}

void Timeline::record(double time, long step, std::string bytes) {
  truncate();
  size_t since_key = 0;
  for (size_t i = entries_.size(); i > 0 && !entries_[i - 1].key; --i) ++since_key;
  Entry e{time, step, true, bytes.size(), {}};
  if (entries_.empty() || since_key + 1 >= kKeyEvery) {
    e.data = bytes;
  } else {
    e.key = false;
    e.data = delta(newest_, bytes);
  }
  e.data.shrink_to_fit();
  bytes_ += e.data.size();
  entries_.push_back(std::move(e));
  newest_ = std::move(bytes);
  last_step_ = step;
  evict();
}

void Timeline::evict() {
  if (entries_.empty()) return;
  const double oldest = entries_.back().time - limits_.seconds;
  // Keeps one state at or before the window's start, so the whole window can be reached.
  while (entries_.size() > 1 &&
         ((entries_[1].time <= oldest) || bytes() > limits_.max_bytes)) {
    if (!entries_[1].key) {  // the next one becomes the key state
      Entry& next = entries_[1];
      std::string whole = entries_[0].data;
      apply(whole, next);
      bytes_ += whole.size() - next.data.size();
      next.data = std::move(whole);
      next.key = true;
    }
    bytes_ -= entries_.front().data.size();
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

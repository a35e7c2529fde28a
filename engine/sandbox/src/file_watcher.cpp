// Directory-level inotify with a polling fallback (file_watcher.h).
#include "file_watcher.h"

#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>

namespace rigidlab::sandbox {

namespace fs = std::filesystem;

std::optional<uint64_t> hashFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bit
  char buffer[1 << 14];
  while (in) {
    in.read(buffer, sizeof buffer);
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buffer[i]);
      h *= 1099511628211ull;
    }
  }
  if (in.bad()) return std::nullopt;
  return h;
}

namespace {

constexpr uint32_t kDirMask = IN_CLOSE_WRITE | IN_MOVED_TO | IN_MOVED_FROM | IN_CREATE | IN_DELETE | IN_MODIFY |
                              IN_DELETE_SELF | IN_MOVE_SELF | IN_ONLYDIR;

fs::path normalized(const fs::path& file) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(file, ec), ec);
  return ec ? fs::absolute(file).lexically_normal() : p;
}

struct StatSignature {
  bool exists = false;
  int64_t mtime_ns = -1, size = -1;
};

StatSignature statOf(const fs::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return {};
  return {true, int64_t{st.st_mtim.tv_sec} * 1'000'000'000 + st.st_mtim.tv_nsec, int64_t{st.st_size}};
}

}  // namespace

FileWatcher::FileWatcher(WatchOptions options) : options_(options) {
  const char* mode = std::getenv("RIGIDLAB_WATCH");
  if (mode && std::strcmp(mode, "poll") == 0) options_.force_polling = true;
  if (!options_.force_polling) inotify_fd_ = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
}

FileWatcher::~FileWatcher() {
  if (inotify_fd_ >= 0) ::close(inotify_fd_);
}

void FileWatcher::watch(const std::vector<fs::path>& files) {
  std::map<fs::path, FileState> next;
  order_.clear();
  for (const fs::path& f : files) {
    const fs::path p = normalized(f);
    if (next.count(p)) continue;
    order_.push_back(p);
    if (const auto it = files_.find(p); it != files_.end()) {
      next[p] = it->second;
      continue;
    }
    FileState s;
    s.baseline = hashFile(p);
    const StatSignature sig = statOf(p);
    s.stat_exists = sig.exists;
    s.stat_mtime_ns = sig.mtime_ns;
    s.stat_size = sig.size;
    next[p] = s;
  }
  files_ = std::move(next);

  std::set<fs::path> wanted;
  for (const auto& [p, s] : files_) wanted.insert(p.parent_path());
  for (auto it = dirs_.begin(); it != dirs_.end();) {
    if (wanted.count(it->first)) {
      ++it;
      continue;
    }
    if (inotify_fd_ >= 0 && it->second.wd >= 0) ::inotify_rm_watch(inotify_fd_, it->second.wd);
    it = dirs_.erase(it);
  }
  for (const fs::path& d : wanted) dirs_.try_emplace(d);
  armDirectories(Clock::now());
}

void FileWatcher::resetBaseline() {
  for (auto& [p, s] : files_) {
    s.baseline = hashFile(p);
    s.writing = false;
  }
  pending_ = false;
}

void FileWatcher::armDirectories(Clock::time_point now) {
  if (inotify_fd_ < 0) return;
  for (auto& [dir, w] : dirs_) {
    if (w.wd >= 0) continue;
    if (w.last_try != Clock::time_point{} && now - w.last_try < options_.poll_interval) continue;
    w.last_try = now;
    w.wd = ::inotify_add_watch(inotify_fd_, dir.c_str(), kDirMask);
    if (w.wd >= 0) {
      // Anything may have happened while the directory was not watched: look at the files.
      pending_ = true;
      last_event_ = now;
    }
  }
}

void FileWatcher::readInotify(Clock::time_point now) {
  alignas(inotify_event) char buffer[16 * 1024];
  for (;;) {
    const ssize_t n = ::read(inotify_fd_, buffer, sizeof buffer);
    if (n <= 0) break;  // EAGAIN: nothing more
    for (ssize_t at = 0; at < n;) {
      const auto* ev = reinterpret_cast<const inotify_event*>(buffer + at);
      at += static_cast<ssize_t>(sizeof(inotify_event) + ev->len);
      if (ev->mask & IN_Q_OVERFLOW) {  // events were lost: compare everything
        pending_ = true;
        last_event_ = now;
        ++events_;
        continue;
      }
      auto dir = dirs_.end();
      for (auto it = dirs_.begin(); it != dirs_.end(); ++it)
        if (it->second.wd == ev->wd) dir = it;
      if (dir == dirs_.end()) continue;
      if (ev->mask & (IN_IGNORED | IN_DELETE_SELF | IN_MOVE_SELF)) {
        // The directory itself went away or moved: re-arm on its path later, poll meanwhile.
        if (!(ev->mask & IN_IGNORED)) ::inotify_rm_watch(inotify_fd_, ev->wd);
        dir->second.wd = -1;
        dir->second.last_try = now;
        pending_ = true;
        last_event_ = now;
        continue;
      }
      if (ev->len == 0) continue;
      const auto file = files_.find(dir->first / ev->name);
      if (file == files_.end()) continue;  // not ours: temporaries, swap files, other scenes
      if (ev->mask & (IN_MODIFY | IN_CREATE)) file->second.writing = true;
      if (ev->mask & (IN_CLOSE_WRITE | IN_MOVED_TO | IN_DELETE | IN_MOVED_FROM)) file->second.writing = false;
      pending_ = true;
      last_event_ = now;
      ++events_;
    }
  }
}

bool FileWatcher::anyPolled() const {
  if (inotify_fd_ < 0) return true;
  for (const auto& [dir, w] : dirs_)
    if (w.wd < 0) return true;
  return false;
}

bool FileWatcher::pollStats(Clock::time_point) {
  bool changed = false;
  for (auto& [p, s] : files_) {
    if (inotify_fd_ >= 0) {
      const auto dir = dirs_.find(p.parent_path());
      if (dir != dirs_.end() && dir->second.wd >= 0) continue;  // inotify covers it
    }
    const StatSignature sig = statOf(p);
    if (sig.exists != s.stat_exists || sig.mtime_ns != s.stat_mtime_ns || sig.size != s.stat_size) {
      s.stat_exists = sig.exists;
      s.stat_mtime_ns = sig.mtime_ns;
      s.stat_size = sig.size;
      changed = true;
    }
  }
  return changed;
}

bool FileWatcher::compareContents(Clock::time_point now) {
  const long events_before = events_;
  std::map<fs::path, std::optional<uint64_t>> now_hash;
  bool missing = false;
  for (const auto& [p, s] : files_) {
    now_hash[p] = hashFile(p);
    // An empty file is a truncation whose write has not come yet (an in-place save from a slow
    // process, measured under load: open(O_TRUNC) … 30+ ms … write). No scene is empty.
    std::error_code ec;
    missing = missing || !now_hash[p] || fs::file_size(p, ec) == 0;
  }
  if (missing) {
    // Between a delete and a create, a rename away and back, a truncation and its write: give the
    // editor a moment.
    if (!missing_since_) missing_since_ = now;
    if (now - *missing_since_ < options_.missing_grace) {
      last_event_ = now;  // look again after another settle period
      return false;
    }
  }
  missing_since_.reset();
  // A write that began while we were reading (the next save of a burst truncating the file) makes
  // what we read suspect: settle again rather than report a half-written file.
  if (inotify_fd_ >= 0) {
    readInotify(now);
    if (events_ != events_before) return false;
  }
  changed_.clear();
  for (auto& [p, s] : files_) {
    if (now_hash[p] != s.baseline) changed_.push_back(p);
    s.baseline = now_hash[p];
    s.writing = false;
  }
  pending_ = false;
  return !changed_.empty();
}

bool FileWatcher::settling(Clock::time_point now) {
  if (inotify_fd_ >= 0) readInotify(now);
  return pending_;
}

bool FileWatcher::poll(Clock::time_point now) {
  if (inotify_fd_ >= 0) {
    readInotify(now);
    armDirectories(now);
  }
  const bool polled = anyPolled();
  if (polled && now - last_poll_ >= options_.poll_interval) {
    last_poll_ = now;
    if (pollStats(now)) {
      pending_ = true;
      last_event_ = now;
    }
  }
  if (!pending_) return false;
  const auto quiet = now - last_event_;
  // Polling sees a change only at a poll: wait for the next one to agree before reading.
  const auto settle = polled ? std::max<Clock::duration>(options_.settle, options_.poll_interval) : options_.settle;
  if (quiet < settle) return false;
  bool writing = false;
  for (const auto& [p, s] : files_) writing = writing || s.writing;
  if (writing && quiet < options_.stale_write) return false;
  return compareContents(now);
}

}  // namespace rigidlab::sandbox

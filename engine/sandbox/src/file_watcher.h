// Watches a scene's files (the scene and every module it required) and reports, once per burst of
// writes, that their content changed (docs/design/reliability.md §3.2–3.3).
//
// Editors save in many ways: in place (truncate + write), by writing a temporary file and renaming
// it over the original (the original inode, and any watch on it, dies), by renaming the original
// to a backup first (vim's writebackup), by deleting and recreating, in several chunks. So:
//   - the watch is on the *directories*, filtered by the watched files' names; events for other
//     names (temporary files, swap files, our own saves' *.rigidlab-tmp-*) are never looked at;
//   - a file that was opened for writing (IN_MODIFY/IN_CREATE) is not read before it is closed
//     (IN_CLOSE_WRITE) or renamed into place (IN_MOVED_TO), or has been quiet for `stale_write`;
//   - a burst of events is settled for `settle` after the last one, then the files' contents are
//     hashed and compared with what was last loaded: a `touch` or a rewrite with the same text
//     reloads nothing, and N saves in quick succession reload once;
//   - a file that is missing (between a delete and a create) or empty (truncated, not yet written)
//     is waited for up to `missing_grace`, then reported;
// Without inotify (RIGIDLAB_WATCH=poll, or inotify_init failing, or a directory whose watch was lost
// until it can be re-armed) the files are polled: size and mtime every `poll_interval`, content
// hashed when they change, reported when two polls agree.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rigidlab::sandbox {

struct WatchOptions {
  using ms = std::chrono::milliseconds;
  ms settle{30};          // quiet time after the last event before the files are read
  ms stale_write{400};    // a file opened for writing and quiet this long is read anyway
  ms missing_grace{1000}; // a watched file that vanished is reported after this long
  ms poll_interval{100};  // polling mode: stat period
  bool force_polling = false;  // also set by the environment variable RIGIDLAB_WATCH=poll
};

class FileWatcher {
 public:
  using Clock = std::chrono::steady_clock;

  explicit FileWatcher(WatchOptions options = {});
  ~FileWatcher();
  FileWatcher(const FileWatcher&) = delete;
  FileWatcher& operator=(const FileWatcher&) = delete;

  // Watches exactly these files from now on. A file already watched keeps its baseline (the content
  // last reported or loaded); a new one takes its current content as baseline.
  void watch(const std::vector<std::filesystem::path>& files);
  // Takes the files' current content as the baseline (after loading them).
  void resetBaseline();

  // Call once per frame. True when a watched file's content differs from its baseline and the
  // writes have settled; the new content becomes the baseline, so each change is reported once.
  bool poll(Clock::time_point now = Clock::now());

  // Reads pending file events without reporting: true while writes to the watched files have not
  // settled (a change is coming). Lets the caller hold back a failed load of a file that is being
  // rewritten at that moment.
  bool settling(Clock::time_point now = Clock::now());

  bool usingInotify() const { return inotify_fd_ >= 0; }
  const std::vector<std::filesystem::path>& files() const { return order_; }
  // The files whose content changed in the last report.
  const std::vector<std::filesystem::path>& changed() const { return changed_; }

 private:
  struct FileState {
    std::optional<uint64_t> baseline;  // content hash; nullopt = missing
    bool writing = false;              // opened for writing, not yet closed
    // polling
    bool stat_exists = false;
    int64_t stat_mtime_ns = -1;
    int64_t stat_size = -1;
  };
  struct DirWatch {
    int wd = -1;  // -1: not (or no longer) watched by inotify, poll instead
    Clock::time_point last_try{};
  };

  void readInotify(Clock::time_point now);
  void armDirectories(Clock::time_point now);
  bool pollStats(Clock::time_point now);  // true if any stat changed
  bool anyPolled() const;
  bool compareContents(Clock::time_point now);

  WatchOptions options_;
  int inotify_fd_ = -1;
  std::map<std::filesystem::path, FileState> files_;
  std::vector<std::filesystem::path> order_, changed_;
  std::map<std::filesystem::path, DirWatch> dirs_;
  bool pending_ = false;
  long events_ = 0;  // events on watched files (or overflows) read so far
  Clock::time_point last_event_{};
  Clock::time_point last_poll_{};
  std::optional<Clock::time_point> missing_since_;
};

// FNV-1a of the file's bytes; nullopt if it cannot be read.
std::optional<uint64_t> hashFile(const std::filesystem::path& file);

}  // namespace rigidlab::sandbox

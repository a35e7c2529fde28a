// Files read within a limit (bounded_file.h).
#include "rigidlab/lua/bounded_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace rigidlab::lua {

BoundedFile::BoundedFile(const std::filesystem::path& file, size_t limit, std::string name, std::string what)
    : limit_(limit), name_(std::move(name)), what_(std::move(what)) {
  // Opened without waiting (a named pipe without a writer would block open() for ever, where no
  // budget can stop it), then read with blocking reads (such a pipe then reads as empty).
  fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw FileUnreadable(name_ + ": cannot read the file (" + std::strerror(errno) + ")");
  if (const int flags = ::fcntl(fd_, F_GETFL); flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
  struct stat st {};
  if (::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode)) known_size_ = static_cast<long long>(st.st_size);
  if (S_ISDIR(st.st_mode)) {
    ::close(fd_);
    throw FileUnreadable(name_ + ": cannot read the file (it is a folder)");
  }
  if (known_size_ >= 0 && static_cast<unsigned long long>(known_size_) > limit_) {
    ::close(fd_);
    throw FileTooLarge(name_ + ": the file is " + std::to_string(known_size_) + " bytes, more than the limit of " +
                       formatBytes(limit_) + " for " + what_);
  }
}

BoundedFile::~BoundedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void BoundedFile::tooLarge() const {
  throw FileTooLarge(name_ + ": the file holds more than the limit of " + formatBytes(limit_) + " for " + what_ +
                     " (read up to there)");
}

size_t BoundedFile::read(std::string& into, size_t n) {
  size_t got = 0;
  char buffer[1 << 16];
  while (got < n) {
    const size_t want = std::min(n - got, sizeof buffer);
    const ssize_t r = ::read(fd_, buffer, want);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) throw FileUnreadable(name_ + ": cannot read the file (" + std::strerror(errno) + ")");
    if (r == 0) break;
    if (static_cast<size_t>(r) > limit_ - consumed_) tooLarge();
    consumed_ += static_cast<size_t>(r);
    into.append(buffer, static_cast<size_t>(r));
    got += static_cast<size_t>(r);
  }
  return got;
}

std::string BoundedFile::rest() {
  std::string text;
  if (known_size_ >= 0) text.reserve(std::min(static_cast<size_t>(known_size_), limit_) - std::min(consumed_, limit_));
  // One byte more than is allowed: read() refuses the file if it is there.
  const size_t allowed = limit_ - consumed_;
  read(text, allowed == SIZE_MAX ? allowed : allowed + 1);
  return text;
}

std::string readBoundedFile(const std::filesystem::path& file, size_t limit, const std::string& name,
                            const std::string& what) {
  return BoundedFile(file, limit, name, what).rest();
}

std::string formatBytes(size_t bytes) {
  char text[48];
  if (bytes >= (size_t{1} << 20) && bytes % (size_t{1} << 20) == 0) {
    std::snprintf(text, sizeof text, "%zu MiB", bytes >> 20);
  } else if (bytes >= (size_t{1} << 10) && bytes % (size_t{1} << 10) == 0) {
    std::snprintf(text, sizeof text, "%zu KiB", bytes >> 10);
  } else {
    std::snprintf(text, sizeof text, "%zu bytes", bytes);
  }
  return text;
}

}  // namespace rigidlab::lua

// Reading a file that a scene or a user hands the program, never more than a limit
// (docs/security.md "Files"): the size is checked before anything is read (fstat of the opened
// file), and reading stops one byte past the limit whatever the size said, so a file that grows
// meanwhile, a pipe or a device such as /dev/zero costs at most the limit. Nothing is allocated
// beyond what has been read (and the size of a regular file within the limit).
//
//   std::string text = readBoundedFile("scene.lua", 4 << 20, "scene.lua", "a scene file");
//   // "scene.lua: the file is 5000000 bytes, more than the limit of 4 MiB for a scene file"
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace rigidlab::lua {

// The file could not be opened or read: "<name>: cannot read the file (<reason>)".
class FileUnreadable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The file holds more than the limit: "<name>: the file is N bytes, more than the limit of
// M MiB for <what>" (or "... holds more than ..." when its size is not known before reading).
class FileTooLarge : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class BoundedFile {
 public:
  // Opens `file` and refuses it (FileTooLarge) if its size is known to be above `limit`. `name`
  // is the file as messages show it, `what` what it is ("a state file").
  BoundedFile(const std::filesystem::path& file, size_t limit, std::string name, std::string what);
  ~BoundedFile();
  BoundedFile(const BoundedFile&) = delete;
  BoundedFile& operator=(const BoundedFile&) = delete;

  // Appends up to `n` more bytes to `into` (fewer at the end of the file) and returns how many;
  // FileTooLarge once the bytes read in all would pass the limit.
  size_t read(std::string& into, size_t n);
  // The rest of the file, up to the limit; FileTooLarge if there is more.
  std::string rest();
  // The size fstat reported for a regular file; -1 for a pipe or a device.
  long long knownSize() const { return known_size_; }

 private:
  [[noreturn]] void tooLarge() const;
  int fd_ = -1;
  size_t limit_;
  size_t consumed_ = 0;
  long long known_size_ = -1;
  std::string name_, what_;
};

// The whole file (BoundedFile(...).rest()).
std::string readBoundedFile(const std::filesystem::path& file, size_t limit, const std::string& name,
                            const std::string& what);

// "4 MiB", "256 MiB", "1.5 KiB", "100 bytes".
std::string formatBytes(size_t bytes);

}  // namespace rigidlab::lua

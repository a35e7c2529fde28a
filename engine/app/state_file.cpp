#include "state_file.h"

#include <stdexcept>

#include "rigidlab/lua/bounded_file.h"
#include "text_file.h"

namespace rigidlab::app {

WorldSnapshot readStateFile(const std::string& path) {
  lua::BoundedFile file(path, kMaxStateBytes, path, "a state file");
  std::string bytes;
  try {
    file.read(bytes, kSnapshotHeaderBytes);
    const uint64_t size = snapshotFileBytes(bytes);
    if (size > kMaxStateBytes)
      throw lua::FileTooLarge(path + ": the header announces a state of " + std::to_string(size) +
                              " bytes, more than the limit of " + lua::formatBytes(kMaxStateBytes) + " for a state file");
    // One byte more than announced, if the file has it: deserializeSnapshot names the mismatch.
    file.read(bytes, static_cast<size_t>(size) - bytes.size() + 1);
    return deserializeSnapshot(bytes);
  } catch (const SnapshotError& e) {
    throw SnapshotError(path + ": " + e.what());
  }
}

void writeStateFile(const std::string& path, const WorldSnapshot& snapshot) {
  const std::string bytes = serializeSnapshot(snapshot);
  if (bytes.size() > kMaxStateBytes)
    throw std::runtime_error(path + ": the state is " + std::to_string(bytes.size()) + " bytes, more than the limit of " +
                             lua::formatBytes(kMaxStateBytes) + " for a state file (it could not be loaded again)");
  writeFile(path, bytes);
}

}  // namespace rigidlab::app

// State files (`rigidlab run --save-state` / `--load-state`, docs/testing.md "Snapshots"): a
// snapshot written to a file and read back within a size limit.
#pragma once

#include <cstddef>
#include <string>

#include "rigidlab/world_snapshot.h"

namespace rigidlab::app {

// The largest state file read or written (docs/security.md "Files"): the scene's memory cap, which
// bounds the world a scene can make. A state above it is refused when saved too, so that
// rigidlab never writes a state it would not read again.
inline constexpr size_t kMaxStateBytes = size_t{256} << 20;

// Reads the header first: a file that is not a snapshot (/dev/zero) is refused after 30 bytes, one
// whose header announces more than kMaxStateBytes before its payload is read, and nothing is
// allocated beyond the bytes read. Throws lua::FileUnreadable, lua::FileTooLarge or SnapshotError,
// each message starting with `path`.
WorldSnapshot readStateFile(const std::string& path);

// Writes the snapshot into `path`, whose folder must exist; throws std::runtime_error if it does
// not, if the file cannot be written or if the state is larger than kMaxStateBytes.
void writeStateFile(const std::string& path, const WorldSnapshot& snapshot);

}  // namespace rigidlab::app

// Whole-simulation snapshots (docs/testing.md "Snapshots"): World::snapshot() copies everything a later step
// reads (bodies, shapes, joints and their accumulated impulses, forces, warm starts, sleep timers
// and islands, sensors' contents, the clock, the settings, the NaN firewall's incidents), and
// World::restore() puts a world back to it, so the steps after a restore give the same bits as
// the steps after the snapshot was taken.
//
//   WorldSnapshot s = world.snapshot();
//   world.step(dt);             // ... any number of steps and edits
//   world.restore(s);           // back, bit-exactly
//   std::string bytes = serializeSnapshot(s);          // for a file
//   WorldSnapshot t = deserializeSnapshot(bytes);      // SnapshotError if corrupt or truncated
//
// Forces that cannot be copied (Force::clone returns nullptr: a script's callback) are kept as the
// same object by an in-memory snapshot. A serialized one records only their kind and id: restoring
// it takes the restoring world's force with that id and kind (the scene file made it again), and
// refuses if there is none. The pre-solve callback is never in a snapshot: the restoring world
// keeps its own.
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rigidlab {

struct WorldImpl;

// A corrupt, truncated or foreign snapshot file, or a snapshot the world cannot take.
class SnapshotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class WorldSnapshot {
 public:
  WorldSnapshot();  // empty: restoring it throws SnapshotError
  ~WorldSnapshot();
  WorldSnapshot(const WorldSnapshot&);
  WorldSnapshot& operator=(const WorldSnapshot&);
  WorldSnapshot(WorldSnapshot&&) noexcept;
  WorldSnapshot& operator=(WorldSnapshot&&) noexcept;

  bool empty() const { return !state_; }
  double time() const;   // simulated time of the snapshot [s]
  long stepCount() const;
  int bodyCount() const;
  // Bytes held in memory (the copied state's vectors, estimated from their capacities).
  size_t memoryBytes() const;
  // A free-form label carried through serialization: the Lua layer and the program store the scene
  // file the snapshot came from.
  const std::string& label() const { return label_; }
  void setLabel(std::string label) { label_ = std::move(label); }
  // Opaque bytes of the application's own state, carried through serialization unread (since
  // format version 2; empty for a version 1 file). The Lua layer stores a scene's SaveState value
  // in it (docs/lua-api.md "Snapshots"). World::restore ignores it.
  const std::string& appData() const { return app_data_; }
  void setAppData(std::string bytes) { app_data_ = std::move(bytes); }

 private:
  friend class World;
  friend std::string serializeSnapshot(const WorldSnapshot&);
  friend WorldSnapshot deserializeSnapshot(std::string_view);
  std::shared_ptr<const WorldImpl> state_;  // immutable once made: copies of a snapshot share it
  std::string label_;
  std::string app_data_;
};

// The snapshot as bytes (snapshot_format.cpp): a versioned binary format with every double as its
// raw bits, a length and a checksum. Forces that cannot be copied are recorded by kind and id.
std::string serializeSnapshot(const WorldSnapshot& snapshot);
// Reads serializeSnapshot's bytes, of this version (2) or version 1 (no application data);
// SnapshotError("snapshot: ...") naming what is wrong and where for anything else (a truncated or
// corrupt file, another version, indices out of range).
WorldSnapshot deserializeSnapshot(std::string_view bytes);

// A snapshot file's header: the magic, the version and the payload's length. From the first
// kSnapshotHeaderBytes bytes of a file, the size of the whole file it announces, so that a reader
// can refuse a file that is not a snapshot (/dev/zero) or one too large before reading the rest;
// SnapshotError as deserializeSnapshot's for a foreign or short header or another version.
inline constexpr size_t kSnapshotHeaderBytes = 30;
uint64_t snapshotFileBytes(std::string_view header);

}  // namespace rigidlab

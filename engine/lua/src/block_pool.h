// Small blocks for a scene's Lua state (ScriptHost::allocate).
//
// What a scene makes and drops every step (contact tables, vectors, closures) is a stream of small
// blocks of a few sizes. The C library's allocator keeps only a handful of each size at hand and
// sorts the rest into its bins, so a step that makes a few thousand of them spent a tenth of its
// Lua time there (docs/performance.md "Events"). Here each size class (16 bytes apart, up to
// kMaxBlock) has a free list, refilled from 64 KiB chunks; a freed block goes back on its list,
// and the chunks are given back when the pool ends, with the state. Larger blocks are the C
// library's.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace rigidlab::lua {

class BlockPool {
 public:
  static constexpr size_t kMaxBlock = 512;  // bytes; a larger block is not the pool's
  static constexpr size_t kChunk = 64 * 1024;

  BlockPool() = default;
  ~BlockPool();
  BlockPool(const BlockPool&) = delete;
  BlockPool& operator=(const BlockPool&) = delete;

  static bool holds(size_t bytes) { return bytes <= kMaxBlock; }
  // The same list serves both sizes: a block of one can stand for the other.
  static bool sameClass(size_t a, size_t b) { return classOf(a) == classOf(b); }

  // A block of at least `bytes` (1 … kMaxBlock), 16-byte aligned; nullptr when no chunk can be had.
  void* take(size_t bytes);
  // Gives back a block that take(bytes) returned (or take of a size of the same class).
  void give(void* block, size_t bytes);

  size_t chunkBytes() const { return chunks_.size() * kChunk; }

 private:
  static size_t classOf(size_t bytes) { return (bytes + 15) / 16 - 1; }
  struct Free {
    Free* next;
  };
  std::array<Free*, kMaxBlock / 16> free_{};
  std::vector<void*> chunks_;
  char* cursor_ = nullptr;  // the unused rest of the newest chunk
  char* end_ = nullptr;
};

}  // namespace rigidlab::lua

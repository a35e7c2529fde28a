#include "block_pool.h"

#include <cstdlib>

// Under AddressSanitizer a block on a free list (and the rest of a chunk) is poisoned, so a use
// after free inside the pool is still caught.
#if defined(__SANITIZE_ADDRESS__)
#define RIGIDLAB_POOL_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RIGIDLAB_POOL_ASAN 1
#endif
#endif
#ifdef RIGIDLAB_POOL_ASAN
#include <sanitizer/asan_interface.h>
#define POISON(p, n) ASAN_POISON_MEMORY_REGION(p, n)
#define UNPOISON(p, n) ASAN_UNPOISON_MEMORY_REGION(p, n)
#else
#define POISON(p, n) ((void)(p), (void)(n))
#define UNPOISON(p, n) ((void)(p), (void)(n))
#endif

namespace rigidlab::lua {

BlockPool::~BlockPool() {
  for (void* chunk : chunks_) {
    UNPOISON(chunk, kChunk);
    std::free(chunk);
  }
}

void* BlockPool::take(size_t bytes) {
  const size_t c = classOf(bytes);
  if (Free* f = free_[c]) {
    UNPOISON(f, (c + 1) * 16);
    free_[c] = f->next;
    return f;
  }
  const size_t size = (c + 1) * 16;
  if (static_cast<size_t>(end_ - cursor_) < size) {
    // The rest of the old chunk (less than one block) is left unused.
    void* chunk = std::aligned_alloc(16, kChunk);
    if (!chunk) return nullptr;
    try {  // Lua's allocator must not throw
      chunks_.push_back(chunk);
    } catch (...) {
      std::free(chunk);
      return nullptr;
    }
    POISON(chunk, kChunk);
    cursor_ = static_cast<char*>(chunk);
    end_ = cursor_ + kChunk;
  }
  void* block = cursor_;
  cursor_ += size;
  UNPOISON(block, size);
  return block;
}

void BlockPool::give(void* block, size_t bytes) {
  Free* f = static_cast<Free*>(block);
  const size_t c = classOf(bytes);
  f->next = free_[c];
  free_[c] = f;
  POISON(f, (c + 1) * 16);
}

}  // namespace rigidlab::lua

// FNV-1a over the exact bits of a state (integers, doubles, vectors), for tests that compare two
// runs bit for bit (tests/core/test_snapshot.cpp, tests/lua/scene_resume.cpp).
#pragma once

#include <bit>
#include <cstdint>

#include "rigidlab/math.h"

namespace rigidlab::test {

struct Hash {
  uint64_t h = 1469598103934665603ull;
  void add(uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      h ^= (v >> (8 * i)) & 0xff;
      h *= 1099511628211ull;
    }
  }
  void add(double x) { add(std::bit_cast<uint64_t>(x)); }
  void add(const Vec2& v) {
    add(v.x());
    add(v.y());
  }
};

}  // namespace rigidlab::test

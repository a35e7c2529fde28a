// The default broad phase: a uniform grid rebuilt every step.
//
// Why a grid: rigidlab's benchmark scenes (pyramids, stacks, rain) are made of bodies of similar
// size packed together, where a grid finds the pairs in O(n) with a few array passes and no tree
// to maintain. Measured on the peer scenes (docs/performance.md): for the 5050-box pyramid it
// takes a fraction of a millisecond per step, against ~13 M box tests for all pairs. Bodies much
// larger than a cell (the ground, the walls of a container) would cover thousands of cells; they go
// to a short "large" list tested against everything instead. A sweep along x was the other
// candidate: cheaper to write, but in tall scenes every box overlaps a whole column in x.
//
//   1. cell size = twice the mean extent of the dynamic bodies' boxes;
//   2. each box is entered in every cell it touches as (cell key, proxy), sorted by key with an
//      LSD radix sort (stable, so proxies stay in slot order within a cell);
//   3. within each cell every pair whose boxes overlap is reported once: in the cell holding the
//      lower-left corner of the two boxes' intersection;
//   4. the pairs are radix-sorted by (a, b), so the order is deterministic.
// The scratch arrays persist, so a step in steady state allocates nothing.
#include <algorithm>
#include <cmath>

#include "broad_phase.h"

namespace rigidlab {
namespace {

constexpr int kLargeCells = 16;  // boxes covering more cells than this go to the large list
constexpr double kFar = 1e15;    // cell numbers beyond this do not fit an int64 safely: the large list

// ⌊x⌋ for |x| < 2⁶², by truncation: std::floor is a library call in the portable x86-64 build
// (no SSE4.1 round instruction), and this file calls it for every box and every candidate pair.
inline int64_t floorToInt(double x) {
  const auto t = static_cast<int64_t>(x);
  return t - (static_cast<double>(t) > x);
}

uint64_t cellKey(int64_t cx, int64_t cy) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(cx)) << 32) | static_cast<uint32_t>(cy);
}

// Stable sort by a 64-bit key: an LSD radix sort with 8-bit digits that skips the digits on which
// all keys agree; small inputs use a stable comparison sort.
template <typename T, typename Key>
void radixSort(std::vector<T>& items, std::vector<T>& scratch, std::vector<uint32_t>& count, Key key) {
  if (items.size() < 64) {
    std::stable_sort(items.begin(), items.end(), [&](const T& a, const T& b) { return key(a) < key(b); });
    return;
  }
  uint64_t all_or = 0, all_and = ~uint64_t{0};
  for (const T& x : items) {
    all_or |= key(x);
    all_and &= key(x);
  }
  scratch.resize(items.size());
  count.resize(256);
  for (int shift = 0; shift < 64; shift += 8) {
    if (((all_or ^ all_and) >> shift & 0xFF) == 0) continue;  // this digit is the same everywhere
    std::fill(count.begin(), count.end(), 0);
    for (const T& x : items) ++count[key(x) >> shift & 0xFF];
    uint32_t sum = 0;
    for (uint32_t& c : count) {
      const uint32_t k = c;
      c = sum;
      sum += k;
    }
    for (const T& x : items) scratch[count[key(x) >> shift & 0xFF]++] = x;
    items.swap(scratch);
  }
}

}  // namespace

bool GridBroadPhase::findPairs(std::span<const Proxy> proxies, std::vector<BodyPair>& pairs, const PairLimit& limit,
                               PairOverflow* overflow) {
  pairs.clear();
  entries_.clear();
  large_.clear();
  is_large_.assign(proxies.size(), 0);

  double extent = 0.0;
  int dynamic = 0;
  for (const Proxy& p : proxies) {
    if (!p.active || p.is_static) continue;
    extent += std::max(p.aabb.upper.x() - p.aabb.lower.x(), p.aabb.upper.y() - p.aabb.lower.y());
    ++dynamic;
  }
  if (dynamic == 0) return true;  // static–static pairs are never reported
  const double cell = std::max(2.0 * extent / dynamic, 1e-6);
  const double inv = 1.0 / cell;
  // Cells are numbered from the lowest corner of the boxes, so the keys are small non-negative
  // numbers and the radix sort skips the digits they share: with cells on both sides of zero, the
  // high bytes of the signed numbers (0x00… and 0xFF…) made every digit differ, and the sort took
  // a third of the stage (rain of 4000 circles, perf).
  int64_t base_x = INT64_MAX, base_y = INT64_MAX;
  for (const Proxy& p : proxies) {
    if (!p.active) continue;
    const double lx = p.aabb.lower.x() * inv, ly = p.aabb.lower.y() * inv;
    if (std::abs(lx) < kFar && std::abs(ly) < kFar) {
      base_x = std::min(base_x, floorToInt(lx));
      base_y = std::min(base_y, floorToInt(ly));
    }
  }
  const auto key = [&](int64_t cx, int64_t cy) { return cellKey(cx - base_x, cy - base_y); };

  for (uint32_t i = 0; i < proxies.size(); ++i) {
    const Proxy& p = proxies[i];
    if (!p.active) continue;
    const double lx = p.aabb.lower.x() * inv, ux = p.aabb.upper.x() * inv;
    const double ly = p.aabb.lower.y() * inv, uy = p.aabb.upper.y() * inv;
    // A box so far out that its cell numbers would not fit an int64 (a body at 1e30 m: converting
    // that double is undefined behaviour), or not finite, or of many cells, is tested against all
    // others.
    const bool far = !(std::abs(lx) < kFar && std::abs(ux) < kFar && std::abs(ly) < kFar && std::abs(uy) < kFar);
    const int64_t x0 = far ? 0 : floorToInt(lx), x1 = far ? 0 : floorToInt(ux);
    const int64_t y0 = far ? 0 : floorToInt(ly), y1 = far ? 0 : floorToInt(uy);
    // The cell count in double: spans up to 2e15 cells a side overflow an int64 product.
    if (far || static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) > kLargeCells) {
      large_.push_back(i);
      is_large_[i] = 1;
      continue;
    }
    for (int64_t cx = x0; cx <= x1; ++cx)
      for (int64_t cy = y0; cy <= y1; ++cy) entries_.push_back({key(cx, cy), i});
  }
  radixSort(entries_, entry_scratch_, counts_, [](const Entry& e) { return e.key; });

  // The limit (PairLimit) is checked as the pairs and tests are made, so a heap of coincident
  // boxes stops after `limit.pairs` pairs instead of producing all n²/2 of them.
  size_t tests = 0;
  const auto emit = [&](uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    if (pairs.size() >= limit.pairs) return false;
    pairs.push_back({a, b});
    return true;
  };
  for (size_t start = 0; start < entries_.size();) {
    size_t end = start + 1;
    while (end < entries_.size() && entries_[end].key == entries_[start].key) ++end;
    const uint64_t here = entries_[start].key;
    for (size_t i = start; i < end; ++i) {
      tests += end - i - 1;
      const Proxy& p = proxies[entries_[i].proxy];
      bool full = tests > limit.tests;
      for (size_t j = full ? end : i + 1; j < end; ++j) {
        const Proxy& q = proxies[entries_[j].proxy];
        if ((p.is_static && q.is_static) || !p.aabb.overlaps(q.aabb)) continue;
        // Report the pair only in the cell of the intersection's lower-left corner.
        const Vec2 corner = p.aabb.lower.cwiseMax(q.aabb.lower);
        if (key(floorToInt(corner.x() * inv), floorToInt(corner.y() * inv)) != here) continue;
        if (!emit(entries_[i].proxy, entries_[j].proxy)) {
          full = true;
          break;
        }
      }
      if (full) {
        noteOverflow(overflow, tests > limit.tests, end - start, proxies[entries_[start].proxy].aabb);
        return false;
      }
    }
    start = end;
  }
  // Large boxes against everything else (and each other once).
  for (size_t k = 0; k < large_.size(); ++k) {
    const uint32_t l = large_[k];
    const Proxy& big = proxies[l];
    tests += proxies.size();
    bool full = tests > limit.tests;
    for (uint32_t i = 0, count = full ? 0 : static_cast<uint32_t>(proxies.size()); i < count; ++i) {
      const Proxy& p = proxies[i];
      if (i == l || !p.active || (big.is_static && p.is_static) || !big.aabb.overlaps(p.aabb)) continue;
      if (is_large_[i] && i < l) continue;  // that pair was reported from i's side
      if (!emit(l, i)) {
        full = true;
        break;
      }
    }
    if (full) {
      noteOverflow(overflow, tests > limit.tests, crowdAround(proxies, l), big.aabb);
      return false;
    }
  }
  radixSort(pairs, pair_scratch_, counts_, [](const BodyPair& p) { return static_cast<uint64_t>(p.a) << 32 | p.b; });
  return true;
}

}  // namespace rigidlab

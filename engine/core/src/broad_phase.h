// Broad phase: which pairs of bodies might touch. It sees only bounding boxes. Pairs come out in a
// deterministic order (a < b, ascending), static–static pairs never (docs/design/thesis.md §7).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "rigidlab/math.h"

namespace rigidlab {

struct BodyPair {
  uint32_t a, b;  // body slots, a < b
};

// What the broad phase knows about one body slot.
struct Proxy {
  Aabb aabb;
  bool is_static = false;
  bool active = false;  // false for destroyed slots
};

// Pairs kept from one step to the next (a Verlet list; Box2D's "fat" boxes serve the same end).
// The list holds every pair whose boxes, grown by a margin, overlapped when it was built. While every
// body's box stays inside its grown box (and no body is added, removed or switched static), every
// pair that can overlap now is in the list, so the step only filters it: the same pairs in the same
// order as a rebuild, at the cost of a containment test per body. Resting piles and contact-free
// scenes rebuild rarely; when lists keep dying within a few steps (a falling rain) the step goes
// back to plain rebuilds for a while (broad_phase.cpp).
struct PairCache {
  std::vector<Proxy> grown;     // per slot when built: the box grown by its margin, and the flags
  std::vector<BodyPair> pairs;  // pairs whose grown boxes overlap, ascending
  int age = 0;                  // steps the list has served
  int cooldown = 0;             // steps left of plain rebuilds
  bool valid = false;
};

// How far one pass may go (WorldDef::pair_cap): it stops as soon as it has `pairs` pairs or has
// made `tests` box tests, so bodies heaped on each other cannot make it quadratic in memory or time.
struct PairLimit {
  size_t pairs = SIZE_MAX;
  size_t tests = SIZE_MAX;
};

// Where a pass that reached its limit stopped: the boxes crowding there, for the error message.
struct PairOverflow {
  bool tests = false;          // the test limit was reached (else the pair limit)
  size_t crowd = 0;            // boxes in the grid cell (or overlapping the box) where it stopped
  Vec2 where = Vec2::Zero();   // the centre of the first of those boxes
};

// For the passes' overflow reports: the active boxes overlapping proxies[i]'s (itself included),
// and filling `overflow` (if given) with a crowd around `box`.
size_t crowdAround(std::span<const Proxy> proxies, uint32_t i);
void noteOverflow(PairOverflow* overflow, bool tests, size_t crowd, const Aabb& box);

class BroadPhase {
 public:
  virtual ~BroadPhase() = default;
  // Replaces `pairs` with every pair of active proxies whose boxes overlap, skipping static–static.
  // False if `limit` was reached first: `pairs` then holds what was found so far, in no particular
  // order, and `overflow` (if given) says where.
  virtual bool findPairs(std::span<const Proxy> proxies, std::vector<BodyPair>& pairs, const PairLimit& limit = {},
                         PairOverflow* overflow = nullptr) = 0;
};

// The thesis's naive test of every pair (docs/design/thesis.md §7), with a bounding-box check per pair. O(n²):
// fine for a few hundred bodies. Only `limit.pairs` applies (testing every pair is its design).
class AllPairsBroadPhase final : public BroadPhase {
 public:
  bool findPairs(std::span<const Proxy> proxies, std::vector<BodyPair>& pairs, const PairLimit& limit = {},
                 PairOverflow* overflow = nullptr) override;
};

// A uniform grid rebuilt every step, with a list for boxes much larger than a cell
// (spatial_grid.cpp): O(n) for scenes of similar-sized bodies. The default.
class GridBroadPhase final : public BroadPhase {
 public:
  bool findPairs(std::span<const Proxy> proxies, std::vector<BodyPair>& pairs, const PairLimit& limit = {},
                 PairOverflow* overflow = nullptr) override;

 private:
  struct Entry {
    uint64_t key;    // cell
    uint32_t proxy;
  };
  std::vector<Entry> entries_, entry_scratch_;
  std::vector<uint32_t> large_, counts_;
  std::vector<char> is_large_;
  std::vector<BodyPair> pair_scratch_;
};

}  // namespace rigidlab

// A dynamic bounding-volume tree (aabb_tree.cpp) for the world's queries and sensors: each leaf
// holds a shape's box grown by a margin ("fat" box), so that a shape moving a little stays in its
// leaf and the tree changes only when a shape leaves its fat box. Insertion picks the sibling that
// grows the tree's total perimeter least (the surface-area heuristic in 2D), and the tree is kept
// balanced by rotations on the way up (E. Catto, "Dynamic Bounding Volume Hierarchies", GDC 2019;
// Box2D's b2DynamicTree). Queries walk it with a small stack and no allocation.
#pragma once

#include <cstdint>
#include <vector>

#include "rigidlab/math.h"

namespace rigidlab {

class AabbTree {
 public:
  static constexpr int32_t kNull = -1;

  // A leaf for `item` with the fat box of `box`; returns its node.
  int32_t insert(const Aabb& box, uint32_t item);
  void remove(int32_t leaf);
  // The shape's box is now `box`: refits the leaf (returns true) if it left the fat box.
  bool move(int32_t leaf, const Aabb& box);
  const Aabb& fatBox(int32_t leaf) const { return nodes_[leaf].box; }
  uint32_t item(int32_t leaf) const { return nodes_[leaf].item; }
  void clear();
  int height() const { return root_ == kNull ? 0 : nodes_[root_].height; }
  bool empty() const { return root_ == kNull; }

  // Calls visit(item) for every leaf whose fat box overlaps `box`; visit returns false to stop.
  template <typename Visit>
  void query(const Aabb& box, Visit visit) const {
    if (root_ == kNull) return;
    int32_t stack[kStack];
    int depth = 0;
    stack[depth++] = root_;
    while (depth > 0) {
      const Node& n = nodes_[stack[--depth]];
      if (!n.box.overlaps(box)) continue;
      if (n.child1 == kNull) {
        if (!visit(n.item)) return;
      } else if (depth + 2 <= kStack) {
        stack[depth++] = n.child1;
        stack[depth++] = n.child2;
      }
    }
  }

  // Ray p1 → p2 (fraction 0 … max_fraction): calls cast(item, current_max) for every leaf whose fat
  // box the ray segment crosses; cast returns the new max fraction (the hit's, to clip the ray; 0
  // to stop; current_max to go on unchanged). The slab test rejects boxes the segment misses.
  template <typename Cast>
  void rayCast(const Vec2& p1, const Vec2& p2, double max_fraction, Cast cast) const {
    if (root_ == kNull) return;
    const Vec2 d = p2 - p1;
    int32_t stack[kStack];
    int depth = 0;
    stack[depth++] = root_;
    while (depth > 0) {
      const Node& n = nodes_[stack[--depth]];
      if (!segmentHitsBox(p1, d, max_fraction, n.box)) continue;
      if (n.child1 == kNull) {
        max_fraction = cast(n.item, max_fraction);
        if (max_fraction <= 0.0) return;
      } else if (depth + 2 <= kStack) {
        stack[depth++] = n.child1;
        stack[depth++] = n.child2;
      }
    }
  }

  // The margin a leaf's box is grown by: a tenth of its larger side plus 1 cm.
  static Aabb fatten(const Aabb& box);

 private:
  static constexpr int kStack = 256;  // deeper than a balanced tree of any size we hold
  struct Node {
    Aabb box;
    uint32_t item = 0;
    int32_t parent = kNull, child1 = kNull, child2 = kNull;  // parent doubles as the free list's next
    int height = 0;                                           // leaf 0, free −1
  };
  static bool segmentHitsBox(const Vec2& p, const Vec2& d, double max_fraction, const Aabb& box);
  int32_t allocate();
  void release(int32_t node);
  void insertLeaf(int32_t leaf);
  void removeLeaf(int32_t leaf);
  int32_t balance(int32_t a);

  std::vector<Node> nodes_;
  int32_t root_ = kNull;
  int32_t free_ = kNull;
};

}  // namespace rigidlab

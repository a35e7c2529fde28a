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
    queryContained(box, [&](uint32_t item, bool) { return visit(item); });
  }

  // As query, with visit(item, contained): contained is true when the leaf's fat box lies inside
  // `box` (then so does its shape, which the fat box holds), so the caller may skip its exact test.
  // A node inside `box` has all its leaves inside: they are visited without a test each.
  template <typename Visit>
  void queryContained(const Aabb& box, Visit visit) const {
    if (root_ == kNull) return;
    struct Entry {
      int32_t node;
      bool contained;
    };
    Entry stack[kStack];
    int depth = 0;
    stack[depth++] = {root_, false};
    while (depth > 0) {
      const Entry e = stack[--depth];
      const Node& n = nodes_[e.node];
      bool contained = e.contained;
      if (!contained) {
        if (!n.box.overlaps(box)) continue;
        contained = inside(n.box, box);
      }
      if (n.child1 == kNull) {
        if (!visit(n.item, contained)) return;
      } else if (depth + 2 <= kStack) {
        stack[depth++] = {n.child1, contained};
        stack[depth++] = {n.child2, contained};
      }
    }
  }

  // Ray p1 → p2 (fraction 0 … max_fraction): calls cast(item, current_max) for every leaf whose fat
  // box the ray segment crosses before current_max; cast returns the new max fraction (the hit's,
  // to clip the ray; 0 to stop; current_max to go on unchanged). The slab test rejects boxes the
  // segment misses; of two children the one the ray enters first is walked first, so a closest-hit
  // cast clips the ray early and skips what lies behind its hit.
  template <typename Cast>
  void rayCast(const Vec2& p1, const Vec2& p2, double max_fraction, Cast cast) const {
    if (root_ == kNull) return;
    const Ray ray(p1, p2 - p1);
    struct Entry {
      int32_t node;
      double enter;  // the fraction at which the ray enters the node's box
    };
    Entry stack[kStack];
    int depth = 0;
    double enter = 0.0;
    if (!ray.hits(nodes_[root_].box, max_fraction, enter)) return;
    stack[depth++] = {root_, enter};
    while (depth > 0) {
      const Entry e = stack[--depth];
      if (e.enter > max_fraction) continue;  // the ray was clipped short of it since
      const Node& n = nodes_[e.node];
      if (n.child1 == kNull) {
        max_fraction = cast(n.item, max_fraction);
        if (max_fraction <= 0.0) return;
        continue;
      }
      if (depth + 2 > kStack) continue;
      double t1 = 0.0, t2 = 0.0;
      const bool h1 = ray.hits(nodes_[n.child1].box, max_fraction, t1);
      const bool h2 = ray.hits(nodes_[n.child2].box, max_fraction, t2);
      if (h1 && h2) {  // the nearer one on top
        if (t1 <= t2) {
          stack[depth++] = {n.child2, t2};
          stack[depth++] = {n.child1, t1};
        } else {
          stack[depth++] = {n.child1, t1};
          stack[depth++] = {n.child2, t2};
        }
      } else if (h1) {
        stack[depth++] = {n.child1, t1};
      } else if (h2) {
        stack[depth++] = {n.child2, t2};
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
  // The segment p + t d, t ∈ [0, max], against boxes by slabs, with 1/d computed once per ray.
  struct Ray {
    Vec2 p, d, inv;
    Ray(const Vec2& p1, const Vec2& dir);
    // Does the segment up to `max_fraction` meet `box`? `enter`: where it does first (≥ 0).
    bool hits(const Aabb& box, double max_fraction, double& enter) const;
  };
  static bool inside(const Aabb& small, const Aabb& big) {
    return big.lower.x() <= small.lower.x() && big.lower.y() <= small.lower.y() && small.upper.x() <= big.upper.x() &&
           small.upper.y() <= big.upper.y();
  }
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

// The dynamic bounding-volume tree (aabb_tree.h).
#include "aabb_tree.h"

#include <algorithm>
#include <cmath>

namespace rigidlab {
namespace {

Aabb merged(const Aabb& a, const Aabb& b) { return {a.lower.cwiseMin(b.lower), a.upper.cwiseMax(b.upper)}; }
double perimeter(const Aabb& a) { return 2.0 * ((a.upper.x() - a.lower.x()) + (a.upper.y() - a.lower.y())); }

}  // namespace

Aabb AabbTree::fatten(const Aabb& box) {
  const Vec2 size = box.upper - box.lower;
  const Vec2 grow = Vec2::Constant(0.1 * size.maxCoeff() + 0.01);
  return {box.lower - grow, box.upper + grow};
}

AabbTree::Ray::Ray(const Vec2& p1, const Vec2& dir) : p(p1), d(dir) {
  for (int axis = 0; axis < 2; ++axis) inv[axis] = d[axis] == 0.0 ? 0.0 : 1.0 / d[axis];
}

bool AabbTree::Ray::hits(const Aabb& box, double max_fraction, double& enter) const {
  // Slabs: the segment p + t d, t ∈ [0, max_fraction], against lower ≤ x ≤ upper per axis.
  double t0 = 0.0, t1 = max_fraction;
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = box.lower[axis], hi = box.upper[axis];
    if (d[axis] == 0.0) {
      if (p[axis] < lo || p[axis] > hi) return false;
      continue;
    }
    double a = (lo - p[axis]) * inv[axis], b = (hi - p[axis]) * inv[axis];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  enter = t0;
  return true;
}

int32_t AabbTree::allocate() {
  if (free_ == kNull) {
    nodes_.emplace_back();
    return static_cast<int32_t>(nodes_.size() - 1);
  }
  const int32_t n = free_;
  free_ = nodes_[n].parent;
  nodes_[n] = Node{};
  return n;
}

void AabbTree::release(int32_t node) {
  nodes_[node].parent = free_;
  nodes_[node].height = -1;
  free_ = node;
}

void AabbTree::clear() {
  nodes_.clear();
  root_ = free_ = kNull;
}

int32_t AabbTree::insert(const Aabb& box, uint32_t item) {
  const int32_t leaf = allocate();
  nodes_[leaf].box = fatten(box);
  nodes_[leaf].item = item;
  nodes_[leaf].height = 0;
  insertLeaf(leaf);
  return leaf;
}

void AabbTree::remove(int32_t leaf) {
  removeLeaf(leaf);
  release(leaf);
}

bool AabbTree::move(int32_t leaf, const Aabb& box) {
  if (inside(box, nodes_[leaf].box)) return false;
  removeLeaf(leaf);
  nodes_[leaf].box = fatten(box);
  insertLeaf(leaf);
  return true;
}

void AabbTree::insertLeaf(int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  // Descend to the sibling whose pairing costs least: the new parent's perimeter, plus the growth
  // it causes in every ancestor (which is paid whichever child is taken).
  const Aabb box = nodes_[leaf].box;
  int32_t index = root_;
  while (nodes_[index].child1 != kNull) {
    const Node& n = nodes_[index];
    const double area = perimeter(n.box), combined = perimeter(merged(n.box, box));
    const double cost = 2.0 * combined;                  // make a new parent here
    const double inheritance = 2.0 * (combined - area);  // pushing the leaf lower grows this node
    const auto childCost = [&](int32_t c) {
      const Node& child = nodes_[c];
      const double grown = perimeter(merged(box, child.box));
      return child.child1 == kNull ? grown + inheritance : grown - perimeter(child.box) + inheritance;
    };
    const double cost1 = childCost(n.child1), cost2 = childCost(n.child2);
    if (cost < cost1 && cost < cost2) break;
    index = cost1 < cost2 ? n.child1 : n.child2;
  }
  const int32_t sibling = index;
  const int32_t old_parent = nodes_[sibling].parent;
  const int32_t parent = allocate();
  nodes_[parent].parent = old_parent;
  nodes_[parent].box = merged(box, nodes_[sibling].box);
  nodes_[parent].height = nodes_[sibling].height + 1;
  nodes_[parent].child1 = sibling;
  nodes_[parent].child2 = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (nodes_[old_parent].child1 == sibling) {
    nodes_[old_parent].child1 = parent;
  } else {
    nodes_[old_parent].child2 = parent;
  }
  // Refit and balance the ancestors.
  for (int32_t i = nodes_[leaf].parent; i != kNull; i = nodes_[i].parent) {
    i = balance(i);
    const Node& n = nodes_[i];
    nodes_[i].height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
    nodes_[i].box = merged(nodes_[n.child1].box, nodes_[n.child2].box);
  }
}

void AabbTree::removeLeaf(int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const int32_t parent = nodes_[leaf].parent;
  const int32_t grand = nodes_[parent].parent;
  const int32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  if (grand == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
    release(parent);
    return;
  }
  if (nodes_[grand].child1 == parent) {
    nodes_[grand].child1 = sibling;
  } else {
    nodes_[grand].child2 = sibling;
  }
  nodes_[sibling].parent = grand;
  release(parent);
  for (int32_t i = grand; i != kNull; i = nodes_[i].parent) {
    i = balance(i);
    const Node& n = nodes_[i];
    nodes_[i].box = merged(nodes_[n.child1].box, nodes_[n.child2].box);
    nodes_[i].height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
  }
}

// If a's subtrees differ in height by more than one, rotates the taller one up (an AVL rotation);
// returns the node now in a's place.
int32_t AabbTree::balance(int32_t ia) {
  Node& a = nodes_[ia];
  if (a.child1 == kNull || a.height < 2) return ia;
  const int32_t ib = a.child1, ic = a.child2;
  const int diff = nodes_[ic].height - nodes_[ib].height;
  const auto rotate = [&](int32_t up, int32_t other) {  // `up` (a child of a) replaces a
    Node& u = nodes_[up];
    const int32_t f = u.child1, g = u.child2;
    u.child1 = ia;
    u.parent = a.parent;
    a.parent = up;
    if (u.parent != kNull) {
      if (nodes_[u.parent].child1 == ia) {
        nodes_[u.parent].child1 = up;
      } else {
        nodes_[u.parent].child2 = up;
      }
    } else {
      root_ = up;
    }
    // The taller of up's children stays with it; the other goes to a.
    const bool f_taller = nodes_[f].height > nodes_[g].height;
    const int32_t keep = f_taller ? f : g, give = f_taller ? g : f;
    u.child2 = keep;
    if (a.child1 == up) {
      a.child1 = give;
    } else {
      a.child2 = give;
    }
    nodes_[give].parent = ia;
    a.box = merged(nodes_[other].box, nodes_[give].box);
    a.height = 1 + std::max(nodes_[other].height, nodes_[give].height);
    u.box = merged(a.box, nodes_[keep].box);
    u.height = 1 + std::max(a.height, nodes_[keep].height);
    return up;
  };
  if (diff > 1) return rotate(ic, ib);
  if (diff < -1) return rotate(ib, ic);
  return ia;
}

}  // namespace rigidlab

// Stage 2 of the step: candidate pairs from bounding boxes (origin.md §7).
#include "broad_phase.h"

#include <limits>

#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

void AllPairsBroadPhase::findPairs(std::span<const Proxy> proxies, std::vector<BodyPair>& pairs) {
  pairs.clear();
  const uint32_t n = static_cast<uint32_t>(proxies.size());
  for (uint32_t i = 0; i < n; ++i) {
    const Proxy& p = proxies[i];
    if (!p.active) continue;
    for (uint32_t j = i + 1; j < n; ++j) {
      const Proxy& q = proxies[j];
      if (q.active && !(p.is_static && q.is_static) && p.aabb.overlaps(q.aabb)) pairs.push_back({i, j});
    }
  }
}

void findPairs(WorldImpl& w) {
  const size_t n = w.bodies.size();
  if (n < 2) {
    w.pairs.clear();
    return;
  }
  w.proxies.resize(n);
  w.polygon_offset.resize(n);
  w.world_vertices.clear();
  w.world_normals.clear();
  for (size_t i = 0; i < n; ++i) {
    Proxy& p = w.proxies[i];
    p.active = w.alive[i];
    if (!p.active) continue;
    const Body& b = w.bodies[i];
    p.is_static = b.isStatic();
    if (b.shape.type == ShapeType::Polygon) {
      // Each polygon is placed in the world once per step; the narrow phase reads it for every
      // pair (manifold.h WorldPolygon), and its box comes from the placed vertices.
      w.polygon_offset[i] = static_cast<uint32_t>(w.world_vertices.size());
      p.aabb = {Vec2::Constant(std::numeric_limits<double>::infinity()), Vec2::Constant(-std::numeric_limits<double>::infinity())};
      for (size_t k = 0; k < b.shape.vertices.size(); ++k) {
        const Vec2 v = b.xf.apply(b.shape.vertices[k]);
        w.world_vertices.push_back(v);
        w.world_normals.push_back(b.xf.q.apply(b.shape.normals[k]));
        p.aabb.lower = p.aabb.lower.cwiseMin(v);
        p.aabb.upper = p.aabb.upper.cwiseMax(v);
      }
    } else {
      p.aabb = computeAabb(b.shape, b.xf);
    }
    // Inflated by half the contact margin each, so pairs within the margin are found.
    const Vec2 half_margin = Vec2::Constant(0.5 * w.def.contact_margin);
    p.aabb.lower -= half_margin;
    p.aabb.upper += half_margin;
  }
  w.broad_phase->findPairs(w.proxies, w.pairs);
}

}  // namespace rigidlab

// The world's queries (world.h): ray casts, box, point and shape overlaps, shape casts, explosions.
// They share one bounding-volume tree of the shapes (aabb_tree.h), synced lazily: the first query
// after a step or an edit refits the leaves of the shapes that left their fat boxes (O(n) checks,
// few refits for a resting scene), and every query after it in the same step only walks the tree.
#include <algorithm>
#include <cmath>

#include "rigidlab/error.h"
#include "rigidlab/world.h"
#include "shape_query.h"
#include "world_impl.h"

namespace rigidlab {

void WorldImpl::syncTree() {
  if (tree_version == layout_version) return;
  tree_version = layout_version;
  // Static shapes move only by an edit that counts in static_version (a shape added, a body moved,
  // retyped or enabled): while it is unchanged their leaves are already right.
  const bool statics_synced = tree_static_version == static_version;
  tree_static_version = static_version;
  tree_leaf.resize(shapes.size(), AabbTree::kNull);
  tree_shapes.resize(shapes.size());
  for (uint32_t s = 0; s < shapes.size(); ++s) {
    const bool in = shape_alive[s] && bodyOf(s).enabled;
    int32_t& leaf = tree_leaf[s];
    if (!in) {
      if (leaf != AabbTree::kNull) {
        tree.remove(leaf);
        leaf = AabbTree::kNull;
      }
      continue;
    }
    const Body& body = bodyOf(s);
    const BodyShape& shape = shapes[s];
    tree_shapes[s] = {shape.id, shape.sensor, shape.filter.category, shape.filter.mask};
    if (leaf != AabbTree::kNull && statics_synced && body.isStatic()) continue;
    const Aabb box = computeAabb(shape.geometry, body.xf);
    if (leaf == AabbTree::kNull) {
      leaf = tree.insert(box, s);
    } else {
      tree.move(leaf, box);
    }
  }
}

namespace {

bool accepts(const WorldImpl& w, uint32_t s, const QueryFilter& f) {
  const WorldImpl::QueryShape& shape = w.tree_shapes[s];
  if (shape.sensor && !f.sensors) return false;
  return (shape.category & f.mask) != 0 && (f.category & shape.mask) != 0;
}

// The exact test of a shape whose bounds cross the edge of the (not flat) query box `box`, given
// also as the polygon `query`: a circle by its centre's distance to the box (the closest point of
// the box, clamped per axis), the others by the distance between the convex shapes.
bool boxOverlapsShape(const Aabb& box, const Shape& query, const Shape& shape, const Transform& xf) {
  if (shape.type == ShapeType::Circle) {
    const Vec2 c = xf.apply(shape.center);
    return (c.cwiseMax(box.lower).cwiseMin(box.upper) - c).squaredNorm() <= shape.radius * shape.radius;
  }
  return shapesOverlap(query, Transform{}, shape, xf);
}

RayHit hitOf(const WorldImpl& w, uint32_t s, const ShapeRayHit& h) {
  return {w.shapes[s].id, w.shapes[s].body, h.point, h.normal, h.fraction};
}

void requireFiniteVec(const char* field, const Vec2& v) { requireFinite(field, v); }

}  // namespace

std::optional<RayHit> World::rayCast(const Vec2& from, const Vec2& to, const QueryFilter& filter) const {
  WorldImpl& w = *impl_;
  requireFiniteVec("from", from);
  requireFiniteVec("to", to);
  w.syncTree();
  std::optional<RayHit> best;
  w.tree.rayCast(from, to, 1.0, [&](uint32_t s, double max_fraction) {
    if (!accepts(w, s, filter)) return max_fraction;
    const auto h = rayCastShape(w.shapes[s].geometry, w.bodyOf(s).xf, from, to, max_fraction);
    if (!h) return max_fraction;
    // Equal fractions (a ray through a shared corner): the lower shape slot, so the answer does not
    // depend on the tree's shape.
    if (best && h->fraction == best->fraction && w.shapes[s].id.index > best->shape.index) return max_fraction;
    best = hitOf(w, s, *h);
    return h->fraction;
  });
  return best;
}

std::vector<RayHit> World::rayCastAll(const Vec2& from, const Vec2& to, const QueryFilter& filter) const {
  WorldImpl& w = *impl_;
  requireFiniteVec("from", from);
  requireFiniteVec("to", to);
  w.syncTree();
  std::vector<RayHit> hits;
  w.tree.rayCast(from, to, 1.0, [&](uint32_t s, double max_fraction) {
    if (!accepts(w, s, filter)) return max_fraction;
    if (const auto h = rayCastShape(w.shapes[s].geometry, w.bodyOf(s).xf, from, to, 1.0)) hits.push_back(hitOf(w, s, *h));
    return max_fraction;
  });
  std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) {
    return a.fraction != b.fraction ? a.fraction < b.fraction : a.shape.index < b.shape.index;
  });
  return hits;
}

std::vector<ShapeId> World::queryBox(const Aabb& box, const QueryFilter& filter) const {
  WorldImpl& w = *impl_;
  requireFiniteVec("lower", box.lower);
  requireFiniteVec("upper", box.upper);
  if (box.lower.x() > box.upper.x() || box.lower.y() > box.upper.y())
    throw InputError("lower", "lower " + formatVec(box.lower) + " must not exceed upper " + formatVec(box.upper));
  w.syncTree();
  // The box as a polygon (or a segment or point when it is flat), for the exact test. A box too
  // large to be a shape (its moment of inertia overflows, about 1e77 m) gets the bounds test alone:
  // it differs from the exact one only for shapes across its far edges.
  const Vec2 size = box.upper - box.lower;
  Shape query;
  if (size.x() > 0.0 && size.y() > 0.0) {
    try {
      query = makeBox(size.x(), size.y(), 0.5 * (box.lower + box.upper));
    } catch (const InputError&) {
    }
  }
  std::vector<ShapeId> out;
  w.tree.queryContained(box, [&](uint32_t s, bool contained) {
    if (!accepts(w, s, filter)) return true;
    if (!contained) {  // a shape whose fat box is inside the box overlaps it: no test
      const Transform& xf = w.bodyOf(s).xf;
      const Shape& shape = w.shapes[s].geometry;
      const Aabb bounds = computeAabb(shape, xf);
      if (!bounds.overlaps(box)) return true;
      // Inside the box, or the box is flat (the bounds test is the answer then): no exact test.
      const bool inside = box.lower.x() <= bounds.lower.x() && box.lower.y() <= bounds.lower.y() &&
                          bounds.upper.x() <= box.upper.x() && bounds.upper.y() <= box.upper.y();
      if (!inside && !query.vertices.empty() && !boxOverlapsShape(box, query, shape, xf)) return true;
    }
    out.push_back(w.tree_shapes[s].id);
    return true;
  });
  std::sort(out.begin(), out.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
  return out;
}

std::vector<ShapeId> World::queryPoint(const Vec2& point, const QueryFilter& filter) const {
  WorldImpl& w = *impl_;
  requireFiniteVec("point", point);
  w.syncTree();
  std::vector<ShapeId> out;
  w.tree.query(Aabb{point, point}, [&](uint32_t s) {
    if (accepts(w, s, filter) && containsPoint(w.shapes[s].geometry, w.bodyOf(s).xf, point)) out.push_back(w.shapes[s].id);
    return true;
  });
  std::sort(out.begin(), out.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
  return out;
}

std::vector<ShapeId> World::overlap(const Shape& shape, const Transform& xf, const QueryFilter& filter) const {
  WorldImpl& w = *impl_;
  const Shape query = WorldImpl::validatedShape(shape);
  requireFiniteVec("position", xf.p);
  w.syncTree();
  std::vector<ShapeId> out;
  w.tree.query(computeAabb(query, xf), [&](uint32_t s) {
    if (accepts(w, s, filter) && shapesOverlap(query, xf, w.shapes[s].geometry, w.bodyOf(s).xf)) out.push_back(w.shapes[s].id);
    return true;
  });
  std::sort(out.begin(), out.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
  return out;
}

std::optional<RayHit> World::shapeCast(const Shape& shape, const Transform& xf, const Vec2& translation,
                                              const QueryFilter& filter) const {
  WorldImpl& w = *impl_;
  const Shape query = WorldImpl::validatedShape(shape);
  requireFiniteVec("position", xf.p);
  requireFiniteVec("translation", translation);
  w.syncTree();
  // Candidates: shapes whose fat boxes meet the box swept by the shape.
  const Aabb start = computeAabb(query, xf);
  Transform end_xf = xf;
  end_xf.p += translation;
  const Aabb end = computeAabb(query, end_xf);
  const Aabb swept{start.lower.cwiseMin(end.lower), start.upper.cwiseMax(end.upper)};
  std::optional<RayHit> best;
  w.tree.query(swept, [&](uint32_t s) {
    if (!accepts(w, s, filter)) return true;
    const auto h = shapeCastShape(query, xf, translation, w.shapes[s].geometry, w.bodyOf(s).xf);
    if (h && (!best || h->fraction < best->fraction || (h->fraction == best->fraction && s < best->shape.index)))
      best = hitOf(w, s, *h);
    return true;
  });
  return best;
}

std::vector<BodyId> World::explode(const ExplosionDef& def) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("explode");
  requireFiniteVec("position", def.position);
  requirePositive("radius", def.radius);
  requireNonNegative("falloff", def.falloff);
  requireNonNegative("impulse", def.impulse);
  w.syncTree();
  const double reach = def.radius + def.falloff;
  const Aabb box{def.position - Vec2::Constant(reach), def.position + Vec2::Constant(reach)};
  const Shape centre = makeCircle(1e-9);
  const Transform at{def.position, Rot{}};
  std::vector<uint32_t> shapes;
  w.tree.query(box, [&](uint32_t s) {
    if (accepts(w, s, def.filter) && w.bodyOf(s).isDynamic()) shapes.push_back(s);
    return true;
  });
  std::sort(shapes.begin(), shapes.end());  // deterministic: slot order, whatever the tree
  std::vector<BodyId> pushed;
  std::vector<char> listed(w.bodies.size(), 0);  // per slot: in `pushed` (a search of it would cost n² for n bodies)
  for (uint32_t s : shapes) {
    Body& b = w.bodies[w.shapes[s].body.index];
    Vec2 on_shape, on_centre;
    const double distance = shapeDistance(w.shapes[s].geometry, b.xf, centre, at, &on_shape, &on_centre);
    if (distance > reach) continue;
    const double scale = distance <= def.radius || def.falloff == 0.0 ? 1.0 : std::clamp((reach - distance) / def.falloff, 0.0, 1.0);
    Vec2 direction = on_shape - def.position;
    if (direction.norm() < 1e-12) direction = b.center - def.position;  // the centre is inside the shape
    if (direction.norm() < 1e-12) continue;
    direction.normalize();
    const double magnitude = def.impulse * scale * projectedWidth(w.shapes[s].geometry, b.xf, direction);
    if (magnitude == 0.0) continue;
    applyImpulse(b.id, magnitude * direction, on_shape);
    if (!listed[b.id.index]) {
      listed[b.id.index] = 1;
      pushed.push_back(b.id);
    }
  }
  return pushed;
}

}  // namespace rigidlab

// Stage 2 of the step: candidate pairs from bounding boxes (docs/design/thesis.md §7).
#include "broad_phase.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "rigidlab/error.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

size_t crowdAround(std::span<const Proxy> proxies, uint32_t i) {
  size_t n = 0;
  for (const Proxy& p : proxies) n += p.active && p.aabb.overlaps(proxies[i].aabb);
  return n;
}

void noteOverflow(PairOverflow* overflow, bool tests, size_t crowd, const Aabb& box) {
  if (overflow) *overflow = {tests, crowd, 0.5 * (box.lower + box.upper)};
}

bool AllPairsBroadPhase::findPairs(std::span<const Proxy> proxies, std::vector<BodyPair>& pairs, const PairLimit& limit,
                                   PairOverflow* overflow) {
  pairs.clear();
  const uint32_t n = static_cast<uint32_t>(proxies.size());
  for (uint32_t i = 0; i < n; ++i) {
    const Proxy& p = proxies[i];
    if (!p.active) continue;
    for (uint32_t j = i + 1; j < n; ++j) {
      const Proxy& q = proxies[j];
      if (q.active && !(p.is_static && q.is_static) && p.aabb.overlaps(q.aabb)) {
        if (pairs.size() >= limit.pairs) {
          noteOverflow(overflow, false, crowdAround(proxies, i), p.aabb);
          return false;
        }
        pairs.push_back({i, j});
      }
    }
  }
  return true;
}

namespace {

// A body's box grows by this fraction of its larger side: a 1 m box may then move 25 cm (or turn)
// before the list is rebuilt, which a resting or slowly moving body takes many steps to do.
constexpr double kGrowth = 0.25;
// A list that served fewer steps than this was not worth building; after one, rebuild plainly for
// kCooldown steps before trying again.
constexpr int kShortLife = 4;
constexpr int kCooldown = 30;

bool& pairCacheOn() {
  static bool on = true;
  return on;
}

bool inside(const Aabb& box, const Aabb& grown) {
  return grown.lower.x() <= box.lower.x() && grown.lower.y() <= box.lower.y() && box.upper.x() <= grown.upper.x() &&
         box.upper.y() <= grown.upper.y();
}

// True if every pair whose boxes overlap now is in the cached list (PairCache).
bool cacheHolds(const PairCache& c, std::span<const Proxy> proxies) {
  if (!c.valid || c.grown.size() != proxies.size()) return false;
  for (size_t i = 0; i < proxies.size(); ++i) {
    const Proxy& p = proxies[i];
    const Proxy& g = c.grown[i];
    if (p.active != g.active || p.is_static != g.is_static || (p.active && !inside(p.aabb, g.aabb))) return false;
  }
  return true;
}

// The pairs of the list whose boxes overlap now, in the list's (ascending) order.
void filterPairs(const PairCache& c, std::span<const Proxy> proxies, std::vector<BodyPair>& pairs) {
  pairs.clear();
  for (const BodyPair& q : c.pairs)
    if (proxies[q.a].aabb.overlaps(proxies[q.b].aabb)) pairs.push_back(q);
}

// False if the pass reached `limit` (see PairLimit). A list of grown boxes that reaches it is
// dropped for a plain pass: only the boxes themselves decide whether the step fails.
bool findPairsCached(WorldImpl& w, const PairLimit& limit, PairOverflow& overflow) {
  PairCache& c = w.pair_cache;
  if (!pairCacheOn()) {
    c.valid = false;
    return w.broad_phase->findPairs(w.proxies, w.pairs, limit, &overflow);
  }
  if (cacheHolds(c, w.proxies)) {
    filterPairs(c, w.proxies, w.pairs);
    ++c.age;
    w.stats.pairs_reused = true;
    return true;
  }
  if (c.valid && c.age < kShortLife) c.cooldown = kCooldown;
  c.valid = false;
  if (c.cooldown > 0) {
    --c.cooldown;
    return w.broad_phase->findPairs(w.proxies, w.pairs, limit, &overflow);
  }
  c.grown.assign(w.proxies.begin(), w.proxies.end());
  for (Proxy& g : c.grown) {
    if (!g.active) continue;
    const Vec2 size = g.aabb.upper - g.aabb.lower;
    const Vec2 grow = Vec2::Constant(kGrowth * size.maxCoeff());
    g.aabb.lower -= grow;
    g.aabb.upper += grow;
  }
  if (!w.broad_phase->findPairs(c.grown, c.pairs, limit)) {
    c.pairs.clear();
    c.cooldown = kCooldown;
    return w.broad_phase->findPairs(w.proxies, w.pairs, limit, &overflow);
  }
  c.valid = true;
  c.age = 0;
  filterPairs(c, w.proxies, w.pairs);
  return true;
}

// Box tests allowed per allowed pair (PairLimit::tests): a grid pass makes a few per pair found
// (a pair is tested in every cell its boxes share, up to 16, plus the near misses).
constexpr size_t kTestsPerPair = 64;

std::string overflowMessage(const WorldImpl& w, const PairOverflow& o, size_t bodies, const PairLimit& limit) {
  const std::string rule = "min(" + std::to_string(w.def.pair_cap_max) + ", max(" + std::to_string(w.def.pair_cap) + ", " +
                           std::to_string(w.def.pair_cap_per_body) + " per body)) for " + std::to_string(bodies) + " bodies";
  const std::string at = " at step " + std::to_string(w.step_count + 1) + " (t = " + formatNumber(w.clock.t) + " s): ";
  char where[64];
  std::snprintf(where, sizeof where, "(%.4g, %.4g)", o.where.x(), o.where.y());
  if (o.tests)
    return "too many bodies crammed into one place" + at + std::to_string(o.crowd) + " bodies share a grid cell around " +
           where + ", and finding their contacts would take more than the " + std::to_string(limit.tests) +
           " box tests a step may make (" + std::to_string(kTestsPerPair) + " per candidate pair allowed, " + rule + ")";
  return "too many bodies on top of each other" + at + std::to_string(o.crowd) + " bodies overlap around " + where +
         ", more than the " + std::to_string(limit.pairs) + " candidate contact pairs a step may have (" + rule +
         "); spread them out";
}

}  // namespace

void usePairCache(bool on) { pairCacheOn() = on; }

namespace {

// The fields of a shape's view and proxy that only an edit changes (WorldImpl::shapesEdited).
void gatherShapeView(const WorldImpl& w, size_t i, bool joints, WorldImpl::ShapeView& view, Proxy& p) {
  p.active = false;
  if (!w.shape_alive[i]) return;
  const BodyShape& s = w.shapes[i];
  const Body& b = w.bodies[s.body.index];
  p.active = b.enabled;
  p.is_static = !b.isDynamic();  // static and kinematic bodies do not collide with each other
  if (!p.active) return;
  const Shape& shape = s.geometry;
  view.placed.shape = &shape;
  view.placed.xf = &b.xf;
  view.body = s.body.index;
  view.type = shape.type;
  view.radius = shape.radius;
  view.local_center = shape.center;
  view.local_vertices = shape.vertices.data();
  view.local_normals = shape.normals.data();
  // A box stays one when placed (manifold.h isBox): rounding to nearest is symmetric, so
  // c·(−x) − s·(−y) = −(c·x − s·y) exactly, and Rot::apply turns n and −n into exact opposites.
  view.placed.poly = {nullptr, nullptr, static_cast<int>(shape.vertices.size()),
                      isBox(shape.normals.data(), static_cast<int>(shape.normals.size())), shape.extent};
  view.extent = shape.extent > 0.0 ? shape.extent : maxExtent(shape);  // maxExtent without the call
  view.material = s.material;
  // A body with joints may be kept from colliding with its jointed partners (collide_connected).
  const bool jointed = joints && s.body.index < w.body_joints.size() && !w.body_joints[s.body.index].empty();
  view.special = s.sensor || !s.default_filter || jointed;
}

#ifdef RIGIDLAB_VERIFY_CACHES
// Sanitizer and fuzz builds: the kept fields must be what a fresh gather gives, or some edit
// forgot WorldImpl::shapesEdited.
void verifyShapeViews(const WorldImpl& w, bool joints) {
  for (size_t i = 0; i < w.shapes.size(); ++i) {
    WorldImpl::ShapeView v{};
    Proxy p;
    gatherShapeView(w, i, joints, v, p);
    const WorldImpl::ShapeView& k = w.shape_views[i];
    const Proxy& q = w.proxies[i];
    const char* stale = p.active != q.active       ? "active"
                        : !p.active                  ? nullptr  // an inactive proxy's other fields are never read
                        : p.is_static != q.is_static ? "static"
                        : v.placed.shape != k.placed.shape || v.placed.xf != k.placed.xf || v.body != k.body ? "body"
                        : v.type != k.type || v.radius != k.radius || v.local_center != k.local_center ||
                                v.extent != k.extent || v.local_vertices != k.local_vertices ||
                                v.local_normals != k.local_normals || v.placed.poly.count != k.placed.poly.count ||
                                v.placed.poly.box != k.placed.poly.box || v.placed.poly.extent != k.placed.poly.extent
                            ? "geometry"
                        : v.material.restitution != k.material.restitution || v.material.friction != k.material.friction ||
                                v.material.static_friction != k.material.static_friction
                            ? "material"
                        : v.special != k.special ? "special"
                                                 : nullptr;
    if (stale) {
      std::fprintf(stderr, "rigidlab: the broad phase's view of shape %zu is stale (%s): an edit did not call shapesEdited\n",
                   i, stale);
      std::abort();
    }
  }
}
#endif

// The collision filter (World::setShouldCollide): each pair that the built-in filters let collide
// (two bodies, no sensor, Filter, joints: the narrow phase's rules) is asked once, when it first
// appears among the pairs, that is when its boxes begin to overlap; the answers of the pairs that
// still overlap are kept (WorldImpl::filter_decisions, ascending like the pairs, so one merge pass
// finds them). Pairs answered false are dropped until their boxes part. Costs nothing without a
// filter; with one, a merge over the pairs each step and a call per new pair.
void askShouldCollide(WorldImpl& w) {
  auto& last = w.filter_decisions;
  if (!w.should_collide) {
    last.clear();
    return;
  }
  auto& next = w.filter_scratch;
  next.clear();
  const bool joints = w.joints.size() > w.free_joints.size();
  size_t j = 0, kept = 0;
  for (const BodyPair& pair : w.pairs) {
    const BodyShape &sa = w.shapes[pair.a], &sb = w.shapes[pair.b];
    const bool left_out = sa.body == sb.body || sa.sensor || sb.sensor || !shouldCollide(sa.filter, sb.filter) ||
                          (joints && w.jointBlocksCollision(sa.body.index, sb.body.index));
    bool collide = true;
    if (!left_out) {
      while (j < last.size() && (last[j].a < pair.a || (last[j].a == pair.a && last[j].b < pair.b))) ++j;
      const bool known = j < last.size() && last[j].a == pair.a && last[j].b == pair.b &&
                         last[j].generation_a == sa.id.generation && last[j].generation_b == sb.id.generation;
      collide = known ? last[j].collide : w.should_collide(sa.id, sb.id);
      next.push_back({pair.a, pair.b, sa.id.generation, sb.id.generation, collide});
    }
    if (collide) w.pairs[kept++] = pair;
  }
  w.pairs.resize(kept);
  last.swap(next);
}

}  // namespace

void World::setShouldCollide(ShouldCollideFn callback) { impl_->should_collide = std::move(callback); }

void findPairs(WorldImpl& w) {
  const size_t n = w.shapes.size();
  if (n < 2) {
    w.pairs.clear();
    w.pair_cache.valid = false;
    w.filter_decisions.clear();
    return;
  }
  w.proxies.resize(n);
  w.polygon_offset.resize(n);
  const bool joints = w.joints.size() > w.free_joints.size();  // some joint is alive
  if (w.shape_views.size() != n) w.shape_views_current.value = false;
  if (!w.shape_views_current.value) {
    w.shape_views.resize(n);
    w.active_shapes = 0;
    for (size_t i = 0; i < n; ++i) {
      gatherShapeView(w, i, joints, w.shape_views[i], w.proxies[i]);
      w.active_shapes += w.proxies[i].active;
    }
    w.shape_views_current.value = true;
  }
#ifdef RIGIDLAB_VERIFY_CACHES
  verifyShapeViews(w, joints);
#endif
  const size_t bodies = w.active_shapes;  // active shapes, in fact: what the cap scales with
  w.world_vertices.clear();
  w.world_normals.clear();
  // The views point into world_vertices and world_normals as they grow; if either moved (it grew
  // past its capacity: the first steps, new shapes), the pointers are set again below.
  const size_t vertex_capacity = w.world_vertices.capacity(), normal_capacity = w.world_normals.capacity();
  // Inflated by half the contact margin each, so pairs within the margin are found.
  const Vec2 half_margin = Vec2::Constant(0.5 * w.def.contact_margin);
  for (size_t i = 0; i < n; ++i) {
    Proxy& p = w.proxies[i];
    if (!p.active) continue;
    WorldImpl::ShapeView& view = w.shape_views[i];
    const Transform& xf = *view.placed.xf;
    // isMoving and isAsleep for a body that is alive and enabled (its proxy is active).
    const Body& b = w.bodies[view.body];
    view.moving = b.isDynamic() ? b.awake : b.isKinematic() && (b.velocity != Vec2::Zero() || b.angular_velocity != 0.0);
    view.asleep = b.isDynamic() && !b.awake;
    if (view.type == ShapeType::Circle) {
      view.center = xf.apply(view.local_center);  // computeAabb's box, from the centre placed once
      const Vec2 r = Vec2::Constant(view.radius);
      p.aabb = {view.center - r - half_margin, view.center + r + half_margin};
      continue;
    }
    if (i + 4 < n && w.proxies[i + 4].active && w.shape_views[i + 4].type != ShapeType::Circle) {
      // each shape's vertices are a separate allocation: ask for them ahead
      __builtin_prefetch(w.shape_views[i + 4].local_vertices);
      __builtin_prefetch(w.shape_views[i + 4].local_normals);
    }
    // Each polygon (and capsule, segment) is placed in the world once per step; the narrow phase
    // reads it for every pair (manifold.h WorldPolygon), and its box comes from the placed corners.
    w.polygon_offset[i] = static_cast<uint32_t>(w.world_vertices.size());
    p.aabb = {Vec2::Constant(std::numeric_limits<double>::infinity()), Vec2::Constant(-std::numeric_limits<double>::infinity())};
    const int count = view.placed.poly.count;
    for (int k = 0; k < count; ++k) {
      const Vec2 v = xf.apply(view.local_vertices[k]);
      w.world_vertices.push_back(v);
      w.world_normals.push_back(xf.q.apply(view.local_normals[k]));
      p.aabb.lower = p.aabb.lower.cwiseMin(v);
      p.aabb.upper = p.aabb.upper.cwiseMax(v);
    }
    if (view.radius > 0.0) {  // capsules
      p.aabb.lower -= Vec2::Constant(view.radius);
      p.aabb.upper += Vec2::Constant(view.radius);
    }
    p.aabb.lower -= half_margin;
    p.aabb.upper += half_margin;
    view.placed.poly.vertices = w.world_vertices.data() + w.polygon_offset[i];
    view.placed.poly.normals = w.world_normals.data() + w.polygon_offset[i];
#ifdef RIGIDLAB_VERIFY_CACHES
    if (view.placed.poly.box && !isBox(view.placed.poly.normals, count)) {
      std::fprintf(stderr, "rigidlab: shape %zu is a box in body coordinates but not once placed\n", i);
      std::abort();
    }
#endif
  }
  if (w.world_vertices.capacity() != vertex_capacity || w.world_normals.capacity() != normal_capacity) {
    for (size_t i = 0; i < n; ++i) {  // the vectors moved: point the views at where they are now
      WorldImpl::ShapeView& view = w.shape_views[i];
      if (!w.proxies[i].active || view.type == ShapeType::Circle) continue;
      view.placed.poly.vertices = w.world_vertices.data() + w.polygon_offset[i];
      view.placed.poly.normals = w.world_normals.data() + w.polygon_offset[i];
    }
  }
  PairLimit limit;
  limit.pairs = std::min(w.def.pair_cap_max, std::max(w.def.pair_cap, static_cast<size_t>(w.def.pair_cap_per_body) * bodies));
  limit.tests = limit.pairs > SIZE_MAX / kTestsPerPair ? SIZE_MAX : kTestsPerPair * limit.pairs;
  PairOverflow overflow;
  if (!findPairsCached(w, limit, overflow)) {
    w.pairs.clear();
    w.pair_cache.valid = false;
    throw InputError("bodies", overflowMessage(w, overflow, bodies, limit));
  }
  if (w.should_collide || !w.filter_decisions.empty()) askShouldCollide(w);
}

}  // namespace rigidlab

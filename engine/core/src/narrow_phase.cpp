// Stage 3 of the step: contact manifolds for the candidate pairs of shapes (docs/design/thesis.md §7), each
// turned into a contact constraint with the two shapes' combined material (shape.h Material).
//
// Persistent contacts: a point whose pair and feature id were in contact in the previous step
// starts with that step's accumulated impulses (warm starting, Catto GDC 2006). The solver then
// refines last step's answer instead of starting from zero, so resting contacts converge over steps
// rather than within one step's iterations. Both the new pairs and the previous contacts are sorted
// by shape pair, so matching is a single merge walk.
#include <algorithm>
#include <cmath>

#include "stages.h"
#include "task_pool.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

const Contact kBlank{};

// Written field by field in place: returned as a 12-byte value, the key was assembled on the stack
// in pieces and read back whole, a store-forwarding stall on every contact (perf).
void addKey(std::vector<ContactKey>& keys, const Contact& c) {
  double deepest = 0.0;
  for (int k = 0; k < c.count; ++k) deepest = std::min(deepest, c.points[k].separation);
  ContactKey& key = keys.emplace_back();
  key.a = c.a;
  key.b = c.b;
  key.count = static_cast<uint8_t>(c.count);
  key.deep_overlap = deepest < -(c.slop + kDeepOverlapMargin);
}

}  // namespace

namespace {

// The manifold of a pair of placed shapes: a pure function of the two views, so it may be computed
// on any thread. The two commonest pairs directly, the others through the table (manifold.h); the
// kinds from the views, not from the shapes, which are further away in memory.
inline Manifold manifoldOf(const WorldImpl::ShapeView& va, const WorldImpl::ShapeView& vb, double margin) {
  return va.type == ShapeType::Circle && vb.type == ShapeType::Circle
             ? collideCircleCentres(va.center, va.radius, vb.center, vb.radius, margin)
         : va.type == ShapeType::Polygon && vb.type == ShapeType::Polygon
             ? collidePolygons(va.placed.poly, vb.placed.poly, margin)
             : kCollideTable[static_cast<int>(va.type)][static_cast<int>(vb.type)](va.placed, vb.placed, margin);
}

// Whether a pair is left out before any geometry: two shapes of one body never collide; filters and
// sensors decide the rest.
inline bool leftOut(const WorldImpl& w, const BodyPair& pair, const WorldImpl::ShapeView& va, const WorldImpl::ShapeView& vb) {
  if (va.body == vb.body) return true;
  if (va.special || vb.special) {
    const BodyShape &sa = w.shapes[pair.a], &sb = w.shapes[pair.b];
    if (sa.sensor || sb.sensor || !shouldCollide(sa.filter, sb.filter) || w.jointBlocksCollision(va.body, vb.body)) return true;
  }
  return false;
}

// Both asleep (or one static): nothing moved, so the contact is kept as it was.
inline bool resting(const WorldImpl& w, uint32_t ia, uint32_t ib) {
  return !w.isActive(ia) && !w.isActive(ib) && !w.isMovingKinematic(ia) && !w.isMovingKinematic(ib);
}

// With several threads (WorldDef::threads) the manifolds are computed first, each into its pair's
// slot, for the pairs that are not left out or resting at the start of the stage; the merge below
// then runs serially in pair order as with one thread and computes the manifolds of the pairs
// whose islands an earlier pair of the list woke. Each manifold is the same function of the same
// views either way, so the contacts are the same bits whatever the thread count.
constexpr size_t kPairGrain = 256;  // pairs per thread below which the stage stays serial

template <bool kPrecomputed>
void mergeContacts(WorldImpl& w);

}  // namespace

void narrowPhase(WorldImpl& w) {
  // Small worlds stay serial and never start the threads.
  TaskPool* pool = w.pairs.size() >= 2 * kPairGrain ? w.taskPool() : nullptr;
  if (!pool || w.pairs.size() < kPairGrain * static_cast<size_t>(pool->threads())) {
    mergeContacts<false>(w);
    return;
  }
  auto& manifolds = w.pair_manifolds;
  manifolds.resize(w.pairs.size());
  const double margin = w.def.contact_margin;
  pool->parallelFor(w.pairs.size(), kPairGrain, [&](size_t begin, size_t end) {
    for (size_t p = begin; p < end; ++p) {
      const BodyPair& pair = w.pairs[p];
      const WorldImpl::ShapeView& va = w.shape_views[pair.a];
      const WorldImpl::ShapeView& vb = w.shape_views[pair.b];
      if (leftOut(w, pair, va, vb) || resting(w, va.body, vb.body)) {
        manifolds[p].count = -1;  // not computed
        continue;
      }
      manifolds[p] = manifoldOf(va, vb, margin);
    }
  });
  mergeContacts<true>(w);
}

namespace {

template <bool kPrecomputed>
void mergeContacts(WorldImpl& w) {
  std::swap(w.contacts, w.previous_contacts);
  w.contacts.clear();
  w.contact_keys.clear();
  size_t old = 0;
  const auto& prev = w.previous_contacts;
  // Events: only when some shape asks for them (or every contact does).
  const bool events = w.every_contact_event || w.event_shapes > 0;
  w.contact_events.clear();
  w.event_contacts.clear();
  if (events) w.previous_matched.assign(prev.size(), 0);
  for (size_t p = 0; p < w.pairs.size(); ++p) {
    const BodyPair& pair = w.pairs[p];
    const WorldImpl::ShapeView& va = w.shape_views[pair.a];
    const WorldImpl::ShapeView& vb = w.shape_views[pair.b];
    const uint32_t ia = va.body, ib = vb.body;
    while (old < prev.size() && (prev[old].shape_a < pair.a || (prev[old].shape_a == pair.a && prev[old].shape_b < pair.b))) ++old;
    const bool had = old < prev.size() && prev[old].shape_a == pair.a && prev[old].shape_b == pair.b;
    if (old + 2 < prev.size()) {  // the previous contacts are walked in order, and out of the cache too
      const char* ahead = reinterpret_cast<const char*>(&prev[old + 2]);
      for (size_t offset = 0; offset < sizeof(Contact); offset += 64) __builtin_prefetch(ahead + offset);
      __builtin_prefetch(ahead + sizeof(Contact) - 1);
    }
    if (leftOut(w, pair, va, vb)) continue;
    const Body& a = w.bodies[ia];
    const Body& b = w.bodies[ib];
    if (resting(w, ia, ib)) {
      // Both asleep (or one static): nothing moved, so the contact is as it was; keep it with its
      // impulses for when the island wakes.
      if (had) {
        w.contacts.push_back(prev[old]);
        addKey(w.contact_keys, prev[old]);
        if (events) w.previous_matched[old] = 1;
      }
      continue;
    }
    // Precomputed unless an earlier pair woke this one's island (see narrowPhase).
    const Manifold m = kPrecomputed && w.pair_manifolds[p].count >= 0 ? w.pair_manifolds[p] : manifoldOf(va, vb, w.def.contact_margin);
    if (m.count == 0) continue;
    // An awake body reaching a sleeping one wakes its island.
    if (a.isDynamic() && !a.awake) w.wakeIsland(ia);
    if (b.isDynamic() && !b.awake) w.wakeIsland(ib);
    // The storage two contacts on, for writing: last written two steps ago, it is out of the cache
    // for a large pile, and clearing a new Contact waited on it (perf, pyramid of base 100).
    if (w.contacts.size() + 2 < w.contacts.capacity()) {
      const char* next = reinterpret_cast<const char*>(w.contacts.data() + w.contacts.size() + 2);
      for (size_t offset = 0; offset < sizeof(Contact); offset += 64) __builtin_prefetch(next + offset, 1);
      __builtin_prefetch(next + sizeof(Contact) - 1, 1);
    }
    // Reused storage: no allocation in steady state. Copied from a blank contact rather than
    // value-initialised, which GCC does with three `rep stos` (Contact, then each point), slow to
    // start: with them this stage took 1.65 ms on the pyramid of base 100, 1.28 ms without.
    Contact& c = w.contacts.emplace_back(kBlank);
    c.a = ia;
    c.b = ib;
    c.shape_a = pair.a;
    c.shape_b = pair.b;
    c.normal = m.normal;
    c.count = m.count;
    for (int i = 0; i < m.count; ++i) {
      ContactPoint& cp = c.points[i];
      cp.point = m.points[i].point;
      cp.separation = m.points[i].separation;
      cp.id = m.points[i].id;
    }
    // Penetration the position pass leaves alone: WorldDef::allowed_penetration, but at most a tenth
    // of the smaller shape's size, so centimetre bodies are not allowed to sink half their height.
    const Material &ma = va.material, &mb = vb.material;
    c.slop = std::min(w.def.allowed_penetration, 0.1 * std::min(va.extent, vb.extent));
    c.restitution = std::max(ma.restitution, mb.restitution);
    c.friction = std::sqrt(ma.friction * mb.friction);
    c.static_friction = std::sqrt(ma.static_friction * mb.static_friction);
    addKey(w.contact_keys, c);
    // Touching from the first step a point overlaps until the contact ends (contact.h).
    c.touching = (had && prev[old].touching) || c.points[0].separation <= 0.0 || (c.count == 2 && c.points[1].separation <= 0.0);
    c.passing = had && prev[old].passing;
    if (events) {
      if (had) w.previous_matched[old] = 1;
      if (c.touching && !(had && prev[old].touching) && w.wantsEvents(pair.a, pair.b))
        contactBegins(w, static_cast<uint32_t>(w.contacts.size() - 1));
    }
    if (had) {
      for (int i = 0; i < c.count; ++i)
        for (int j = 0; j < prev[old].count; ++j)
          if (prev[old].points[j].id == c.points[i].id) {
            c.points[i].persisted = true;
            // An impact's impulse says nothing about the next step's contact force: only a
            // point that was not bouncing starts from its last impulse.
            if (prev[old].points[j].target_velocity <= 0.0) {
              c.points[i].normal_impulse = prev[old].points[j].normal_impulse;
              c.points[i].tangent_impulse = prev[old].points[j].tangent_impulse;
            }
          }
    }
  }
  if (events)  // contacts of the last step that did not continue
    for (size_t k = 0; k < prev.size(); ++k)
      if (!w.previous_matched[k] && prev[k].touching && w.shape_alive[prev[k].shape_a] && w.shape_alive[prev[k].shape_b] &&
          w.wantsEvents(prev[k].shape_a, prev[k].shape_b))
        contactEnds(w, prev[k]);
}

}  // namespace
}  // namespace rigidlab

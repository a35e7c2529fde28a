// Stage 3 of the step: contact manifolds for the candidate pairs of shapes (docs/design/thesis.md §7), each
// turned into a contact constraint with the two shapes' combined material (shape.h Material).
//
// Persistent contacts: a point whose pair and feature id were in contact in the previous step
// starts with that step's accumulated impulses (warm starting, Catto GDC 2006). The solver then
// refines last step's answer instead of starting from zero, so resting contacts converge over steps
// rather than within one step's iterations. Both the new pairs and the previous contacts are sorted
// by shape pair, so matching is a single merge walk.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>

#include "stages.h"
#include "task_pool.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

const Contact kBlank{};

// Written field by field in place: returned as a 12-byte value, the key was assembled on the stack
// in pieces and read back whole, a store-forwarding stall on every contact (perf). `deepest`: the
// smallest of 0 and the points' separations. Out of line, so that GCC inlines emplace_back here.
[[gnu::noinline]] void addKey(std::vector<ContactKey>& keys, uint32_t a, uint32_t b, int count, double deepest, double slop) {
  ContactKey& key = keys.emplace_back();
  key.a = a;
  key.b = b;
  key.count = static_cast<uint8_t>(count);
  key.deep_overlap = deepest < -(slop + kDeepOverlapMargin);
}

void addKey(std::vector<ContactKey>& keys, const Contact& c) {
  double deepest = 0.0;
  for (int k = 0; k < c.count; ++k) deepest = std::min(deepest, c.points[k].separation);
  addKey(keys, c.a, c.b, c.count, deepest, c.slop);
}

// The combined frictions √(f_A f_B) of the last pair of materials seen: a scene's pairs combine a
// few materials, mostly the same ones one after the other, and a square root is slow to finish.
// Materials are compared bit for bit, so the values are always those of the formula.
class CombinedFriction {
 public:
  void of(const Material& a, const Material& b, double& friction, double& static_friction) {
    const uint64_t key[4] = {std::bit_cast<uint64_t>(a.friction), std::bit_cast<uint64_t>(b.friction),
                             std::bit_cast<uint64_t>(a.static_friction), std::bit_cast<uint64_t>(b.static_friction)};
    if (key[0] != key_[0] || key[1] != key_[1] || key[2] != key_[2] || key[3] != key_[3]) {
      std::copy(key, key + 4, key_);
      friction_ = std::sqrt(a.friction * b.friction);
      static_friction_ = std::sqrt(a.static_friction * b.static_friction);
    }
    friction = friction_;
    static_friction = static_friction_;
  }

 private:
  uint64_t key_[4] = {~0ull, ~0ull, ~0ull, ~0ull};  // a NaN's bits: no material has them
  double friction_ = 0.0, static_friction_ = 0.0;
};

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
inline bool resting(const WorldImpl& w, uint32_t ia, uint32_t ib) { return !w.isMoving(ia) && !w.isMoving(ib); }

// Pairs whose manifolds are computed together (computeManifolds) before they are merged.
constexpr size_t kBlock = 64;

// Manifold::count of a pair whose manifold computeManifolds did not compute.
constexpr int kLeftOut = -1, kResting = -2;

// The manifolds of pairs [begin, end) into out[0 .. end − begin), count kLeftOut or kResting for a
// pair left out or resting when the stage began. Pairs of polygons take collidePolygons' three
// steps (manifold.h) a block of pairs at a time, each step over the whole block before the next:
// one pair's long chain of dependent operations (the reference edge's direction, a square root
// then a division, which the clipping waits for) then runs beside the other pairs' work instead of
// holding up the processor. The same functions of the same views in the same order for each pair:
// the same bits as collidePolygons pair by pair.
void computeManifolds(const WorldImpl& w, size_t begin, size_t end, Manifold* out) {
  const double margin = w.def.contact_margin;
  struct Clip {
    Vec2 tangent;
    const WorldPolygon *a, *b;
    PolygonAxes axes;
    size_t slot;  // in out
  };
  Clip clips[kBlock];
  for (size_t first = begin; first < end; first += kBlock) {
    const size_t last = std::min(end, first + kBlock);
    size_t n = 0;
    for (size_t p = first; p < last; ++p) {
      const BodyPair& pair = w.pairs[p];
      const WorldImpl::ShapeView& va = w.shape_views[pair.a];
      const WorldImpl::ShapeView& vb = w.shape_views[pair.b];
      Manifold& m = out[p - begin];
      if (leftOut(w, pair, va, vb)) {
        m.count = kLeftOut;
        continue;
      }
      if (!va.moving && !vb.moving) {  // resting() when the stage began (ShapeView::moving)
        m.count = kResting;
        continue;
      }
      if (va.type == ShapeType::Polygon && vb.type == ShapeType::Polygon) {
        Clip& c = clips[n];
        if (polygonAxes(va.placed.poly, vb.placed.poly, margin, c.axes)) {
          c.a = &va.placed.poly;
          c.b = &vb.placed.poly;
          c.slot = p - begin;
          ++n;
        } else {
          m.count = 0;
        }
      } else {
        new (&m) Manifold(manifoldOf(va, vb, margin));  // made in place, not copied
      }
    }
    for (size_t k = 0; k < n; ++k) {
      Clip& c = clips[k];
      c.tangent = edgeDirection(c.axes.flip ? *c.b : *c.a, c.axes.ref_edge);
    }
    for (size_t k = 0; k < n; ++k) {
      const Clip& c = clips[k];
      clipPolygons(*c.a, *c.b, c.axes, c.tangent, margin, out[c.slot]);
    }
  }
}

// The manifolds are computed before they are merged, and the merge (mergeContacts) runs serially
// in pair order: with one thread a block of pairs at a time, with several (WorldDef::threads) all
// pairs on the threads first, each into its pair's slot. The merge computes the manifolds of the
// pairs whose islands an earlier pair of the list woke (resting when the stage began).
// Each manifold is the same function of the same views either way, so the contacts are the same
// bits whatever the thread count.
constexpr size_t kPairGrain = 256;  // pairs per thread below which the stage stays serial

void mergeContacts(WorldImpl& w, bool precomputed);

}  // namespace

void narrowPhase(WorldImpl& w) {
#ifdef RIGIDLAB_VERIFY_CACHES
  // Sanitizer and fuzz builds: the views' sleep flags must be those of the bodies now.
  for (const BodyPair& pair : w.pairs)
    for (const uint32_t shape : {pair.a, pair.b}) {
      const WorldImpl::ShapeView& v = w.shape_views[shape];
      if (v.moving != w.isMoving(v.body) || v.asleep != w.isAsleep(v.body)) {
        std::fprintf(stderr, "rigidlab: the view of shape %u has stale sleep flags at the narrow phase\n", shape);
        std::abort();
      }
    }
#endif
  // Small worlds stay serial and never start the threads.
  TaskPool* pool = w.pairs.size() >= 2 * kPairGrain ? w.taskPool() : nullptr;
  if (!pool || w.pairs.size() < kPairGrain * static_cast<size_t>(pool->threads())) {
    mergeContacts(w, false);
    return;
  }
  w.pair_manifolds.resize(w.pairs.size());
  pool->parallelFor(w.pairs.size(), kPairGrain,
                    [&](size_t begin, size_t end) { computeManifolds(w, begin, end, w.pair_manifolds.data() + begin); });
  mergeContacts(w, true);
}

namespace {

// Last step's contacts, read in pair order as this step's are written, in one of two ways.
// In place: they stay in w.contacts, which the merge overwrites, each contact written where its
// predecessor was read. A pile whose contacts persist then fetches each record once (instead of the
// old record and the storage for the new one), and a resting contact is not copied at all. A
// contact written where one is still to be read (the merge has written more contacts than it has
// read) first moves that one to w.previous_contacts, whose contacts come before those left in
// place; every contact after it then moves too, until as many have ended as begun.
// Anew: they are all moved to w.previous_contacts at the start and kept whole, and this
// step's are written into w.contacts from its start. For events (contactEnds reads the contacts
// that ended), and after a step whose contacts would have moved (WorldImpl::contacts_displaced).
class LastContacts {
 public:
  LastContacts(WorldImpl& w, bool anew) : array_(w.contacts), queue_(w.previous_contacts), fresh_(anew) {
    if (anew) {
      std::swap(array_, queue_);
      array_.clear();
    } else {
      queue_.clear();
    }
    end_ = array_.size();
    tail_ = queue_.size();
    total_ = end_ + tail_;
  }
  size_t size() const { return total_; }  // how many
  bool empty() const { return popped_ == total_; }
  const Contact& front() const { return head_ < tail_ ? queue_[head_] : array_[next_]; }
  size_t frontIndex() const { return popped_; }  // its index among them, in pair order
  void pop() {
    ++popped_;
    if (head_ == tail_) {
      ++next_;
    } else if (++head_ == tail_ && !fresh_) {
      queue_.clear();  // reused from its start, so that it stays in the cache
      head_ = tail_ = 0;
    }
  }
  // Asks for the contact k after the front, which is out of the cache in a large pile.
  void prefetch(size_t k) const {
    const size_t queued = tail_ - head_;
    const Contact* c = k < queued ? &queue_[head_ + k] : next_ + (k - queued) < end_ ? &array_[next_ + (k - queued)] : nullptr;
    if (!c) return;
    const char* bytes = reinterpret_cast<const char*>(c);
    for (size_t offset = 0; offset < sizeof(Contact); offset += 64) __builtin_prefetch(bytes + offset);
    __builtin_prefetch(bytes + sizeof(Contact) - 1);
  }
  // Slot `out` of w.contacts (the contacts written so far being those before it) set to a new
  // contact, `value`.
  Contact& write(size_t out, const Contact& value) {
    // Written in place, this would move a contact still to be read (the first time: vacate below).
    displaced_ |= out == popped_ && popped_ < total_;
    vacate(out);
    return out < array_.size() ? (array_[out] = value) : array_.emplace_back(value);
  }
  // The front, kept as this step's contact in slot `out`, and popped.
  const Contact& keepFront(size_t out) {
    if (head_ == tail_ && next_ == out && next_ < end_) {  // already there
      ++popped_;
      return array_[next_++];
    }
    vacate(out);
    const Contact& f = front();  // after vacate, which may have moved the queue
    Contact& kept = out < array_.size() ? (array_[out] = f) : array_.emplace_back(f);
    pop();
    return kept;
  }
  // Whether slot `out` lies beyond last step's contacts (storage nothing has read this step).
  bool fresh(size_t out) const { return fresh_ || out >= end_; }
  // Cuts w.contacts to the `out` written; whether writing in place moved or would have moved contacts.
  bool finish(size_t out) {
    array_.resize(out);
    return displaced_;
  }

 private:
  // A contact still to be read in slot `out` moves to the queue before the slot is written.
  void vacate(size_t out) {
    if (out == next_ && next_ < end_) {
      queue_.push_back(array_[next_++]);
      ++tail_;
    }
  }

  std::vector<Contact>& array_;
  std::vector<Contact>& queue_;
  bool fresh_, displaced_ = false;
  size_t next_ = 0, end_ = 0;  // array_[next_ .. end_): last step's contacts still in place
  size_t head_ = 0, tail_ = 0;  // queue_[head_ .. tail_): those moved out of the way, which come first
  size_t popped_ = 0, total_ = 0;  // read so far, of all
};

// The merge of this step's manifolds with last step's contacts, pair by pair in order.
class Merge {
 public:
  Merge(WorldImpl& w, bool events) : w_(w), events_(events), prev_(w, events || w.contacts_displaced) {
    w.contact_keys.clear();
    w.contact_events.clear();
    w.event_contacts.clear();
    if (events) w.previous_matched.assign(prev_.size(), 0);
  }

  void run(bool precomputed) {
    const size_t pairs = w_.pairs.size();
    Manifold block[kBlock];  // with one thread: the manifolds of pairs first .. last
    for (size_t first = 0; first < pairs; first += kBlock) {
      const size_t last = std::min(pairs, first + kBlock);
      const Manifold* manifolds = precomputed ? w_.pair_manifolds.data() + first : block;
      if (!precomputed) computeManifolds(w_, first, last, block);
      for (size_t p = first; p < last; ++p) {
        const BodyPair& pair = w_.pairs[p];
        const bool had = matchPrevious(pair);
        const WorldImpl::ShapeView& va = w_.shape_views[pair.a];
        const WorldImpl::ShapeView& vb = w_.shape_views[pair.b];
        const Manifold* m = &manifolds[p - first];
        if (m->count < 0) {
          // Left out, resting, or resting when the stage began and woken since by an earlier
          // pair. (A pair computed is neither: no body falls asleep during this stage.)
          if (m->count == kLeftOut) continue;
          if (!woken_ || resting(w_, va.body, vb.body)) {
            // Both asleep (or one static): nothing moved, so the contact is as it was; keep it
            // with its impulses for when the island wakes.
            if (had) keep();
            continue;
          }
          m = &(block[p - first] = manifoldOf(va, vb, w_.def.contact_margin));
        }
        if (m->count > 0) add(pair, va, vb, *m, had);
      }
    }
    w_.contacts_displaced = prev_.finish(out_);
    if (events_) {  // contacts of the last step that did not continue
      const std::vector<Contact>& last = w_.previous_contacts;
      for (size_t k = 0; k < last.size(); ++k)
        if (!w_.previous_matched[k] && last[k].touching && w_.shape_alive[last[k].shape_a] &&
            w_.shape_alive[last[k].shape_b] && w_.wantsEvents(last[k].shape_a, last[k].shape_b))
          contactEnds(w_, last[k]);
    }
  }

 private:
  // Skips last step's contacts before the pair; true if the next one is the pair's.
  bool matchPrevious(const BodyPair& pair) {
    for (; !prev_.empty(); prev_.pop()) {
      const Contact& c = prev_.front();
      if (c.shape_a < pair.a || (c.shape_a == pair.a && c.shape_b < pair.b)) continue;
      if (c.shape_a != pair.a || c.shape_b != pair.b) return false;
      prev_.prefetch(8);
      return true;
    }
    return false;
  }

  // The pair's contact of last step, kept as it was.
  void keep() {
    if (events_) w_.previous_matched[prev_.frontIndex()] = 1;
    addKey(w_.contact_keys, prev_.keepFront(out_++));
  }

  // A contact from the pair's manifold (m.count > 0), taking over the impulses of last step's
  // points with the same features (`had`: the pair had a contact).
  void add(const BodyPair& pair, const WorldImpl::ShapeView& va, const WorldImpl::ShapeView& vb, const Manifold& m,
           bool had) {
    WorldImpl& w = w_;
    const uint32_t ia = va.body, ib = vb.body;
    // An awake body reaching a sleeping one wakes its island. (Only a body asleep when the stage
    // began can be: ShapeView::asleep.)
    if (va.asleep && w.isAsleep(ia)) {
      w.wakeIsland(ia);
      woken_ = true;
    }
    if (vb.asleep && w.isAsleep(ib)) {
      w.wakeIsland(ib);
      woken_ = true;
    }
    // What the contact takes over from its predecessor, read before the slot is written (it may be
    // the predecessor's).
    bool was_touching = false, was_passing = false;
    int had_count = 0;
    uint32_t had_id[2] = {0, 0};
    bool had_impulse[2] = {false, false};
    double had_normal_impulse[2] = {0.0, 0.0}, had_tangent_impulse[2] = {0.0, 0.0};
    if (had) {
      const Contact& q = prev_.front();
      was_touching = q.touching;
      was_passing = q.passing;
      had_count = q.count;
      for (int j = 0; j < 2; ++j) {  // both points, set or blank: had_count says which count
        had_id[j] = q.points[j].id;
        // An impact's impulse says nothing about the next step's contact force: only a point
        // that was not bouncing starts from its last impulse.
        had_impulse[j] = !q.points[j].bounced;
        had_normal_impulse[j] = q.points[j].normal_impulse;
        had_tangent_impulse[j] = q.points[j].tangent_impulse;
      }
      if (events_) w.previous_matched[prev_.frontIndex()] = 1;
      prev_.pop();
    }
    // Storage beyond last step's contacts, for writing: not read this step, it is out of the cache
    // for a large pile, and clearing a new Contact waited on it (perf, pyramid of base 100).
    if (prev_.fresh(out_ + 8) && out_ + 8 < w.contacts.capacity()) {
      const char* next = reinterpret_cast<const char*>(w.contacts.data() + out_ + 8);
      for (size_t offset = 0; offset < sizeof(Contact); offset += 64) __builtin_prefetch(next + offset, 1);
      __builtin_prefetch(next + sizeof(Contact) - 1, 1);
    }
    // Reused storage: no allocation in steady state. Copied from a blank contact rather than
    // value-initialised, which GCC does with three `rep stos` (Contact, then each point), slow to
    // start: with them this stage took 1.65 ms on the pyramid of base 100, 1.28 ms without.
    Contact& c = prev_.write(out_, kBlank);
    c.a = ia;
    c.b = ib;
    c.shape_a = pair.a;
    c.shape_b = pair.b;
    c.normal = m.normal;
    c.count = m.count;
    double deepest = 0.0;  // for the key
    for (int i = 0; i < m.count; ++i) {
      ContactPoint& cp = c.points[i];
      cp.point = m.points[i].point;
      cp.separation = m.points[i].separation;
      cp.id = m.points[i].id;
      deepest = std::min(deepest, m.points[i].separation);
      for (int j = 0; j < 2; ++j)  // last step's points in order (at most two)
        if (j < had_count && had_id[j] == m.points[i].id) {
          cp.persisted = true;
          if (had_impulse[j]) {
            cp.normal_impulse = had_normal_impulse[j];
            cp.tangent_impulse = had_tangent_impulse[j];
          }
        }
    }
    // Penetration the position pass leaves alone: WorldDef::allowed_penetration, but at most a tenth
    // of the smaller shape's size, so centimetre bodies are not allowed to sink half their height.
    const Material &ma = va.material, &mb = vb.material;
    c.slop = std::min(w.def.allowed_penetration, 0.1 * std::min(va.extent, vb.extent));
    c.restitution = std::max(ma.restitution, mb.restitution);
    friction_.of(ma, mb, c.friction, c.static_friction);
    addKey(w.contact_keys, ia, ib, m.count, deepest, c.slop);
    // Touching from the first step a point overlaps until the contact ends (contact.h).
    c.touching = was_touching || m.points[0].separation <= 0.0 || (m.count == 2 && m.points[1].separation <= 0.0);
    c.passing = was_passing;
    if (events_ && c.touching && !was_touching && w.wantsEvents(pair.a, pair.b)) contactBegins(w, static_cast<uint32_t>(out_));
    ++out_;
  }

  WorldImpl& w_;
  // Events: only when some shape asks for them (or every contact does).
  const bool events_;
  LastContacts prev_;
  size_t out_ = 0;  // contacts written
  // Some island was woken during the stage: a pair may no longer rest that did when it began.
  bool woken_ = false;
  CombinedFriction friction_;
};

void mergeContacts(WorldImpl& w, bool precomputed) {
  Merge(w, w.every_contact_event || w.event_shapes > 0).run(precomputed);
}

}  // namespace
}  // namespace rigidlab

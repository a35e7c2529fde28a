// Which bodies get located impacts this step (WorldDef::impacts = Located): the per-island rule.
//
// Islands are the awake dynamic bodies linked by last step's contacts (speculative ones included),
// two-body forces and joints, found with a union–find in slot order (deterministic). An island's
// impacts are located when
//   - it has at most WorldDef::impact_island_bodies bodies,
//   - no joint acts on it (an impact would have to be resolved with the joint's constraint; the
//     contact solver does that once per step), and
//   - none of its contact points touched at the step's start (separation ≤ touchTolerance): a
//     touching contact is resting or persistent contact, which stays with the contact solver, so an
//     island that rests on something (a stack, a pile, a ball at rest, a block sliding on a slope)
//     has nothing to locate and is handled once per step as before;
// and only while at most WorldDef::impact_max_bodies dynamic bodies are awake in the world. What
// the bounds cost and buy is measured in docs/physics.md "Impacts: located or once per step": on 100 balls
// bouncing apart the search adds 0.1 µs per located body and step to the integrate stage (9 % of
// the step), which a rain of 1000 falling discs would pay on every disc for no visible gain (its
// discs touch one another), while for a few bouncing bodies it is the difference between first and
// fourth order.
//
// Each located island is a mover: its bodies are integrated together again when one of them has
// an impact (no force links it to another island).
#include <algorithm>
#include <cmath>

#include "impact.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

uint32_t root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

bool locatablePair(const WorldImpl& w, uint32_t shape_a, uint32_t shape_b) {
  const BodyShape &a = w.shapes[shape_a], &b = w.shapes[shape_b];
  if (a.sensor || b.sensor || a.one_way || b.one_way || a.pre_solve || b.pre_solve) return false;
  if (a.body.index == b.body.index) return false;
  return a.default_filter && b.default_filter ? true : shouldCollide(a.filter, b.filter);
}

void chooseLocatedBodies(WorldImpl& w) {
  ImpactScratch& im = w.impact;
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  // Clear last step's marks only (a large world with no located bodies pays nothing per body).
  for (uint32_t i : im.bodies)
    if (i < im.located.size()) im.located[i] = 0;
  im.located.resize(n, 0);
  im.bodies.clear();
  im.mover_first.clear();
  im.mover_bodies.clear();
  if (w.def.impacts != ImpactHandling::Located) return;
  int awake = 0;
  for (uint32_t i = 0; i < n; ++i)
    if (w.isActive(i) && ++awake > w.def.impact_max_bodies) return;
  if (awake == 0) return;

  // Bodies that block their island: jointed ones, and those in resting or persistent contact:
  // touching at the start of the step (the separations the narrow phase found at the end of the
  // last one), unless a located impact has just sent the pair apart (last step's log: an impact at
  // the very end of the step leaves the pair touching).
  auto& blocked = im.island_blocked;
  blocked.assign(n, 0);
  for (const Joint& j : w.joints) {
    if (!j.alive) continue;
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (s != kWorldSlot) blocked[s] = 1;
  }
  const auto bounced = [&](const Contact& c) {
    for (const LocatedImpact& l : im.log)
      if (l.separating && l.shape_a == c.shape_a && l.shape_b == c.shape_b) return true;
    return false;
  };
  for (size_t k = 0; k < w.contacts.size() && k < w.contact_keys.size(); ++k) {
    const Contact& c = w.contacts[k];
    double deepest = c.points[0].separation;
    for (int p = 1; p < c.count; ++p) deepest = std::min(deepest, c.points[p].separation);
    // The tolerance is at least 1e-9 (impact_search.cpp): a point as deep as that touches whatever
    // the bodies' scale, which is then not read (a resting pile's contacts all are).
    const bool touching = deepest <= 1e-9 || deepest <= touchTolerance(std::max(w.bodies[c.a].center.cwiseAbs().maxCoeff(),
                                                                                 w.bodies[c.b].center.cwiseAbs().maxCoeff()));
    if (!touching || bounced(c)) continue;
    blocked[c.a] = 1;
    blocked[c.b] = 1;
  }
  // Every awake body blocked by itself (a resting stack, a pile): none can be located, and the
  // islands need not be found.
  bool free = false;
  for (uint32_t i = 0; i < n && !free; ++i) free = w.isActive(i) && !blocked[i];
  if (!free) return;

  // Islands: awake bodies joined by contacts, two-body forces and joints.
  auto& parent = im.parent;
  parent.resize(n);
  for (uint32_t i = 0; i < n; ++i) parent[i] = i;
  const auto unite = [&](uint32_t a, uint32_t b) {
    if (!w.isActive(a) || !w.isActive(b)) return;
    const uint32_t ra = root(parent, a), rb = root(parent, b);
    parent[std::max(ra, rb)] = std::min(ra, rb);
  };
  for (const ContactKey& k : w.contact_keys) unite(k.a, k.b);
  for (const ForceEntry& f : w.forces)
    if (f.alive && !f.b.isNull()) unite(f.a.index, f.b.index);
  for (const Joint& j : w.joints) {
    if (!j.alive) continue;
    const uint32_t slots[4] = {j.a, j.b, j.c, j.d};
    for (uint32_t s : slots)
      if (s != kWorldSlot && slots[0] != kWorldSlot) unite(slots[0], s);
  }
  // Per island root: its size, and whether any member blocks it.
  auto& size = im.island_bodies;
  size.assign(n, 0);
  for (uint32_t i = 0; i < n; ++i) {
    if (!w.isActive(i)) continue;
    const uint32_t r = root(parent, i);
    ++size[r];
    if (blocked[i] && r != i) blocked[r] = 1;
  }
  const uint32_t limit = static_cast<uint32_t>(std::max(1, w.def.impact_island_bodies));
  for (uint32_t i = 0; i < n; ++i) {
    if (!w.isActive(i)) continue;
    const uint32_t r = root(parent, i);
    if (blocked[r] || size[r] > limit) continue;
    im.located[i] = 1;
    im.bodies.push_back(i);
  }
  // Movers: the located islands, each a run of mover_bodies (islands by root slot, bodies by slot).
  im.mover.resize(n, -1);
  for (uint32_t i : im.bodies) im.mover[i] = -1;
  for (uint32_t i : im.bodies) {
    // The root is the island's smallest slot, so it came first and holds the island's mover.
    const uint32_t r = root(parent, i);
    if (r != i) {
      im.mover[i] = im.mover[r];
      continue;
    }
    im.mover[i] = static_cast<int32_t>(im.mover_first.size());
    im.mover_first.push_back(0);
  }
  // Counting sort of the bodies by mover.
  const size_t movers = im.mover_first.size();
  std::vector<uint32_t>& first = im.mover_first;
  std::fill(first.begin(), first.end(), 0u);
  first.push_back(0);
  for (uint32_t i : im.bodies) ++first[im.mover[i] + 1];
  for (size_t m = 0; m < movers; ++m) first[m + 1] += first[m];
  im.mover_bodies.resize(im.bodies.size());
  std::vector<uint32_t>& fill = im.island_bodies;  // reused as the fill cursor
  fill.assign(first.begin(), first.end() - 1);
  for (uint32_t i : im.bodies) im.mover_bodies[fill[im.mover[i]]++] = i;
  w.stats.impact_bodies = static_cast<int>(im.bodies.size());
}

}  // namespace rigidlab

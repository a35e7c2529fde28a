// Islands and sleeping. At the end of each step, bodies are grouped into islands: dynamic bodies
// linked by a contact, a joint or a two-body force (static bodies link nothing). A body counts its time
// below WorldDef::sleep_linear_speed and sleep_angular_speed; when every body of an island has been
// that still for WorldDef::time_to_sleep, the whole island sleeps: zero velocity, no integration,
// no contact solving, no force evaluation. An island with a moving member wakes its sleeping ones.
// Disabled bodies (World::setEnabled) are never awake and belong to no island.
// Bodies wake when an awake body touches them (narrow_phase.cpp), when they are edited or pushed
// (world.cpp), or when a force that forbids sleep is attached (Force::allowsSleep).
// Islands are found with a union–find over slots in slot order, so the result is deterministic.
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

uint32_t root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}

void link(WorldImpl& w, uint32_t a, uint32_t b) {
  if (!w.island_dynamic[a] || !w.island_dynamic[b]) return;  // static bodies link nothing
  const uint32_t ra = root(w.island_parent, a), rb = root(w.island_parent, b);
  if (ra != rb) w.island_parent[std::max(ra, rb)] = std::min(ra, rb);  // the smaller slot is the root
}

}  // namespace

void WorldImpl::wakeIsland(uint32_t slot) {
  if (slot >= bodies.size() || !alive[slot] || bodies[slot].awake || !bodies[slot].enabled) return;
  const auto wake = [&](uint32_t i) {
    if (i >= bodies.size() || !alive[i] || !bodies[i].enabled) return;
    bodies[i].awake = true;
    bodies[i].sleep_time = 0.0;
  };
  if (slot >= island.size()) {  // made since the islands were found: an island of its own
    wake(slot);
    return;
  }
  // The members by island (a counting sort of the slots by root), once per update of the islands:
  // waking the islands of a heap of sleeping bodies one by one then costs their sizes, not the
  // number of bodies for each island.
  if (!island_members_current.value) {
    const size_t n = island.size();
    island_first.assign(n + 1, 0);
    for (uint32_t r : island) ++island_first[r + 1];
    for (size_t r = 0; r < n; ++r) island_first[r + 1] += island_first[r];
    island_members.resize(n);
    for (uint32_t i = 0; i < n; ++i) island_members[island_first[island[i]]++] = i;
    for (size_t r = n; r > 0; --r) island_first[r] = island_first[r - 1];  // back to the starts
    island_first[0] = 0;
    island_members_current.value = true;
  }
  const uint32_t id = island[slot];
  for (uint32_t k = island_first[id]; k < island_first[id + 1]; ++k) wake(island_members[k]);
}

void updateSleep(WorldImpl& w, const StepContext& ctx) {
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  const double dt = ctx.dt;
  if (!ctx.settings.sleeping) {
    // Nothing sleeps: no islands to find (pay for what you use). Bodies put to sleep before
    // sleeping was switched off wake; sleep times restart once it is switched on again.
    for (uint32_t i = 0; i < n; ++i) {
      Body& b = w.bodies[i];
      if (!w.alive[i] || !b.isDynamic() || !b.enabled) continue;
      b.sleep_time = 0.0;
      b.awake = true;
    }
    return;
  }
  // Forces that keep their bodies awake.
  w.keep_awake.assign(n, 0);
  for (const ForceEntry& f : w.forces) {
    if (!f.alive || f.force->allowsSleep()) continue;
    w.keep_awake[f.a.index] = 1;
    if (!f.b.isNull()) w.keep_awake[f.b.index] = 1;
  }
  const double v2 = ctx.settings.sleep_linear_speed * ctx.settings.sleep_linear_speed;
  bool kinematic = false;  // some kinematic body moves: what it touches stays awake
  for (uint32_t i = 0; i < n; ++i) {
    Body& b = w.bodies[i];
    kinematic |= w.isMovingKinematic(i);
    if (!w.isActive(i)) continue;
    const bool still = b.velocity.squaredNorm() <= v2 && std::abs(b.angular_velocity) <= ctx.settings.sleep_angular_speed;
    // A body not allowed to sleep (BodyDef::sleeping_allowed) keeps its sleep time at zero, and so
    // its island awake.
    b.sleep_time = still && !w.keep_awake[i] && b.sleeping_allowed ? b.sleep_time + dt : 0.0;
  }
  // A body still overlapping deeply is not at rest, only slow: the position pass (or the soft
  // step's push-out, limited to contact_push_speed) is still separating it. Letting it sleep would
  // freeze the overlap (boxes spawned half inside each other slept with 4.9 cm left; stability
  // case deep_overlap).
  // The same walk over the contacts (their keys, contact.h ContactKey: deeper than slop +
  // kDeepOverlapMargin) links their bodies into islands. A body carried or pushed by a moving
  // kinematic body is not at rest either.
  w.island_parent.resize(n);
  for (uint32_t i = 0; i < n; ++i) w.island_parent[i] = i;
  w.island_dynamic.resize(n);
  for (uint32_t i = 0; i < n; ++i) w.island_dynamic[i] = w.alive[i] && w.bodies[i].isDynamic() && w.bodies[i].enabled;
  for (const ContactKey& c : w.contact_keys) {
    link(w, c.a, c.b);
    if (!c.deep_overlap && !(kinematic && (w.isMovingKinematic(c.a) || w.isMovingKinematic(c.b)))) continue;
    w.bodies[c.a].sleep_time = 0.0;
    w.bodies[c.b].sleep_time = 0.0;
  }
  for (const ForceEntry& f : w.forces)
    if (f.alive && !f.b.isNull()) link(w, f.a.index, f.b.index);
  for (const Joint& j : w.joints) {  // jointed bodies sleep and wake together
    if (!j.alive) continue;
    const uint32_t slots[4] = {j.a, j.b, j.c, j.d};
    for (int i = 1; i < 4; ++i)
      if (slots[0] != kWorldSlot && slots[i] != kWorldSlot) link(w, slots[0], slots[i]);
    if (slots[0] == kWorldSlot && slots[1] != kWorldSlot && slots[3] != kWorldSlot) link(w, slots[1], slots[3]);
  }

  // Per island: the shortest sleep time of its members (a sleeping member counts as asleep).
  w.island.resize(n);
  w.island_members_current.value = false;
  w.island_sleep.assign(n, std::numeric_limits<double>::infinity());
  for (uint32_t i = 0; i < n; ++i) {
    w.island[i] = root(w.island_parent, i);
    if (!w.alive[i] || !w.bodies[i].isDynamic() || !w.bodies[i].enabled) continue;
    const double t = w.bodies[i].awake ? w.bodies[i].sleep_time : std::numeric_limits<double>::infinity();
    w.island_sleep[w.island[i]] = std::min(w.island_sleep[w.island[i]], t);
  }
  for (uint32_t i = 0; i < n; ++i) {
    if (!w.alive[i] || !w.bodies[i].isDynamic() || !w.bodies[i].enabled) continue;
    Body& b = w.bodies[i];
    const double t = w.island_sleep[w.island[i]];
    if (ctx.settings.sleeping && t >= ctx.settings.time_to_sleep) {
      if (b.awake) {
        b.awake = false;
        b.velocity = Vec2::Zero();
        b.angular_velocity = 0.0;
      }
    } else if (!b.awake) {
      b.awake = true;  // an island with a moving member wakes its sleeping ones
      b.sleep_time = 0.0;
    }
  }
}

}  // namespace rigidlab

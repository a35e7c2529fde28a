// Forces attached to bodies (docs/design/thesis.md §4, §6): adding, removing, reading.
#include "rigidlab/error.h"
#include "rigidlab/world.h"
#include "world_impl.h"

namespace rigidlab {

namespace {
ForceEntry& liveForce(WorldImpl& w, ForceId id) {
  if (id.index >= w.forces.size() || !w.forces[id.index].alive || w.forces[id.index].generation != id.generation)
    throw InputError("force", "force handle is not valid (the force was removed or has expired)");
  return w.forces[id.index];
}
}  // namespace

ForceId World::addForce(std::unique_ptr<Force> force, BodyId a, BodyId b, double duration) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("addForce");
  if (!force) throw InputError("force", "force is null");
  w.get(a);
  if (!b.isNull()) {
    w.get(b);
    if (a == b) throw InputError("b", "a two-body force needs two different bodies");
  }
  if (!(duration > 0.0) && duration != kNextStep)
    throw InputError("duration", "duration must be > 0, got " + formatNumber(duration));
  ForceEntry e;
  e.force = std::move(force);
  e.a = a;
  e.b = b;
  e.next_step_only = duration == kNextStep;
  e.expires_at = duration == kForever || e.next_step_only ? kForever : w.clock.t + duration;
  w.wakeIsland(a.index);
  if (!b.isNull()) w.wakeIsland(b.index);
  e.alive = true;
  uint32_t index;
  if (!w.free_forces.empty()) {
    index = w.free_forces.back();
    w.free_forces.pop_back();
    e.generation = w.forces[index].generation;
    w.forces[index] = std::move(e);
  } else {
    index = static_cast<uint32_t>(w.forces.size());
    w.forces.push_back(std::move(e));
  }
  return {index, w.forces[index].generation};
}

ForceId World::addSpring(const SpringDef& def, double duration) {
  WorldImpl& w = *impl_;
  SpringDef d = def;
  const BodyState a = WorldImpl::stateOf(w.get(def.a));
  if (!d.rest_length) {
    // Default rest length: the distance between the ends now.
    const Vec2 pa = a.worldPoint(requireFinite("local_a", d.local_a));
    const Vec2 pb = d.b.isNull() ? requireFinite("anchor", d.anchor)
                                 : WorldImpl::stateOf(w.get(d.b)).worldPoint(requireFinite("local_b", d.local_b));
    d.rest_length = (pb - pa).norm();
  }
  return addForce(std::make_unique<SpringForce>(d), d.a, d.b, duration);
}

ForceId World::addDamper(const DamperDef& def, double duration) {
  return addForce(std::make_unique<DamperForce>(def), def.body, {}, duration);
}

void World::removeForce(ForceId id) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("removeForce");
  ForceEntry& f = liveForce(w, id);
  w.wakeIsland(f.a.index);  // what the force held may now move
  if (!f.b.isNull()) w.wakeIsland(f.b.index);
  f.alive = false;
  f.force.reset();
  ++f.generation;
  w.free_forces.push_back(id.index);
}

bool World::isValid(ForceId id) const {
  const WorldImpl& w = *impl_;
  return id.index < w.forces.size() && w.forces[id.index].alive && w.forces[id.index].generation == id.generation;
}
Force& World::force(ForceId id) { return *liveForce(*impl_, id).force; }
const Force& World::force(ForceId id) const { return *liveForce(*impl_, id).force; }
BodyId World::forceBodyA(ForceId id) const { return liveForce(*impl_, id).a; }
BodyId World::forceBodyB(ForceId id) const { return liveForce(*impl_, id).b; }
double World::forceTimeLeft(ForceId id) const { return liveForce(*impl_, id).expires_at - impl_->clock.t; }

std::vector<ForceId> World::forceIds() const {
  std::vector<ForceId> ids;
  for (uint32_t i = 0; i < impl_->forces.size(); ++i)
    if (impl_->forces[i].alive) ids.push_back({i, impl_->forces[i].generation});
  return ids;
}

}  // namespace rigidlab

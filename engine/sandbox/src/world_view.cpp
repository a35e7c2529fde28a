// Forces at interpolated poses (world_view.h).
#include "world_view.h"

#include <cmath>
#include <numbers>

namespace rigidlab::sandbox {

void drawForces(const World& world, std::span<const Transform> poses, const DrawToggles& toggles, DebugDraw& dd) {
  const auto stateAt = [&](BodyId id) {
    BodyState state = world.bodyState(id);
    if (id.index < poses.size()) {
      const Transform& xf = poses[id.index];
      const Body& b = world.body(id);
      state.position = xf.p;
      state.q = xf.q;
      state.angle = b.angle + std::remainder(std::atan2(xf.q.s, xf.q.c) - b.angle, 2.0 * std::numbers::pi);
      state.center = xf.apply(b.local_center);
    }
    return state;
  };
  for (const ForceId f : world.forceIds()) {
    const Force& force = world.force(f);
    if (force.kind() == "spring" ? !toggles.springs : !toggles.forces) continue;  // World::draw's split
    const BodyState a = stateAt(world.forceBodyA(f));
    const BodyId other = world.forceBodyB(f);
    if (other.isNull()) {
      force.draw(dd, a, nullptr);
    } else {
      const BodyState b = stateAt(other);
      force.draw(dd, a, &b);
    }
  }
}

}  // namespace rigidlab::sandbox

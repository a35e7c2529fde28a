// The NaN firewall: a body whose state stops being finite during a step (a force returned 1e308 or
// NaN, an extreme spring overflowed) is put back where the step began, made static and reported
// (World::incidents): which body, which step, which force. It runs right after integration, before
// the contacts are found, so a non-finite body never reaches the contact solver and cannot poison
// the bodies it touches; and again at the end of the step for anything the solve produced.
#include <cmath>

#include "rigidlab/error.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

[[gnu::always_inline]] inline bool finiteState(const Body& b) {
  // x · 0 is ±0 for a finite x and NaN for ±∞ or NaN (IEEE 754; the build never allows fast-math),
  // so the sum is zero exactly when every number is finite: one test per body instead of eight
  // branches, which every body takes twice a step. The origin too: a centre near 1e308 plus the
  // centroid offset can overflow it (fuzz_world).
  const double sum = ((b.center.x() * 0.0 + b.center.y() * 0.0) + (b.velocity.x() * 0.0 + b.velocity.y() * 0.0)) +
                     ((b.angle * 0.0 + b.angular_velocity * 0.0) + (b.xf.p.x() * 0.0 + b.xf.p.y() * 0.0));
  return sum == 0.0;
}

std::string cause(const WorldImpl& w, uint32_t slot, const char* stage) {
  if (const int32_t f = w.force_fault[slot]; f >= 0 && w.forces[f].force)
    return std::string(w.forces[f].force->kind()) + " returned a non-finite force or torque";
  std::string forces;
  for (const ForceEntry& f : w.forces)
    if (f.alive && (f.a.index == slot || f.b.index == slot))
      forces += (forces.empty() ? "" : ", ") + std::string(f.force->kind());
  return std::string("its state became non-finite in ") + stage + (forces.empty() ? "" : " (forces on it: " + forces + ")");
}

// Back to the state at the start of the step, at rest.
void putBack(WorldImpl& w, uint32_t i) {
  Body& b = w.bodies[i];
  b.center = w.start_center[i];
  b.angle = w.start_angle[i];
  b.velocity = Vec2::Zero();
  b.angular_velocity = 0.0;
  WorldImpl::syncTransform(b);
}

}  // namespace

void guardNonFinite(WorldImpl& w, const char* stage) {
  for (uint32_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.alive[i]) continue;
    Body& b = w.bodies[i];
    if (b.isStatic()) {
      // A static body never moves during a step, but a stage's update scaled by its zero inverse
      // mass is NaN when the update overflowed (0 · ∞; found by fuzz_world with bodies near 1e308):
      // put it back as it was.
      if (!finiteState(b)) putBack(w, i);
      continue;
    }
    if (finiteState(b) && w.force_fault[i] < 0) continue;
    w.incidents.push_back({b.uid, b.name, w.step_count + 1, w.clock.t, cause(w, i, stage)});
    putBack(w, i);
    b.type = BodyType::Static;
    w.shapesEdited();
    ++w.static_version;
    b.inv_mass = 0.0;
    b.inv_inertia = 0.0;
    b.frozen = true;
  }
}

std::string Incident::message() const {
  return "body " + std::to_string(uid) + (name.empty() ? "" : " '" + name + "'") + (frozen ? " frozen" : " blew up") + " at step " +
         std::to_string(step) + " (t = " + formatNumber(time) + " s): " + cause;
}

}  // namespace rigidlab

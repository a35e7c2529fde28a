// Interpolated poses between the last two steps (interpolation.h).
#include "interpolation.h"

#include <cmath>
#include <numbers>

namespace rigidlab::sandbox {

void TransformHistory::capture(const World& world) {
  for (Pose& p : previous_) p.valid = false;
  for (const BodyId id : world.bodyIds()) {
    if (id.index >= previous_.size()) previous_.resize(id.index + 1);
    const Body& b = world.body(id);
    previous_[id.index] = {id.generation, true, b.center, b.angle};
  }
}

std::span<const Transform> TransformHistory::interpolate(const World& world, double alpha) {
  out_.clear();
  for (const BodyId id : world.bodyIds()) {
    if (id.index >= out_.size()) out_.resize(id.index + 1);
    const Body& b = world.body(id);
    Transform& xf = out_[id.index];
    xf = b.xf;
    if (id.index >= previous_.size()) continue;
    const Pose& p = previous_[id.index];
    if (!p.valid || p.generation != id.generation) continue;
    // Rotation through the short way, so an angle that was wrapped to (−π, π] does not spin.
    const double turn = std::remainder(b.angle - p.angle, 2.0 * std::numbers::pi);
    xf.q = Rot::fromAngle(p.angle + alpha * turn);
    xf.p = p.center + alpha * (b.center - p.center) - xf.q.apply(b.local_center);
  }
  return out_;
}

}  // namespace rigidlab::sandbox

// A constant force through the centre of mass or at a point fixed on the body.
#include <algorithm>

#include "rigidlab/debug_draw.h"
#include "rigidlab/error.h"
#include "rigidlab/forces.h"

namespace rigidlab {

ConstantForce::ConstantForce(const Vec2& force, std::optional<Vec2> local_point)
    : force_(requireFinite("force", force)), local_point_(local_point) {
  if (local_point_) requireFinite("point", *local_point_);
}

void ConstantForce::evaluate(const ForceInput& in, ForceOutput& out) {
  out.a = local_point_ ? atPoint(in.a, force_, in.a.worldPoint(*local_point_)) : Wrench{force_, 0.0};
}

void ConstantForce::draw(DebugDraw& dd, const BodyState& a, const BodyState*) const {
  // Arrow length: the force in units of the body's weight (1 m per m·g), kept readable.
  const double weight = std::max(a.mass * 9.80665, 1e-12);
  const double length = std::clamp(force_.norm() / weight, 0.2, 3.0);
  if (force_.norm() == 0.0) return;
  const Vec2 from = local_point_ ? a.worldPoint(*local_point_) : a.center;
  dd.drawArrow(from, from + force_.normalized() * length, {1.0f, 0.4f, 0.3f, 1.0f});
}

}  // namespace rigidlab

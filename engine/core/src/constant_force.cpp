// A constant force through the centre of mass or at a point fixed on the body.
#include "rigidlab/debug_draw.h"
#include "rigidlab/error.h"
#include "rigidlab/forces.h"

namespace rigidlab {

ConstantForce::ConstantForce(const Vec2& force, std::optional<Vec2> local_point, double torque)
    : force_(requireFinite("force", force)), local_point_(local_point), torque_(requireFinite("torque", torque)) {
  if (local_point_) requireFinite("point", *local_point_);
}

void ConstantForce::evaluate(const ForceInput& in, ForceOutput& out) {
  out.a = local_point_ ? atPoint(in.a, force_, in.a.worldPoint(*local_point_)) : Wrench{force_, 0.0};
  if (torque_ != 0.0) out.a.torque += torque_;  // without one, the wrench keeps its bits (a −0 torque too)
}

void ConstantForce::draw(DebugDraw& dd, const BodyState& a, const BodyState*) const {
  drawForceArrow(dd, local_point_ ? a.worldPoint(*local_point_) : a.center, force_, a.mass);
}

}  // namespace rigidlab

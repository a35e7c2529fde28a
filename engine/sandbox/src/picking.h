// What is under the cursor: the body or joint a click selects (tools, joint tool).
#pragma once

#include <optional>

#include "rigidlab/world.h"

namespace rigidlab::sandbox {

// The topmost body with a shape that contains `p`, or, for shapes without area (segments, chain
// segments), that passes within `tolerance` [m] of it; `except` is passed over (the joint tool's
// second click looks for another body than the first).
std::optional<BodyId> pickBody(const World& world, const Vec2& p, double tolerance, BodyId except = {});
// The joint with an anchor (or a pulley's fixed point) nearest to `p`, within `tolerance` [m].
std::optional<JointId> pickJoint(const World& world, const Vec2& p, double tolerance);

}  // namespace rigidlab::sandbox

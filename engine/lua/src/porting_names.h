// The names porters bring from LÖVE's love.physics and from Box2D (v3's C functions, 2.x's C++
// methods), and what rigidlab calls the same thing (docs/porting.md): an unknown option or field
// that is one of them is answered with rigidlab's name, or with what rigidlab has instead when it
// lacks the feature (lua_args.cpp suggestion()).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rigidlab::lua {

// For `name` (as a script wrote it: frequency, dampingRatio, applyTorque, getWorldPoint,
// setLinearVelocity, b2Body_GetPosition, ...) among the names the function or handle has
// (`candidates`): "rigidlab calls it 'spring_hertz'", a sentence saying what rigidlab has instead
// of a feature it lacks, or "" when the name is none of those.
//   1. a table of names that differ (frequency → spring_hertz, motor_hertz or angular_hertz,
//      whichever the function has; target → linear_offset; linearVelocity → velocity);
//   2. else the same words in rigidlab's spelling: without a Box2D C prefix (b2Body_) or a get/set/is
//      in front, camelCase as snake_case (applyTorque → apply_torque, localAnchorA → local_anchor_a).
std::string portingSuggestion(std::string_view name, const std::vector<std::string_view>& candidates);

}  // namespace rigidlab::lua

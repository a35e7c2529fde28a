// Drawing the world at the interpolated poses of the fixed-step loop (interpolation.h).
#pragma once

#include <span>

#include "rigidlab/world.h"
#include "session.h"

namespace rigidlab::sandbox {

// Forces drawn at the same poses as the bodies. World::draw would draw them at the last step's
// poses, a step ahead of bodies drawn at alpha < 1: a spring's end would visibly miss a fast bob
// by up to v·dt. `poses` is indexed by BodyId::index (TransformHistory::interpolate).
void drawForces(const World& world, std::span<const Transform> poses, const DrawToggles& toggles, DebugDraw& dd);

}  // namespace rigidlab::sandbox

// What the stages of one World::step read besides the world's state: the step's length and the
// settings. Made once at the top of World::step (world.cpp) and passed down the pipeline, so that
// a stage's inputs for this step are visible in its signature.
#pragma once

#include "rigidlab/world.h"

namespace rigidlab {

struct StepContext {
  double dt;  // of the step in progress [s]
  // The world's settings (WorldDef), by reference and not copied: the setters are allowed during a
  // step (a Lua force or the pre-solve callback may call one), and the stages after the call read
  // the new value, as they did when they read it from the world.
  const WorldDef& settings;
};

}  // namespace rigidlab

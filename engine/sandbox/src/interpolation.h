// Drawing between two steps (frame_clock.h): the state before the last step of a frame is kept per
// body slot, and a frame is drawn at previous + alpha·(current − previous). Without it a 60 Hz
// simulation on a 144 Hz screen (or any fixed step that is not the frame period) judders.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rigidlab/world.h"

namespace rigidlab::sandbox {

class TransformHistory {
 public:
  // Remembers every live body's pose as "previous". Call before each world step of a frame.
  void capture(const World& world);
  // Poses to draw, indexed by BodyId::index (DrawOptions::transforms). A body that did not exist
  // at the last capture, or whose slot was reused since, is drawn where it is.
  std::span<const Transform> interpolate(const World& world, double alpha);
  void clear() { previous_.clear(); }

 private:
  struct Pose {
    uint32_t generation = 0;
    bool valid = false;
    Vec2 center = Vec2::Zero();  // centre of mass: bodies turn about it
    double angle = 0.0;
  };
  std::vector<Pose> previous_;
  std::vector<Transform> out_;
};

}  // namespace rigidlab::sandbox

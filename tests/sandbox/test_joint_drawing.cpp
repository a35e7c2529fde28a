// Joints as World::draw draws them (core debug_draw.cpp, DrawOptions::joints), recorded through a
// DebugDraw: anchors as points where jointState reads them, at the poses the sandbox draws
// (interpolated transforms), limits as extra lines, nothing with the toggle off.
#include <doctest/doctest.h>

#include <vector>

#include "rigidlab/world.h"

using namespace rigidlab;

namespace {

struct Recorder : DebugDraw {
  std::vector<Vec2> points;
  int segments = 0;
  void drawPolygon(std::span<const Vec2>, const Color&, const Color&) override {}
  void drawCircle(const Vec2&, double, double, const Color&, const Color&) override {}
  void drawSegment(const Vec2&, const Vec2&, const Color&) override { ++segments; }
  void drawPoint(const Vec2& p, float, const Color&) override { points.push_back(p); }
  bool drew(const Vec2& p) const {
    for (const Vec2& q : points)
      if ((q - p).norm() < 1e-12) return true;
    return false;
  }
};

BodyId box(World& w, Vec2 at) {
  BodyDef d;
  d.shape = makeBox(1, 1);
  d.position = at;
  return w.createBody(d);
}

}  // namespace

TEST_CASE("joint drawing: anchors where the joints read them, limits, pulley points, nothing with the toggle off") {
  World w;
  const BodyId a = box(w, {0, 0}), b = box(w, {2, 0}), c = box(w, {5, 0}), d = box(w, {8, 0});
  JointDef rev;
  rev.type = JointType::Revolute;
  rev.a = a;
  rev.b = b;
  rev.anchor_a = {1, 0};
  rev.enable_limit = true;
  rev.lower = -0.3;
  rev.upper = 0.3;
  const JointId hinge = w.createJoint(rev);
  JointDef slide;
  slide.type = JointType::Prismatic;
  slide.a = c;
  slide.anchor_a = {5, 0};
  slide.axis = {0, 1};
  const JointId slider = w.createJoint(slide);
  JointDef pulley;
  pulley.type = JointType::Pulley;
  pulley.a = b;
  pulley.b = d;
  pulley.anchor_a = {2, 0.5};
  pulley.anchor_b = {8, 0.5};
  pulley.ground_a = {2, 4};
  pulley.ground_b = {8, 4};
  w.createJoint(pulley);

  DrawOptions off;
  off.shapes = false;
  off.joints = false;
  Recorder none;
  w.draw(none, off);
  CHECK(none.points.empty());
  CHECK(none.segments == 0);

  DrawOptions on = off;
  on.joints = true;
  Recorder r;
  w.draw(r, on);
  CHECK(r.drew(w.jointState(hinge).world_anchor_a));
  CHECK(r.drew(w.jointState(slider).world_anchor_b));
  CHECK(r.drew(Vec2(2, 4)));
  CHECK(r.drew(Vec2(8, 4)));
  const int with_limit = r.segments;
  JointDef free = w.joint(hinge);
  free.enable_limit = false;
  w.updateJoint(hinge, free);
  Recorder r2;
  w.draw(r2, on);
  CHECK(r2.segments == with_limit - 2);  // the two bounds

  // At the poses the sandbox draws (between two steps), not the world's.
  std::vector<Transform> poses;
  for (const BodyId id : w.bodyIds()) {
    poses.resize(std::max<size_t>(poses.size(), id.index + 1));
    poses[id.index] = w.body(id).xf;
    poses[id.index].p += Vec2(0, 1);
  }
  on.transforms = poses;
  Recorder moved;
  w.draw(moved, on);
  CHECK(moved.drew(w.jointState(hinge).world_anchor_a + Vec2(0, 1)));
  CHECK_FALSE(moved.drew(w.jointState(hinge).world_anchor_a));
}

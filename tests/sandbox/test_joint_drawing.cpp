// Joints as World::draw draws them (core debug_draw.cpp, DrawOptions::joints), recorded through a
// DebugDraw: anchors as points where jointState reads them, at the poses the sandbox draws
// (interpolated transforms), limits as extra lines, nothing with the toggle off; lines from the
// bodies' centres to the anchors and between the anchors, a colour and a mark per kind.
#include <doctest/doctest.h>

#include <algorithm>
#include <iterator>
#include <optional>
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

namespace {

// Every primitive with its colour, for the lines of each joint kind.
struct LineRecorder : DebugDraw {
  struct Segment {
    Vec2 a, b;
    Color color;
  };
  std::vector<Segment> segments;
  std::vector<std::pair<Vec2, double>> rings;       // outlined circles: centre, radius
  std::vector<std::vector<Vec2>> outlines;          // outlined polygons
  void drawPolygon(std::span<const Vec2> v, const Color& fill, const Color&) override {
    if (fill.a == 0.0f) outlines.emplace_back(v.begin(), v.end());
  }
  void drawCircle(const Vec2& c, double r, double, const Color& fill, const Color&) override {
    if (fill.a == 0.0f) rings.emplace_back(c, r);
  }
  void drawSegment(const Vec2& a, const Vec2& b, const Color& color) override { segments.push_back({a, b, color}); }
  void drawPoint(const Vec2&, float, const Color&) override {}
  // The colour of a segment from p to q (either way round), if one was drawn.
  std::optional<Color> segment(const Vec2& p, const Vec2& q) const {
    for (const Segment& s : segments)
      if (((s.a - p).norm() < 1e-9 && (s.b - q).norm() < 1e-9) || ((s.a - q).norm() < 1e-9 && (s.b - p).norm() < 1e-9))
        return s.color;
    return std::nullopt;
  }
};

bool same(const Color& x, const Color& y) { return x.r == y.r && x.g == y.g && x.b == y.b && x.a == y.a; }

}  // namespace

TEST_CASE("joint drawing: lines between the bodies' centres and the anchors, each kind in its own colour and mark") {
  World w;
  std::vector<std::pair<JointType, JointId>> joints;
  std::vector<std::pair<BodyId, BodyId>> bodies;
  // One pair of bodies per kind, 10 m apart, with the anchors offset so that every line has length.
  const JointType kinds[] = {JointType::Revolute, JointType::Weld, JointType::Distance, JointType::Prismatic,
                             JointType::Wheel, JointType::Friction};
  for (size_t k = 0; k < std::size(kinds); ++k) {
    const double x = 10.0 * static_cast<double>(k);
    const BodyId a = box(w, {x, 0}), b = box(w, {x + 2, 0.5});
    JointDef d;
    d.type = kinds[k];
    d.a = a;
    d.b = b;
    d.anchor_a = {x + 1, 0.2};
    d.anchor_b = {x + 1.4, 0.3};  // the distance joint's second anchor (the others take anchor_a)
    d.axis = {1, 0};
    joints.emplace_back(kinds[k], w.createJoint(d));
    bodies.emplace_back(a, b);
  }
  DrawOptions only_joints;
  only_joints.shapes = false;
  LineRecorder r;
  w.draw(r, only_joints);

  std::vector<Color> colors;
  for (size_t k = 0; k < joints.size(); ++k) {
    const auto [type, id] = joints[k];
    CAPTURE(jointTypeName(type));
    const JointState js = w.jointState(id);
    const Vec2 ca = w.body(bodies[k].first).center, cb = w.body(bodies[k].second).center;
    const auto to_a = r.segment(ca, js.world_anchor_a), to_b = r.segment(cb, js.world_anchor_b);
    REQUIRE(to_a);
    REQUIRE(to_b);
    CHECK(same(*to_a, *to_b));
    colors.push_back(*to_a);
    if (type == JointType::Distance || type == JointType::Prismatic || type == JointType::Wheel ||
        type == JointType::Friction) {
      const auto between = r.segment(js.world_anchor_a, js.world_anchor_b);  // anchor to anchor
      REQUIRE(between);
      CHECK(same(*between, *to_a));
    }
    const auto near = [&](const Vec2& p) { return (p - js.world_anchor_b).norm() < 1e-9; };
    const bool ring = std::any_of(r.rings.begin(), r.rings.end(), [&](const auto& c) { return near(c.first); });
    CHECK(ring == (type == JointType::Revolute || type == JointType::Wheel));
    const bool square = std::any_of(r.outlines.begin(), r.outlines.end(), [&](const std::vector<Vec2>& v) {
      Vec2 mean = Vec2::Zero();
      for (const Vec2& q : v) mean += q;
      return v.size() == 4 && near(mean / 4.0);
    });
    CHECK(square == (type == JointType::Weld));
  }
  for (size_t i = 0; i < colors.size(); ++i)
    for (size_t j = i + 1; j < colors.size(); ++j) {
      CAPTURE(i);
      CAPTURE(j);
      CHECK_FALSE(same(colors[i], colors[j]));
    }
}

// Picking bodies and joints under the cursor (picking.h).
#include "picking.h"

#include <algorithm>

namespace rigidlab::sandbox {

namespace {

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = d.squaredNorm() > 0.0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

}  // namespace

std::optional<BodyId> pickBody(const World& world, const Vec2& p, double tolerance, BodyId except) {
  const std::vector<BodyId> ids = world.bodyIds();
  for (auto it = ids.rbegin(); it != ids.rend(); ++it) {  // the last made is drawn on top
    if (*it == except) continue;
    const Body& b = world.body(*it);
    for (const ShapeId sid : b.shapes) {
      const Shape& g = world.shape(sid).geometry;
      if (hasArea(g.type) ? containsPoint(g, b.xf, p)
                          : distanceToSegment(p, b.xf.apply(g.vertices[0]), b.xf.apply(g.vertices[1])) <= tolerance)
        return *it;
    }
  }
  return std::nullopt;
}

std::optional<JointId> pickJoint(const World& world, const Vec2& p, double tolerance) {
  std::optional<JointId> best;
  double nearest = tolerance;
  for (const JointId id : world.jointIds()) {
    const JointDef& d = world.joint(id);
    if (d.type == JointType::Gear) continue;  // no anchor of its own
    const JointState s = world.jointState(id);
    for (const Vec2& q : {s.world_anchor_a, s.world_anchor_b}) {
      const double r = (q - p).norm();
      if (r <= nearest) {
        nearest = r;
        best = id;
      }
    }
    if (d.type == JointType::Pulley) {
      for (const Vec2& q : {d.ground_a, d.ground_b}) {
        const double r = (q - p).norm();
        if (r <= nearest) {
          nearest = r;
          best = id;
        }
      }
    }
  }
  return best;
}

}  // namespace rigidlab::sandbox

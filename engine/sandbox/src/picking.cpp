// Picking bodies and joints under the cursor (picking.h). Bodies through the world's queries
// (World::queryPoint, World::overlap), which never find a disabled body: a click does not select
// one (a body disabled from the Body panel stays selected there until something else is).
#include "picking.h"

#include <algorithm>

namespace rigidlab::sandbox {

namespace {

// Every shape, whatever its filter, sensors included: the user clicks what is drawn.
QueryFilter everything() {
  QueryFilter f;
  f.category = ~uint64_t{0};
  f.sensors = true;
  return f;
}

}  // namespace

std::optional<BodyId> pickBody(const World& world, const Vec2& p, double tolerance, BodyId except) {
  // Through the world's queries: shapes with area containing p, shapes without (segments, chain
  // segments) within `tolerance` of it.
  std::vector<BodyId> hits;
  for (const ShapeId sid : world.queryPoint(p, everything())) hits.push_back(world.shape(sid).body);
  Transform at;
  at.p = p;
  if (tolerance > 0.0)
    for (const ShapeId sid : world.overlap(makeCircle(tolerance), at, everything()))
      if (!hasArea(world.shape(sid).geometry.type)) hits.push_back(world.shape(sid).body);
  std::erase(hits, except);
  if (hits.empty()) return std::nullopt;
  // The last made is drawn on top: the hit latest in creation order.
  const std::vector<BodyId> order = world.bodyIds();
  for (auto it = order.rbegin(); it != order.rend(); ++it)
    if (std::find(hits.begin(), hits.end(), *it) != hits.end()) return *it;
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

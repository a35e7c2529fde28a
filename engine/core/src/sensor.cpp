// Sensors (ShapeDef::sensor): shapes that collide with nothing and report what overlaps them. At
// the end of each step every sensor's overlaps are found with the query tree (world_query.cpp) and
// compared with the last step's: new ones begin, missing ones end (World::sensorEvents). Every
// shape the sensor's filter accepts counts, on any body (static and sleeping ones included), except
// other sensors and the sensor's own body.
//
// A fast body does not skip a thin sensor: a shape whose body moved further in the step than its
// thinnest shape is thick is also swept, from where the step began to where it ended, and if the
// sweep met the sensor the shape counts as having been in it this step: it begins and, unless it
// is still in, ends in the same step (conservative advancement, as continuous.cpp).
#include <algorithm>
#include <cmath>

#include "manifold.h"
#include "shape_query.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

Transform placed(const Body& b, const Vec2& center, double angle) {
  Transform xf{Vec2::Zero(), Rot::fromAngle(angle)};
  xf.p = center - xf.q.apply(b.local_center);
  return xf;
}

// Did the shape, moving with its body from the step's start to its end, meet the sensor?
bool sweptThrough(const WorldImpl& w, uint32_t shape, const BodyShape& sensor, const Transform& sensor_xf) {
  const BodyShape& s = w.shapes[shape];
  const uint32_t i = s.body.index;
  const Body& b = w.bodies[i];
  if (!b.isDynamic() || i >= w.start_center.size()) return false;
  const Vec2 c0 = w.start_center[i], c1 = b.center;
  const double a0 = w.start_angle[i], a1 = b.angle;
  const double travel = (c1 - c0).norm() + std::abs(a1 - a0) * b.max_extent;
  if (!(travel > b.min_inradius)) return false;  // it cannot have skipped anything
  double t = 0.0;
  for (int iteration = 0; iteration < 50 && t <= 1.0; ++iteration) {
    const double d = separationLowerBound(s.geometry, placed(b, c0 + t * (c1 - c0), a0 + t * (a1 - a0)), sensor.geometry, sensor_xf);
    if (d <= 0.0) return true;
    t += std::max(d, 1e-9) / travel;
  }
  return false;
}

}  // namespace

void updateSensors(WorldImpl& w) {
  w.sensor_events.clear();
  if (w.sensor_shapes == 0) return;
  w.syncTree();
  w.sensor_overlaps.resize(w.shapes.size());
  // The bodies that moved further this step than their thinnest shape is thick (they are swept).
  std::vector<uint32_t> fast;
  for (uint32_t i = 0; i < w.bodies.size() && i < w.start_center.size(); ++i) {
    if (!w.isActive(i)) continue;
    const Body& b = w.bodies[i];
    if ((w.start_center[i] - b.center).norm() + std::abs(w.start_angle[i] - b.angle) * b.max_extent > b.min_inradius)
      fast.push_back(i);
  }
  std::vector<ShapeId> now;
  std::vector<uint32_t> passed;  // swept through but not in at the end
  for (uint32_t s = 0; s < w.shapes.size(); ++s) {
    if (!w.shape_alive[s] || !w.shapes[s].sensor) continue;
    const BodyShape& sensor = w.shapes[s];
    const Body& body = w.bodyOf(s);
    now.clear();
    passed.clear();
    if (body.enabled) {
      const Transform& xf = body.xf;
      w.tree.query(computeAabb(sensor.geometry, xf), [&](uint32_t v) {
        const BodyShape& visitor = w.shapes[v];
        if (visitor.sensor || visitor.body.index == sensor.body.index || !shouldCollide(sensor.filter, visitor.filter)) return true;
        if (shapesOverlap(sensor.geometry, xf, visitor.geometry, w.bodyOf(v).xf)) now.push_back(visitor.id);
        return true;
      });
      // Fast bodies that passed through in one step: the sweep from each body's start.
      for (const uint32_t i : fast) {
        const Body& b = w.bodies[i];
        for (ShapeId vid : b.shapes) {
          const BodyShape& visitor = w.shapes[vid.index];
          if (visitor.sensor || i == sensor.body.index || !shouldCollide(sensor.filter, visitor.filter)) continue;
          if (std::find(now.begin(), now.end(), visitor.id) != now.end()) continue;
          const auto& before = w.sensor_overlaps[s];  // in it last step: it ends as usual
          if (std::find(before.begin(), before.end(), visitor.id) != before.end()) continue;
          if (sweptThrough(w, vid.index, sensor, xf)) passed.push_back(vid.index);
        }
      }
    }
    std::sort(now.begin(), now.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
    std::vector<ShapeId>& before = w.sensor_overlaps[s];
    const auto event = [&](bool begin, ShapeId visitor) {
      w.sensor_events.push_back({begin, sensor.id, visitor, sensor.body, w.shapes[visitor.index].id == visitor
                                                                               ? w.shapes[visitor.index].body
                                                                               : BodyId{}});
    };
    for (const ShapeId v : before)  // gone (or removed with its body)
      if (std::find(now.begin(), now.end(), v) == now.end()) event(false, v);
    for (const ShapeId v : now)
      if (std::find(before.begin(), before.end(), v) == before.end()) event(true, v);
    for (const uint32_t v : passed) {
      event(true, w.shapes[v].id);
      event(false, w.shapes[v].id);
    }
    before = now;
  }
}

const std::vector<World::SensorEvent>& World::sensorEvents() const { return impl_->sensor_events; }

std::vector<ShapeId> World::sensorOverlaps(ShapeId sensor) const {
  WorldImpl& w = *impl_;
  w.get(sensor);
  return sensor.index < w.sensor_overlaps.size() ? w.sensor_overlaps[sensor.index] : std::vector<ShapeId>{};
}

}  // namespace rigidlab

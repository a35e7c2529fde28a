// Contact events (World::contactEvents): begin when two shapes first touch, end when their contact
// is gone, hit for a beginning contact closing faster than a shape's hit_speed. The narrow phase
// finds them as it merges this step's contacts with the last step's (narrow_phase.cpp); their
// impulses are filled in after the solve. Both come in the contacts' order (by shape pair), so the
// events are as deterministic as the step.
#include <algorithm>
#include <cmath>

#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

World::ContactEvent eventOf(const WorldImpl& w, const Contact& c, World::ContactEvent::Kind kind) {
  World::ContactEvent e;
  e.kind = kind;
  e.shape_a = w.shapes[c.shape_a].id;
  e.shape_b = w.shapes[c.shape_b].id;
  e.a = w.bodies[c.a].id;
  e.b = w.bodies[c.b].id;
  e.normal = c.normal;
  e.count = c.count;
  for (int i = 0; i < c.count; ++i) e.points[i] = c.points[i].point;
  e.point = c.count == 2 ? Vec2(0.5 * (e.points[0] + e.points[1])) : e.points[0];
  return e;
}

}  // namespace

void contactBegins(WorldImpl& w, uint32_t k) {
  const Contact& c = w.contacts[k];
  World::ContactEvent e = eventOf(w, c, World::ContactEvent::Kind::Begin);
  // The closing speed with the velocities at the start of the step (before the forces of this step
  // and the impact changed them): −n · (v_B + ω_B × r_B − v_A − ω_A × r_A) at the contact point.
  const Vec2 ra = e.point - w.bodies[c.a].center, rb = e.point - w.bodies[c.b].center;
  const auto start = [&](uint32_t slot, const Vec2& r) {
    return slot < w.start_velocity.size() ? Vec2(w.start_velocity[slot] + cross(w.start_angular_velocity[slot], r))
                                          : Vec2(Vec2::Zero());
  };
  e.approach_speed = -(start(c.b, rb) - start(c.a, ra)).dot(e.normal);
  const BodyShape &sa = w.shapes[c.shape_a], &sb = w.shapes[c.shape_b];
  if (w.every_contact_event || sa.contact_events || sb.contact_events) {
    w.contact_events.push_back(e);
    w.event_contacts.push_back(k);
  }
  const double threshold = std::min(sa.hit_events ? sa.hit_speed : INFINITY, sb.hit_events ? sb.hit_speed : INFINITY);
  if (e.approach_speed >= threshold) {
    e.kind = World::ContactEvent::Kind::Hit;
    w.contact_events.push_back(e);
    w.event_contacts.push_back(k);
  }
}

void contactEnds(WorldImpl& w, const Contact& previous) {
  const BodyShape &sa = w.shapes[previous.shape_a], &sb = w.shapes[previous.shape_b];
  if (!(w.every_contact_event || sa.contact_events || sb.contact_events)) return;  // hit shapes only: no end
  w.contact_events.push_back(eventOf(w, previous, World::ContactEvent::Kind::End));
  w.event_contacts.push_back(UINT32_MAX);
}

void finishContactEvents(WorldImpl& w) {
  for (size_t i = 0; i < w.contact_events.size(); ++i) {
    if (w.event_contacts[i] == UINT32_MAX) continue;
    const Contact& c = w.contacts[w.event_contacts[i]];
    World::ContactEvent& e = w.contact_events[i];
    e.normal_impulse = e.tangent_impulse = 0.0;
    for (int p = 0; p < c.count; ++p) {
      e.normal_impulse += c.points[p].step_normal_impulse;
      e.tangent_impulse += c.points[p].step_tangent_impulse;
    }
  }
}

void WorldImpl::countShape(const BodyShape& s, int sign) {
  const auto add = [&](uint32_t& counter, bool flagged) {
    if (flagged) counter = static_cast<uint32_t>(static_cast<int64_t>(counter) + sign);
  };
  add(event_shapes, s.contact_events || s.hit_events);
  add(presolve_shapes, s.pre_solve || s.one_way.has_value());
  add(sensor_shapes, s.sensor);
}

const std::vector<World::ContactEvent>& World::contactEvents() const { return impl_->contact_events; }
void World::setContactEvents(bool every_contact) { impl_->every_contact_event = every_contact; }

}  // namespace rigidlab

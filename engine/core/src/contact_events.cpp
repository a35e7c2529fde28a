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

void copySurface(const Contact& c, const ContactSurface& surface, World::ContactEvent& e) {
  e.friction = c.friction;
  e.static_friction = c.static_friction;
  e.restitution = c.restitution;
  e.tangent_speed = surface.tangent_speed;
  e.rolling_resistance = surface.rolling_resistance;
}

World::ContactEvent eventOf(const WorldImpl& w, const Contact& c, World::ContactEvent::Kind kind) {
  World::ContactEvent e;
  e.kind = kind;
  e.shape_a = w.shapes[c.shape_a].id;
  e.shape_b = w.shapes[c.shape_b].id;
  e.a = w.bodies[c.a].id;
  e.b = w.bodies[c.b].id;
  e.normal = c.normal;
  e.count = c.count;
  for (int i = 0; i < c.count; ++i) {
    e.points[i] = c.points[i].point;
    e.separations[i] = c.points[i].separation;
  }
  e.point = c.count == 2 ? Vec2(0.5 * (e.points[0] + e.points[1])) : e.points[0];
  copySurface(c, w.surfaceOf(c), e);
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
    // The surface the solve used (after the pre-solve callback).
    copySurface(c, w.contact_surfaces.empty() ? w.surfaceOf(c) : w.contact_surfaces[w.event_contacts[i]], e);
    e.normal_impulse = e.tangent_impulse = 0.0;
    for (int p = 0; p < c.count; ++p) {
      e.normal_impulses[p] = c.points[p].step_normal_impulse;
      e.tangent_impulses[p] = c.points[p].step_tangent_impulse;
      e.normal_impulse += c.points[p].step_normal_impulse;
      e.tangent_impulse += c.points[p].step_tangent_impulse;
    }
    // An impact located inside this step that ended in this resting contact gave the pair its
    // impulse before the contact solver ran: it is part of the step's impulse at the contact.
    for (const LocatedImpact& li : w.impact.log)
      if (!li.separating && li.shape_a == c.shape_a && li.shape_b == c.shape_b) {
        e.normal_impulse += li.normal_impulse;
        e.tangent_impulse += li.tangent_impulse;
      }
  }
}

// Impacts located inside the step (event_location.cpp) that ended in a bounce: the shapes touched
// and parted between two narrow phases, so the events come from the impact itself, with the
// closing speed at the impact and its impulses. An impact that ended in resting contact is left to
// the narrow phase, which finds the contact touching at the end of the step and reports it as
// any other (begin and hit with the closing speed at the start of the step).
void locatedImpactEvents(WorldImpl& w) {
  if (!(w.every_contact_event || w.event_shapes > 0)) return;
  for (const LocatedImpact& li : w.impact.log) {
    if (!li.separating) continue;
    const BodyShape &sa = w.shapes[li.shape_a], &sb = w.shapes[li.shape_b];
    const bool contact = w.every_contact_event || sa.contact_events || sb.contact_events;
    const double threshold = std::min(sa.hit_events ? sa.hit_speed : INFINITY, sb.hit_events ? sb.hit_speed : INFINITY);
    if (!contact && !(li.approach_speed >= threshold)) continue;
    // Still touching at the end of the step (an impact at its very end): the narrow phase reports it.
    const auto at = std::lower_bound(w.contacts.begin(), w.contacts.end(), li, [](const Contact& c, const LocatedImpact& l) {
      return c.shape_a < l.shape_a || (c.shape_a == l.shape_a && c.shape_b < l.shape_b);
    });
    if (at != w.contacts.end() && at->shape_a == li.shape_a && at->shape_b == li.shape_b && at->touching) continue;
    World::ContactEvent e;
    e.shape_a = sa.id;
    e.shape_b = sb.id;
    e.a = w.bodies[li.a].id;
    e.b = w.bodies[li.b].id;
    e.normal = li.normal;
    e.count = li.count;
    for (int i = 0; i < li.count; ++i) e.points[i] = li.points[i];
    e.point = li.count == 2 ? Vec2(0.5 * (e.points[0] + e.points[1])) : e.points[0];
    e.approach_speed = li.approach_speed;
    e.normal_impulse = li.normal_impulse;
    e.tangent_impulse = li.tangent_impulse;
    const auto push = [&](World::ContactEvent::Kind kind) {
      e.kind = kind;
      w.contact_events.push_back(e);
      w.event_contacts.push_back(UINT32_MAX);
    };
    if (contact) push(World::ContactEvent::Kind::Begin);
    if (li.approach_speed >= threshold) push(World::ContactEvent::Kind::Hit);
    if (contact) push(World::ContactEvent::Kind::End);
  }
}

void WorldImpl::countShape(const BodyShape& s, int sign) {
  const auto add = [&](uint32_t& counter, bool flagged) {
    if (flagged) counter = static_cast<uint32_t>(static_cast<int64_t>(counter) + sign);
  };
  add(event_shapes, s.contact_events || s.hit_events);
  add(presolve_shapes, s.pre_solve || s.one_way.has_value());
  add(sensor_shapes, s.sensor);
  add(surface_shapes, s.tangent_speed != 0.0 || s.rolling_resistance > 0.0);
}

const std::vector<World::ContactEvent>& World::contactEvents() const { return impl_->contact_events; }

std::vector<World::Impact> World::impacts() const {
  const WorldImpl& w = *impl_;
  std::vector<Impact> out;
  for (const LocatedImpact& l : w.impact.log) {
    Impact& i = out.emplace_back();
    i.shape_a = w.shapes[l.shape_a].id;
    i.shape_b = w.shapes[l.shape_b].id;
    i.a = w.bodies[l.a].id;
    i.b = w.bodies[l.b].id;
    i.time = w.impact.intervals.front().start + l.time;
    i.normal = l.normal;
    i.count = l.count;
    for (int k = 0; k < l.count; ++k) i.points[k] = l.points[k];
    i.approach_speed = l.approach_speed;
    i.normal_impulse = l.normal_impulse;
    i.tangent_impulse = l.tangent_impulse;
    i.separating = l.separating;
  }
  return out;
}
void World::setContactEvents(bool every_contact) { impl_->every_contact_event = every_contact; }

}  // namespace rigidlab

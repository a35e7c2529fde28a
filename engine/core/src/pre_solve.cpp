// Pre-solve (between the narrow phase and the solve): contacts of one-way platforms, and contacts
// the world's pre-solve callback turns off, are disabled for this step (their keys say so; the
// solvers skip them). The callback may also change a contact's friction, restitution and tangent
// speed for this step. And the surface effects of the step's contacts (ContactSurface: conveyor
// belts, rolling resistance) are gathered here, when some shape has them or the callback gives
// some: the solvers read them beside the contacts (WorldImpl::contact_surfaces).
//
// One-way platform (ShapeDef::one_way, normal n of the side to stand on): the contact holds only
// while the other shape is on that side, coming towards it, and has not started through it:
//   - the contact normal from the platform to the other shape points along n (n_c · n ≥ 0.7), and
//   - the other shape does not move away along n faster than 1 cm/s relative to the platform,
//   - and it was not passing through when the contact began (Contact::passing: once disabled, a
//     contact stays disabled until it ends, so a body half way through is not popped out).
#include <algorithm>
#include <cmath>

#include "rigidlab/error.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

bool oneWayAllows(const WorldImpl& w, const Contact& c, uint32_t platform_shape, bool platform_is_a) {
  const BodyShape& p = w.shapes[platform_shape];
  const Body& platform = w.bodies[platform_is_a ? c.a : c.b];
  const Body& other = w.bodies[platform_is_a ? c.b : c.a];
  const Vec2 n = platform.xf.q.apply(*p.one_way);
  const Vec2 towards_other = platform_is_a ? Vec2(c.normal) : Vec2(-c.normal);
  if (towards_other.dot(n) < 0.7) return false;
  const Vec2 point = c.count == 2 ? Vec2(0.5 * (c.points[0].point + c.points[1].point)) : Vec2(c.points[0].point);
  const double away = (other.pointVelocity(point) - platform.pointVelocity(point)).dot(n);
  return away <= 0.01;
}

// The contacts' surface effects as their shapes give them (all zero when no shape has any).
void gatherSurfaces(WorldImpl& w) {
  w.contact_surfaces.resize(w.contacts.size());
  for (size_t k = 0; k < w.contacts.size(); ++k) w.contact_surfaces[k] = w.surfaceOf(w.contacts[k]);
}

// What a callback wrote, checked as the shape options are: non-negative frictions, restitution in
// [0, 1], a finite tangent speed.
void requireSurfaceValues(const ContactInfo& info) {
  requireNonNegative("friction", info.friction);
  requireNonNegative("static_friction", info.static_friction);
  requireNonNegative("restitution", info.restitution);
  if (info.restitution > 1.0) throw InputError("restitution", "restitution must be between 0 and 1, got " + formatNumber(info.restitution));
  requireFinite("tangent_speed", info.tangent_speed);
}

}  // namespace

void preSolve(WorldImpl& w) {
  w.contact_surfaces.clear();
  if (w.surface_shapes > 0) gatherSurfaces(w);
  if (w.presolve_shapes == 0) return;
  for (size_t k = 0; k < w.contacts.size(); ++k) {
    Contact& c = w.contacts[k];
    const BodyShape &sa = w.shapes[c.shape_a], &sb = w.shapes[c.shape_b];
    if (!sa.one_way && !sb.one_way && !sa.pre_solve && !sb.pre_solve) continue;
    bool enabled = !c.passing;
    if (enabled && sa.one_way) enabled = oneWayAllows(w, c, c.shape_a, true);
    if (enabled && sb.one_way) enabled = oneWayAllows(w, c, c.shape_b, false);
    if ((sa.one_way || sb.one_way) && !enabled) c.passing = true;
    if (enabled && (sa.pre_solve || sb.pre_solve) && w.pre_solve) {
      ContactInfo info;
      info.a = w.bodies[c.a].id;
      info.b = w.bodies[c.b].id;
      info.shape_a = sa.id;
      info.shape_b = sb.id;
      info.normal = c.normal;
      info.count = c.count;
      info.touching = c.touching;
      for (int i = 0; i < c.count; ++i) {
        info.points[i] = c.points[i].point;
        info.separations[i] = c.points[i].separation;
        info.normal_impulses[i] = c.points[i].normal_impulse;  // last step's, as the solve starts from them
        info.tangent_impulses[i] = c.points[i].tangent_impulse;
        info.ids[i] = c.points[i].id;
      }
      info.friction = c.friction;
      info.static_friction = c.static_friction;
      info.restitution = c.restitution;
      const ContactSurface surface = w.contact_surfaces.empty() ? w.surfaceOf(c) : w.contact_surfaces[k];
      info.tangent_speed = surface.tangent_speed;
      info.rolling_resistance = surface.rolling_resistance;
      enabled = w.pre_solve(info);
      requireSurfaceValues(info);
      c.friction = info.friction;
      c.static_friction = info.static_friction;
      c.restitution = info.restitution;
      if (info.tangent_speed != surface.tangent_speed) {
        if (w.contact_surfaces.empty()) gatherSurfaces(w);
        w.contact_surfaces[k].tangent_speed = info.tangent_speed;
      }
    }
    if (!enabled) {
      w.contact_keys[k].disabled = true;
      for (int i = 0; i < c.count; ++i) c.points[i].normal_impulse = c.points[i].tangent_impulse = 0.0;
    }
  }
}

void World::setPreSolve(PreSolveFn callback) { impl_->pre_solve = std::move(callback); }

}  // namespace rigidlab

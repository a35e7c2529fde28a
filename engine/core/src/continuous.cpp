// Continuous collision detection of fast bodies against static ones (docs/design/thesis.md §3.3.1 and §13:
// without it a small fast body tunnels through a thin wall between two steps).
//
// After integration, a dynamic body that moved more than its inner radius in the step is
// swept from where it started to where it ended (position and angle interpolated linearly)
// against every static shape whose box meets the swept box (a tree of the static shapes, kept
// between steps, finds them). The time of impact is found by
// conservative advancement (B. Mirtich 1996; E. Catto, "Continuous Collision", GDC 2013): at the
// current time t the distance d between the shapes (a lower bound, manifold.cpp
// separationLowerBound) cannot close faster than the sweep's bound on the speed of any point,
//   |Δc| + |Δθ|·extent   per unit of t,
// so t may advance by d over that bound without missing contact. Once the shapes are within a
// fraction of the contact margin, the body is put back there for the rest of the step, keeping its
// velocity as it was at that moment (the start and end velocities interpolated like the position:
// exact under a constant force); the narrow phase then finds the contact (speculatively) and the
// solver stops or bounces the body right away (contact_solver.cpp: the impact happens now, not next
// step). The body loses the part of the step after the impact (as Box2D 2.4's does). Keeping the
// end-of-step velocity there instead put the body on the surface with the speed it would have had
// a fraction of a step later: an elastic ball (r = 0.1 m) dropped 1 m gained 7 % of its energy per
// bounce with RK4 at dt = 1/30.
// Bodies whose impacts are located (event_location.cpp) are not swept against static bodies: the
// search along their path already finds the first contact; located bullets are still swept against
// the dynamic bodies that are not located (kinematic bodies are in the search).
// Bullets (BodyDef::bullet) are also swept against moving bodies that are not bullets, where the
// integration left them, so that a fast small body stops at a thin moving one.
#include <algorithm>
#include <cmath>
#include <limits>

#include "manifold.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

Transform placed(const Body& b, const Vec2& center, double angle) {
  Transform xf{Vec2::Zero(), Rot::fromAngle(angle)};
  xf.p = center - xf.q.apply(b.local_center);
  return xf;
}

}  // namespace

namespace {

void syncStaticTree(WorldImpl& w) {
  if (w.static_tree_version == w.static_version) return;
  w.static_tree_version = w.static_version;
  w.static_tree.clear();
  for (uint32_t s = 0; s < w.shapes.size(); ++s)
    if (w.shape_alive[s] && w.bodyOf(s).isStatic()) w.static_tree.insert(computeAabb(w.shapes[s].geometry, w.bodyOf(s).xf), s);
}

}  // namespace

void sweepFastBodies(WorldImpl& w) {
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  const double target = 0.25 * w.def.contact_margin;  // stop this far from contact
  // The bodies that could skip over something: most steps have none, and then nothing else is done.
  w.fast_bodies.clear();
  bool bullets = false;
  const auto located = [&](uint32_t slot) { return slot < w.impact.located.size() && w.impact.located[slot]; };
  for (uint32_t i = 0; i < n; ++i) {
    if (!w.isActive(i)) continue;
    const Body& b = w.bodies[i];
    bullets |= b.bullet;
    if (located(i) && !b.bullet) continue;  // the search along its path already finds its first contact
    // A body's thinnest and widest shapes bound what it can skip and how far its points travel.
    if (b.max_extent == 0.0) continue;  // no solid shape
    const double travel = (b.center - w.start_center[i]).norm() + std::abs(b.angle - w.start_angle[i]) * b.max_extent;
    if (travel > b.min_inradius) w.fast_bodies.push_back(i);  // else discrete detection sees it
  }
  if (w.fast_bodies.empty()) return;
  // Obstacles: every static shape (a tree kept between steps); for bullets also the shapes of moving
  // bodies that are not bullets, where the integration left them (Box2D's rule: bullets against
  // bullets are not swept).
  syncStaticTree(w);
  w.ccd_movers.clear();
  if (bullets)
    for (uint32_t s = 0; s < w.shapes.size(); ++s) {
      if (!w.shape_alive[s] || w.shapes[s].sensor) continue;
      const Body& b = w.bodyOf(s);
      if (b.enabled && !b.isStatic() && !b.bullet && (b.isKinematic() || b.awake)) w.ccd_movers.push_back(s);
    }
  if (w.static_tree.empty() && w.ccd_movers.empty()) return;

  for (uint32_t i : w.fast_bodies) {
    Body& b = w.bodies[i];
    const double extent = b.max_extent;
    const Vec2 c0 = w.start_center[i], c1 = b.center;
    const double a0 = w.start_angle[i], a1 = b.angle;
    const double travel = (c1 - c0).norm() + std::abs(a1 - a0) * extent;
    ++w.stats.ccd_sweeps;

    const Transform start = placed(b, c0, a0);
    // The earliest time of impact over all obstacles is their minimum, whatever order they come in
    // (an obstacle's own time does not depend on the others').
    double first = 1.0;
    const auto sweepOne = [&](const BodyShape& mover, const Aabb& swept, uint32_t s) {
      const BodyShape& wall = w.shapes[s];
      if (wall.body.index == i || wall.sensor || !shouldCollide(mover.filter, wall.filter)) return;
      if (located(wall.body.index)) return;  // two located bodies: their impacts are located
      const Body& wall_body = w.bodies[wall.body.index];
      if (wall_body.isKinematic() && located(i)) return;  // its impacts with kinematic bodies are located too
      if (!wall_body.enabled || !swept.overlaps(computeAabb(wall.geometry, wall_body.xf))) return;
      if (wall_body.isDynamic() && w.jointBlocksCollision(i, wall.body.index)) return;
      const double d0 = separationLowerBound(mover.geometry, start, wall.geometry, wall_body.xf);
      if (d0 <= target) return;  // already in contact at the start: the contact solver has it
      double t = 0.0;
      for (int iteration = 0; iteration < 50 && t < first; ++iteration) {
        const double d = separationLowerBound(mover.geometry, placed(b, c0 + t * (c1 - c0), a0 + t * (a1 - a0)),
                                              wall.geometry, wall_body.xf);
        if (d <= target) {
          first = t;
          break;
        }
        t += (d - 0.5 * target) / travel;
      }
    };
    for (ShapeId id : b.shapes) {
      const BodyShape& mover = w.shapes[id.index];
      if (mover.sensor) continue;
      // Swept box: the shape's boxes at both ends, grown by the rotation bound.
      Aabb swept = computeAabb(mover.geometry, start);
      const Aabb end = computeAabb(mover.geometry, b.xf);
      swept.lower = swept.lower.cwiseMin(end.lower);
      swept.upper = swept.upper.cwiseMax(end.upper);
      if (!located(i))
        w.static_tree.query(swept, [&](uint32_t s) {
          if (w.shape_alive[s] && w.bodyOf(s).isStatic()) sweepOne(mover, swept, s);
          return true;
        });
      if (b.bullet)
        for (uint32_t s : w.ccd_movers) sweepOne(mover, swept, s);
    }
    if (first < 1.0) {
      ++w.stats.ccd_hits;
      w.ccd_hit[i] = 1;
      b.center = c0 + first * (c1 - c0);
      b.angle = a0 + first * (a1 - a0);
      b.velocity = w.start_velocity[i] + first * (b.velocity - w.start_velocity[i]);
      b.angular_velocity = w.start_angular_velocity[i] + first * (b.angular_velocity - w.start_angular_velocity[i]);
      WorldImpl::syncTransform(b);
    }
  }
}

}  // namespace rigidlab

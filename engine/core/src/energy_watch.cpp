// The energy balance of every step, and the blow-up incident (energy_watch.h has the bound).
#include "energy_watch.h"

#include <algorithm>
#include <cmath>

#include "joint.h"
#include "step_context.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

// X > 100 S (energy_watch.h): a stable method may swing its energy well above E₀ without growing
// (semi-implicit Euler on a spring by up to 1/(1 − (ωh)²/4): 10× at ωh = 1.9, the factor
// `rigidlab stability` allows a stable run); one that blows up multiplies it every step.
constexpr double kBlowUpFactor = 100.0;

double kineticOf(const Body& b) {
  return 0.5 * b.mass * b.velocity.squaredNorm() + 0.5 * b.inertia * b.angular_velocity * b.angular_velocity;
}

// Can the joint put energy in: a motor, a spring (the stiffness of a joint spring depends on the
// bodies' masses, so its energy is not among World::potentialEnergy's), or a kinematic body?
// `kinematic`: the world has kinematic bodies (else their types are not looked up).
bool jointIsSource(const WorldImpl& w, const Joint& j, bool kinematic) {
  const JointDef& d = j.def;
  const auto moved = [&](uint32_t slot) { return slot != kWorldSlot && w.bodies[slot].isKinematic(); };
  return d.enable_motor || d.enable_spring || d.type == JointType::Motor ||
         (d.type == JointType::Weld && (d.linear_hertz > 0.0 || d.angular_hertz > 0.0)) ||
         (kinematic && (moved(j.a) || moved(j.b)));
}

// How fast the joint's force and torque can do work now: the anchors' relative speed and spin;
// with a kinematic body, the anchors' own speeds (the kinematic body works on the other through
// the joint however still they are relative to each other).
struct Motion {
  double slide = 0.0, spin = 0.0;
};
Motion jointMotion(const WorldImpl& w, const Joint& j) {
  Vec2 va = Vec2::Zero(), vb = Vec2::Zero();
  double wa = 0.0, wb = 0.0;
  bool kinematic = false;
  if (j.a != kWorldSlot) {
    const Body& b = w.bodies[j.a];
    va = b.pointVelocity(b.xf.apply(j.local_a));
    wa = b.angular_velocity;
    kinematic |= b.isKinematic();
  }
  if (j.b != kWorldSlot) {
    const Body& b = w.bodies[j.b];
    vb = b.pointVelocity(b.xf.apply(j.local_b));
    wb = b.angular_velocity;
    kinematic |= b.isKinematic();
  }
  if (kinematic) return {va.norm() + vb.norm(), std::abs(wa) + std::abs(wb)};
  return {(vb - va).norm(), std::abs(wb - wa)};
}

// Energy the step's sources may have put in (energy_watch.h): forces, joints, kinematic contacts.
double workBound(const WorldImpl& w, const EnergyWatch& e, double h) {
  double work = 0.0;
  if (e.forces_noted) {
    for (uint32_t i = 0; i < w.bodies.size(); ++i) {
      if (!w.alive[i] || !w.bodies[i].isDynamic() || i >= e.push.size()) continue;
      const Body& b = w.bodies[i];
      work += h * (e.push[i] * std::max(e.speed[i], b.velocity.norm()) +
                   e.turn[i] * std::max(e.spin[i], std::abs(b.angular_velocity)));
    }
  }
  for (const EnergyWatch::SourceJoint& source : e.source_joints) {
    const Joint& j = w.joints[source.slot];
    if (!j.alive) continue;
    Vec2 force;
    double torque;
    jointReaction(j, force, torque);
    const Motion now = jointMotion(w, j);
    work += h * (force.norm() * std::max(now.slide, source.slide) + std::abs(torque) * std::max(now.spin, source.spin));
  }
  if (w.kinematic_bodies > 0 || w.surface_shapes > 0 || !w.contact_surfaces.empty()) {
    for (size_t c = 0; c < w.contacts.size(); ++c) {
      const Contact& contact = w.contacts[c];
      const Body &a = w.bodies[contact.a], &b = w.bodies[contact.b];
      const double surface = c < w.contact_surfaces.size() ? std::abs(w.contact_surfaces[c].tangent_speed)
                                                            : std::abs(w.surfaceOf(contact).tangent_speed);
      if (!a.isKinematic() && !b.isKinematic() && surface == 0.0) continue;
      for (int p = 0; p < contact.count; ++p) {
        const ContactPoint& cp = contact.points[p];
        const Vec2 at = cp.point;
        const double carried = (a.isKinematic() ? a.pointVelocity(at).norm() : 0.0) +
                               (b.isKinematic() ? b.pointVelocity(at).norm() : 0.0);
        work += (std::abs(cp.step_normal_impulse) + std::abs(cp.step_tangent_impulse)) * carried +
                std::abs(cp.step_tangent_impulse) * surface;
      }
    }
  }
  return work;
}

}  // namespace

void EnergyWatch::noteForce(uint32_t i, const Wrench& wr) {
  if (i >= push.size()) return;
  push[i] = std::max(push[i], wr.force.norm());
  turn[i] = std::max(turn[i], std::abs(wr.torque));
  forces_noted = true;
}

void beginEnergyWatch(WorldImpl& w) {
  EnergyWatch& e = w.energy;
  if (e.reported) return;
  const size_t n = w.bodies.size();
  // The bodies' speeds at the start bound the work of forces that put energy in: kept only when
  // some such force acts (one pass over the bodies either way).
  bool forces = false;
  for (const ForceEntry& f : w.forces) forces |= f.alive && f.force->putsEnergyIn();
  if (forces) {
    e.speed.resize(n);
    e.spin.resize(n);
    e.push.assign(n, 0.0);
    e.turn.assign(n, 0.0);
  } else {
    e.push.clear();
    e.turn.clear();
  }
  e.forces_noted = false;
  double kinetic = 0.0, gravity = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    const Body& b = w.bodies[i];
    const bool counted = w.alive[i] && b.isDynamic();
    if (counted) {
      kinetic += kineticOf(b);
      gravity -= b.mass * b.gravity_scale * b.gravityOr(w.def.gravity).dot(b.center);
    }
    if (forces) {
      e.speed[i] = counted ? b.velocity.norm() : 0.0;
      e.spin[i] = counted ? std::abs(b.angular_velocity) : 0.0;
    }
  }
  const double stored = w.forces.empty() ? 0.0 : w.forcePotentialEnergy();
  const double potential = gravity + stored;
  const double energy = kinetic + potential;
  if (!e.started) {
    e.started = true;
    e.budget = kinetic + std::max(0.0, stored);  // K₀ + what forces store
    e.potential_first = e.potential_least = potential;
  } else if (energy > e.energy_end) {
    e.budget += energy - e.energy_end;  // an edit between steps put it in
  }
  e.energy_start = energy;
  e.potential_least = std::min(e.potential_least, potential);
  // The joints that may put energy in, and their anchors' motion now. A world of plain joints
  // (no motor, spring or kinematic body) keeps the list empty.
  // Listed again only when joints or body types changed (a world of 20 000 joints is not walked
  // every step).
  if (e.joints_listed != w.joint_edits || e.joints_listed_count != w.joints.size()) {
    e.source_joints.clear();
    const bool kinematic = w.kinematic_bodies > 0;
    for (uint32_t k = 0; k < w.joints.size(); ++k)
      if (w.joints[k].alive && jointIsSource(w, w.joints[k], kinematic)) e.source_joints.push_back({k, 0.0, 0.0});
    e.joints_listed = w.joint_edits;
    e.joints_listed_count = w.joints.size();
  }
  for (EnergyWatch::SourceJoint& source : e.source_joints) {
    const Joint& j = w.joints[source.slot];
    if (!j.alive) continue;  // broken in an earlier step
    const Motion m = jointMotion(w, j);
    source.slide = m.slide;
    source.spin = m.spin;
  }
}

void endEnergyWatch(WorldImpl& w, const StepContext& ctx) {
  EnergyWatch& e = w.energy;
  if (e.reported || !e.started) return;
  // The bodies contacts may push: those in a contact now or at the end of an earlier step.
  if (!w.contacts.empty()) {
    e.touched.resize(w.bodies.size(), 0);
    for (const Contact& c : w.contacts) e.touched[c.a] = e.touched[c.b] = 1;
  }
  // One pass: kinetic and gravity's energy, what contacts may give back (energy_watch.h), and the
  // body with the most kinetic energy (the one an incident names).
  const double push = ctx.settings.contact_push_speed;
  double kinetic = 0.0, gravity = 0.0, give_back = 0.0, weight = 0.0, most = -1.0;
  uint32_t named = UINT32_MAX;
  for (uint32_t i = 0; i < w.bodies.size(); ++i) {
    const Body& b = w.bodies[i];
    if (!w.alive[i] || !b.isDynamic()) continue;
    const Vec2 g = b.gravity_scale * b.gravityOr(ctx.settings.gravity);
    const double k = kineticOf(b);
    kinetic += k;
    gravity -= b.mass * g.dot(b.center);
    weight += b.mass * g.squaredNorm();
    const bool pushed = (i < e.touched.size() && e.touched[i]) || (i < w.body_joints.size() && !w.body_joints[i].empty());
    if (pushed) give_back += b.mass * (0.5 * push * push + g.norm() * b.max_extent);
    if (k > most) most = k, named = i;
  }
  const double potential = gravity + (w.forces.empty() ? 0.0 : w.forcePotentialEnergy());
  const double energy = kinetic + potential;
  // What a first-order integrator gains in a step from gravity alone: explicit Euler in free fall
  // gains ½ m (g h)² a step (v grows by g h before x moves), a bounded error, not a blow-up.
  const double first_order = 0.5 * ctx.dt * ctx.dt * weight;
  const double work = workBound(w, e, ctx.dt);
  e.excess += energy - e.energy_start - work;
  e.budget += work + first_order;
  e.energy_end = energy;
  e.potential_least = std::min(e.potential_least, potential);
  if (!std::isfinite(energy)) return;  // the non-finite case is the NaN firewall's and the runner's
  const double allowed = e.budget + (e.potential_first - e.potential_least) + give_back;
  if (!(e.excess > kBlowUpFactor * allowed)) return;
  e.reported = true;
  if (named == UINT32_MAX) return;  // no dynamic body: the energy is all in kinematic motion
  const Body& b = w.bodies[named];
  Incident incident{b.uid, b.name, w.step_count, w.clock.t - ctx.dt, ""};
  incident.frozen = false;
  incident.cause = "the energy grew by " + formatNumber(e.excess) +
                   " J more than forces, motors and kinematic bodies put in, past the bound of " + formatNumber(kBlowUpFactor * allowed) +
                   " J (docs/stability.md, \"Blow-ups caught\"); the energy is now " + formatNumber(energy) +
                   " J, and this body has the most kinetic energy";
  w.incidents.push_back(std::move(incident));
}

}  // namespace rigidlab

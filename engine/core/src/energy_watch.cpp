// The energy balance of every step, and the blow-up incident (energy_watch.h has the bound).
#include "energy_watch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "joint.h"
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
bool jointIsSource(const WorldImpl& w, const Joint& j) {
  const JointDef& d = j.def;
  const auto kinematic = [&](uint32_t slot) { return slot != kWorldSlot && w.bodies[slot].isKinematic(); };
  return d.enable_motor || d.enable_spring || d.type == JointType::Motor ||
         (d.type == JointType::Weld && (d.linear_hertz > 0.0 || d.angular_hertz > 0.0)) || kinematic(j.a) ||
         kinematic(j.b);
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
  for (uint32_t k = 0; k < w.joints.size() && k < e.joint_slide.size(); ++k) {
    const Joint& j = w.joints[k];
    if (!j.alive || !jointIsSource(w, j)) continue;
    Vec2 force;
    double torque;
    jointReaction(j, force, torque);
    const Motion now = jointMotion(w, j);
    work += h * (force.norm() * std::max(now.slide, e.joint_slide[k]) + std::abs(torque) * std::max(now.spin, e.joint_spin[k]));
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

// What contacts may give back pushing overlaps apart: Σ m (½ v_push² + |g| r) (energy_watch.h).
double pushAllowance(const WorldImpl& w) {
  const double push = w.def.contact_push_speed;
  double allowance = 0.0;
  for (uint32_t i = 0; i < w.bodies.size(); ++i) {
    const Body& b = w.bodies[i];
    if (!w.alive[i] || !b.isDynamic()) continue;
    const double g = std::abs(b.gravity_scale) * b.gravityOr(w.def.gravity).norm();
    allowance += b.mass * (0.5 * push * push + g * b.max_extent);
  }
  return allowance;
}

// The body that gained the most kinetic energy in the step: the one the incident names.
uint32_t fastestGainer(const WorldImpl& w, const EnergyWatch& e) {
  uint32_t best = UINT32_MAX;
  double most = -std::numeric_limits<double>::infinity();
  for (uint32_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.alive[i] || !w.bodies[i].isDynamic()) continue;
    const double gain = kineticOf(w.bodies[i]) - (i < e.kinetic.size() ? e.kinetic[i] : 0.0);
    if (gain > most) most = gain, best = i;
  }
  return best;
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
  e.speed.resize(n);
  e.spin.resize(n);
  e.kinetic.resize(n);
  double kinetic = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    const Body& b = w.bodies[i];
    e.speed[i] = b.velocity.norm();
    e.spin[i] = std::abs(b.angular_velocity);
    e.kinetic[i] = w.alive[i] && b.isDynamic() ? kineticOf(b) : 0.0;
    kinetic += e.kinetic[i];
  }
  const double potential = w.potentialEnergy();
  const double energy = kinetic + potential;
  if (!e.started) {
    e.started = true;
    e.budget = kinetic + std::max(0.0, potential - w.gravityPotentialEnergy());  // K₀ + what forces store
    e.potential_first = e.potential_least = potential;
  } else if (energy > e.energy_end) {
    e.budget += energy - e.energy_end;  // an edit between steps put it in
  }
  e.energy_start = energy;
  e.potential_least = std::min(e.potential_least, potential);
  bool forces = false;
  for (const ForceEntry& f : w.forces) forces |= f.alive && f.force->putsEnergyIn();
  if (forces || e.forces_noted) {
    e.push.assign(n, 0.0);
    e.turn.assign(n, 0.0);
  } else {
    e.push.clear();
    e.turn.clear();
  }
  e.forces_noted = false;
  e.joint_slide.assign(w.joints.size(), 0.0);
  e.joint_spin.assign(w.joints.size(), 0.0);
  for (uint32_t k = 0; k < w.joints.size(); ++k) {
    const Joint& j = w.joints[k];
    if (!j.alive || !jointIsSource(w, j)) continue;
    const Motion m = jointMotion(w, j);
    e.joint_slide[k] = m.slide;
    e.joint_spin[k] = m.spin;
  }
}

void endEnergyWatch(WorldImpl& w) {
  EnergyWatch& e = w.energy;
  if (e.reported || !e.started) return;
  const double kinetic = w.kineticEnergy(), potential = w.potentialEnergy();
  const double energy = kinetic + potential;
  const double work = workBound(w, e, w.dt);
  e.excess += energy - e.energy_start - work;
  e.budget += work;
  e.energy_end = energy;
  e.potential_least = std::min(e.potential_least, potential);
  if (!std::isfinite(energy)) return;  // the non-finite case is the NaN firewall's and the runner's
  const double allowed = e.budget + (e.potential_first - e.potential_least) + pushAllowance(w);
  if (!(e.excess > kBlowUpFactor * allowed)) return;
  e.reported = true;
  const uint32_t i = fastestGainer(w, e);
  if (i == UINT32_MAX) return;  // no dynamic body: the energy is all in kinematic motion
  const Body& b = w.bodies[i];
  Incident incident{b.uid, b.name, w.step_count, w.clock.t - w.dt, ""};
  incident.frozen = false;
  incident.cause = "the energy grew by " + formatNumber(e.excess) +
                   " J more than forces, motors and kinematic bodies put in, past the bound of " + formatNumber(kBlowUpFactor * allowed) +
                   " J (docs/stability.md, \"Blow-ups caught\"); the energy is now " + formatNumber(energy) +
                   " J, and this body gained the most kinetic energy in the step";
  w.incidents.push_back(std::move(incident));
}

}  // namespace rigidlab

// Exact mechanisms inside the step (mechanism_step.h): the world's joints handed to the mechanism
// solver (mechanism.h) as islands of plain bodies and coordinates, and its forces, projections and
// multipliers handed back.
//
// Which islands: the awake dynamic bodies linked by joints (all four bodies of a gear) form an
// island; it is integrated exactly when
//   - none of its bodies had a contact point at the start of the step (the narrow phase's contacts
//     of the last step, speculative ones included): an island that touches something keeps the
//     contact solvers, which solve its joints with its contacts, and
//   - every joint of it is one this path models: revolute, prismatic and wheel joints without an
//     enabled limit or motor, welds (rigid or soft), distance joints without a range, pulleys and
//     gears. Limits and motors are inequalities (a limit reached inside a step is an impact) and
//     motor and friction joints are velocity servos; islands with them keep the contact solvers
//     (docs/limitations.md).
// Bodies the joints hold on to that are not in the island (static ones, the world, sleeping and
// kinematic bodies) are fixed bodies of the island: kinematic ones move with their velocity.
//
// The joints' impulses are the multipliers' integral over the step (each stage's λ with its weight
// in the integrator's update), so that a joint's reaction force and break test read the exact
// constraint force, and a joint that goes back to the contact solvers warm-starts from it.
#include "mechanism_step.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "body_acceleration.h"
#include "mechanism.h"
#include "world_impl.h"

namespace rigidlab {

// The stage's own scratch (WorldImpl::mechanisms holds it, opaque to the other stages).
struct MechanismStage {
  // Where a row's multiplier is reported: the joint's slot and its impulse field.
  struct Report {
    uint32_t joint;
    double JointImpulses::*field;
    double scale = 1.0;  // the field's sign against the row's λ (an upper limit's impulse is −λ)
  };
  struct Exact {
    mechanism::Island island;
    mechanism::Solver solver;
    std::vector<uint32_t> slots;   // island body → body slot (kWorldSlot: the world)
    std::vector<uint32_t> joints;  // joint slots
    std::vector<Report> equality_report, motor_report, spring_report;
    std::vector<Eigen::Vector3d> accel, force;
    bool joined = false;  // touches something after the narrow phase: joints go to the contact solvers
    // The fastest rate of its springs: the largest |eigenvalue| of a damped spring's motion relative
    // to its own mass (springRate) [1/s].
    double spring_rate = 0.0;
    // Its length scale: the largest lever arm of its joints and extent of its bodies [m], which a
    // step's drift off the joints is measured against.
    double size = 0.0;
    bool stiff = false;  // kStiffMechanism (mechanism_step.h)
    double stiffness = 0.0;  // the fastest geometric rate of its joints' last forces [1/s]
    double drift = 0.0;  // the largest drift of a step of the current attempt, per size
    bool unprojected = false;  // a projection of the attempt did not reach the joints
  };
  std::vector<Exact> islands;
  size_t count = 0;  // islands this step (islands[0 .. count))
  std::vector<char> moving;         // per body slot: a moving body of an exact island
  std::vector<char> settled;        // per joint slot: solved here, left out of the contact solvers
  std::vector<JointImpulses> kept;  // per joint slot of a joined island: its impulses of the step
  std::vector<uint32_t> parent;     // union–find
  std::vector<char> touching, unsupported;  // per root slot (unsupported's bit 2: grounded)
  std::vector<int32_t> loops;               // per root slot
  std::vector<uint32_t> island_index;  // per root slot: its island, or UINT32_MAX
  std::vector<uint32_t> roots;         // per body slot: its root (UINT32_MAX: not active)
  std::vector<uint32_t> island_of;     // per body slot of a moving body: its island
  std::vector<double> held;            // per body slot: Σ |F| |r| of its joints' last forces
  std::vector<uint8_t> holds;          // per body slot: how many joints hold it (counted to 2)
  double step_start = 0.0;
  double dt = 0.0;
  uint64_t shapes = 0;  // the last mechanism::Island::shape given
  // An attempt at an interval (integrateInterval): what to put back when a step drifts too far.
  struct Saved {
    uint32_t slot;
    Vec2 c, v;
    double angle, w;
  };
  std::vector<Saved> saved_bodies;
  std::vector<JointImpulses> saved_impulses;  // per joint of the islands, in their order
};

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

uint32_t root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// A spring's fastest rate: the largest |eigenvalue| of a damped spring's motion ẍ = −ω² x − 2ζω ẋ,
// λ = ω (−ζ ± √(ζ² − 1)) [1/s]: ω while ζ ≤ 1 (a complex pair of modulus ω), ω (ζ + √(ζ² − 1))
// overdamped. (The bound ω (1 + 2ζ) taken before gave a ragdoll's 5 Hz, ζ = 0.5 springs 62.8/s, two
// sub-steps at 1/60 where their motion turns 0.52 rad a step.)
double springRate(double hertz, double damping_ratio) {
  const double omega = 2.0 * std::numbers::pi * hertz, zeta = std::max(damping_ratio, 0.0);
  return zeta <= 1.0 ? omega : omega * (zeta + std::sqrt(zeta * zeta - 1.0));
}

// The fastest of the joint's springs.
double jointSpringRate(const JointDef& d) {
  double rate = 0.0;
  if (d.enable_spring) rate = springRate(d.spring_hertz, d.spring_damping);
  if (d.type == JointType::Weld)
    rate = std::max(springRate(d.linear_hertz, d.linear_damping), springRate(d.angular_hertz, d.angular_damping));
  return rate;
}

// Joints this path models now (the file comment says why the others are left out). A pulley's
// rope measures a distance, whose direction turns over where the length passes zero: a side that
// could reach zero within the step (twice the step's travel at its rate, or 1 mm) leaves the island
// to the contact solvers, as a distance joint of zero length does (a pin without an angle).
bool modelled(const WorldImpl& w, const Joint& j, double dt) {
  const JointDef& d = j.def;
  // A spring too stiff for the explicit integrator even in kMaxMechanismSteps steps: the contact
  // solvers' soft constraints take it (implicit, stable at any stiffness).
  if (jointSpringRate(d) * dt > kMaxMechanismSteps * kMechanismTurn) return false;
  const auto anchor = [&](uint32_t slot, const Vec2& local, Vec2& velocity) {
    if (slot == kWorldSlot) {
      velocity = Vec2::Zero();
      return local;
    }
    const Body& b = w.bodies[slot];
    const Vec2 p = b.xf.apply(local);
    velocity = b.pointVelocity(p);
    return p;
  };
  const auto clear = [&](const Vec2& p, const Vec2& v, const Vec2& ground) {
    const Vec2 d = p - ground;
    const double length = d.norm(), rate = length > 0.0 ? d.dot(v) / length : 0.0;
    return length > std::max(1e-3, 2.0 * std::abs(rate) * dt);
  };
  switch (d.type) {
    case JointType::Revolute:
    case JointType::Prismatic:
    case JointType::Wheel:
    case JointType::Weld:
    case JointType::Gear: return true;
    case JointType::Pulley: {
      Vec2 va, vb;
      const Vec2 pa = anchor(j.a, j.local_a, va), pb = anchor(j.b, j.local_b, vb);
      return clear(pa, va, d.ground_a) && clear(pb, vb, d.ground_b);
    }
    case JointType::Distance: {
      // Its length measures a distance too: a rigid one of (nearly) zero length is a pin without an
      // angle; a range or a spring is modelled while the anchors stay apart.
      Vec2 va, vb;
      const Vec2 pa = anchor(j.a, j.local_a, va), pb = anchor(j.b, j.local_b, vb);
      const bool range = d.enable_limit && d.min_length < d.max_length;
      return range || d.enable_spring ? clear(pb, vb, pa) : j.length > 1e-3;
    }
    case JointType::Motor:
    case JointType::Friction: return false;
  }
  return false;
}

// A joint's last force |F| at each of its moving bodies' lever arm |r|, summed per body into
// `held` (and the joints counted into `holds`): a body held at two or more points by forces F_i at
// lever arms r_i turns back about its centre like a torsional spring of stiffness Σ |F_i| |r_i|
// (the forces' geometric stiffness), at ω² = I⁻¹ Σ |F_i| |r_i|. A chain link of mass m and length ℓ
// pulled by tension T at both ends turns back at √(12 T / (m ℓ)): the tension of a long chain
// makes it stiff. A body held at one point has no such motion (it swings about that point).
void geometricStiffness(const WorldImpl& w, const Joint& j, std::vector<double>& held, std::vector<uint8_t>& holds) {
  Vec2 force;
  double torque;
  jointReaction(j, force, torque);
  const double f = force.norm();
  const auto side = [&](uint32_t slot, const Vec2& local) {
    if (slot == kWorldSlot || !w.isActive(slot)) return;
    const Body& b = w.bodies[slot];
    held[slot] += f * (b.xf.apply(local) - b.center).norm();
    holds[slot] = static_cast<uint8_t>(std::min(holds[slot] + 1, 2));
  };
  side(j.a, j.local_a);
  side(j.b, j.local_b);
}

// The island index of a body slot, adding it as a fixed body when it is not one of the island's
// own (the moving ones are numbered first).
uint32_t fixedBody(const WorldImpl& w, MechanismStage::Exact& e, uint32_t slot, const std::vector<uint32_t>& local) {
  if (slot != kWorldSlot && local[slot] != UINT32_MAX) return local[slot];
  for (uint32_t k = e.island.moving; k < e.slots.size(); ++k)
    if (e.slots[k] == slot) return k;
  e.slots.push_back(slot);
  mechanism::State s;
  if (slot != kWorldSlot) {
    const Body& b = w.bodies[slot];
    s = {b.center, b.angle, b.isKinematic() ? b.velocity : Vec2::Zero(), b.isKinematic() ? b.angular_velocity : 0.0};
  }
  e.island.states.push_back(s);
  e.island.im.push_back(0.0);
  e.island.ii.push_back(0.0);
  return static_cast<uint32_t>(e.slots.size() - 1);
}

// A body's anchor from its centre of mass, in its frame (the world's frame is the world's).
Vec2 anchorOf(const WorldImpl& w, uint32_t slot, const Vec2& local) {
  return slot == kWorldSlot ? local : Vec2(local - w.bodies[slot].local_center);
}

mechanism::Term term(mechanism::Measure m, uint32_t a, uint32_t b, const Vec2& sa = Vec2::Zero(), const Vec2& sb = Vec2::Zero()) {
  mechanism::Term t;
  t.measure = m;
  t.a = a;
  t.b = b;
  t.sa = sa;
  t.sb = sb;
  return t;
}

mechanism::Coordinate coordinate(const mechanism::Term& t) {
  mechanism::Coordinate c;
  c.term[0] = t;
  return c;
}

// The joint's constraints and springs, added to the island.
void addJoint(const WorldImpl& w, MechanismStage::Exact& e, uint32_t k, const std::vector<uint32_t>& local) {
  using mechanism::Measure;
  const Joint& j = w.joints[k];
  const JointDef& d = j.def;
  const uint32_t a = fixedBody(w, e, j.a, local), b = fixedBody(w, e, j.b, local);
  const Vec2 sa = anchorOf(w, j.a, j.local_a), sb = anchorOf(w, j.b, j.local_b);
  const auto equality = [&](const mechanism::Coordinate& c, double target, double JointImpulses::*field) {
    e.island.equalities.push_back({c, target, 0.0});
    e.equality_report.push_back({k, field});
  };
  // A range lower ≤ x ≤ upper as two one-sided rows (an infinite bound is none).
  const auto limits = [&](const mechanism::Coordinate& c, double lower, double upper) {
    if (std::isfinite(lower)) {
      e.island.equalities.push_back({c, lower, 1.0});
      e.equality_report.push_back({k, &JointImpulses::lower});
    }
    if (std::isfinite(upper)) {
      e.island.equalities.push_back({c, upper, -1.0});
      e.equality_report.push_back({k, &JointImpulses::upper, -1.0});
    }
  };
  const auto motor = [&](const mechanism::Coordinate& c, double speed, double max_force) {
    e.island.motors.push_back({c, speed, max_force});
    e.motor_report.push_back({k, &JointImpulses::motor});
  };
  const auto spring = [&](const mechanism::Coordinate& c, double rest, double hertz, double damping,
                          double JointImpulses::*field) {
    mechanism::Spring s;
    s.coordinate[0] = c;
    s.rest[0] = rest;
    s.hertz = hertz;
    s.damping_ratio = damping;
    e.island.springs.push_back(s);
    e.spring_report.push_back({k, field});
    e.spring_rate = std::max(e.spring_rate, springRate(hertz, damping));
  };
  const auto point = [&](bool soft, double hertz, double damping) {
    const mechanism::Coordinate x = coordinate(term(Measure::PointX, a, b, sa, sb));
    const mechanism::Coordinate y = coordinate(term(Measure::PointY, a, b, sa, sb));
    if (!soft) {
      equality(x, 0.0, &JointImpulses::linear_x);
      equality(y, 0.0, &JointImpulses::linear_y);
      return;
    }
    mechanism::Spring s;  // a soft weld's anchors: one spring of dimension 2
    s.coordinate[0] = x;
    s.coordinate[1] = y;
    s.dimension = 2;
    s.hertz = hertz;
    s.damping_ratio = damping;
    e.island.springs.push_back(s);
    e.spring_report.push_back({k, &JointImpulses::linear_x});
    e.spring_rate = std::max(e.spring_rate, springRate(hertz, damping));
  };
  mechanism::Term angle = term(Measure::Angle, a, b);
  angle.offset = j.reference_angle;
  // Along a direction fixed in a: the axis, or the perpendicular to it.
  const auto along = [&](const Vec2& axis) {
    mechanism::Term t = term(Measure::Axis, a, b, sa, sb);
    t.axis = axis;
    return coordinate(t);
  };
  const bool spring_on = d.enable_spring && d.spring_hertz > 0.0;
  switch (d.type) {
    case JointType::Revolute:
      point(false, 0.0, 0.0);
      if (spring_on) spring(coordinate(angle), 0.0, d.spring_hertz, d.spring_damping, &JointImpulses::spring);
      if (d.enable_limit) limits(coordinate(angle), d.lower, d.upper);
      if (d.enable_motor) motor(coordinate(angle), d.motor_speed, d.max_motor_torque);
      break;
    case JointType::Weld:
      if (d.angular_hertz > 0.0) {
        spring(coordinate(angle), 0.0, d.angular_hertz, d.angular_damping, &JointImpulses::angular);
      } else {
        equality(coordinate(angle), 0.0, &JointImpulses::angular);
      }
      point(d.linear_hertz > 0.0, d.linear_hertz, d.linear_damping);
      break;
    case JointType::Prismatic:
    case JointType::Wheel:
      equality(along(cross(1.0, j.local_axis)), 0.0, &JointImpulses::perpendicular);
      if (d.type == JointType::Prismatic) equality(coordinate(angle), 0.0, &JointImpulses::angular);
      if (spring_on) spring(along(j.local_axis), 0.0, d.spring_hertz, d.spring_damping, &JointImpulses::spring);
      if (d.enable_limit) limits(along(j.local_axis), d.lower, d.upper);
      if (d.enable_motor && d.type == JointType::Prismatic) motor(along(j.local_axis), d.motor_speed, d.max_motor_force);
      if (d.enable_motor && d.type == JointType::Wheel) motor(coordinate(angle), d.motor_speed, d.max_motor_torque);
      break;
    case JointType::Distance: {
      const mechanism::Coordinate c = coordinate(term(Measure::Distance, a, b, sa, sb));
      const bool range = d.enable_limit && d.min_length < d.max_length;
      if (spring_on) {
        spring(c, j.length, d.spring_hertz, d.spring_damping, &JointImpulses::axial);
        e.island.springs.back().max_force = d.max_spring_force;
      } else if (!range) {
        equality(c, d.enable_limit ? d.min_length : j.length, &JointImpulses::axial);
      }
      if (range) limits(c, d.min_length > 0.0 ? d.min_length : -kInfinity, d.max_length);
      break;
    }
    case JointType::Pulley: {
      // length_a + ratio · length_b: each a distance from a ground point (the world's) to an anchor.
      const uint32_t world = fixedBody(w, e, kWorldSlot, local);
      mechanism::Coordinate c;
      c.terms = 2;
      c.term[0] = term(Measure::Distance, world, a, d.ground_a, sa);
      c.term[1] = term(Measure::Distance, world, b, d.ground_b, sb);
      c.term[1].weight = d.ratio;
      equality(c, j.length, &JointImpulses::axial);
      break;
    }
    case JointType::Gear: {
      // coordinate_1 + ratio · coordinate_2 (joint_gear.cpp): side s turns or slides body a (b)
      // against its ground c (d).
      mechanism::Coordinate c;
      c.terms = 2;
      for (int s = 0; s < 2; ++s) {
        const Joint::GearSide& side = j.gear[s];
        const uint32_t x_slot = s == 0 ? j.a : j.b, g_slot = s == 0 ? j.c : j.d;
        const uint32_t x = s == 0 ? a : b, g = fixedBody(w, e, g_slot, local);
        mechanism::Term& t = c.term[s];
        if (side.revolute) {
          t = term(Measure::Angle, g, x);
          t.offset = side.reference;
        } else {
          t = term(Measure::Axis, g, x, anchorOf(w, g_slot, side.local_ground), anchorOf(w, x_slot, side.local_body));
          t.axis = side.local_axis;
        }
        t.weight = s == 0 ? 1.0 : d.ratio;
      }
      equality(c, j.gear_constant, &JointImpulses::axial);
      break;
    }
    case JointType::Motor:
    case JointType::Friction: break;  // not modelled (chooseMechanisms leaves their islands out)
  }
}

// The state of a fixed body at time t (kinematic bodies move at their velocity from the step's
// start; the others stay).
void placeFixed(const WorldImpl& w, MechanismStage::Exact& e, const MechanismStage& m, double t) {
  for (uint32_t k = e.island.moving; k < e.slots.size(); ++k) {
    const uint32_t slot = e.slots[k];
    if (slot == kWorldSlot || !w.bodies[slot].isKinematic()) continue;
    const Body& b = w.bodies[slot];
    const double tau = t - m.step_start;
    e.island.states[k].c = b.center + tau * b.velocity;
    e.island.states[k].angle = b.angle + tau * b.angular_velocity;
  }
}

// The world directions jointReaction reads for a joint the contact solvers did not prepare: the
// axis of a prismatic or wheel joint, a distance joint's direction, b's rope of a pulley.
void reactionFrame(const WorldImpl& w, Joint& j) {
  const auto pose = [&](uint32_t slot) { return slot == kWorldSlot ? Transform{} : w.bodies[slot].xf; };
  const Transform xa = pose(j.a), xb = pose(j.b);
  const Vec2 pa = xa.apply(j.local_a), pb = xb.apply(j.local_b);
  switch (j.def.type) {
    case JointType::Prismatic:
    case JointType::Wheel: j.axis = xa.q.apply(j.local_axis); break;
    case JointType::Distance: {
      const Vec2 d = pb - pa;
      j.axis = d.norm() > 1e-12 ? Vec2(d / d.norm()) : Vec2(1.0, 0.0);
      break;
    }
    case JointType::Pulley: {
      const Vec2 db = pb - j.def.ground_b;
      j.axis = db.norm() > 1e-9 ? Vec2(db.normalized()) : Vec2::Zero();
      break;
    }
    default: break;
  }
}

// Adds value(row) × scale to the joints' impulse fields the island's rows report into (its
// equalities and limits, then its motors).
template <typename Value>
void report(WorldImpl& w, const MechanismStage::Exact& e, double scale, Value value) {
  const size_t m = e.equality_report.size();
  for (size_t r = 0; r < m; ++r) {
    const MechanismStage::Report& to = e.equality_report[r];
    w.joints[to.joint].impulses.*to.field += to.scale * scale * value(r);
  }
  for (size_t q = 0; q < e.motor_report.size(); ++q) {
    const MechanismStage::Report& to = e.motor_report[q];
    w.joints[to.joint].impulses.*to.field += to.scale * scale * value(m + q);
  }
}

// The island's bodies as they are now (fixed ones at time t).
void gather(const WorldImpl& w, MechanismStage::Exact& e, const MechanismStage& m, double t, double& scale,
            double& speed) {
  scale = speed = 1.0;
  for (uint32_t k = 0; k < e.island.moving; ++k) {
    const Body& b = w.bodies[e.slots[k]];
    e.island.states[k] = {b.center, b.angle, b.velocity, b.angular_velocity};
    scale = std::max(scale, b.center.cwiseAbs().maxCoeff());
    speed = std::max({speed, b.velocity.cwiseAbs().maxCoeff(), std::abs(b.angular_velocity)});
  }
  placeFixed(w, e, m, t);
}

// Projects the island's bodies onto its joints at time t (mechanism.h) and adds the impulses that
// made their velocities tangent to the joints' impulses of the step.
void project(WorldImpl& w, MechanismStage& m, MechanismStage::Exact& e, double t) {
  double scale, speed;
  gather(w, e, m, t, scale, speed);
  // Newton stops at a few units in the last place of the island's coordinates, or where round-off
  // stops the error from falling.
  const double tolerance = 0x1p-50 * scale;
  const mechanism::Projection p = e.solver.project(e.island, tolerance);
  e.drift = std::max(e.drift, p.drift / e.size);
  e.unprojected |= !(p.residual <= std::max(kProjected * e.size, kRoundOff * tolerance)) ||
                   (p.closed && p.drift > kMaxClosedDrift * e.size);
  w.stats.mechanism_newton += p.iterations;
  w.stats.mechanism_residual = std::max(w.stats.mechanism_residual, p.residual);
  for (uint32_t k = 0; k < e.island.moving; ++k) {
    Body& b = w.bodies[e.slots[k]];
    const mechanism::State& s = e.island.states[k];
    b.center = s.c;
    b.angle = s.angle;
    b.velocity = s.v;
    b.angular_velocity = s.w;
  }
  report(w, e, 1.0, [&](size_t r) { return e.solver.impulse(r); });
}

}  // namespace

void chooseMechanisms(WorldImpl& w, const StepContext& ctx) {
  MechanismStage& m = w.mechanisms.get();
  for (size_t q = 0; q < m.count; ++q)
    for (uint32_t k = 0; k < m.islands[q].island.moving; ++k) m.moving[m.islands[q].slots[k]] = 0;
  m.count = 0;
  m.step_start = w.clock.t;
  m.dt = ctx.dt;
  m.settled.assign(w.joints.size(), 0);
  if (!ctx.settings.exact_joints) return;
  bool any = false;
  for (const Joint& j : w.joints) any |= j.alive;
  if (!any) return;
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  m.moving.resize(n, 0);
  auto& parent = m.parent;
  parent.resize(n);
  for (uint32_t i = 0; i < n; ++i) parent[i] = i;
  const auto active = [&](uint32_t slot) { return slot != kWorldSlot && w.isActive(slot); };
  for (const Joint& j : w.joints) {
    if (!j.alive) continue;
    uint32_t first = kWorldSlot;
    for (uint32_t s : {j.a, j.b, j.c, j.d}) {
      if (!active(s)) continue;
      if (first == kWorldSlot) {
        first = s;
        continue;
      }
      const uint32_t ra = root(parent, first), rb = root(parent, s);
      parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  // Islands left out: a member that touched something, or a joint this path does not model.
  m.touching.assign(n, 0);
  for (const Contact& c : w.contacts) {
    if (c.count == 0) continue;
    if (active(c.a)) m.touching[root(parent, c.a)] = 1;
    if (active(c.b)) m.touching[root(parent, c.b)] = 1;
  }
  // And an island with more than kMaxMechanismLoops closed loops: the loops of its graph (bodies,
  // one ground for every body that is not its own, joints as edges), E − V + 1.
  m.unsupported.assign(n, 0);
  m.loops.assign(n, 1);
  for (uint32_t i = 0; i < n; ++i)
    if (active(i)) --m.loops[root(parent, i)];
  for (const Joint& j : w.joints) {
    if (!j.alive) continue;
    uint32_t first = kWorldSlot;
    bool grounded = false;
    for (uint32_t s : {j.a, j.b}) grounded |= !active(s);
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (active(s) && first == kWorldSlot) first = s;
    if (first == kWorldSlot) continue;
    const uint32_t r = root(parent, first);
    if (!modelled(w, j, ctx.dt)) m.unsupported[r] |= 1;
    ++m.loops[r];
    if (grounded && !(m.unsupported[r] & 2)) {  // the ground joins the island once
      --m.loops[r];
      m.unsupported[r] |= 2;
    }
  }
  bool some = false;
  for (uint32_t i = 0; i < n; ++i) {
    if (!active(i) || root(parent, i) != i) continue;
    m.unsupported[i] = (m.unsupported[i] & 1) || m.loops[i] > kMaxMechanismLoops;
    some |= !m.unsupported[i] && !m.touching[i];
  }
  if (!some) return;
  // Number the islands by root slot, their moving bodies by slot.
  m.island_index.assign(n, UINT32_MAX);
  auto& roots = m.roots;
  roots.resize(n);
  for (uint32_t i = 0; i < n; ++i) roots[i] = active(i) ? root(parent, i) : UINT32_MAX;
  std::vector<uint32_t>& local = m.parent;  // reused: the roots are known
  m.island_of.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t r = roots[i];
    if (r == UINT32_MAX || m.touching[r] || m.unsupported[r]) continue;
    if (m.island_index[r] == UINT32_MAX) {
      m.island_index[r] = static_cast<uint32_t>(m.count++);
      if (m.islands.size() < m.count) m.islands.emplace_back();
      MechanismStage::Exact& e = m.islands[m.count - 1];
      e.slots.clear();
      e.joints.clear();
      e.island.states.clear();
      e.island.im.clear();
      e.island.ii.clear();
      e.island.equalities.clear();
      e.island.motors.clear();
      e.island.springs.clear();
      e.island.moving = 0;
      e.island.shape = ++m.shapes;
      e.equality_report.clear();
      e.motor_report.clear();
      e.spring_report.clear();
      e.joined = false;
      e.spring_rate = 0.0;
      e.size = 1e-3;
      e.stiff = false;
      e.stiffness = 0.0;
    }
    MechanismStage::Exact& e = m.islands[m.island_index[r]];
    const Body& b = w.bodies[i];
    e.slots.push_back(i);
    e.size = std::max(e.size, b.max_extent);
    e.island.states.push_back({b.center, b.angle, b.velocity, b.angular_velocity});
    e.island.im.push_back(b.inv_mass);
    e.island.ii.push_back(b.inv_inertia);
    ++e.island.moving;
    m.moving[i] = kStagedMechanism;
    m.island_of[i] = m.island_index[r];
  }
  // Each body's index in its island.
  local.assign(n, UINT32_MAX);
  m.held.assign(n, 0.0);
  m.holds.assign(n, 0);
  for (size_t q = 0; q < m.count; ++q)
    for (uint32_t k = 0; k < m.islands[q].island.moving; ++k) local[m.islands[q].slots[k]] = k;
  for (uint32_t k = 0; k < w.joints.size(); ++k) {
    const Joint& j = w.joints[k];
    if (!j.alive) continue;
    uint32_t first = kWorldSlot;
    for (uint32_t s : {j.a, j.b, j.c, j.d})
      if (active(s) && first == kWorldSlot) first = s;
    if (first == kWorldSlot || !m.moving[first]) continue;
    MechanismStage::Exact& e = m.islands[m.island_index[roots[first]]];
    e.joints.push_back(k);
    addJoint(w, e, k, local);
    geometricStiffness(w, w.joints[k], m.held, m.holds);
    w.joints[k].impulses = {};
  }
  for (size_t q = 0; q < m.count; ++q) {
    MechanismStage::Exact& e = m.islands[q];
    e.accel.resize(e.island.moving);
    e.force.resize(e.island.moving);
    for (const mechanism::Equality& eq : e.island.equalities)
      for (int t = 0; t < eq.coordinate.terms; ++t)
        e.size = std::max({e.size, eq.coordinate.term[t].sa.norm(), eq.coordinate.term[t].sb.norm()});
    for (uint32_t k = 0; k < e.island.moving; ++k) {
      const uint32_t slot = e.slots[k];
      if (m.holds[slot] >= 2) e.stiffness = std::max(e.stiffness, std::sqrt(m.held[slot] * w.bodies[slot].inv_inertia));
    }
    if (e.stiffness * ctx.dt > kStiffTurns) {
      e.stiff = true;
      for (uint32_t k = 0; k < e.island.moving; ++k) m.moving[e.slots[k]] = kStiffMechanism;
    }
    // An island off its joints at the start of the step (an impulse applied, a velocity or a
    // position set, a joint just made) is projected onto them first: the joints' impulsive answer
    // to the edit, in the mass metric, as rigid joints answer a blow. An island on its joints (any
    // that the last step projected) is left as it is.
    double scale, speed;
    gather(w, e, m, m.step_start, scale, speed);
    // A limit is at its bound, a motor at its speed, within a few units in the last place that
    // the projections leave.
    e.island.tolerance = 1e-9 * scale;
    e.island.speed_tolerance = 1e-9 * speed;
    const mechanism::Residuals off = e.solver.residuals(e.island);
    if (off.position > 0x1p-40 * scale || off.velocity > 0x1p-40 * speed) {
      project(w, m, e, m.step_start);
      for (uint32_t k = 0; k < e.island.moving; ++k) WorldImpl::syncTransform(w.bodies[e.slots[k]]);
    }
  }
}

int mechanismSteps(const WorldImpl& w, double h) {
  const MechanismStage* m = w.mechanisms.find();
  if (!m || m->count == 0) return 1;
  double rate = 0.0;
  for (size_t q = 0; q < m->count; ++q) {
    const MechanismStage::Exact& e = m->islands[q];
    // A stiff island's springs and tension: stable at any step.
    if (!e.stiff) rate = std::max({rate, e.spring_rate, e.stiffness});
    for (uint32_t k = 0; k < e.island.moving; ++k) rate = std::max(rate, std::abs(w.bodies[e.slots[k]].angular_velocity));
  }
  const double steps = std::ceil(h * rate / kMechanismTurn);
  return steps <= 1.0 ? 1 : static_cast<int>(std::min(steps, double{kMaxMechanismSteps}));
}

void beginMechanismAttempt(WorldImpl& w) {
  MechanismStage& m = w.mechanisms.get();
  for (size_t q = 0; q < m.count; ++q) {
    m.islands[q].drift = 0.0;
    m.islands[q].unprojected = false;
  }
  w.stats.mechanism_newton = 0;
  w.stats.mechanism_residual = 0.0;
  m.saved_bodies.clear();
  for (uint32_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.isActive(i)) continue;
    const Body& b = w.bodies[i];
    m.saved_bodies.push_back({i, b.center, b.velocity, b.angle, b.angular_velocity});
  }
  m.saved_impulses.clear();
  for (size_t q = 0; q < m.count; ++q)
    for (uint32_t k : m.islands[q].joints) m.saved_impulses.push_back(w.joints[k].impulses);
}

bool mechanismAttemptFailed(const WorldImpl& w) {
  const MechanismStage* m = w.mechanisms.find();
  if (!m) return false;
  for (size_t q = 0; q < m->count; ++q) {
    const MechanismStage::Exact& e = m->islands[q];
    if (e.unprojected || (!e.stiff && e.drift > kMaxMechanismDrift)) return true;
  }
  return false;
}

bool stiffenDriftingMechanisms(WorldImpl& w) {
  MechanismStage& m = w.mechanisms.get();
  bool changed = false;
  for (size_t q = 0; q < m.count; ++q) {
    MechanismStage::Exact& e = m.islands[q];
    if (e.stiff || !(e.unprojected || e.drift > kMaxMechanismDrift)) continue;
    e.stiff = true;
    changed = true;
    for (uint32_t k = 0; k < e.island.moving; ++k) m.moving[e.slots[k]] = kStiffMechanism;
  }
  return changed;
}

void restoreMechanismAttempt(WorldImpl& w) {
  MechanismStage& m = w.mechanisms.get();
  for (const MechanismStage::Saved& s : m.saved_bodies) {
    Body& b = w.bodies[s.slot];
    b.center = s.c;
    b.angle = s.angle;
    b.velocity = s.v;
    b.angular_velocity = s.w;
    WorldImpl::syncTransform(b);
  }
  size_t at = 0;
  for (size_t q = 0; q < m.count; ++q)
    for (uint32_t k : m.islands[q].joints) w.joints[k].impulses = m.saved_impulses[at++];
  ++w.stats.mechanism_retries;
}

const char* mechanismBodies(const WorldImpl& w) {
  const MechanismStage* m = w.mechanisms.find();
  return m && m->count > 0 ? m->moving.data() : nullptr;
}

void addMechanismForces(WorldImpl& w, double t, double weight, double h, bool staged_damping) {
  MechanismStage& m = w.mechanisms.get();
  for (size_t q = 0; q < m.count; ++q) {
    MechanismStage::Exact& e = m.islands[q];
    if (e.stiff) continue;
    for (uint32_t k = 0; k < e.island.moving; ++k) {
      const uint32_t slot = e.slots[k];
      const BodyState& st = w.states[slot];
      e.island.states[k] = {st.center, st.angle, st.velocity, st.angular_velocity};
      const Body& b = w.bodies[slot];
      const Accel acc = staged_damping && dampingInStages(b, h)
                            ? dampedAcceleration(b, w.def.gravity, w.wrenches[slot], st.velocity, st.angular_velocity)
                            : bodyAcceleration(b, w.def.gravity, w.wrenches[slot]);
      e.accel[k] = Eigen::Vector3d(acc.a.x(), acc.a.y(), acc.alpha);
    }
    placeFixed(w, e, m, t);
    e.solver.forces(e.island, e.accel.data(), e.force.data());
    for (uint32_t k = 0; k < e.island.moving; ++k) {
      Wrench& wr = w.wrenches[e.slots[k]];
      wr.force += Vec2(e.force[k].x(), e.force[k].y());
      wr.torque += e.force[k].z();
    }
    // The joints' impulses: ∫ λ dt over the step, as the integrator weighs its stages.
    const double share = weight * h;
    report(w, e, share, [&](size_t r) { return e.solver.multiplier(r); });
    for (size_t r = 0; r < e.spring_report.size(); ++r)
      w.joints[e.spring_report[r].joint].impulses.*e.spring_report[r].field += share * e.solver.springForce(r);
  }
}

void beginMechanismStep(WorldImpl& w, double t0, double h) {
  MechanismStage& m = w.mechanisms.get();
  for (size_t q = 0; q < m.count; ++q) {
    MechanismStage::Exact& e = m.islands[q];
    if (e.island.motors.empty()) continue;
    double scale, speed;
    gather(w, e, m, t0, scale, speed);
    e.solver.beginStep(e.island, h);
    for (uint32_t k = 0; k < e.island.moving; ++k) {
      Body& b = w.bodies[e.slots[k]];
      b.velocity = e.island.states[k].v;
      b.angular_velocity = e.island.states[k].w;
    }
    report(w, e, 1.0, [&](size_t r) { return e.solver.impulse(r); });
  }
}

void stepStiffMechanisms(WorldImpl& w, double t0, double h) {
  MechanismStage& m = w.mechanisms.get();
  for (size_t q = 0; q < m.count; ++q) {
    MechanismStage::Exact& e = m.islands[q];
    if (!e.stiff) continue;
    // v ← v + h a (the forces at the step's start, w.wrenches; damping implicit), then v onto the
    // joints where the bodies are (the joints' impulse over the step), then c ← c + h v.
    for (uint32_t k = 0; k < e.island.moving; ++k) {
      Body& b = w.bodies[e.slots[k]];
      const Accel acc = bodyAcceleration(b, w.def.gravity, w.wrenches[e.slots[k]]);
      if (b.linear_damping > 0.0) b.velocity *= 1.0 / (1.0 + h * b.linear_damping);
      if (b.angular_damping > 0.0) b.angular_velocity *= 1.0 / (1.0 + h * b.angular_damping);
      b.velocity += h * acc.a;
      b.angular_velocity += h * acc.alpha;
    }
    double scale, speed;
    gather(w, e, m, t0, scale, speed);
    e.solver.projectVelocities(e.island);
    report(w, e, 1.0, [&](size_t r) { return e.solver.impulse(r); });
    for (uint32_t k = 0; k < e.island.moving; ++k) {
      Body& b = w.bodies[e.slots[k]];
      b.velocity = e.island.states[k].v;
      b.angular_velocity = e.island.states[k].w;
      b.center += h * b.velocity;
      b.angle += h * b.angular_velocity;
    }
  }
}

void projectMechanisms(WorldImpl& w, double t_end) {
  MechanismStage& m = w.mechanisms.get();
  for (size_t q = 0; q < m.count; ++q) project(w, m, m.islands[q], t_end);
}

void settleMechanisms(WorldImpl& w, const StepContext& ctx) {
  MechanismStage* m = w.mechanisms.find();
  if (!m || m->count == 0) return;
  // Islands that touch something now (a contact the narrow phase found, not disabled by pre-solve;
  // a body continuous collision stopped) have their joints solved with their contacts this step,
  // from the velocities the exact path gave (which hold the joints' forces already: no warm start).
  for (size_t k = 0; k < w.contact_keys.size(); ++k) {
    const ContactKey& c = w.contact_keys[k];
    if (c.disabled || w.contacts[k].count == 0) continue;
    for (uint32_t s : {c.a, c.b})
      if (s < m->moving.size() && m->moving[s]) m->islands[m->island_of[s]].joined = true;
  }
  for (size_t i = 0; i < w.ccd_hit.size() && i < m->moving.size(); ++i)
    if (w.ccd_hit[i] && m->moving[i]) m->islands[m->island_of[i]].joined = true;
  m->settled.resize(w.joints.size(), 0);
  m->kept.resize(w.joints.size());
  for (size_t q = 0; q < m->count; ++q) {
    MechanismStage::Exact& e = m->islands[q];
    for (uint32_t k : e.joints) {
      Joint& j = w.joints[k];
      if (e.joined) {
        m->kept[k] = j.impulses;
        j.impulses = {};
        continue;
      }
      m->settled[k] = 1;
      j.impulse_h = ctx.dt;
      reactionFrame(w, j);
    }
  }
}

bool mechanismSettled(const WorldImpl& w, uint32_t joint) {
  const MechanismStage* m = w.mechanisms.find();
  return m && joint < m->settled.size() && m->settled[joint];
}

int exactJointCount(const WorldImpl& w) {
  const MechanismStage* m = w.mechanisms.find();
  if (!m) return 0;
  int count = 0;
  for (char c : m->settled) count += c;
  return count;
}

void finishMechanisms(WorldImpl& w, const StepContext& ctx) {
  MechanismStage* m = w.mechanisms.find();
  if (!m) return;
  // A joined island's joints: the contact solver's impulses (over its impulse_h) plus the exact
  // path's, scaled to the same time.
  for (size_t q = 0; q < m->count; ++q) {
    const MechanismStage::Exact& e = m->islands[q];
    if (!e.joined) continue;
    for (uint32_t k : e.joints) {
      Joint& j = w.joints[k];
      if (!j.alive) continue;
      const double s = j.impulse_h > 0.0 ? j.impulse_h / ctx.dt : 1.0;
      const JointImpulses& x = m->kept[k];
      JointImpulses& p = j.impulses;
      p.linear_x += s * x.linear_x;
      p.linear_y += s * x.linear_y;
      p.angular += s * x.angular;
      p.perpendicular += s * x.perpendicular;
      p.axial += s * x.axial;
      p.spring += s * x.spring;
      p.motor += s * x.motor;
      p.lower += s * x.lower;
      p.upper += s * x.upper;
      if (j.impulse_h <= 0.0) j.impulse_h = ctx.dt;
    }
  }
}

}  // namespace rigidlab

// The snapshot file format (world_snapshot.h). Binary, little-endian, versioned:
//
//   "RIGIDLAB-SNAPSHOT\n"  magic (18 bytes)
//   u32 version            kVersion (5); versions 1 to 4 are read too
//   u64 payload length
//   payload                the label; since version 2 the application data (u64 length, bytes);
//                          then the state, field by field (io() below)
//   u64 checksum           FNV-1a of the payload
//
// Doubles are written as their raw 64 bits, so a restored state is the same bits. One io()
// function per struct lists its fields once, for writing and for reading, so the two cannot drift.
// Reading checks everything a later step would index with (slots, counts, sizes of per-slot
// vectors) and throws SnapshotError naming the field: a corrupt or hostile file is an error,
// never undefined behaviour. Written is what a step, an edit or a query reads from the state kept
// between steps (docs/testing.md "Snapshots"); the step's scratch (solver copies, per-step buffers) is not:
// steps size and fill it themselves.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "rigidlab/error.h"
#include "snapshot_state.h"
#include "world_impl.h"

namespace rigidlab {

namespace {

constexpr char kMagic[] = "RIGIDLAB-SNAPSHOT\n";
constexpr size_t kMagicBytes = sizeof kMagic - 1;
// Version 1: version 2 without the application data. Version 2: version 3 with five more numbers
// per contact point, which only sequential impulses' prepare writes and the step reads no more
// (io(ContactPoint) below). Version 4 adds what version 3 lacks, each at the end of its record:
// a body's own gravity, sleeping_allowed and set inertia; a shape's tangent speed and rolling
// resistance; a joint's local anchors; a constant force's torque; contact events' per-point
// values; the collision filter's decisions. A version 3 file reads with their defaults.
// Version 5 adds WorldDef::exact_joints, which a file of version 4 or older reads as off: its
// writer solved every joint in the contact solvers, and the file resumes in its writer's bits.
constexpr uint32_t kVersion = 5;
constexpr uint32_t kOldestVersion = 1;

uint64_t fnv1a(std::string_view bytes) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

enum ForceTag : uint8_t { kNoForce, kSpring, kDamper, kMouse, kConstant, kOpaque, kForceTags };

class Writer {
 public:
  static constexpr bool kReading = false;
  static constexpr uint32_t version = kVersion;  // what is written
  std::string out;

  void raw(uint64_t v, int bytes) {
    char b[8];
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(b, &v, 8);  // the low bytes first, as the format says
    } else {
      for (int i = 0; i < 8; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xff);
    }
    out.append(b, static_cast<size_t>(bytes));
  }
  void operator()(const bool& v, const char* = "") { raw(v ? 1 : 0, 1); }
  void operator()(const char& v, const char* = "") { raw(static_cast<uint8_t>(v), 1); }
  void operator()(const uint8_t& v, const char* = "") { raw(v, 1); }
  void operator()(const uint32_t& v, const char* = "") { raw(v, 4); }
  void operator()(const int32_t& v, const char* = "") { raw(static_cast<uint32_t>(v), 4); }
  void operator()(const uint64_t& v, const char* = "") { raw(v, 8); }
  void operator()(const int64_t& v, const char* = "") { raw(static_cast<uint64_t>(v), 8); }
  void operator()(const double& v, const char* = "") { raw(std::bit_cast<uint64_t>(v), 8); }
  template <typename E>
    requires std::is_enum_v<E>
  void enumeration(const E& e, int /*count*/, const char* = "") {
    raw(static_cast<uint8_t>(e), 1);
  }
  void operator()(const std::string& s, const char* = "") {
    raw(s.size(), 8);
    out.append(s);
  }
  // A count of elements to follow.
  void count(const size_t& n, const char* = "") { raw(n, 8); }
};

class Reader {
 public:
  static constexpr bool kReading = true;
  Reader(std::string_view in, size_t base, uint32_t version = kVersion) : version(version), in_(in), base_(base) {}
  const uint32_t version;  // the file's

  [[noreturn]] void fail(const std::string& what) const {
    throw SnapshotError("snapshot: " + what + " (at byte " + std::to_string(base_ + pos_) + ")");
  }
  uint64_t raw(int bytes, const char* field) {
    if (in_.size() - pos_ < static_cast<size_t>(bytes)) fail(std::string("truncated, reading ") + field);
    uint64_t v = 0;
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(&v, in_.data() + pos_, static_cast<size_t>(bytes));
    } else {
      for (int i = 0; i < bytes; ++i) v |= uint64_t{static_cast<unsigned char>(in_[pos_ + i])} << (8 * i);
    }
    pos_ += bytes;
    return v;
  }
  void operator()(bool& v, const char* field = "a flag") {
    const uint64_t x = raw(1, field);
    if (x > 1) fail(std::string(field) + " is " + std::to_string(x) + ", not 0 or 1");
    v = x == 1;
  }
  void operator()(char& v, const char* field = "a byte") { v = static_cast<char>(raw(1, field)); }
  void operator()(uint8_t& v, const char* field = "a byte") { v = static_cast<uint8_t>(raw(1, field)); }
  void operator()(uint32_t& v, const char* field = "an integer") { v = static_cast<uint32_t>(raw(4, field)); }
  void operator()(int32_t& v, const char* field = "an integer") { v = static_cast<int32_t>(static_cast<uint32_t>(raw(4, field))); }
  void operator()(uint64_t& v, const char* field = "an integer") { v = raw(8, field); }
  void operator()(int64_t& v, const char* field = "an integer") { v = static_cast<int64_t>(raw(8, field)); }
  void operator()(double& v, const char* field = "a number") { v = std::bit_cast<double>(raw(8, field)); }
  template <typename E>
    requires std::is_enum_v<E>
  void enumeration(E& e, int count, const char* field = "a kind") {
    const uint64_t x = raw(1, field);
    if (x >= static_cast<uint64_t>(count))
      fail(std::string(field) + " is " + std::to_string(x) + ", not one of the " + std::to_string(count) + " kinds");
    e = static_cast<E>(x);
  }
  void operator()(std::string& s, const char* field = "a name") {
    size_t n;
    count(n, field);
    s.assign(in_.substr(pos_, n));
    pos_ += n;
  }
  // A count of elements that follow: each takes at least a byte, so a count beyond what is left
  // is corruption (and never a huge allocation).
  void count(size_t& n, const char* field = "a count") {
    n = raw(8, field);
    if (n > in_.size() - pos_) fail(std::string(field) + ": " + std::to_string(n) + " items cannot fit in what is left");
  }
  bool atEnd() const { return pos_ == in_.size(); }

 private:
  std::string_view in_;
  size_t base_;
  size_t pos_ = 0;
};

// --- fields, once for both directions. `a` is a Writer (the values are only read) or a Reader.

template <typename A, typename T>
void io(A& a, T& v)
  requires std::is_arithmetic_v<T>
{
  a(v);
}
template <typename A>
void io(A& a, std::string& s) {
  a(s);
}
template <typename A>
void io(A& a, Vec2& v) {
  a(v.x());
  a(v.y());
}
template <typename A>
void io(A& a, Vec2u& v) {
  a(v.x());
  a(v.y());
}
template <typename A, typename T>
void io(A& a, std::vector<T>& v) {
  size_t n = v.size();
  a.count(n, "a list's length");
  if constexpr (A::kReading) {
    // Grown as the elements are read, not resized to the count first: a count that lies (each
    // element is larger in memory than its smallest encoding) costs only what the file holds.
    v.clear();
    v.reserve(std::min(n, size_t{1024}));
    for (size_t i = 0; i < n; ++i) io(a, v.emplace_back());
    v.shrink_to_fit();
  } else {
    for (T& x : v) io(a, x);
  }
}
template <typename A, typename T>
void io(A& a, std::optional<T>& o) {
  bool has = o.has_value();
  a(has, "an optional's flag");
  if constexpr (A::kReading) {
    if (has) o.emplace();
    else o.reset();
  }
  if (o) io(a, *o);
}
template <typename A>
void io(A& a, BodyId& id) {
  a(id.index);
  a(id.generation);
}
template <typename A>
void io(A& a, ShapeId& id) {
  a(id.index);
  a(id.generation);
}
template <typename A>
void io(A& a, JointId& id) {
  a(id.index);
  a(id.generation);
}
template <typename A>
void io(A& a, Rot& q) {
  a(q.c);
  a(q.s);
}
template <typename A>
void io(A& a, Transform& xf) {
  io(a, xf.p);
  io(a, xf.q);
}
template <typename A>
void io(A& a, Aabb& b) {
  io(a, b.lower);
  io(a, b.upper);
}
template <typename A>
void io(A& a, Material& m) {
  a(m.restitution);
  a(m.friction);
  a(m.static_friction);
}
template <typename A>
void io(A& a, Filter& f) {
  a(f.category);
  a(f.mask);
  a(f.group);
}
template <typename A>
void io(A& a, Shape& s) {
  a.enumeration(s.type, kShapeTypes, "shape type");
  a(s.radius);
  a(s.extent);
  a(s.inradius);
  io(a, s.center);
  io(a, s.vertices);
  io(a, s.normals);
  io(a, s.ghost1);
  io(a, s.ghost2);
}

template <typename A>
void io(A& a, WorldDef& d) {
  io(a, d.gravity);
  a.enumeration(d.integrator, 4, "integrator");
  a.enumeration(d.contact_solver, 3, "contact_solver");
  a(d.soft_step_points);
  a(d.substeps);
  a(d.contact_hertz);
  a(d.contact_damping_ratio);
  a(d.contact_push_speed);
  a(d.iterations);
  a(d.warm_starting);
  a.enumeration(d.position_correction, 2, "position_correction");
  a(d.position_iterations);
  a(d.allowed_penetration);
  a(d.position_correction_rate);
  a(d.contact_displacement);
  a.enumeration(d.broad_phase, 2, "broad_phase");
  a(d.pair_cap);
  a(d.pair_cap_per_body);
  a(d.pair_cap_max);
  a.enumeration(d.impacts, 2, "impacts");
  a(d.impact_island_bodies);
  a(d.impact_max_bodies);
  a(d.continuous);
  a(d.sleeping);
  a(d.sleep_linear_speed);
  a(d.sleep_angular_speed);
  a(d.time_to_sleep);
  a(d.contact_margin);
  a(d.restitution_threshold);
  a(d.joint_hertz);
  a(d.joint_damping_ratio);
  a(d.static_friction_speed);
  bool before_version_5 = false;
  if constexpr (A::kReading) before_version_5 = a.version < 5;
  if (before_version_5) {
    d.exact_joints = false;
  } else {
    a(d.exact_joints);
  }
}

template <typename A>
void io(A& a, Body& b) {
  io(a, b.id);
  a(b.uid);
  a.enumeration(b.type, 3, "body type");
  a(b.enabled);
  a(b.awake);
  a(b.frozen);
  a(b.fixed_rotation);
  a(b.bullet);
  io(a, b.xf);
  io(a, b.center);
  a(b.angle);
  io(a, b.velocity);
  a(b.angular_velocity);
  a(b.inv_mass);
  a(b.inv_inertia);
  a(b.mass);
  a(b.inertia);
  io(a, b.local_center);
  a(b.density);
  a(b.area);
  a(b.min_inradius);
  a(b.max_extent);
  a(b.linear_damping);
  a(b.angular_damping);
  a(b.gravity_scale);
  a(b.sleep_time);
  io(a, b.shapes);
  a(b.name);
  if (a.version >= 4) {
    a(b.own_gravity);
    io(a, b.gravity);
    a(b.sleeping_allowed);
    a(b.inertia_set);
  }
}

template <typename A>
void io(A& a, BodyShape& s) {
  io(a, s.body);
  a(s.sensor);
  a(s.default_filter);
  a(s.contact_events);
  a(s.hit_events);
  a(s.pre_solve);
  a(s.hit_speed);
  io(a, s.one_way);
  a(s.chain);
  io(a, s.id);
  io(a, s.material);
  io(a, s.filter);
  a(s.density);
  io(a, s.geometry);
  if (a.version >= 4) {
    a(s.tangent_speed);
    a(s.rolling_resistance);
  }
}

template <typename A>
void io(A& a, JointDef& d) {
  a.enumeration(d.type, kJointTypes, "joint type");
  io(a, d.a);
  io(a, d.b);
  io(a, d.anchor_a);
  io(a, d.anchor_b);
  io(a, d.axis);
  a(d.collide_connected);
  a(d.break_force);
  a(d.break_torque);
  a(d.name);
  io(a, d.reference_angle);
  a(d.enable_limit);
  a(d.lower);
  a(d.upper);
  a(d.enable_motor);
  a(d.motor_speed);
  a(d.max_motor_torque);
  a(d.max_motor_force);
  a(d.enable_spring);
  a(d.spring_hertz);
  a(d.spring_damping);
  a(d.length);
  a(d.min_length);
  a(d.max_length);
  a(d.max_spring_force);
  a(d.linear_hertz);
  a(d.linear_damping);
  a(d.angular_hertz);
  a(d.angular_damping);
  a(d.use_offsets);
  io(a, d.linear_offset);
  a(d.angular_offset);
  a(d.motor_hertz);
  a(d.motor_damping);
  io(a, d.linear_velocity);
  a(d.angular_velocity);
  a(d.max_force);
  a(d.max_torque);
  io(a, d.ground_a);
  io(a, d.ground_b);
  a(d.ratio);
  io(a, d.joint_a);
  io(a, d.joint_b);
  if (a.version >= 4) {
    io(a, d.local_anchor_a);
    io(a, d.local_anchor_b);
  }
}

template <typename A>
void io(A& a, Softness& s) {
  a(s.bias_rate);
  a(s.mass_scale);
  a(s.impulse_scale);
}

template <typename A>
void io(A& a, Joint& j) {
  a.enumeration(j.type, kJointTypes, "joint type");
  a(j.enable_limit);
  a(j.enable_motor);
  a(j.enable_spring);
  a(j.a);
  a(j.b);
  a(j.c);
  a(j.d);
  io(a, j.ra);
  io(a, j.rb);
  io(a, j.delta_center);
  a(j.delta_angle);
  a(j.ma);
  a(j.mb);
  a(j.ia);
  a(j.ib);
  a(j.axial_mass);
  io(a, j.spring);
  JointImpulses& p = j.impulses;
  for (double* x : {&p.linear_x, &p.linear_y, &p.angular, &p.perpendicular, &p.axial, &p.spring, &p.motor, &p.lower,
                    &p.upper, &p.spring_x, &p.spring_y})
    a(*x);
  a(j.lower);
  a(j.upper);
  a(j.motor_speed);
  a(j.max_motor_torque);
  io(a, j.def);
  j.breakable = breakableDef(j.def);  // not stored: it follows from the definition
  a(j.generation);
  a(j.alive);
  a(j.broken);
  io(a, j.local_a);
  io(a, j.local_b);
  io(a, j.local_axis);
  a(j.reference_angle);
  a(j.length);
  // Before version 4 a pulley's definition did not keep its constant (now its `length`, which
  // World::updateJoint checks and keeps): it is the joint's.
  if constexpr (A::kReading)
    if (a.version < 4 && j.def.type == JointType::Pulley) j.def.length = j.length;
  a(j.joint_a);
  a(j.joint_b);
  for (Joint::GearSide& g : j.gear) {
    a(g.revolute);
    io(a, g.local_ground);
    io(a, g.local_body);
    io(a, g.local_axis);
    a(g.reference);
    io(a, g.rg);
    io(a, g.rx);
    io(a, g.u);
  }
  a(j.gear_constant);
  io(a, j.axis);
  a(j.mc);
  a(j.md);
  a(j.ic);
  a(j.id);
  io(a, j.linear_soft);
  io(a, j.angular_soft);
  for (Vec2* c : {&j.center_a0, &j.center_b0, &j.center_c0, &j.center_d0}) io(a, *c);
  for (double* x : {&j.angle_a0, &j.angle_b0, &j.angle_c0, &j.angle_d0}) a(*x);
  a(j.impulse_h);
}

template <typename A>
void io(A& a, WorldImpl::JointBreak& b) {
  io(a, b.id);
  io(a, b.def);
  io(a, b.force);
  a(b.torque);
}

template <typename A>
void io(A& a, ForceEntry& e) {
  uint8_t tag = kNoForce;
  if constexpr (!A::kReading) {
    const Force* f = e.force.get();
    if (!f) tag = kNoForce;
    else if (dynamic_cast<const SpringForce*>(f)) tag = kSpring;
    else if (dynamic_cast<const DamperForce*>(f)) tag = kDamper;
    else if (dynamic_cast<const MouseForce*>(f)) tag = kMouse;
    else if (dynamic_cast<const ConstantForce*>(f)) tag = kConstant;
    else tag = kOpaque;
  }
  a(tag, "force kind");
  if (tag >= kForceTags) {
    if constexpr (A::kReading) a.fail("force kind is " + std::to_string(tag));
  }
  try {
    switch (tag) {
      case kNoForce:
        break;
      case kSpring: {
        SpringDef d = A::kReading ? SpringDef{} : static_cast<const SpringForce&>(*e.force).def();
        io(a, d.a);
        io(a, d.b);
        io(a, d.local_a);
        io(a, d.local_b);
        io(a, d.anchor);
        a(d.stiffness);
        io(a, d.rest_length);
        a(d.damping);
        if constexpr (A::kReading) {
          if (!d.rest_length) a.fail("a spring without its rest length");
          e.force = std::make_shared<SpringForce>(d);
        }
        break;
      }
      case kDamper: {
        DamperDef d = A::kReading ? DamperDef{} : static_cast<const DamperForce&>(*e.force).def();
        io(a, d.body);
        a(d.coefficient);
        a(d.angular_coefficient);
        if constexpr (A::kReading) e.force = std::make_shared<DamperForce>(d);
        break;
      }
      case kMouse: {
        MouseForceDef d = A::kReading ? MouseForceDef{} : static_cast<const MouseForce&>(*e.force).def();
        io(a, d.body);
        io(a, d.local_point);
        io(a, d.target);
        a(d.stiffness);
        a(d.damping);
        a(d.max_force);
        if constexpr (A::kReading) e.force = std::make_shared<MouseForce>(d);
        break;
      }
      case kConstant: {
        Vec2 force = Vec2::Zero();
        std::optional<Vec2> point;
        double torque = 0.0;
        if constexpr (!A::kReading) {
          const auto& c = static_cast<const ConstantForce&>(*e.force);
          force = c.force();
          point = c.localPoint();
          torque = c.torque();
        }
        io(a, force);
        io(a, point);
        if (a.version >= 4) a(torque);
        if constexpr (A::kReading) e.force = std::make_shared<ConstantForce>(force, point, torque);
        break;
      }
      default: {  // kOpaque
        std::string kind = A::kReading ? std::string() : std::string(e.force->kind());
        a(kind, "a force's kind");
        if constexpr (A::kReading) e.force = std::make_shared<PlaceholderForce>(kind);
        break;
      }
    }
  } catch (const InputError& err) {
    if constexpr (A::kReading) a.fail(std::string("a force with a bad value: ") + err.what());
    throw;
  }
  io(a, e.a);
  io(a, e.b);
  a(e.expires_at);
  a(e.next_step_only);
  a(e.generation);
  a(e.alive);
}

template <typename A>
void io(A& a, Incident& i) {
  a(i.uid);
  a(i.name);
  a(i.step);
  a(i.time);
  a(i.cause);
}

template <typename A>
void io(A& a, StepStats& s) {
  for (double* x : {&s.integrate_ms, &s.broad_phase_ms, &s.narrow_phase_ms, &s.solve_ms, &s.correct_ms, &s.finish_ms,
                    &s.forces_ms})
    a(*x);
  for (int* x : {&s.bodies, &s.dynamic_bodies, &s.awake_bodies, &s.forces, &s.pairs, &s.contacts, &s.contact_points,
                 &s.joints, &s.ccd_sweeps, &s.ccd_hits, &s.impact_bodies, &s.impacts_located, &s.impact_searches,
                 &s.rk4_handovers, &s.joint_position_passes, &s.joint_newton_steps})
    a(*x);
  a(s.force_evaluations);
  a(s.pairs_reused);
}

template <typename A>
void io(A& a, World::ContactEvent& e) {
  a.enumeration(e.kind, 3, "contact event kind");
  io(a, e.shape_a);
  io(a, e.shape_b);
  io(a, e.a);
  io(a, e.b);
  io(a, e.normal);
  a(e.count);
  io(a, e.points[0]);
  io(a, e.points[1]);
  io(a, e.point);
  a(e.approach_speed);
  a(e.normal_impulse);
  a(e.tangent_impulse);
  if (a.version >= 4) {
    for (int i = 0; i < 2; ++i) {
      a(e.separations[i]);
      a(e.normal_impulses[i]);
      a(e.tangent_impulses[i]);
    }
    for (double* x : {&e.friction, &e.static_friction, &e.restitution, &e.tangent_speed, &e.rolling_resistance}) a(*x);
  }
}

template <typename A>
void io(A& a, WorldImpl::FilterDecision& d) {
  a(d.a);
  a(d.b);
  a(d.generation_a);
  a(d.generation_b);
  a(d.collide);
}

template <typename A>
void io(A& a, World::SensorEvent& e) {
  a(e.begin);
  io(a, e.sensor);
  io(a, e.visitor);
  io(a, e.sensor_body);
  io(a, e.visitor_body);
}

template <typename A>
void io(A& a, Proxy& p) {
  io(a, p.aabb);
  a(p.is_static);
  a(p.active);
}
template <typename A>
void io(A& a, BodyPair& p) {
  a(p.a);
  a(p.b);
}
template <typename A>
void io(A& a, PairCache& c) {
  io(a, c.grown);
  io(a, c.pairs);
  a(c.age);
  a(c.cooldown);
  a(c.valid);
}

template <typename A>
void io(A& a, ContactPoint& p) {
  io(a, p.point);
  a(p.separation);
  a(p.id);
  a(p.persisted);
  bool before_version_3 = false;
  if constexpr (A::kReading) before_version_3 = a.version < 3;
  if (before_version_3) {
    // Versions 1 and 2 stored the prepare's anchors, target velocity, overlap time and friction per
    // point. The next step computes them again; of them it reads only whether the target velocity
    // was positive, which is the flag.
    Vec2u anchor;
    double target_velocity = 0.0, unused = 0.0;
    io(a, anchor);
    io(a, anchor);
    a(target_velocity);
    a(unused);
    a(unused);
    p.bounced = !(target_velocity <= 0.0);
  } else {
    a(p.bounced);
  }
  a(p.normal_impulse);
  a(p.tangent_impulse);
  a(p.step_normal_impulse);
  a(p.step_tangent_impulse);
}
template <typename A>
void io(A& a, Contact& c) {
  a(c.a);
  a(c.b);
  a(c.shape_a);
  a(c.shape_b);
  a(c.count);
  a(c.block);
  a(c.touching);
  a(c.passing);
  io(a, c.normal);
  io(a, c.points[0]);
  io(a, c.points[1]);
  a(c.restitution);
  a(c.friction);
  a(c.static_friction);
  a(c.slop);
}
template <typename A>
void io(A& a, ContactKey& k) {
  a(k.a);
  a(k.b);
  a(k.count);
  a(k.deep_overlap);
  a(k.disabled);
}
template <typename A>
void io(A& a, LocatedImpact& l) {
  a(l.shape_a);
  a(l.shape_b);
  a(l.a);
  a(l.b);
  a(l.time);
  io(a, l.normal);
  a(l.count);
  io(a, l.points[0]);
  io(a, l.points[1]);
  a(l.approach_speed);
  a(l.normal_impulse);
  a(l.tangent_impulse);
  a(l.separating);
}
template <typename A>
void io(A& a, ImpactScratch::Interval& i) {
  a(i.start);
  a(i.t0);
  a(i.h);
}

template <typename A>
void io(A& a, WorldImpl& w) {
  io(a, w.def);
  io(a, w.bodies);
  io(a, w.alive);
  io(a, w.free_bodies);
  io(a, w.shapes);
  io(a, w.shape_alive);
  io(a, w.free_shapes);
  a(w.chains);
  io(a, w.forces);
  io(a, w.free_forces);
  io(a, w.joints);
  io(a, w.free_joints);
  io(a, w.body_joints);
  io(a, w.si_joints);
  io(a, w.soft_joints);
  io(a, w.joint_breaks);
  a(w.clock.t);
  a(w.clock.carry);
  a(w.last_dt);
  a(w.step_count);
  io(a, w.created_asleep_before);
  a(w.next_uid);
  io(a, w.stats);
  io(a, w.incidents);
  a(w.every_contact_event);
  a(w.event_shapes);
  a(w.presolve_shapes);
  a(w.sensor_shapes);
  io(a, w.contact_events);
  io(a, w.event_contacts);
  io(a, w.previous_matched);
  io(a, w.sensor_events);
  io(a, w.sensor_overlaps);
  a(w.layout_version);
  a(w.static_version);
  io(a, w.proxies);
  io(a, w.pair_cache);
  io(a, w.pairs);
  io(a, w.contacts);
  io(a, w.contact_keys);
  // Not previous_contacts: the narrow phase's scratch, cleared or swapped out unread at its start
  // (narrow_phase.cpp LastContacts); only its capacity is reused.
  io(a, w.island);
  // What kinematic bodies moved with last step: a velocity set since is a jump (integrator.cpp).
  io(a, w.kinematic_velocity);
  io(a, w.kinematic_angular_velocity);
  io(a, w.kinematic_uid);
  io(a, w.kinematic_jump);
  io(a, w.kinematic_angular_jump);
  a(w.kinematic_jumped);
  io(a, w.keep_awake);
  io(a, w.ccd_hit);
  io(a, w.fast_bodies);
  io(a, w.impact.log);
  io(a, w.impact.intervals);
  if (a.version >= 4) {
    a(w.surface_shapes);
    io(a, w.filter_decisions);
  } else if constexpr (A::kReading) {
    w.surface_shapes = 0;  // no shape of an older file has surface effects
  }
}

// --- the checks a read state must pass before a step may index with it

void check(bool ok, const std::string& what) {
  if (!ok) throw SnapshotError("snapshot: " + what);
}

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

bool finiteBody(const Body& b) {
  for (const double x : {b.xf.q.c, b.xf.q.s, b.angle, b.angular_velocity, b.inv_mass, b.inv_inertia, b.mass, b.inertia,
                         b.linear_damping, b.angular_damping, b.gravity_scale})
    if (!std::isfinite(x)) return false;
  return finite(b.xf.p) && finite(b.center) && finite(b.velocity) && finite(b.local_center);
}

bool finiteShape(const Shape& g) {
  if (!std::isfinite(g.radius) || !std::isfinite(g.extent) || !finite(g.center) || !finite(g.ghost1) || !finite(g.ghost2))
    return false;
  for (const Vec2& v : g.vertices) if (!finite(v)) return false;
  for (const Vec2& n : g.normals) if (!finite(n)) return false;
  return true;
}

void validate(const WorldImpl& w) {
  try {
    World probe(w.def);  // the settings' own validation
  } catch (const InputError& e) {
    throw SnapshotError(std::string("snapshot: bad setting: ") + e.what());
  }
  const size_t nb = w.bodies.size(), ns = w.shapes.size(), nj = w.joints.size(), nf = w.forces.size();
  check(w.alive.size() == nb && w.body_joints.size() == nb && w.created_asleep_before.size() == nb,
        "the per-body lists do not match the " + std::to_string(nb) + " body slots");
  check(w.shape_alive.size() == ns, "the per-shape lists do not match the " + std::to_string(ns) + " shape slots");
  const auto slotList = [](const std::vector<uint32_t>& v, size_t n, const char* what) {
    for (uint32_t i : v) check(i < n, std::string(what) + " names slot " + std::to_string(i) + " of " + std::to_string(n));
  };
  slotList(w.free_bodies, nb, "the free body list");
  slotList(w.free_shapes, ns, "the free shape list");
  slotList(w.free_joints, nj, "the free joint list");
  slotList(w.free_forces, nf, "the free force list");
  slotList(w.si_joints, nj, "the step's joint list");
  slotList(w.soft_joints, nj, "the step's joint list");
  slotList(w.fast_bodies, nb, "the fast body list");
  for (const auto& list : w.body_joints) slotList(list, nj, "a body's joint list");
  const auto bodyOk = [&](const BodyId& id) { return id.isNull() || id.index < nb; };
  for (uint32_t i = 0; i < nb; ++i) {
    const Body& b = w.bodies[i];
    check(b.id.index == i, "body slot " + std::to_string(i) + " holds id " + std::to_string(b.id.index));
    // A step leaves every live body's state finite (nan_guard.cpp puts a body back where its step
    // began), and the firewall can only put a body back to a finite start: a non-finite state read
    // from a file would stay non-finite for good (fuzz_snapshot).
    if (w.alive[i])
      check(finiteBody(b), "body " + std::to_string(b.uid) + " has a non-finite position, angle, velocity or mass");
    for (ShapeId s : b.shapes)
      check(s.index < ns && (!w.alive[i] || (w.shape_alive[s.index] && w.shapes[s.index].body.index == i)),
            "body slot " + std::to_string(i) + " lists a shape that is not its own");
  }
  for (uint32_t i = 0; i < ns; ++i) {
    const BodyShape& s = w.shapes[i];
    check(s.id.index == i, "shape slot " + std::to_string(i) + " holds id " + std::to_string(s.id.index));
    if (!w.shape_alive[i]) continue;
    check(s.body.index < nb && w.alive[s.body.index], "shape " + std::to_string(i) + " belongs to no live body");
    const Shape& g = s.geometry;
    check(finiteShape(g), "shape " + std::to_string(i) + " has a non-finite vertex, normal or radius");
    check(g.vertices.size() <= kMaxPolygonVertices && g.normals.size() == g.vertices.size(),
          "shape " + std::to_string(i) + " has " + std::to_string(g.vertices.size()) + " vertices and " +
              std::to_string(g.normals.size()) + " normals");
    const size_t need = g.type == ShapeType::Polygon ? 3 : g.type == ShapeType::Circle ? 0 : 2;
    check(g.type == ShapeType::Polygon ? g.vertices.size() >= need : g.vertices.size() == need, "shape " + std::to_string(i) + " has too few vertices for a " + shapeTypeName(g.type));
  }
  const auto jointSlot = [&](uint32_t s) { return s == kWorldSlot || s < nb; };
  for (uint32_t i = 0; i < nj; ++i) {
    const Joint& j = w.joints[i];
    check(jointSlot(j.a) && jointSlot(j.b) && jointSlot(j.c) && jointSlot(j.d),
          "joint " + std::to_string(i) + " names a body slot out of range");
    if (j.alive && j.type == JointType::Gear)
      check((j.joint_a < nj && j.joint_b < nj) || (j.joint_a == kNoJoint && j.joint_b == kNoJoint),
            "gear " + std::to_string(i) + " names a joint out of range");
  }
  for (uint32_t i = 0; i < nf; ++i) {
    const ForceEntry& f = w.forces[i];
    if (!f.alive) continue;
    check(f.force && f.a.index < nb && w.alive[f.a.index] && bodyOk(f.b) && (f.b.isNull() || w.alive[f.b.index]),
          "force " + std::to_string(i) + " acts on no live body");
  }
  const auto contactsOk = [&](const std::vector<Contact>& cs, const char* what) {
    for (const Contact& c : cs)
      check(c.a < nb && c.b < nb && c.shape_a < ns && c.shape_b < ns && c.count >= 0 && c.count <= 2,
            std::string(what) + " name slots out of range");
  };
  contactsOk(w.contacts, "the contacts");
  check(w.contact_keys.size() == w.contacts.size(), "the contact keys do not match the contacts");
  for (const ContactKey& k : w.contact_keys)
    check(k.a < nb && k.b < nb && k.count <= 2, "the contact keys name slots out of range");
  for (uint32_t e : w.event_contacts) check(e < w.contacts.size(), "an event names a contact out of range");
  check(w.sensor_overlaps.size() <= ns, "more sensor lists than shapes");
  for (const auto& o : w.sensor_overlaps)
    for (ShapeId s : o) check(s.index < ns, "a sensor holds a shape out of range");
  check(w.island.size() <= nb, "more islands than body slots");
  for (const size_t k : {w.kinematic_velocity.size(), w.kinematic_angular_velocity.size(), w.kinematic_uid.size(),
                         w.kinematic_jump.size(), w.kinematic_angular_jump.size()})
    check(k <= nb, "more kinematic velocities than body slots");
  for (uint32_t r : w.island) check(r < nb, "an island root out of range");
  for (const BodyPair& p : w.pairs) check(p.a < ns && p.b < ns, "a pair names a shape out of range");
  for (const BodyPair& p : w.pair_cache.pairs)
    check(p.a < w.pair_cache.grown.size() && p.b < w.pair_cache.grown.size(), "the kept pairs name slots out of range");
  for (const LocatedImpact& l : w.impact.log)
    check(l.a < nb && l.b < nb && l.shape_a < ns && l.shape_b < ns && l.count >= 0 && l.count <= 2,
          "a located impact names slots out of range");
  check(w.impact.log.empty() || !w.impact.intervals.empty(), "located impacts without the step's intervals");
  check(w.step_count >= 0, "a negative step count");
}

}  // namespace

std::string serializeSnapshot(const WorldSnapshot& snapshot) {
  if (!snapshot.state_) throw SnapshotError("snapshot: the snapshot is empty");
  Writer payload;
  payload.out.reserve(4096 + 600 * snapshot.state_->bodies.size() + 200 * snapshot.state_->contacts.size());
  payload(snapshot.label_);
  payload(snapshot.app_data_);
  io(payload, const_cast<WorldImpl&>(*snapshot.state_));  // a Writer only reads
  Writer file;
  file.out.assign(kMagic, kMagicBytes);
  file(kVersion);
  file(static_cast<uint64_t>(payload.out.size()));
  file.out += payload.out;
  file(fnv1a(payload.out));
  return std::move(file.out);
}

namespace {

struct Header {
  uint32_t version = 0;
  uint64_t length = 0;  // of the payload
};
constexpr size_t kPayloadStart = kMagicBytes + 12;
static_assert(kSnapshotHeaderBytes == kPayloadStart);

Header readHeader(std::string_view bytes) {
  if (bytes.size() < kMagicBytes || bytes.substr(0, kMagicBytes) != std::string_view(kMagic, kMagicBytes))
    throw SnapshotError("snapshot: not a rigidlab snapshot (no \"RIGIDLAB-SNAPSHOT\" header)");
  Reader head(bytes.substr(kMagicBytes), kMagicBytes);
  Header h;
  head(h.version, "the version");
  if (h.version < kOldestVersion || h.version > kVersion)
    throw SnapshotError("snapshot: version " + std::to_string(h.version) + ", this program reads versions " +
                        std::to_string(kOldestVersion) + " to " + std::to_string(kVersion));
  head(h.length, "the length");
  return h;
}

}  // namespace

uint64_t snapshotFileBytes(std::string_view header) {
  const Header h = readHeader(header.substr(0, std::min(header.size(), kSnapshotHeaderBytes)));
  // payload + checksum after the header, saturating: a hostile length must not wrap around
  return h.length > UINT64_MAX - kPayloadStart - 8 ? UINT64_MAX : kPayloadStart + h.length + 8;
}

WorldSnapshot deserializeSnapshot(std::string_view bytes) {
  const Header header = readHeader(bytes);
  const uint32_t version = header.version;
  const uint64_t length = header.length;
  const size_t start = kPayloadStart;
  if (bytes.size() < start || bytes.size() - start < 8 || length != bytes.size() - start - 8)
    throw SnapshotError("snapshot: truncated or extended: the header says " + std::to_string(length) +
                        " bytes of state, the file has " +
                        std::to_string(bytes.size() >= start + 8 ? bytes.size() - start - 8 : 0));
  const std::string_view body = bytes.substr(start, length);
  Reader tail(bytes.substr(start + length), start + length);
  uint64_t sum = 0;
  tail(sum, "the checksum");
  if (sum != fnv1a(body)) throw SnapshotError("snapshot: corrupt (the checksum does not match)");

  Reader r(body, start, version);
  WorldSnapshot s;
  r(s.label_, "the label");
  if (version >= 2) r(s.app_data_, "the application data");
  auto w = std::make_shared<WorldImpl>();
  io(r, *w);
  if (!r.atEnd()) r.fail("bytes left over after the state");
  validate(*w);
  w->countKinematicBodies();
  w->broad_phase = w->def.broad_phase == BroadPhaseKind::AllPairs
                       ? std::unique_ptr<BroadPhase>(std::make_unique<AllPairsBroadPhase>())
                       : std::unique_ptr<BroadPhase>(std::make_unique<GridBroadPhase>());
  s.state_ = std::move(w);
  return s;
}

}  // namespace rigidlab

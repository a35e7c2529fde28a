// libFuzzer target: a random world description (bodies of every type made of every kind of shape,
// compounds, chains (long ones, sensors, their points as concave outlines), filters, sensors, one-way platforms, joints of every type with random limits,
// motors and springs, queries and explosions between steps), read from the bytes, built through
// the core's public API and stepped. Numbers come from a pool of nasty values (NaN, ±inf, 0, −0, denormals,
// 1e±30, 1e308) or from ranges around sensible ones. The core must reject bad input with
// InputError (caught here) and never crash; after every step every body's state must be finite
// (the NaN firewall freezes a body that would not be) — otherwise the target aborts.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <vector>

#include "rigidlab/error.h"
#include "rigidlab/forces.h"
#include "rigidlab/world.h"

using namespace rigidlab;

namespace {

double number(FuzzedDataProvider& in, double lo, double hi) {
  static constexpr double kNasty[] = {std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      0.0,
                                      -0.0,
                                      4.9e-324,
                                      1e-30,
                                      -1e-30,
                                      1e30,
                                      -1e30,
                                      1e308,
                                      -1.0,
                                      1e-7,
                                      1e6};
  const uint8_t kind = in.ConsumeIntegral<uint8_t>();
  if (kind < 24) return kNasty[kind % std::size(kNasty)];
  return in.ConsumeFloatingPointInRange(lo, hi);
}

Vec2 vec(FuzzedDataProvider& in, double lo, double hi) {
  const double x = number(in, lo, hi);
  return Vec2(x, number(in, lo, hi));
}

bool finiteBody(const Body& b) {
  return std::isfinite(b.position().x()) && std::isfinite(b.position().y()) && std::isfinite(b.angle) &&
         std::isfinite(b.velocity.x()) && std::isfinite(b.velocity.y()) && std::isfinite(b.angular_velocity) &&
         std::isfinite(b.center.x()) && std::isfinite(b.center.y());
}

Shape shape(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange(0, 4)) {
    case 3: return makeCapsule(vec(in, -3, 3), vec(in, -3, 3), number(in, 0.01, 2.0));
    case 4: return makeSegment(vec(in, -5, 5), vec(in, -5, 5));
    case 0: return makeCircle(number(in, 0.01, 5.0), in.ConsumeBool() ? vec(in, -2, 2) : Vec2::Zero());
    case 1: {
      const double w = number(in, 0.01, 10.0);
      return makeBox(w, number(in, 0.01, 10.0), in.ConsumeBool() ? vec(in, -2, 2) : Vec2::Zero(), number(in, -4, 4));
    }
    default: {
      std::vector<Vec2> points(in.ConsumeIntegralInRange(0, 40));
      for (Vec2& p : points) p = vec(in, -3, 3);
      return makePolygon(points);
    }
  }
}

BodyId pick(FuzzedDataProvider& in, const std::vector<BodyId>& bodies) {
  return bodies[in.ConsumeIntegralInRange<size_t>(0, bodies.size() - 1)];
}

Filter filter(FuzzedDataProvider& in) {
  Filter f;
  if (in.ConsumeBool()) {
    f.category = in.ConsumeIntegral<uint64_t>();
    f.mask = in.ConsumeIntegral<uint64_t>();
    f.group = in.ConsumeIntegralInRange<int32_t>(-3, 3);
  }
  return f;
}

// A joint of any type between random bodies (or the world), with random settings.
void joint(FuzzedDataProvider& in, World& w, const std::vector<BodyId>& bodies, std::vector<JointId>& joints) {
  JointDef d;
  d.type = static_cast<JointType>(in.ConsumeIntegralInRange(0, kJointTypes - 1));
  d.a = pick(in, bodies);
  if (in.ConsumeBool()) d.b = pick(in, bodies);
  d.anchor_a = vec(in, -20, 20);
  d.anchor_b = vec(in, -20, 20);
  d.axis = vec(in, -1, 1);
  d.collide_connected = in.ConsumeBool();
  if (in.ConsumeBool()) d.break_force = number(in, 0, 1e4);
  if (in.ConsumeBool()) d.break_torque = number(in, 0, 1e4);
  d.enable_limit = in.ConsumeBool();
  d.lower = number(in, -4, 4);
  d.upper = number(in, -4, 4);
  d.enable_motor = in.ConsumeBool();
  d.motor_speed = number(in, -20, 20);
  d.max_motor_torque = number(in, 0, 1e4);
  d.max_motor_force = number(in, 0, 1e4);
  d.enable_spring = in.ConsumeBool();
  d.spring_hertz = number(in, 0, 60);
  d.spring_damping = number(in, 0, 5);
  if (in.ConsumeBool()) d.length = number(in, 0, 10);
  d.min_length = number(in, 0, 5);
  d.max_length = in.ConsumeBool() ? std::numeric_limits<double>::infinity() : number(in, 0, 10);
  d.max_spring_force = number(in, 0, 1e4);
  d.linear_hertz = number(in, 0, 60);
  d.angular_hertz = number(in, 0, 60);
  d.use_offsets = in.ConsumeBool();
  d.linear_offset = vec(in, -5, 5);
  d.angular_offset = number(in, -4, 4);
  d.motor_hertz = number(in, 0, 60);
  d.max_force = number(in, 0, 1e4);
  d.max_torque = number(in, 0, 1e4);
  d.ground_a = vec(in, -20, 20);
  d.ground_b = vec(in, -20, 20);
  d.ratio = number(in, -5, 5);
  if (!joints.empty()) {
    d.joint_a = joints[in.ConsumeIntegralInRange<size_t>(0, joints.size() - 1)];
    d.joint_b = joints[in.ConsumeIntegralInRange<size_t>(0, joints.size() - 1)];
  }
  joints.push_back(w.createJoint(d));
}

void build(FuzzedDataProvider& in, World& w, std::vector<BodyId>& bodies, std::vector<ForceId>& forces,
           std::vector<JointId>& joints) {
  try {
    switch (in.ConsumeIntegralInRange(0, 10)) {
      case 7:
        if (!bodies.empty()) joint(in, w, bodies, joints);
        break;
      case 8: {  // another shape on a body (a compound), with the shape options
        if (bodies.empty()) break;
        ShapeDef d;
        d.shape = shape(in);
        d.density = number(in, 0.01, 1000);
        d.filter = filter(in);
        d.sensor = in.ConsumeIntegralInRange(0, 5) == 0;
        d.contact_events = in.ConsumeBool();
        d.hit_events = in.ConsumeBool();
        if (in.ConsumeBool()) d.one_way = vec(in, -1, 1);
        w.createShape(pick(in, bodies), d);
        break;
      }
      case 9: {  // a chain on a static body; its points as a concave outline too
        if (bodies.empty()) break;
        World::ChainDef d;
        d.points.resize(in.ConsumeIntegralInRange(0, 12));
        for (Vec2& p : d.points) p = vec(in, -20, 20);
        d.loop = in.ConsumeBool();
        // Sometimes long (issue 32: a chain was quadratic in its points): the points repeated, shifted.
        const int copies = in.ConsumeIntegralInRange(0, 3) == 0 ? in.ConsumeIntegralInRange(1, 400) : 1;
        const size_t n = d.points.size();
        for (int c = 1; c < copies; ++c)
          for (size_t i = 0; i < n; ++i) d.points.push_back(d.points[i] + Vec2(41.0 * c, 0.0));
        d.sensor = in.ConsumeIntegralInRange(0, 3) == 0;
        const BodyId body = pick(in, bodies);
        const bool sensor_after = in.ConsumeBool(), sensor = in.ConsumeBool(), outline = in.ConsumeBool();
        if (outline && d.points.size() >= 3 && d.points.size() <= 1024) {
          try {
            (void)decomposeConcave(d.points);
          } catch (const InputError&) {
          }
        }
        w.createChain(body, d);
        if (sensor_after) w.setBodySensor(body, sensor);
        break;
      }
      case 10:
        w.setContactEvents(in.ConsumeBool());
        break;
      case 0:
      case 1:
      case 2: {
        BodyDef d;
        d.shape = shape(in);
        const int type = in.ConsumeIntegralInRange(0, 5);
        d.type = type == 0 ? BodyType::Static : type == 1 ? BodyType::Kinematic : BodyType::Dynamic;
        d.filter = filter(in);
        d.linear_damping = number(in, 0, 10);
        d.angular_damping = number(in, 0, 10);
        d.gravity_scale = number(in, -2, 2);
        d.fixed_rotation = in.ConsumeIntegralInRange(0, 4) == 0;
        d.bullet = in.ConsumeIntegralInRange(0, 4) == 0;
        d.position = vec(in, -20, 20);
        d.angle = number(in, -7, 7);
        d.velocity = vec(in, -50, 50);
        d.angular_velocity = number(in, -50, 50);
        if (in.ConsumeBool()) {
          d.mass = number(in, 0.01, 1000);
        } else {
          d.density = number(in, 0.01, 1000);
        }
        d.restitution = number(in, 0, 1);
        d.friction = number(in, 0, 2);
        if (in.ConsumeBool()) d.static_friction = number(in, 0, 2);
        bodies.push_back(w.createBody(d));
        break;
      }
      case 3: {
        if (bodies.empty()) break;
        SpringDef d;
        d.a = bodies[in.ConsumeIntegralInRange<size_t>(0, bodies.size() - 1)];
        if (in.ConsumeBool()) d.b = bodies[in.ConsumeIntegralInRange<size_t>(0, bodies.size() - 1)];
        d.anchor = vec(in, -20, 20);
        d.local_a = vec(in, -1, 1);
        d.local_b = vec(in, -1, 1);
        d.stiffness = number(in, 0, 1e5);
        if (in.ConsumeBool()) d.rest_length = number(in, 0, 10);
        d.damping = number(in, 0, 100);
        forces.push_back(w.addSpring(d, in.ConsumeBool() ? World::kForever : number(in, 0, 2)));
        break;
      }
      case 4: {
        if (bodies.empty()) break;
        DamperDef d;
        d.body = bodies[in.ConsumeIntegralInRange<size_t>(0, bodies.size() - 1)];
        d.coefficient = number(in, 0, 100);
        d.angular_coefficient = number(in, 0, 100);
        forces.push_back(w.addDamper(d));
        break;
      }
      case 5: {
        if (bodies.empty()) break;
        const BodyId b = bodies[in.ConsumeIntegralInRange<size_t>(0, bodies.size() - 1)];
        std::optional<Vec2> point;
        if (in.ConsumeBool()) point = vec(in, -1, 1);
        forces.push_back(w.addForce(std::make_unique<ConstantForce>(vec(in, -1e4, 1e4), point), b, {},
                                    in.ConsumeBool() ? World::kNextStep : number(in, 0, 2)));
        break;
      }
      default: {  // settings
        switch (in.ConsumeIntegralInRange(0, 6)) {
          case 0: w.setGravity(vec(in, -100, 100)); break;
          case 1: w.setIntegrator(static_cast<Integrator>(in.ConsumeIntegralInRange(0, 2))); break;
          case 2: w.setIterations(in.ConsumeIntegralInRange(-2, 60)); break;
          case 3: w.setWarmStarting(in.ConsumeBool()); break;
          case 4: w.setContactDisplacement(in.ConsumeBool()); break;
          case 5: w.setContactMargin(number(in, 0, 0.1)); break;
          default: w.setRestitutionThreshold(number(in, 0, 2)); break;
        }
      }
    }
  } catch (const InputError&) {
  }
}

// Between steps: the edits the sandbox and scripts make.
void edit(FuzzedDataProvider& in, World& w, std::vector<BodyId>& bodies, std::vector<ForceId>& forces,
          std::vector<JointId>& joints) {
  if (bodies.empty()) return;
  const BodyId b = bodies[in.ConsumeIntegralInRange<size_t>(0, bodies.size() - 1)];
  try {
    switch (in.ConsumeIntegralInRange(0, 16)) {
      case 10:
        if (!joints.empty()) w.destroyJoint(joints[in.ConsumeIntegralInRange<size_t>(0, joints.size() - 1)]);
        break;
      case 11:
        if (!joints.empty()) {
          const JointId j = joints[in.ConsumeIntegralInRange<size_t>(0, joints.size() - 1)];
          JointDef d = w.joint(j);
          d.motor_speed = number(in, -50, 50);
          d.lower = number(in, -4, 4);
          d.upper = number(in, -4, 4);
          d.linear_offset = vec(in, -5, 5);
          w.updateJoint(j, d);
        }
        break;
      case 12: w.setTarget(b, vec(in, -20, 20), number(in, -7, 7), number(in, 0, 2)); break;
      case 13: w.setEnabled(b, in.ConsumeBool()); break;
      case 14: {
        const auto shapes = w.body(b).shapes;
        if (!shapes.empty()) w.destroyShape(shapes[in.ConsumeIntegralInRange<size_t>(0, shapes.size() - 1)]);
        break;
      }
      case 15: {  // queries
        (void)w.rayCast(vec(in, -30, 30), vec(in, -30, 30));
        (void)w.rayCastAll(vec(in, -30, 30), vec(in, -30, 30));
        const Vec2 lo = vec(in, -30, 30);
        (void)w.queryBox({lo, lo + vec(in, 0, 10)});
        (void)w.shapeCast(shape(in), {vec(in, -20, 20), Rot::fromAngle(number(in, -4, 4))}, vec(in, -10, 10));
        break;
      }
      case 16: {
        ExplosionDef e;
        e.position = vec(in, -20, 20);
        e.radius = number(in, 0, 10);
        e.falloff = number(in, 0, 5);
        e.impulse = number(in, 0, 100);
        (void)w.explode(e);
        break;
      }
      case 0: w.setVelocity(b, vec(in, -50, 50)); break;
      case 1: w.setAngularVelocity(b, number(in, -50, 50)); break;
      case 2: w.setTransform(b, vec(in, -20, 20), number(in, -7, 7)); break;
      case 3: w.setMass(b, number(in, 0.01, 100)); break;
      case 4: w.setType(b, static_cast<BodyType>(in.ConsumeIntegralInRange(0, 2))); break;
      case 5: w.applyImpulse(b, vec(in, -100, 100), vec(in, -20, 20)); break;
      case 6: {
        Material m;
        m.restitution = number(in, 0, 1);
        m.friction = number(in, 0, 2);
        m.static_friction = number(in, 0, 2);
        w.setMaterial(b, m);
        break;
      }
      case 7: w.destroyBody(b); break;
      case 8:
        if (!forces.empty()) w.removeForce(forces[in.ConsumeIntegralInRange<size_t>(0, forces.size() - 1)]);
        break;
      default: build(in, w, bodies, forces, joints); break;
    }
  } catch (const InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  World w;
  std::vector<BodyId> bodies;
  std::vector<ForceId> forces;
  std::vector<JointId> joints;
  const int items = in.ConsumeIntegralInRange(0, 40);
  for (int i = 0; i < items; ++i) build(in, w, bodies, forces, joints);
  const int steps = in.ConsumeIntegralInRange(1, 60);
  for (int s = 0; s < steps && in.remaining_bytes() > 0; ++s) {
    try {
      w.step(number(in, 1.0 / 960, 1.0 / 20));
    } catch (const InputError&) {
      continue;
    }
    for (BodyId id : w.bodyIds()) {
      if (!finiteBody(w.body(id))) {
        std::fprintf(stderr, "fuzz_world: body uid %u has a non-finite state after step %ld\n", w.body(id).uid,
                     w.stepCount());
        std::abort();
      }
    }
    for (JointId j : w.jointIds()) {
      const JointState s = w.jointState(j);  // a joint's readings stay finite with its bodies
      if (!isFinite(s.world_anchor_a) || !isFinite(s.world_anchor_b)) {
        const JointDef& d = w.joint(j);
        std::fprintf(stderr, "fuzz_world: joint %u (%s) has a non-finite anchor after step %ld: a (%g, %g), b (%g, %g)\n",
                     j.index, jointTypeName(d.type), w.stepCount(), s.world_anchor_a.x(), s.world_anchor_a.y(),
                     s.world_anchor_b.x(), s.world_anchor_b.y());
        for (BodyId b : {d.a, d.b})
          if (!b.isNull())
            std::fprintf(stderr, "  body uid %u at (%g, %g) angle %g\n", w.body(b).uid, w.body(b).position().x(),
                         w.body(b).position().y(), w.body(b).angle);
        std::abort();
      }
    }
    if (in.ConsumeBool()) edit(in, w, bodies, forces, joints);
  }
  (void)w.kineticEnergy();
  (void)w.potentialEnergy();
  (void)w.contacts();
  return 0;
}

// libFuzzer target: a random world description, read from the bytes, built through the core's
// public API and stepped. Numbers come from a pool of nasty values (NaN, ±inf, 0, −0, denormals,
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
  switch (in.ConsumeIntegralInRange(0, 2)) {
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

void build(FuzzedDataProvider& in, World& w, std::vector<BodyId>& bodies, std::vector<ForceId>& forces) {
  try {
    switch (in.ConsumeIntegralInRange(0, 6)) {
      case 0:
      case 1:
      case 2: {
        BodyDef d;
        d.shape = shape(in);
        d.type = in.ConsumeIntegralInRange(0, 4) == 0 ? BodyType::Static : BodyType::Dynamic;
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
void edit(FuzzedDataProvider& in, World& w, std::vector<BodyId>& bodies, std::vector<ForceId>& forces) {
  if (bodies.empty()) return;
  const BodyId b = bodies[in.ConsumeIntegralInRange<size_t>(0, bodies.size() - 1)];
  try {
    switch (in.ConsumeIntegralInRange(0, 9)) {
      case 0: w.setVelocity(b, vec(in, -50, 50)); break;
      case 1: w.setAngularVelocity(b, number(in, -50, 50)); break;
      case 2: w.setTransform(b, vec(in, -20, 20), number(in, -7, 7)); break;
      case 3: w.setMass(b, number(in, 0.01, 100)); break;
      case 4: w.setType(b, in.ConsumeBool() ? BodyType::Static : BodyType::Dynamic); break;
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
      default: build(in, w, bodies, forces); break;
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
  const int items = in.ConsumeIntegralInRange(0, 40);
  for (int i = 0; i < items; ++i) build(in, w, bodies, forces);
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
    if (in.ConsumeBool()) edit(in, w, bodies, forces);
  }
  (void)w.kineticEnergy();
  (void)w.potentialEnergy();
  (void)w.contacts();
  return 0;
}

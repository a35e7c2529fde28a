// A body's acceleration at a stage of the integrator, as integrator.cpp and mechanism_step.cpp both
// read it: from its accumulated wrench, a = F/m + s g and α = τ/I (s the body's gravity scale, g
// its own gravity if it has one, BodyDef::gravity, else the world's),
// and, when its damping is evaluated in the stages (RK4), −c v and −c_ω ω at the stage's velocity:
// the damped body v' = a − c v is then a smooth ODE whose order RK4 keeps.
#pragma once

#include "rigidlab/body.h"
#include "rigidlab/force.h"

namespace rigidlab {

struct Accel {
  Vec2 a;
  double alpha;
};

[[gnu::always_inline]] inline Accel bodyAcceleration(const Body& b, const Vec2& gravity, const Wrench& wr) {
  return {wr.force * b.inv_mass + b.gravityOr(gravity) * b.gravity_scale, wr.torque * b.inv_inertia};
}

// Beyond h c = 2.5 RK4 multiplies a damped velocity by more than 1 per step (its factor is the
// degree-4 Taylor polynomial of e^(−h c): 291 at h c = 10; docs/design/accuracy.md S5), so there
// the damping is taken in the implicit form v ← v / (1 + h c) instead, which never flips or grows
// a velocity (first order).
constexpr double kRk4DampingLimit = 2.5;
inline bool dampingInStages(const Body& b, double h) {
  return (b.linear_damping > 0.0 || b.angular_damping > 0.0) && h * b.linear_damping <= kRk4DampingLimit &&
         h * b.angular_damping <= kRk4DampingLimit;
}

inline Accel dampedAcceleration(const Body& b, const Vec2& gravity, const Wrench& wr, const Vec2& v, double w) {
  Accel acc = bodyAcceleration(b, gravity, wr);
  acc.a -= b.linear_damping * v;
  acc.alpha -= b.angular_damping * w;
  return acc;
}

}  // namespace rigidlab

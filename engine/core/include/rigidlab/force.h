// The force interface (docs/design/thesis.md §4): a force is evaluated on the state of its body (or two bodies)
// at a time, and answers with a force, a torque and an application point. New kinds of force need no
// change to the core: derive from Force and hand it to World::addForce.
//
// Integrators call evaluate() once per stage on the stage's state: explicit and semi-implicit Euler
// once per step, RK4 four times (docs/design/thesis.md §5). A force must therefore compute from its arguments
// only and never cache a value between calls; a force sampled once per step would silently drop RK4
// to first order (docs/design/accuracy.md §0.6, tested in tests/core/test_integrators.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include <Eigen/Core>

#include "rigidlab/body.h"
#include "rigidlab/math.h"

namespace rigidlab {

class DebugDraw;

// State of one body as a force sees it: the step's start state or an RK4 intermediate state.
struct BodyState {
  Vec2 position = Vec2::Zero();   // body origin, world [m]
  Vec2 center = Vec2::Zero();     // centre of mass, world [m]
  double angle = 0.0;             // [rad]
  Rot q;                          // rotation of `angle`
  Vec2 velocity = Vec2::Zero();   // centre-of-mass velocity [m/s]
  double angular_velocity = 0.0;  // [rad/s]
  double mass = 0.0;              // [kg]
  double inertia = 0.0;           // [kg·m²] about the centre of mass
  bool is_static = false;
  BodyId id;
  uint32_t uid = 0;  // Body::uid

  // World position of a point given in body coordinates.
  Vec2 worldPoint(const Vec2& local) const { return position + q.apply(local); }
  // Velocity of a world point attached to the body.
  Vec2 pointVelocity(const Vec2& world) const { return velocity + cross(angular_velocity, world - center); }
};

// A force through the centre of mass plus a torque about it: what the integrator consumes.
struct Wrench {
  Vec2 force = Vec2::Zero();  // [N]
  double torque = 0.0;        // [N·m]

  Wrench& operator+=(const Wrench& o) {
    force += o.force;
    torque += o.torque;
    return *this;
  }
};

// A force F applied at a world point P on a body: torque τ = (P − c) × F (docs/design/thesis.md §1).
inline Wrench atPoint(const BodyState& s, const Vec2& force, const Vec2& world_point) {
  return {force, cross(world_point - s.center, force)};
}

struct ForceInput {
  const BodyState& a;
  const BodyState* b;  // second body of a two-body force, else nullptr
  double time;         // [s] simulation time of this evaluation (stage time for RK4)
};

struct ForceOutput {
  Wrench a;  // on body a
  Wrench b;  // on body b (two-body forces); ignored otherwise
};

// The force's linearisation, for the implicit integrators: derivatives of the generalised forces
// Q = (F_x, F_y, τ) of body i with respect to the coordinates q = (x, y, θ) and velocities
// v = (v_x, v_y, ω) of body j, i, j ∈ {a = 0, b = 1}. Start from zero; fill what applies.
struct ForceJacobian {
  Eigen::Matrix3d dq[2][2];  // ∂Q_i / ∂q_j  (stiffness)
  Eigen::Matrix3d dv[2][2];  // ∂Q_i / ∂v_j  (damping)
  ForceJacobian() {
    for (auto& row : dq)
      for (auto& m : row) m.setZero();
    for (auto& row : dv)
      for (auto& m : row) m.setZero();
  }
};

class Force {
 public:
  virtual ~Force() = default;

  // Computes the force at `in.time` on the given states. May be called several times per step.
  virtual void evaluate(const ForceInput& in, ForceOutput& out) = 0;

  // False if the result does not depend on the body states (e.g. a constant push through the centre
  // of mass): RK4 then evaluates it once per step instead of four times.
  virtual bool dependsOnState() const { return true; }
  // Fills `out` and returns true if the force can be integrated implicitly (springs, dampers):
  // implicit_euler then treats its stiffness and damping implicitly, and the Euler methods its
  // damping (so a damper never flips a velocity's sign). The default: explicit only.
  virtual bool linearize(const ForceInput& /*in*/, ForceJacobian& /*out*/) const { return false; }
  // How strongly the force resists velocity: linear ∂F/∂v [N·s/m] and, per body it acts on
  // (a, b), angular ∂τ/∂ω [N·m·s], estimates. RK4 uses them to see a damper too stiff for it
  // (integrator.cpp). The default: none (forces that do not damp, and forces that cannot say,
  // such as scripts).
  struct DampingRate {
    double linear = 0.0, angular_a = 0.0, angular_b = 0.0;
  };
  virtual DampingRate dampingRate() const { return {}; }
  // True if the bodies it acts on may fall asleep while it acts: a force that depends only on the
  // bodies' states (springs, dampers) is constant while they rest. Forces that may change with time
  // (scripts, pushes, the mouse) keep their bodies awake. The default: keep awake.
  virtual bool allowsSleep() const { return false; }
  // False if the force never does positive work that its potentialEnergy does not account for
  // (springs store it, dampers only take): the blow-up watch (docs/stability.md) then does not count
  // its work as energy put in. The default: it may put energy in (scripts, pushes, the mouse).
  virtual bool putsEnergyIn() const { return true; }
  // Potential energy stored in the force (springs), for World::potentialEnergy. [J]
  virtual double potentialEnergy(const BodyState& /*a*/, const BodyState* /*b*/) const { return 0.0; }
  virtual void draw(DebugDraw& /*dd*/, const BodyState& /*a*/, const BodyState* /*b*/) const {}
  // A short name for messages and statistics ("spring", "damper", "lua", ...).
  virtual std::string_view kind() const = 0;
  // An independent copy, for World::snapshot and World::restore. The default, nullptr, says the
  // force cannot be copied (a script's callback): a snapshot then keeps the object itself, and a
  // snapshot read from a file (world_snapshot.h) takes the restoring world's force of the same id
  // and kind. A force whose behaviour depends on state it changes must return a copy.
  virtual std::unique_ptr<Force> clone() const { return nullptr; }
};

struct ForceId {
  uint32_t index = UINT32_MAX;
  uint32_t generation = 0;

  bool isNull() const { return index == UINT32_MAX; }
  friend bool operator==(const ForceId&, const ForceId&) = default;
};

}  // namespace rigidlab

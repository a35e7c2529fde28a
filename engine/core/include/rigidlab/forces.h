// Built-in forces (docs/design/thesis.md §4). Gravity is a world setting (WorldDef::gravity), not a Force object:
// it acts on every dynamic body and RK4 needs to evaluate it only once per step.
#pragma once

#include <optional>

#include "rigidlab/force.h"

namespace rigidlab {

// Hooke spring with optional linear damping along its axis, between a body point and a fixed world
// anchor or between points of two bodies:
//   F_a = [k (L − L0) + c (v_b − v_a)·u] u,   F_b = −F_a,   u = (p_b − p_a)/L,   L = |p_b − p_a|
// (docs/design/thesis.md §1 F = −k x, §4 F = −k (current_length − length)). When L = 0 the direction is
// undefined and the spring applies no force.
struct SpringDef {
  BodyId a;                           // required
  BodyId b;                           // null: the spring ends at `anchor`
  Vec2 local_a = Vec2::Zero();        // attachment on a, body coordinates [m]
  Vec2 local_b = Vec2::Zero();        // attachment on b, body coordinates [m]
  Vec2 anchor = Vec2::Zero();         // fixed end in world coordinates when b is null [m]
  double stiffness = 0.0;             // k [N/m], ≥ 0
  std::optional<double> rest_length;  // L0 [m] ≥ 0; default: the distance when created
  double damping = 0.0;               // c [N·s/m] ≥ 0
};

class SpringForce final : public Force {
 public:
  explicit SpringForce(const SpringDef& def);  // rest_length must be resolved
  void evaluate(const ForceInput& in, ForceOutput& out) override;
  bool linearize(const ForceInput& in, ForceJacobian& out) const override;
  DampingRate dampingRate() const override;  // c, and c·r² with r each attachment point's lever
  bool allowsSleep() const override { return true; }
  double potentialEnergy(const BodyState& a, const BodyState* b) const override;  // ½ k (L − L0)²
  bool putsEnergyIn() const override { return false; }  // stores it (potentialEnergy) or its damping takes it
  void draw(DebugDraw& dd, const BodyState& a, const BodyState* b) const override;
  std::string_view kind() const override { return "spring"; }
  std::unique_ptr<Force> clone() const override { return std::make_unique<SpringForce>(*this); }
  const SpringDef& def() const { return def_; }
  SpringDef& def() { return def_; }
  // End points in world coordinates for the given states.
  void endPoints(const BodyState& a, const BodyState* b, Vec2& pa, Vec2& pb) const;

 private:
  SpringDef def_;
};

// Linear and angular damper on one body (docs/design/thesis.md §1 F_b = −b v): F = −c v, τ = −c_ω ω.
struct DamperDef {
  BodyId body;                   // required
  double coefficient = 0.0;      // c [N·s/m] ≥ 0
  double angular_coefficient = 0.0;  // c_ω [N·m·s] ≥ 0
};

class DamperForce final : public Force {
 public:
  explicit DamperForce(const DamperDef& def);
  void evaluate(const ForceInput& in, ForceOutput& out) override;
  bool linearize(const ForceInput& in, ForceJacobian& out) const override;
  DampingRate dampingRate() const override { return {def_.coefficient, def_.angular_coefficient, 0.0}; }
  bool putsEnergyIn() const override { return false; }  // only takes: F = −c v
  bool allowsSleep() const override { return true; }
  void draw(DebugDraw& dd, const BodyState& a, const BodyState* b) const override;
  std::string_view kind() const override { return "damper"; }
  std::unique_ptr<Force> clone() const override { return std::make_unique<DamperForce>(*this); }
  const DamperDef& def() const { return def_; }
  DamperDef& def() { return def_; }

 private:
  DamperDef def_;
};

// The cursor drag force (docs/design/thesis.md §4 "mouse force", §11): a damped spring from a point on the body
// to the cursor, its magnitude capped so a drag cannot launch a body or destabilise a stack:
//   F = clamp(k (target − p) − c v_p, max_force)
struct MouseForceDef {
  BodyId body;
  Vec2 local_point = Vec2::Zero();  // grabbed point, body coordinates [m]
  Vec2 target = Vec2::Zero();       // cursor, world [m]
  double stiffness = 0.0;           // k [N/m]
  double damping = 0.0;             // c [N·s/m]
  double max_force = 0.0;           // [N], > 0
};

class MouseForce final : public Force {
 public:
  explicit MouseForce(const MouseForceDef& def);
  void evaluate(const ForceInput& in, ForceOutput& out) override;
  void draw(DebugDraw& dd, const BodyState& a, const BodyState* b) const override;
  std::string_view kind() const override { return "mouse"; }
  std::unique_ptr<Force> clone() const override { return std::make_unique<MouseForce>(*this); }
  void setTarget(const Vec2& target) { def_.target = target; }
  const MouseForceDef& def() const { return def_; }
  // Stiffness and damping for a drag that feels the same on any body: natural frequency `hertz`,
  // damping ratio `zeta`, capped at `max_accel` times the body's mass.
  static MouseForceDef forBody(const Body& body, const Vec2& grab_point, double hertz = 5.0, double zeta = 0.7,
                               double max_accel = 100.0);

 private:
  MouseForceDef def_;
};

// A constant force, through the centre of mass or at a point fixed on the body (body.apply_force),
// and a constant torque (body.apply_torque).
class ConstantForce final : public Force {
 public:
  ConstantForce(const Vec2& force, std::optional<Vec2> local_point, double torque = 0.0);
  void evaluate(const ForceInput& in, ForceOutput& out) override;
  bool dependsOnState() const override { return local_point_.has_value(); }  // torque depends on the angle
  void draw(DebugDraw& dd, const BodyState& a, const BodyState* b) const override;
  std::string_view kind() const override { return "constant"; }
  std::unique_ptr<Force> clone() const override { return std::make_unique<ConstantForce>(*this); }
  const Vec2& force() const { return force_; }
  const std::optional<Vec2>& localPoint() const { return local_point_; }
  double torque() const { return torque_; }

 private:
  Vec2 force_;
  std::optional<Vec2> local_point_;
  double torque_ = 0.0;  // [N·m]
};

}  // namespace rigidlab

// Joints (docs/physics.md "Joints"): constraints between two bodies, or a body and the world, solved
// with the contacts by both contact solvers (engine/core/src/joint*.cpp).
//
//   JointDef d;
//   d.type = JointType::Revolute;
//   d.a = door; d.b = frame;            // b null: the world
//   d.anchor_a = d.anchor_b = hinge;     // world coordinates, now; stored in each body's frame
//   d.enable_limit = true; d.lower = -1.2; d.upper = 1.2;
//   JointId hinge_joint = world.createJoint(d);
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "rigidlab/body.h"
#include "rigidlab/math.h"

namespace rigidlab {

enum class JointType : uint8_t {
  Revolute,   // a pin: the anchors coincide; optional angle limits, motor, rotational spring
  Prismatic,  // a slider: b moves along an axis fixed in a, without turning relative to it
  Distance,   // the anchors keep a length (rigid), or a range (min/max: a rope), or a spring
  Weld,       // b is glued to a; rigid, or soft (linear and angular springs)
  Wheel,      // b slides along an axis of a on a suspension spring and turns freely (a car wheel)
  Motor,      // drives b towards an offset from a (position spring, velocity target), force-limited
  Friction,   // top-down friction: resists relative motion up to a force and a torque
  Pulley,     // two bodies on a rope over two fixed pulleys: length_a + ratio · length_b constant
  Gear,       // couples two revolute or prismatic joints: coordinate_a + ratio · coordinate_b constant
};
inline constexpr int kJointTypes = 9;
const char* jointTypeName(JointType t);  // "revolute", "prismatic", ... (the Lua `kind`)

struct JointId {
  uint32_t index = UINT32_MAX;
  uint32_t generation = 0;

  bool isNull() const { return index == UINT32_MAX; }
  friend bool operator==(const JointId&, const JointId&) = default;
};

// Everything needed to create a joint; each type reads the fields its comment names. Points and
// directions are world coordinates at creation. SI units; angles in radians.
struct JointDef {
  JointType type = JointType::Revolute;
  BodyId a, b;                           // b null: the world (a static point)
  Vec2 anchor_a = Vec2::Zero();          // on a; revolute, prismatic, weld, wheel, motor, friction: the one anchor
  Vec2 anchor_b = Vec2::Zero();          // on b; distance and pulley only (the others use anchor_a)
  // Each body's anchor in its own coordinates (Box2D's localAnchorA, localAnchorB), instead of the
  // world anchors above: given, they are used as they are (a's anchor held to b's even where they
  // are apart at creation: the joint pulls them together). The world's coordinates for a null
  // body. Motor joint: a's anchor is the target (the linear offset).
  std::optional<Vec2> local_anchor_a, local_anchor_b;
  Vec2 axis = Vec2(1.0, 0.0);            // prismatic, wheel: direction of motion (fixed in a), not zero
  bool collide_connected = false;        // may a and b collide with each other?
  double break_force = std::numeric_limits<double>::infinity();   // [N]: above it the joint breaks
  double break_torque = std::numeric_limits<double>::infinity();  // [N·m]
  std::string name;

  // Revolute, prismatic, weld, wheel: b's angle relative to a that counts as angle 0 (the limits,
  // the revolute spring's rest angle, the weld's glued angle) [rad]; default: the angle at creation.
  std::optional<double> reference_angle;

  // Limits: revolute angle (b's angle relative to a, from reference_angle) [rad]; prismatic
  // and wheel translation along the axis [m]; lower ≤ upper.
  bool enable_limit = false;
  double lower = 0.0, upper = 0.0;
  // Motor: revolute and wheel turn b relative to a at motor_speed [rad/s] with at most
  // max_motor_torque [N·m]; prismatic slides at motor_speed [m/s] with at most max_motor_force [N].
  // Bounds here and below may be infinite (unlimited).
  bool enable_motor = false;
  double motor_speed = 0.0, max_motor_torque = 0.0, max_motor_force = 0.0;
  // Spring: revolute (towards the angle at creation), prismatic (towards translation 0), wheel
  // (the suspension), distance (towards `length`). Frequency [Hz] ≥ 0 and damping ratio ≥ 0.
  bool enable_spring = false;
  double spring_hertz = 0.0, spring_damping = 0.0;

  // Distance: rest length (default: the anchors' distance at creation), limits, the spring's force
  // limit. min_length ≤ length ≤ max_length; a rope is max_length alone (min_length 0, no spring).
  double length = -1.0;                  // < 0: the distance at creation; pulley: length_a + ratio · length_b
  double min_length = 0.0;
  double max_length = std::numeric_limits<double>::infinity();
  double max_spring_force = std::numeric_limits<double>::infinity();  // [N]

  // Weld: linear and angular springs (0 Hz: rigid).
  double linear_hertz = 0.0, linear_damping = 0.0, angular_hertz = 0.0, angular_damping = 0.0;

  // Motor joint: b's target pose relative to a, in a's frame (default: as at creation, set
  // `use_offsets` to give them), reached by a spring (motor_hertz, motor_damping; 0 Hz: as stiff
  // as joints are), with the force and torque it may use; a velocity target can be added.
  // Friction joint: only max_force and max_torque (resistance to relative motion).
  bool use_offsets = false;
  Vec2 linear_offset = Vec2::Zero();     // [m]
  double angular_offset = 0.0;           // [rad]
  double motor_hertz = 0.0, motor_damping = 1.0;
  Vec2 linear_velocity = Vec2::Zero();   // [m/s] of b relative to a, world directions
  double angular_velocity = 0.0;         // [rad/s]
  double max_force = 0.0, max_torque = 0.0;  // [N], [N·m] ≥ 0

  // Pulley: the fixed points the rope runs over (world), and the ratio (> 0).
  Vec2 ground_a = Vec2::Zero(), ground_b = Vec2::Zero();
  double ratio = 1.0;                    // pulley and gear (gear: not 0)

  // Gear: two revolute or prismatic joints; each one's body b is geared (its body a is usually the
  // ground). The gear's a and b are those bodies; set them null, they are filled in. Or two bodies
  // a and b and no joints: their angles are geared, θ_a + ratio · θ_b constant (Chipmunk's gear).
  JointId joint_a, joint_b;
};

// A joint's current readings (World::jointState).
struct JointState {
  double angle = 0.0;        // revolute, wheel: b's angle relative to a, from creation [rad]
  double speed = 0.0;        // revolute, wheel: relative angular speed [rad/s]; prismatic: along the axis [m/s]
  double translation = 0.0;  // prismatic, wheel: along the axis [m]; distance: current length [m]
  Vec2 reaction_force = Vec2::Zero();  // on b, of the last step [N]
  double reaction_torque = 0.0;        // on b, of the last step [N·m]
  Vec2 world_anchor_a = Vec2::Zero(), world_anchor_b = Vec2::Zero();
  Vec2 axis = Vec2(1.0, 0.0);  // prismatic, wheel: the axis now (it turns with a), unit, world
  bool broken = false;       // exceeded break_force or break_torque (the joint is removed)
  Vec2 local_anchor_a = Vec2::Zero(), local_anchor_b = Vec2::Zero();  // in each body's coordinates (world: world)
  // What the motor applied in the last step: revolute, wheel: torque [N·m]; prismatic: force [N].
  double motor = 0.0;
};

}  // namespace rigidlab

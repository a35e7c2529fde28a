// The names of the Lua API, in one place: the bindings check fields and options against them, and
// tests/lua/test_annotations.cpp checks the editor annotations (scripts/meta/rigidlab.lua) list
// exactly these.
#pragma once

#include <string_view>
#include <vector>

namespace rigidlab::lua::api {

// body.<field>: readable ones (methods included) and the writable subset.
inline const std::vector<std::string_view> kBodyReadable = {
    "position", "angle", "velocity", "angular_velocity", "mass", "static", "type", "name", "restitution",
    "friction", "static_friction", "awake", "id", "center", "local_center", "inertia", "density", "shape", "radius",
    "vertices", "shapes", "removed", "linear_damping", "angular_damping", "gravity_scale", "fixed_rotation", "bullet",
    "enabled", "user_data", "sensor", "category", "mask", "group", "gravity", "sleeping_allowed", "world",
    "apply_impulse", "apply_force", "apply_torque", "apply_angular_impulse", "add_shape", "set_target", "joints",
    "contacts", "world_point", "local_point", "world_vector", "local_vector", "velocity_at", "reset_mass"};
inline const std::vector<std::string_view> kBodyWritable = {
    "position", "angle", "velocity", "angular_velocity", "mass", "static", "type", "name", "restitution",
    "friction", "static_friction", "awake", "linear_damping", "angular_damping", "gravity_scale", "fixed_rotation",
    "bullet", "enabled", "user_data", "sensor", "category", "mask", "group", "inertia", "gravity", "sleeping_allowed"};

// shape.<field> (body:add_shape returns a shape; body.shapes lists them).
inline const std::vector<std::string_view> kShapeReadable = {
    "kind", "body", "radius", "center", "vertices", "a", "b", "ghost1", "ghost2", "density", "mass", "area", "inertia",
    "bounds", "restitution", "friction", "static_friction", "sensor", "category", "mask", "group", "tangent_speed",
    "rolling_resistance", "user_data", "removed", "remove", "test_point", "ray_cast", "distance", "contact_events",
    "hit_events", "hit_speed", "one_way", "pre_solve"};
// The geometry (radius, center, vertices, a, b, ghost1, ghost2) is writable where the kind has it
// (circles: radius, center; capsules: a, b, radius; polygons: vertices; segments: a, b; chain
// segments: a, b, ghost1, ghost2).
inline const std::vector<std::string_view> kShapeWritable = {
    "radius", "center", "vertices", "a", "b", "ghost1", "ghost2", "density", "restitution", "friction",
    "static_friction", "sensor", "category", "mask", "group", "tangent_speed", "rolling_resistance", "user_data",
    "contact_events", "hit_events", "hit_speed", "one_way", "pre_solve"};

inline const std::vector<std::string_view> kWorldFields = {"gravity", "integrator", "dt", "solver", "iterations",
                                                           "substeps", "sleeping", "exact_joints", "time", "step_count",
                                                           "title", "locked"};
inline const std::vector<std::string_view> kWorldMethods = {
    "add_body", "add_box", "add_circle", "add_polygon", "add_capsule", "add_segment", "add_chain", "add_spring",
    "add_damper", "add_force", "add_revolute", "add_prismatic", "add_distance", "add_weld", "add_wheel",
    "add_motor_joint", "add_friction_joint", "add_pulley", "add_gear", "bodies", "find", "joints", "find_joint",
    "remove", "step", "kinetic_energy", "potential_energy", "contact_events", "contacts", "ray_cast", "ray_cast_all",
    "query_box", "query_point", "overlap", "shape_cast", "explode", "snapshot", "restore"};
// A snapshot handle's fields (world:snapshot()), all read-only.
inline const std::vector<std::string_view> kSnapshotFields = {"time", "step_count", "bytes"};

// What every function that makes a body takes (add_body takes only these).
inline const std::vector<std::string_view> kBodyOptions = {
    "position", "angle", "velocity", "angular_velocity", "type", "static", "name", "linear_damping",
    "angular_damping", "gravity_scale", "fixed_rotation", "bullet", "enabled", "user_data",
    // false: created asleep (BodyDef::awake)
    "awake", "gravity", "sleeping_allowed"};
// The options of a shape: body:add_shape{} and, for their one shape, add_box, add_circle, ...
inline const std::vector<std::string_view> kShapeOptions = {
    "density", "restitution", "friction", "static_friction", "sensor", "category", "mask", "group", "tangent_speed",
    "rolling_resistance", "contact_events", "hit_events", "hit_speed", "one_way", "pre_solve"};
// The one-shape world:add_* functions take kBodyOptions, kShapeOptions, these and their geometry.
inline const std::vector<std::string_view> kShapedBodyOptions = {"mass"};
inline const std::vector<std::string_view> kBoxOptions = {"width", "height"};
inline const std::vector<std::string_view> kCircleOptions = {"radius"};
inline const std::vector<std::string_view> kPolygonOptions = {"vertices", "concave"};
inline const std::vector<std::string_view> kCapsuleOptions = {"a", "b", "radius"};
inline const std::vector<std::string_view> kSegmentOptions = {"a", "b"};
inline const std::vector<std::string_view> kChainOptions = {"points", "loop"};
// body:add_shape{} takes kShapeOptions and these (user_data: the shape's; the one-shape
// world:add_* functions take the body's).
inline const std::vector<std::string_view> kAddShapeOptions = {"shape", "radius", "width",  "height",   "vertices",
                                                               "a",     "b",      "offset", "angle",    "user_data"};
inline const std::vector<std::string_view> kTargetOptions = {"position", "angle", "time"};

inline const std::vector<std::string_view> kSpringOptions = {"a", "b", "anchor", "local_a", "local_b", "stiffness",
                                                             "rest_length", "damping"};
inline const std::vector<std::string_view> kDamperOptions = {"body", "coefficient", "angular_coefficient"};
inline const std::vector<std::string_view> kForceOptions = {"body", "evaluate", "duration", "point", "other"};
inline const std::vector<std::string_view> kSceneOptions = {"title", "gravity", "dt", "integrator", "solver",
                                                            "iterations", "substeps", "sleeping", "exact_joints",
                                                            "duration",
                                                            "camera", "memory_limit", "expect_incidents",
                                                            "impacts",
                                                            // rigidlab test (docs/testing.md)
                                                            "golden", "golden_every", "golden_tolerance", "skip"};

// Joints: every add_* joint function takes kJointOptions and its own.
inline const std::vector<std::string_view> kJointOptions = {"collide_connected", "break_force", "break_torque", "name",
                                                           "user_data"};
// Every kind with an anchor (or anchor_a, anchor_b) also takes local_anchor_a and local_anchor_b.
inline const std::vector<std::string_view> kRevoluteOptions = {
    "a", "b", "anchor", "local_anchor_a", "local_anchor_b", "enable_limit", "lower_angle", "upper_angle", "enable_motor", "motor_speed", "max_motor_torque",
    "enable_spring", "spring_hertz", "spring_damping",
    "reference_angle"};
inline const std::vector<std::string_view> kPrismaticOptions = {
    "a", "b", "anchor", "local_anchor_a", "local_anchor_b", "axis", "enable_limit", "lower", "upper", "enable_motor",
    "motor_speed", "max_motor_force",
    "enable_spring", "spring_hertz", "spring_damping",
    "reference_angle"};
inline const std::vector<std::string_view> kDistanceOptions = {
    "a", "b", "anchor_a", "anchor_b", "local_anchor_a", "local_anchor_b", "length", "enable_limit", "min_length",
    "max_length", "enable_spring",
    "spring_hertz", "spring_damping", "max_spring_force"};
inline const std::vector<std::string_view> kWeldOptions = {"a", "b", "anchor", "local_anchor_a", "local_anchor_b",
                                                           "linear_hertz", "linear_damping",
                                                           "angular_hertz", "angular_damping",
                                                           "reference_angle"};
inline const std::vector<std::string_view> kWheelOptions = {
    "a", "b", "anchor", "local_anchor_a", "local_anchor_b", "axis", "enable_limit", "lower", "upper", "enable_motor",
    "motor_speed", "max_motor_torque", "enable_spring", "spring_hertz", "spring_damping",
    "reference_angle"};
inline const std::vector<std::string_view> kMotorJointOptions = {
    "a", "b", "anchor", "local_anchor_a", "local_anchor_b", "linear_offset", "angular_offset", "linear_velocity", "angular_velocity", "max_force",
    "max_torque", "motor_hertz", "motor_damping"};
inline const std::vector<std::string_view> kFrictionJointOptions = {"a", "b", "anchor", "local_anchor_a",
                                                                    "local_anchor_b", "max_force", "max_torque"};
inline const std::vector<std::string_view> kPulleyOptions = {"a", "b", "anchor_a", "anchor_b", "local_anchor_a",
                                                             "local_anchor_b", "ground_a", "ground_b", "ratio"};
// joint_a and joint_b (two revolute or prismatic joints), or a and b (two bodies' angles).
inline const std::vector<std::string_view> kGearOptions = {"joint_a", "joint_b", "a", "b", "ratio"};

// joint.<field>: what every joint has (methods included); the writable ones of kJointOptions; and
// each kind's own fields, writable unless listed in kJointReadOnly.
inline const std::vector<std::string_view> kJointReadable = {
    "kind", "a", "b", "name", "collide_connected", "break_force", "break_torque", "user_data", "angle", "speed",
    "translation", "reaction_force", "reaction_torque", "anchor_a", "anchor_b", "broken", "removed", "remove"};
inline const std::vector<std::string_view> kJointWritable = {"name", "collide_connected", "break_force",
                                                             "break_torque", "user_data"};
inline const std::vector<std::string_view> kJointReadOnly = {"ground_a", "ground_b", "joint_a", "joint_b",
                                                             "set_limits", "reference_angle", "local_anchor_a",
                                                             "local_anchor_b", "axis", "motor_torque", "motor_force",
                                                             "length_a", "length_b"};

// The option lists of the joint functions, in JointType order (revolute ... gear).
inline const std::vector<const std::vector<std::string_view>*> kJointKindOptions = {
    &kRevoluteOptions, &kPrismaticOptions, &kDistanceOptions,      &kWeldOptions,  &kWheelOptions,
    &kMotorJointOptions, &kFrictionJointOptions, &kPulleyOptions, &kGearOptions};

// The fields a joint handle has besides kJointReadable: its kind's options that are not fixed at
// creation (the bodies, world anchors and axis), set_limits for the kinds with limits, the axis
// of the kinds with one, the motor's torque or force, and a pulley's constant and rope lengths.
inline std::vector<std::string_view> jointOwnFields(const std::vector<std::string_view>& options) {
  std::vector<std::string_view> own;
  bool limits = false, axis = false, torque = false, force = false, pulley = false;
  for (std::string_view name : options) {
    limits = limits || name == "enable_limit";
    axis = axis || name == "axis";
    torque = torque || name == "max_motor_torque";
    force = force || name == "max_motor_force";
    pulley = pulley || name == "ground_a";
    if (name != "a" && name != "b" && name != "anchor" && name != "anchor_a" && name != "anchor_b" && name != "axis")
      own.push_back(name);
  }
  if (limits) own.push_back("set_limits");
  if (axis) own.push_back("axis");
  if (torque) own.push_back("motor_torque");
  if (force) own.push_back("motor_force");
  if (pulley) {
    own.push_back("length");
    own.push_back("length_a");
    own.push_back("length_b");
  }
  return own;
}

// --- events and queries (lua_events.cpp, lua_contact.cpp, lua_query.cpp)
// The shape options and fields of events (also in kShapeOptions, kShapeReadable, kShapeWritable).
inline const std::vector<std::string_view> kShapeEventOptions = {"contact_events", "hit_events", "hit_speed", "one_way",
                                                                 "pre_solve"};
// A shape's surface options and fields (also in kShapeOptions, kShapeReadable, kShapeWritable).
inline const std::vector<std::string_view> kShapeSurfaceOptions = {"tangent_speed", "rolling_resistance"};
// The hooks a scene may define for the events of a step, in the order they are called.
inline const std::vector<std::string_view> kEventHooks = {"OnContactBegin", "OnContactEnd",   "OnHit",
                                                          "OnSensorBegin",  "OnSensorEnd",    "OnJointBreak"};
// The collision filter hook: ShouldCollide(shape_a, shape_b), during the step (lua_events.cpp).
inline const std::vector<std::string_view> kFilterHooks = {"ShouldCollide"};
// A contact as hooks, pre_solve functions, body:contacts() and world:contact_events() give it
// (the events also have `kind`).
inline const std::vector<std::string_view> kContactFields = {
    "a", "b", "shape_a", "shape_b", "point", "normal", "approach_speed", "normal_impulse", "tangent_impulse", "points",
    "friction", "static_friction", "restitution", "tangent_speed", "rolling_resistance", "touching"};
// Each of a contact's `points`.
inline const std::vector<std::string_view> kContactPointFields = {"point", "separation", "normal_impulse",
                                                                  "tangent_impulse"};
// What a pre_solve function may write in its contact table (for that step), besides returning false.
inline const std::vector<std::string_view> kPreSolveWritable = {"friction", "static_friction", "restitution",
                                                                "tangent_speed", "enabled"};
// A hit of a ray or shape cast.
inline const std::vector<std::string_view> kQueryHitFields = {"body", "shape", "point", "normal", "fraction"};
// The filter every query takes.
inline const std::vector<std::string_view> kQueryFilterOptions = {"category", "mask", "sensors"};
inline const std::vector<std::string_view> kRayCastOptions = {"from", "to"};
inline const std::vector<std::string_view> kQueryBoxOptions = {"lower", "upper"};
inline const std::vector<std::string_view> kQueryPointOptions = {"point"};
inline const std::vector<std::string_view> kOverlapOptions = {"shape", "position", "angle"};
inline const std::vector<std::string_view> kShapeCastOptions = {"shape", "from", "to", "angle"};
// The shape of overlap{} and shape_cast{}: add_shape's kind and geometry.
inline const std::vector<std::string_view> kQueryShapeOptions = {"shape", "radius", "width", "height", "vertices", "a", "b"};
inline const std::vector<std::string_view> kExplodeOptions = {"position", "radius", "falloff", "impulse", "category", "mask"};
// --- sandbox mod hooks: OnMouse's event, scene.keys and scene.controls, world.controls, draw.
inline const std::vector<std::string_view> kSceneModOptions = {"keys", "controls"};  // besides kSceneOptions
inline const std::vector<std::string_view> kWorldModFields = {"controls"};           // besides kWorldFields
inline const std::vector<std::string_view> kControlOptions = {"name", "kind", "min", "max", "value"};
inline const std::vector<std::string_view> kControlKinds = {"slider", "button"};
inline const std::vector<std::string_view> kMouseEventFields = {"kind", "button", "position", "screen",
                                                                "shift", "ctrl", "alt", "wheel"};
inline const std::vector<std::string_view> kMouseEventKinds = {"press", "release", "move", "wheel"};
inline const std::vector<std::string_view> kMouseButtons = {"left", "right", "middle"};
inline const std::vector<std::string_view> kDrawFunctions = {"line", "circle", "text", "polygon", "capsule", "screen"};

}  // namespace rigidlab::lua::api

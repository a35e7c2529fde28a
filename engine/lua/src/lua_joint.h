// Joints in Lua, shared by the world's joint functions (lua_world_joints.cpp) and the joint handles
// (lua_joint.cpp): one table of the JointDef fields a script sets, both as options at creation and
// as fields of a handle afterwards, so the two read, check and enable alike.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bindings.h"
#include "lua_args.h"

namespace rigidlab::lua {

// A field of JointDef under its Lua name. Giving a limit, motor or spring value turns that part of
// the joint on (`enables`): lower_angle, upper_angle, lower, upper, min_length, max_length →
// enable_limit; motor_speed, max_motor_torque, max_motor_force → enable_motor; spring_hertz →
// enable_spring when > 0 (and off at 0); linear_offset, angular_offset → use_offsets.
struct JointField {
  std::string_view name;
  enum class Type { Number, Boolean, Vector } type = Type::Number;
  Range range = Range::Finite;
  double JointDef::*number = nullptr;
  bool JointDef::*flag = nullptr;
  Vec2 JointDef::*vector = nullptr;
  bool JointDef::*enables = nullptr;
};
// The field named `name` (nullptr if no JointDef field has that Lua name: a, b, anchor, name, ...).
const JointField* jointField(std::string_view name);
// Checks `value` and sets the field in `def`, with what it enables. `subject`: the option's name
// at creation, empty for a field write (the function names the field then).
void setJointField(lua_State* L, std::string_view function, std::string_view subject, const JointField& field,
                   const sol::object& value, JointDef& def);
sol::object jointFieldValue(lua_State* L, const JointField& field, const JointDef& def);

// The Lua face of each joint type: its function ("add_revolute") and its own options (api_names.h).
const char* jointFunction(JointType type);
const std::vector<std::string_view>& jointOptions(JointType type);
// The fields a handle of this type has besides the common ones (api::jointOwnFields).
std::vector<std::string_view> jointOwnFields(JointType type);
bool hasLimits(JointType type);  // revolute, prismatic, wheel, distance
// The core's field names in messages as the Lua API names them: revolute limits are lower_angle
// and upper_angle, the one anchor of most types is `anchor`, and a joint pinned to the world
// (b omitted) has its anchors the other way round in the core (lua_world_joints.cpp).
std::vector<std::pair<std::string_view, std::string_view>> jointRenames(JointType type, bool swapped);

// The names of the same thing in the other joint types (revolute lower_angle, prismatic lower),
// suggested for a name this type does not have.
Options::Synonyms jointSynonyms(JointType type);

// The core holds a joint pinned to the world with the world as its body a, so that its angle,
// speed and translation are the body's own; Lua shows the body as `a` and the world as b = nil.
inline bool pinnedToWorld(const JointDef& def) { return def.a.isNull() && !def.b.isNull(); }

// The handle of a live joint (cached, weak); "revolute joint 'hinge'" for messages.
sol::object jointHandle(lua_State* L, Scene::Impl& scene, JointId id);
std::string describeJoint(const LuaJoint& joint);

}  // namespace rigidlab::lua

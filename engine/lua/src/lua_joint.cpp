// Joint handles in Lua (world:add_revolute{...} and the other joint functions return one).
//
//   read        kind, a, b (nil: the world), angle, speed, translation, reaction_force,
//               reaction_torque, anchor_a, anchor_b (world, now), local_anchor_a, local_anchor_b
//               (each body's coordinates), broken, removed; per type ground_a, ground_b, joint_a,
//               joint_b, axis (prismatic, wheel: world, now), motor_torque (revolute, wheel),
//               motor_force (prismatic), length_a, length_b (pulley: the ropes now)
//   read/write  name, collide_connected, break_force, break_torque, user_data and the type's
//               limits, motor, spring and offsets (the same names as its options; see JointField),
//               length (distance; pulley: length_a + ratio · length_b), ratio (gear, pulley)
//   methods     joint:remove(), joint:set_limits(lower, upper)
#include "lua_joint.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "api_names.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

using T = JointField::Type;

// clang-format off
const JointField kFields[] = {
    {"collide_connected", T::Boolean, Range::Finite, nullptr, &JointDef::collide_connected},
    {"break_force",       T::Number, Range::PositiveOrInfinity, &JointDef::break_force},
    {"break_torque",      T::Number, Range::PositiveOrInfinity, &JointDef::break_torque},
    {"enable_limit",      T::Boolean, Range::Finite, nullptr, &JointDef::enable_limit},
    {"enable_motor",      T::Boolean, Range::Finite, nullptr, &JointDef::enable_motor},
    {"enable_spring",     T::Boolean, Range::Finite, nullptr, &JointDef::enable_spring},
    {"lower_angle",       T::Number, Range::Finite, &JointDef::lower, nullptr, nullptr, &JointDef::enable_limit},
    {"upper_angle",       T::Number, Range::Finite, &JointDef::upper, nullptr, nullptr, &JointDef::enable_limit},
    {"lower",             T::Number, Range::Finite, &JointDef::lower, nullptr, nullptr, &JointDef::enable_limit},
    {"upper",             T::Number, Range::Finite, &JointDef::upper, nullptr, nullptr, &JointDef::enable_limit},
    {"min_length",        T::Number, Range::NonNegative, &JointDef::min_length, nullptr, nullptr, &JointDef::enable_limit},
    {"max_length",        T::Number, Range::NonNegativeOrInfinity, &JointDef::max_length, nullptr, nullptr, &JointDef::enable_limit},
    {"motor_speed",       T::Number, Range::Finite, &JointDef::motor_speed, nullptr, nullptr, &JointDef::enable_motor},
    {"max_motor_torque",  T::Number, Range::NonNegative, &JointDef::max_motor_torque, nullptr, nullptr, &JointDef::enable_motor},
    {"max_motor_force",   T::Number, Range::NonNegative, &JointDef::max_motor_force, nullptr, nullptr, &JointDef::enable_motor},
    {"spring_hertz",      T::Number, Range::NonNegative, &JointDef::spring_hertz, nullptr, nullptr, &JointDef::enable_spring},
    {"spring_damping",    T::Number, Range::NonNegative, &JointDef::spring_damping},
    {"max_spring_force",  T::Number, Range::NonNegativeOrInfinity, &JointDef::max_spring_force},
    {"length",            T::Number, Range::NonNegative, &JointDef::length},
    {"linear_hertz",      T::Number, Range::NonNegative, &JointDef::linear_hertz},
    {"linear_damping",    T::Number, Range::NonNegative, &JointDef::linear_damping},
    {"angular_hertz",     T::Number, Range::NonNegative, &JointDef::angular_hertz},
    {"angular_damping",   T::Number, Range::NonNegative, &JointDef::angular_damping},
    {"linear_offset",     T::Vector, Range::Finite, nullptr, nullptr, &JointDef::linear_offset, &JointDef::use_offsets},
    {"angular_offset",    T::Number, Range::Finite, &JointDef::angular_offset, nullptr, nullptr, &JointDef::use_offsets},
    {"linear_velocity",   T::Vector, Range::Finite, nullptr, nullptr, &JointDef::linear_velocity},
    {"angular_velocity",  T::Number, Range::Finite, &JointDef::angular_velocity},
    {"max_force",         T::Number, Range::NonNegative, &JointDef::max_force},
    {"max_torque",        T::Number, Range::NonNegative, &JointDef::max_torque},
    {"motor_hertz",       T::Number, Range::NonNegative, &JointDef::motor_hertz},
    {"motor_damping",     T::Number, Range::NonNegative, &JointDef::motor_damping},
    {"ground_a",          T::Vector, Range::Finite, nullptr, nullptr, &JointDef::ground_a},
    {"ground_b",          T::Vector, Range::Finite, nullptr, nullptr, &JointDef::ground_b},
    {"ratio",             T::Number, Range::Finite, &JointDef::ratio},
};

// In JointType order.
const char* const kFunctions[] = {"add_revolute", "add_prismatic", "add_distance",       "add_weld",  "add_wheel",
                                  "add_motor_joint", "add_friction_joint", "add_pulley", "add_gear"};
static_assert(std::size(kFunctions) == kJointTypes);
// clang-format on

bool contains(const std::vector<std::string_view>& list, std::string_view name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

const LuaJoint& selfJoint(lua_State* L, std::string_view function) {
  const LuaJoint* j = toHandle<LuaJoint>(L, 1);
  if (!j) fail(L, function, "call it as joint:" + std::string(function) + "(...), with a colon; got " + describe(L, 1));
  return *j;
}

std::string kindName(const LuaJoint& j) { return std::string(jointTypeName(j.type)) + " joint"; }

// The joint a handle designates; fails "<function>: the revolute joint broke and was removed".
JointId liveJoint(lua_State* L, const LuaJoint& j, std::string_view function) {
  if (!liveWorld(L, *j.scene, function).isValid(j.id))
    fail(L, function,
         "the " + kindName(j) +
             (j.scene->broken_joints.count(handleKey(j.id.index, j.id.generation)) ? " broke and was removed"
                                                                                   : " was removed"));
  return j.id;
}

// The names a joint of this type answers to, for "has no field" and its suggestion.
std::vector<std::string_view> fieldsOf(JointType type) {
  std::vector<std::string_view> all = api::kJointReadable;
  const std::vector<std::string_view> own = jointOwnFields(type);
  all.insert(all.end(), own.begin(), own.end());
  return all;
}

[[noreturn]] void unknownField(lua_State* L, const LuaJoint& j, const std::string& k,
                               const std::vector<std::string_view>& names) {
  std::string hint;
  for (const auto& [name, meant] : jointSynonyms(j.type))
    if (name == k) hint = std::string(meant);
  noSuchField(L, kindName(j), k, names, hint);
}

void update(lua_State* L, World& w, const LuaJoint& j, std::string_view function, const JointDef& def) {
  try {
    w.updateJoint(j.id, def);
  } catch (const InputError& e) {
    failCore(L, function, e, jointRenames(j.type, pinnedToWorld(def)));
  }
}

int removeMethod(lua_State* L) {
  const LuaJoint& j = selfJoint(L, "remove");
  requireIdle(L, *j.scene, "remove");
  if (liveWorld(L, *j.scene, "remove").isValid(j.id)) liveWorld(L, *j.scene, "remove").destroyJoint(j.id);
  return 0;  // removing a removed joint does nothing, as for forces and shapes
}

// joint:set_limits(lower, upper): both bounds at once (one at a time could pass the other).
int setLimits(lua_State* L) {
  const LuaJoint& j = selfJoint(L, "set_limits");
  if (!hasLimits(j.type)) fail(L, "set_limits", "a " + kindName(j) + " has no limits");
  requireIdle(L, *j.scene, "set_limits");
  World& w = liveWorld(L, *j.scene, "set_limits");
  JointDef def = w.joint(liveJoint(L, j, "set_limits"));
  const char* lower = j.type == JointType::Revolute   ? "lower_angle"
                      : j.type == JointType::Distance ? "min_length"
                                                      : "lower";
  const char* upper = j.type == JointType::Revolute   ? "upper_angle"
                      : j.type == JointType::Distance ? "max_length"
                                                      : "upper";
  setJointField(L, "set_limits", lower, *jointField(lower), sol::stack_object(L, 2), def);
  setJointField(L, "set_limits", upper, *jointField(upper), sol::stack_object(L, 3), def);
  update(L, w, j, "set_limits", def);
  return 0;
}

// The body Lua shows as `a` or `b` (pinnedToWorld), or nil.
void pushBody(lua_State* L, Scene::Impl& scene, BodyId id) {
  if (id.isNull() || !scene.world->isValid(id)) {
    lua_pushnil(L);
  } else {
    bodyHandle(L, scene, id).push(L);
  }
}

int jointIndex(lua_State* L) {
  const LuaJoint& self = selfJoint(L, "joint");
  sol::stack_object key(L, 2);
  const std::string k = fieldName(L, "joint", key);
  const std::vector<std::string_view> names = fieldsOf(self.type);
  if (!contains(names, k)) unknownField(L, self, k, names);
  Scene::Impl& scene = *self.scene;
  const World& w = liveWorld(L, scene, "joint." + k);
  if (k == "kind") {
    lua_pushstring(L, jointTypeName(self.type));
    return 1;
  }
  if (k == "removed" || k == "broken") {
    lua_pushboolean(L, k == "removed" ? !w.isValid(self.id)
                                      : scene.broken_joints.count(handleKey(self.id.index, self.id.generation)) > 0);
    return 1;
  }
  if (k == "remove" || k == "set_limits") {
    lua_pushcfunction(L, k == "remove" ? guarded<removeMethod> : guarded<setLimits>);
    return 1;
  }
  if (k == "user_data") {  // also of a broken or removed joint: what the script gave it
    scene.joint_user_data.raw_get<sol::object>(static_cast<lua_Integer>(handleKey(self.id.index, self.id.generation))).push(L);
    return 1;
  }
  const JointDef& def = w.joint(liveJoint(L, self, "joint." + k));
  const bool pinned = pinnedToWorld(def);
  if (k == "a" || k == "b") {
    pushBody(L, scene, k == "a" ? (pinned ? def.b : def.a) : (pinned ? BodyId{} : def.b));
  } else if (k == "name") {
    lua_pushlstring(L, def.name.data(), def.name.size());
  } else if (k == "joint_a" || k == "joint_b") {
    const JointId g = k == "joint_a" ? def.joint_a : def.joint_b;
    if (!w.isValid(g)) return 0;
    jointHandle(L, scene, g).push(L);
  } else if (const JointField* f = jointField(k)) {
    jointFieldValue(L, *f, def).push(L);
  } else {
    const JointState s = w.jointState(self.id);
    if (k == "reference_angle") {
      // As given, or else the relative angle at creation: b's angle relative to a now, less the
      // joint angle counted from it (the core keeps no other record of it).
      const auto angle = [&](BodyId id) { return id.isNull() ? 0.0 : w.body(id).angle; };
      lua_pushnumber(L, def.reference_angle ? *def.reference_angle : angle(def.b) - angle(def.a) - s.angle);
      return 1;
    }
    // The core's a is the world for a joint pinned to it: its anchors are the other way round.
    const Vec2& on_a = pinned ? s.world_anchor_b : s.world_anchor_a;
    const Vec2& on_b = pinned ? s.world_anchor_a : s.world_anchor_b;
    const Vec2& local_a = pinned ? s.local_anchor_b : s.local_anchor_a;
    const Vec2& local_b = pinned ? s.local_anchor_a : s.local_anchor_b;
    if (k == "reaction_force" || k == "anchor_a" || k == "anchor_b") {
      pushVec(L, k == "reaction_force" ? s.reaction_force : k == "anchor_a" ? on_a : on_b);
    } else if (k == "local_anchor_a" || k == "local_anchor_b") {
      pushVec(L, k == "local_anchor_a" ? local_a : local_b);
    } else if (k == "axis") {
      pushVec(L, s.axis);
    } else if (k == "motor_torque" || k == "motor_force") {
      lua_pushnumber(L, s.motor);
    } else if (k == "length_a" || k == "length_b") {
      lua_pushnumber(L, k == "length_a" ? (on_a - def.ground_a).norm() : (on_b - def.ground_b).norm());
    } else {
      lua_pushnumber(L, k == "angle" ? s.angle : k == "speed" ? s.speed : k == "translation" ? s.translation : s.reaction_torque);
    }
  }
  return 1;
}

int jointNewIndex(lua_State* L) {
  const LuaJoint& self = selfJoint(L, "joint");
  sol::stack_object key(L, 2), value(L, 3);
  const std::string k = fieldName(L, "joint", key);
  const std::string function = "joint." + k;
  const std::vector<std::string_view> names = fieldsOf(self.type);
  const std::vector<std::string_view> own = jointOwnFields(self.type);
  const bool writable = contains(api::kJointWritable, k) || (contains(own, k) && !contains(api::kJointReadOnly, k));
  if (!writable) {
    if (contains(names, k)) fail(L, function, "is read-only");
    unknownField(L, self, k, names);
  }
  requireIdle(L, *self.scene, function);
  World& w = liveWorld(L, *self.scene, function);
  JointDef def = w.joint(liveJoint(L, self, function));
  if (k == "user_data") {
    self.scene->joint_user_data.raw_set(static_cast<lua_Integer>(handleKey(self.id.index, self.id.generation)),
                                        sol::object(value));
    return 0;
  }
  if (k == "name") {
    if (value.get_type() != sol::type::string) fail(L, function, "must be a string, got " + describe(value));
    def.name = boundedString(L, 3, function, "", kNameBytes);
  } else {
    setJointField(L, function, "", *jointField(k), sol::object(value), def);
  }
  update(L, w, self, function, def);
  return 0;
}

}  // namespace

const JointField* jointField(std::string_view name) {
  for (const JointField& f : kFields)
    if (f.name == name) return &f;
  return nullptr;
}

void setJointField(lua_State* L, std::string_view function, std::string_view subject, const JointField& f,
                   const sol::object& value, JointDef& def) {
  switch (f.type) {
    case T::Boolean:
      def.*f.flag = checkBool(L, function, subject, value);
      break;
    case T::Vector:
      def.*f.vector = checkVec(L, function, subject, value);
      break;
    case T::Number:
      def.*f.number = checkNumber(L, function, subject, value, f.range);
      break;
  }
  if (f.enables == &JointDef::enable_spring)
    def.enable_spring = def.*f.number > 0.0;
  else if (f.enables)
    def.*f.enables = true;
}

sol::object jointFieldValue(lua_State* L, const JointField& f, const JointDef& def) {
  switch (f.type) {
    case T::Boolean:
      return sol::make_object(L, def.*f.flag);
    case T::Vector:
      return makeVec(L, def.*f.vector);
    case T::Number:
      break;
  }
  return sol::make_object(L, def.*f.number);
}

const char* jointFunction(JointType type) { return kFunctions[static_cast<size_t>(type)]; }

const std::vector<std::string_view>& jointOptions(JointType type) {
  return *api::kJointKindOptions[static_cast<size_t>(type)];
}

bool hasLimits(JointType type) {
  const auto& o = jointOptions(type);
  return std::find(o.begin(), o.end(), "enable_limit") != o.end();
}

std::vector<std::string_view> jointOwnFields(JointType type) { return api::jointOwnFields(jointOptions(type)); }

std::vector<std::pair<std::string_view, std::string_view>> jointRenames(JointType type, bool swapped) {
  if (type == JointType::Revolute) return {{"lower", "lower_angle"}, {"upper", "upper_angle"}, {"anchor_a", "anchor"}};
  if (type == JointType::Distance || type == JointType::Pulley) {
    if (swapped) return {{"anchor_a", "anchor_b"}, {"anchor_b", "anchor_a"}};
    return {};
  }
  return {{"anchor_a", "anchor"}};
}

Options::Synonyms jointSynonyms(JointType type) {
  if (type == JointType::Revolute)
    return {{"lower", "lower_angle"}, {"upper", "upper_angle"}, {"max_motor_force", "max_motor_torque"}};
  if (type == JointType::Prismatic)
    return {{"lower_angle", "lower"}, {"upper_angle", "upper"}, {"max_motor_torque", "max_motor_force"}};
  if (type == JointType::Wheel)
    return {{"lower_angle", "lower"}, {"upper_angle", "upper"}, {"max_motor_force", "max_motor_torque"}};
  return {};
}

void registerJointType(lua_State* L) {
  registerHandleType(L, LuaJoint::kMetatable, guarded<jointIndex>, guarded<jointNewIndex>,
                     guarded<handleToString<LuaJoint, describeJoint>>, guarded<handlesEqual<LuaJoint, &LuaJoint::id>>);
}

sol::object jointHandle(lua_State* L, Scene::Impl& scene, JointId id) {
  return cachedHandle(L, scene.joint_handles, handleKey(id.index, id.generation),
                      LuaJoint{&scene, id, scene.world->joint(id).type});
}

std::string describeJoint(const LuaJoint& j) {
  const World* w = j.scene->world.get();
  const std::string kind = kindName(j);
  if (!w || !w->isValid(j.id)) return kind + " (removed)";
  const std::string& name = w->joint(j.id).name;
  return name.empty() ? kind : kind + " '" + displayText(name, 40) + "'";
}

void removeJoint(lua_State* L, const LuaJoint& joint, std::string_view function) {
  liveWorld(L, *joint.scene, function).destroyJoint(liveJoint(L, joint, function));
}

void noteJointBreaks(Scene::Impl& scene) {
  if (!scene.world) return;
  for (const World::JointBreakInfo& b : scene.world->jointBreaks())
    scene.broken_joints.insert(handleKey(b.id.index, b.id.generation));
}

}  // namespace rigidlab::lua

// The world's joint functions (docs/lua-api.md "Joints"): add_revolute, add_prismatic,
// add_distance, add_weld, add_wheel, add_motor_joint, add_friction_joint, add_pulley, add_gear,
// each returning a joint handle (lua_joint.cpp); world:joints(), world:find_joint(name) and
// body:joints().
//
// `b` may be omitted: the joint pins `a` to the world. The core then gets the world as its body a
// and `a` as its body b (pinnedToWorld), so that a pinned body's angle, speed and translation read
// as its own, motor_speed > 0 turns it counter-clockwise and an axis stays fixed in the world.
#include "api_names.h"
#include "lua_joint.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

// The JointDef fields a joint's options set, then the explicit enable_limit, enable_motor and
// enable_spring, which win over what the other options enable.
void readTunables(const Options& o, JointDef& d) {
  const std::vector<std::string_view> names = joined({&api::kJointOptions, &jointOptions(d.type)});
  for (const bool enables : {false, true})
    for (std::string_view name : names) {
      const JointField* f = jointField(name);
      if (f && o.has(name) && name.starts_with("enable_") == enables)
        setJointField(o.L(), o.function(), name, *f, o.get(name), d);
    }
  d.name = o.string("name", "", kNameBytes);
}

// A limit has two bounds, and a motor needs its torque (or force): one given without the other is
// refused rather than left at 0.
void requireTogether(const Options& o, std::string_view first, std::string_view second, const char* why) {
  if (o.has(first) != o.has(second))
    o.fail(o.has(first) ? second : first,
           "is required with " + std::string(o.has(first) ? first : second) + " (" + why + ")");
}

std::string bodyType(const World& w, BodyId id) {
  return id.isNull() ? "" : std::string(", ") + bodyTypeName(w.body(id).type);
}

// a, and b or the world; at least one of them dynamic.
std::pair<BodyId, BodyId> readBodies(const Options& o, Scene::Impl& scene, bool b_required) {
  lua_State* L = o.L();
  if (!o.has("a")) o.fail("a", "is required: the body the joint holds (from world:add_box, add_circle, ...)");
  const BodyId a = bodyOption(L, scene, o.function(), "a", o.get("a"));
  BodyId b;
  if (o.has("b")) {
    b = bodyOption(L, scene, o.function(), "b", o.get("b"));
    if (b == a) o.fail("b", "must be another body than a, got the same " + describe(o.get("b")));
  } else if (b_required) {
    o.fail("b", "is required: a pulley joins two bodies");
  }
  const World& w = *scene.world;
  if (!w.body(a).isDynamic() && (b.isNull() || !w.body(b).isDynamic()))
    o.fail("a", "and b are both static or kinematic (a: " + describe(o.get("a")) + bodyType(w, a) +
                    "; b: " + (b.isNull() ? std::string("the world") : describe(o.get("b")) + bodyType(w, b)) +
                    "): at least one of the joint's bodies must be dynamic (a joint between static or kinematic "
                    "bodies does nothing)");
  return {a, b};
}

JointId jointOption(const Options& o, Scene::Impl& scene, std::string_view key) {
  const sol::object v = o.get(key);
  v.push(o.L());
  const LuaJoint* j = toHandle<LuaJoint>(o.L(), -1);
  lua_pop(o.L(), 1);
  if (!j)
    o.fail(key, (o.has(key) ? "must be a joint (from world:add_revolute or add_prismatic), got " + describe(v)
                            : std::string("is required: a revolute or prismatic joint")));
  if (j->scene != &scene) o.fail(key, "is a joint of another scene");
  if (!scene.world->isValid(j->id)) o.fail(key, "is " + describe(v) + ", which was removed");
  return j->id;
}

// Each body's own anchor (local_anchor_a, local_anchor_b: body coordinates; the world's for the
// world) instead of world anchors: refused together with them. A missing one is where the other
// anchor is now (the joint starts satisfied); a distance or pulley joint's, the body's centre of
// mass as for its world anchors, and a world end must be given. True if the local form was used.
// `a`, `b`: the Lua bodies (b null: the world); the core's are swapped when pinned (d.a null).
bool readLocalAnchors(const Options& o, const World& w, BodyId a, BodyId b, JointDef& d) {
  const bool local = o.has("local_anchor_a") || o.has("local_anchor_b");
  if (!local) return false;
  const bool two = d.type == JointType::Distance || d.type == JointType::Pulley;
  for (const char* world_form : {"anchor", "anchor_a", "anchor_b"})
    if (o.has(world_form))
      o.fail(world_form, std::string("and ") + (o.has("local_anchor_a") ? "local_anchor_a" : "local_anchor_b") +
                             " cannot both be given: " + (two ? "anchor_a and anchor_b are world points" : "anchor is one world point for both bodies") +
                             ", local_anchor_a and local_anchor_b each body's own point in its own coordinates; "
                             "give one form or the other");
  if (d.type == JointType::Motor && o.has("local_anchor_a") && o.has("linear_offset"))
    o.fail("local_anchor_a", "and linear_offset cannot both be given: a motor joint's local_anchor_a is its target "
                             "in a's coordinates, the linear offset");
  const auto frame = [&](BodyId id) { return id.isNull() ? Transform{} : w.body(id).xf; };
  const auto centre = [&](BodyId id) { return id.isNull() ? Vec2(Vec2::Zero()) : w.body(id).local_center; };
  Vec2 la, lb;
  if (two) {
    if (b.isNull() && !o.has("local_anchor_b"))
      o.fail("local_anchor_b", "is required: the joint holds a to the world, and this is its world point");
    la = o.vec("local_anchor_a", centre(a));
    lb = o.vec("local_anchor_b", centre(b));
  } else if (o.has("local_anchor_a")) {
    la = o.vec("local_anchor_a");
    lb = o.has("local_anchor_b") ? o.vec("local_anchor_b") : frame(b).applyInverse(frame(a).apply(la));
  } else {
    lb = o.vec("local_anchor_b");
    la = frame(a).applyInverse(frame(b).apply(lb));
  }
  const bool pinned = b.isNull();
  d.local_anchor_a = pinned ? lb : la;
  d.local_anchor_b = pinned ? la : lb;
  return true;
}

// A gear of two bodies' angles (a, b) or of two joints (joint_a, joint_b).
void readGeared(const Options& o, Scene::Impl& scene, JointDef& d) {
  if (!o.has("a") && !o.has("b")) {
    d.joint_a = jointOption(o, scene, "joint_a");
    d.joint_b = jointOption(o, scene, "joint_b");
    return;
  }
  for (const char* joint : {"joint_a", "joint_b"})
    if (o.has(joint))
      o.fail(joint, std::string("and ") + (o.has("a") ? "a" : "b") +
                        " cannot both be given: a gear joins two joints (joint_a, joint_b) or two bodies' angles (a, b)");
  if (!o.has("a") || !o.has("b"))
    o.fail(o.has("a") ? "b" : "a", "is required: a gear of bodies joins the angles of two bodies, a and b");
  const auto [a, b] = readBodies(o, scene, true);
  d.a = a;
  d.b = b;
}

int addJoint(lua_State* L, JointType type) {
  const char* function = jointFunction(type);
  Scene::Impl& scene = editedWorld(L, function);
  const Options o(L, function, sol::stack_object(L, 2), joined({&jointOptions(type), &api::kJointOptions}),
                  jointSynonyms(type));
  World& w = *scene.world;
  JointDef d;
  d.type = type;
  bool pinned = false;
  if (type == JointType::Gear) {
    readGeared(o, scene, d);
  } else {
    const auto [a, b] = readBodies(o, scene, type == JointType::Pulley);
    pinned = b.isNull();
    d.a = pinned ? BodyId{} : a;
    d.b = pinned ? a : b;
    if (readLocalAnchors(o, w, a, b, d)) {
      // The world anchors follow from the local ones (the core's createJoint).
    } else if (type == JointType::Distance || type == JointType::Pulley) {
      // Default: the centres of mass; a world end must be given.
      const Vec2 anchor_a = o.vec("anchor_a", w.body(a).center);
      const Vec2 anchor_b = pinned ? o.vec("anchor_b") : o.vec("anchor_b", w.body(b).center);
      d.anchor_a = pinned ? anchor_b : anchor_a;
      d.anchor_b = pinned ? anchor_a : anchor_b;
    } else if (type == JointType::Motor || type == JointType::Friction) {
      d.anchor_a = o.vec("anchor", w.body(d.b).center);  // the driven body's centre of mass
    } else {
      d.anchor_a = o.vec("anchor");  // where a pin or weld holds is the scene's choice
    }
    if (type == JointType::Prismatic || type == JointType::Wheel) d.axis = o.vec("axis");
    if (type == JointType::Pulley)
      for (const char* ground : {"ground_a", "ground_b"})
        if (!o.has(ground)) o.fail(ground, "is required: the fixed world point the rope runs over");
  }
  readTunables(o, d);
  // The relative angle that counts as 0 (limits, springs, the weld's glued angle): a ragdoll's
  // bones built straight but meant to rest bent. Only the kinds whose options list it accept it.
  if (o.has("reference_angle")) d.reference_angle = o.number("reference_angle");
  if (type == JointType::Revolute) requireTogether(o, "lower_angle", "upper_angle", "an angle limit has two bounds");
  if (type == JointType::Prismatic || type == JointType::Wheel)
    requireTogether(o, "lower", "upper", "a limit has two bounds");
  const char* strength = type == JointType::Prismatic ? "max_motor_force" : "max_motor_torque";
  if (o.has("motor_speed") && !o.has(strength))
    o.fail(strength, std::string("is required with motor_speed (without it the motor has no ") +
                         (type == JointType::Prismatic ? "force" : "torque") + ")");
  if (type == JointType::Pulley && !(d.ratio > 0.0)) o.fail("ratio", "must be > 0, got " + formatNumber(d.ratio));
  if (type == JointType::Gear && d.ratio == 0.0) o.fail("ratio", "must not be 0");

  JointId id;
  try {
    id = w.createJoint(d);
  } catch (const InputError& e) {
    failCore(L, function, e, jointRenames(type, pinned));
  }
  chargeJoint(L, scene, function, id);
  // user_data: the option's, or none (a slot used before keeps nothing of the old joint's).
  scene.joint_user_data.raw_set(static_cast<lua_Integer>(handleKey(id.index, id.generation)),
                                o.has("user_data") ? o.get("user_data") : sol::make_object(L, sol::lua_nil));
  jointHandle(L, scene, id).push(L);
  return 1;
}

template <JointType Type>
int addJointOf(lua_State* L) {
  return addJoint(L, Type);
}

void pushJoints(lua_State* L, Scene::Impl& scene, const std::vector<JointId>& ids) {
  pushHandles(L, ids, [&](JointId id) { return jointHandle(L, scene, id); });
}

int joints(lua_State* L) {
  Scene::Impl& scene = selfWorld(L, "joints");
  pushJoints(L, scene, scene.world->jointIds());
  return 1;
}

int findJoint(lua_State* L) {
  Scene::Impl& scene = selfWorld(L, "find_joint");
  const auto id = scene.world->findJoint(std::string_view(stringArg(L, 2, "find_joint", "name")));
  if (!id) return 0;
  jointHandle(L, scene, *id).push(L);
  return 1;
}

int bodyJoints(lua_State* L) {
  const LuaBody* b = toHandle<LuaBody>(L, 1);
  if (!b) fail(L, "joints", "call it as body:joints(), with a colon; got " + describe(L, 1) + " as the body");
  const BodyId id = liveBody(L, *b, "joints");
  pushJoints(L, *b->scene, b->scene->world->jointsOf(id));
  return 1;
}

}  // namespace

lua_CFunction jointWorldMethod(std::string_view name) {
  static const NamedFunction kMethods[] = {{"add_revolute", guarded<addJointOf<JointType::Revolute>>},
                                           {"add_prismatic", guarded<addJointOf<JointType::Prismatic>>},
                                           {"add_distance", guarded<addJointOf<JointType::Distance>>},
                                           {"add_weld", guarded<addJointOf<JointType::Weld>>},
                                           {"add_wheel", guarded<addJointOf<JointType::Wheel>>},
                                           {"add_motor_joint", guarded<addJointOf<JointType::Motor>>},
                                           {"add_friction_joint", guarded<addJointOf<JointType::Friction>>},
                                           {"add_pulley", guarded<addJointOf<JointType::Pulley>>},
                                           {"add_gear", guarded<addJointOf<JointType::Gear>>},
                                           {"joints", guarded<joints>},
                                           {"find_joint", guarded<findJoint>}};
  return lookUp(kMethods, name);
}

int bodyJointsMethod(lua_State* L) { return guarded<bodyJoints>(L); }

}  // namespace rigidlab::lua

// The scene API double (scene_api_double.h), on Lua's C API.
#include "scene_api_double.h"

#include <utility>
#include <lua.hpp>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"

namespace rigidlab::sandbox_test {
namespace {

constexpr const char* kWorldKey = "double.world";
constexpr const char* kBodyMeta = "double.body";
constexpr const char* kJointMeta = "double.joint";

using Names = std::vector<std::string>;

// The options every shorthand (add_circle, add_box, ..., add_chain) takes: the body's and those
// of its one shape.
const Names kBodyOptions = {"position", "angle", "velocity", "angular_velocity", "density", "mass", "restitution",
                            "friction", "static_friction", "static", "type", "name", "linear_damping",
                            "angular_damping", "gravity_scale", "fixed_rotation", "bullet", "enabled", "category",
                            "mask", "group", "sensor"};
const Names kShapeOptions = {"shape", "radius", "width", "height", "vertices", "a", "b", "offset", "angle", "density",
                             "friction", "static_friction", "restitution", "sensor", "category", "mask", "group"};
// Every joint: the common options. Then each kind's: the names where it gives
// them, otherwise JointDef's field names (what scene_writer.cpp writes).
const Names kJointCommon = {"a", "b", "collide_connected", "break_force", "break_torque", "name"};
const Names kSpringOptions = {"spring_hertz", "spring_damping"};

Names with(Names base, const Names& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}

World& worldOf(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kWorldKey);
  auto* w = static_cast<World*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return *w;
}

// The options table of a call, checked against the names the function takes.
class Options {
 public:
  Options(lua_State* L, int index, const Names& allowed) : L_(L), t_(lua_absindex(L, index)) {
    if (!lua_istable(L, t_)) throw std::runtime_error("expects a table of options");
    lua_pushnil(L);
    while (lua_next(L, t_) != 0) {
      lua_pop(L, 1);
      if (lua_type(L, -1) != LUA_TSTRING) throw std::runtime_error("option names must be strings");
      const std::string key = lua_tostring(L, -1);
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        throw std::runtime_error("unknown option '" + key + "'");
    }
  }

  bool has(const char* key) const {
    const bool present = lua_getfield(L_, t_, key) != LUA_TNIL;
    lua_pop(L_, 1);
    return present;
  }
  double number(const char* key, double otherwise) const {
    if (!has(key)) return otherwise;
    lua_getfield(L_, t_, key);
    int ok = 0;
    const double x = lua_tonumberx(L_, -1, &ok);
    lua_pop(L_, 1);
    if (!ok) throw std::runtime_error(std::string(key) + " must be a number");
    return x;
  }
  bool boolean(const char* key, bool otherwise) const {
    if (!has(key)) return otherwise;
    lua_getfield(L_, t_, key);
    const bool b = lua_toboolean(L_, -1);
    lua_pop(L_, 1);
    return b;
  }
  std::string string(const char* key, const std::string& otherwise) const {
    if (!has(key)) return otherwise;
    lua_getfield(L_, t_, key);
    size_t n = 0;
    const char* s = lua_tolstring(L_, -1, &n);
    std::string out = s ? std::string(s, n) : std::string();
    lua_pop(L_, 1);
    return out;
  }
  // A 64-bit filter value: a Lua integer of those bits (the writer writes hexadecimal literals).
  uint64_t bits(const char* key, uint64_t otherwise) const {
    if (!has(key)) return otherwise;
    lua_getfield(L_, t_, key);
    int ok = 0;
    const lua_Integer x = lua_tointegerx(L_, -1, &ok);
    lua_pop(L_, 1);
    if (!ok) throw std::runtime_error(std::string(key) + " must be an integer");
    return static_cast<uint64_t>(x);
  }
  Vec2 vec(const char* key, const Vec2& otherwise) const {
    if (!has(key)) return otherwise;
    lua_getfield(L_, t_, key);
    const Vec2 v = vecAt(L_, -1, key);
    lua_pop(L_, 1);
    return v;
  }
  std::vector<Vec2> points(const char* key) const {
    if (lua_getfield(L_, t_, key) != LUA_TTABLE) throw std::runtime_error(std::string(key) + " must be a list of points");
    std::vector<Vec2> out;
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L_, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L_, -1, i);
      out.push_back(vecAt(L_, -1, key));
      lua_pop(L_, 1);
    }
    lua_pop(L_, 1);
    return out;
  }
  // A handle option (a body or a joint).
  template <typename Id>
  Id handle(const char* key, const char* meta) const {
    lua_getfield(L_, t_, key);
    auto* id = static_cast<Id*>(luaL_testudata(L_, -1, meta));
    lua_pop(L_, 1);
    if (!id) throw std::runtime_error(std::string(key) + " must be a " + (meta == kBodyMeta ? "body" : "joint"));
    return *id;
  }

  static Vec2 vecAt(lua_State* L, int index, const char* what) {
    if (!lua_istable(L, index)) throw std::runtime_error(std::string(what) + " must be a point {x, y}");
    lua_rawgeti(L, index, 1);
    lua_rawgeti(L, index < 0 ? index - 1 : index, 2);
    const Vec2 v(lua_tonumber(L, -2), lua_tonumber(L, -1));
    lua_pop(L, 2);
    return v;
  }

 private:
  lua_State* L_;
  int t_;
};

void pushVec(lua_State* L, const Vec2& v) {
  lua_createtable(L, 2, 0);
  lua_pushnumber(L, v.x());
  lua_rawseti(L, -2, 1);
  lua_pushnumber(L, v.y());
  lua_rawseti(L, -2, 2);
}

template <typename Id>
void pushHandle(lua_State* L, Id id, const char* meta) {
  *static_cast<Id*>(lua_newuserdatauv(L, sizeof(Id), 0)) = id;
  luaL_setmetatable(L, meta);
}

// A C function whose C++ exceptions become Lua errors naming the function.
template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  std::string message;
  try {
    return F(L);
  } catch (const std::exception& e) {
    message = e.what();
  }
  lua_Debug ar;
  const char* name = lua_getstack(L, 0, &ar) && lua_getinfo(L, "n", &ar) && ar.name ? ar.name : "?";
  return luaL_error(L, "%s: %s", name, message.c_str());
}

BodyType parseType(const std::string& t) {
  if (t == "static") return BodyType::Static;
  if (t == "kinematic") return BodyType::Kinematic;
  if (t == "dynamic") return BodyType::Dynamic;
  throw std::runtime_error("type must be \"static\", \"kinematic\" or \"dynamic\", got \"" + t + "\"");
}

Filter filterOf(const Options& o) {
  Filter f;
  f.category = o.bits("category", f.category);
  f.mask = o.bits("mask", f.mask);
  f.group = static_cast<int32_t>(o.bits("group", 0));
  return f;
}

BodyDef bodyDef(const Options& o) {
  BodyDef d;
  if (o.boolean("static", false)) d.type = BodyType::Static;
  if (o.has("type")) d.type = parseType(o.string("type", ""));
  d.position = o.vec("position", d.position);
  d.angle = o.number("angle", d.angle);
  d.velocity = o.vec("velocity", d.velocity);
  d.angular_velocity = o.number("angular_velocity", d.angular_velocity);
  if (o.has("mass")) d.mass = o.number("mass", 1.0);
  d.density = o.number("density", d.density);
  d.restitution = o.number("restitution", d.restitution);
  d.friction = o.number("friction", d.friction);
  if (o.has("static_friction")) d.static_friction = o.number("static_friction", d.friction);
  d.name = o.string("name", "");
  d.linear_damping = o.number("linear_damping", d.linear_damping);
  d.angular_damping = o.number("angular_damping", d.angular_damping);
  d.gravity_scale = o.number("gravity_scale", d.gravity_scale);
  d.fixed_rotation = o.boolean("fixed_rotation", false);
  d.bullet = o.boolean("bullet", false);
  d.enabled = o.boolean("enabled", true);
  d.filter = filterOf(o);
  d.sensor = o.boolean("sensor", false);
  return d;
}

int pushBody(lua_State* L, BodyId id) {
  pushHandle(L, id, kBodyMeta);
  return 1;
}

int addCircle(lua_State* L) {
  const Options o(L, 2, with(kBodyOptions, {"radius"}));
  BodyDef d = bodyDef(o);
  d.shape = makeCircle(o.number("radius", 0.0));
  return pushBody(L, worldOf(L).createBody(d));
}
int addBox(lua_State* L) {
  const Options o(L, 2, with(kBodyOptions, {"width", "height"}));
  BodyDef d = bodyDef(o);
  d.shape = makeBox(o.number("width", 0.0), o.number("height", 0.0));
  return pushBody(L, worldOf(L).createBody(d));
}
int addPolygon(lua_State* L) {
  const Options o(L, 2, with(kBodyOptions, {"vertices"}));
  BodyDef d = bodyDef(o);
  d.shape = makePolygon(o.points("vertices"));
  return pushBody(L, worldOf(L).createBody(d));
}
int addCapsule(lua_State* L) {
  const Options o(L, 2, with(kBodyOptions, {"a", "b", "radius"}));
  BodyDef d = bodyDef(o);
  d.shape = makeCapsule(o.vec("a", Vec2::Zero()), o.vec("b", Vec2::Zero()), o.number("radius", 0.0));
  return pushBody(L, worldOf(L).createBody(d));
}
int addSegment(lua_State* L) {
  const Options o(L, 2, with(kBodyOptions, {"a", "b"}));
  BodyDef d = bodyDef(o);
  d.shape = makeSegment(o.vec("a", Vec2::Zero()), o.vec("b", Vec2::Zero()));
  return pushBody(L, worldOf(L).createBody(d));
}
int addChain(lua_State* L) {
  const Options o(L, 2, with(kBodyOptions, {"points", "loop"}));
  BodyDef d = bodyDef(o);
  d.type = BodyType::Static;
  World& w = worldOf(L);
  const BodyId id = w.createBody(d);
  World::ChainDef chain;
  chain.points = o.points("points");
  chain.loop = o.boolean("loop", false);
  chain.material = {d.restitution, d.friction, d.static_friction.value_or(d.friction)};
  chain.filter = d.filter;
  w.createChain(id, chain);
  return pushBody(L, id);
}

int bodyAddShape(lua_State* L) {
  const BodyId body = *static_cast<BodyId*>(luaL_checkudata(L, 1, kBodyMeta));
  const Options o(L, 2, kShapeOptions);
  const std::string kind = o.string("shape", "");
  Shape shape;
  if (kind == "circle") shape = makeCircle(o.number("radius", 0.0));
  else if (kind == "box") shape = makeBox(o.number("width", 0.0), o.number("height", 0.0));
  else if (kind == "polygon") shape = makePolygon(o.points("vertices"));
  else if (kind == "capsule") shape = makeCapsule(o.vec("a", Vec2::Zero()), o.vec("b", Vec2::Zero()), o.number("radius", 0.0));
  else if (kind == "segment") shape = makeSegment(o.vec("a", Vec2::Zero()), o.vec("b", Vec2::Zero()));
  else throw std::runtime_error("shape must be circle, box, polygon, capsule or segment, got \"" + kind + "\"");
  if (o.has("offset") || o.has("angle")) shape = transformShape(shape, o.vec("offset", Vec2::Zero()), o.number("angle", 0.0));
  ShapeDef d;
  d.shape = shape;
  d.density = o.number("density", d.density);
  d.material.restitution = o.number("restitution", d.material.restitution);
  d.material.friction = o.number("friction", d.material.friction);
  d.material.static_friction = o.number("static_friction", d.material.friction);
  d.filter = filterOf(o);
  d.sensor = o.boolean("sensor", false);
  worldOf(L).createShape(body, d);
  return 0;
}

int bodyIndex(lua_State* L) {
  const BodyId id = *static_cast<BodyId*>(luaL_checkudata(L, 1, kBodyMeta));
  const std::string key = luaL_checkstring(L, 2);
  const Body& b = worldOf(L).body(id);
  if (key == "position") pushVec(L, b.xf.p);
  else if (key == "angle") lua_pushnumber(L, b.angle);
  else if (key == "velocity") pushVec(L, b.velocity);
  else if (key == "angular_velocity") lua_pushnumber(L, b.angular_velocity);
  else if (key == "type") lua_pushstring(L, bodyTypeName(b.type));
  else if (key == "add_shape") lua_pushcfunction(L, guarded<bodyAddShape>);
  else throw std::runtime_error("body has no field '" + key + "' in the double");
  return 1;
}

int bodyNewIndex(lua_State* L) {
  const BodyId id = *static_cast<BodyId*>(luaL_checkudata(L, 1, kBodyMeta));
  const std::string key = luaL_checkstring(L, 2);
  World& w = worldOf(L);
  const Body& b = w.body(id);
  if (key == "position") w.setTransform(id, Options::vecAt(L, 3, "position"), b.angle);
  else if (key == "angle") w.setTransform(id, b.xf.p, luaL_checknumber(L, 3));
  else if (key == "velocity") w.setVelocity(id, Options::vecAt(L, 3, "velocity"));
  else if (key == "angular_velocity") w.setAngularVelocity(id, luaL_checknumber(L, 3));
  else if (key == "type") w.setType(id, parseType(luaL_checkstring(L, 3)));
  else throw std::runtime_error("body field '" + key + "' cannot be written in the double");
  return 0;
}

// Joints. A limit, motor or spring is on when one of its options is given.
JointDef jointCommon(const Options& o, JointType type) {
  JointDef d;
  d.type = type;
  if (type != JointType::Gear) {
    // As the bindings do: without b the joint pins a to the world, which is the core's body a.
    d.a = o.handle<BodyId>("a", kBodyMeta);
    if (o.has("b")) d.b = o.handle<BodyId>("b", kBodyMeta);
    else std::swap(d.a, d.b);
  }
  d.collide_connected = o.boolean("collide_connected", false);
  d.break_force = o.number("break_force", d.break_force);
  d.break_torque = o.number("break_torque", d.break_torque);
  d.name = o.string("name", "");
  return d;
}

void springOf(const Options& o, JointDef& d) {
  d.enable_spring = o.has("spring_hertz") || o.has("spring_damping");
  d.spring_hertz = o.number("spring_hertz", 0.0);
  d.spring_damping = o.number("spring_damping", 0.0);
}

int pushJoint(lua_State* L, const JointDef& d) {
  pushHandle(L, worldOf(L).createJoint(d), kJointMeta);
  return 1;
}

int addRevolute(lua_State* L) {
  const Options o(L, 2, with(with(kJointCommon, kSpringOptions), {"anchor", "lower_angle", "upper_angle", "motor_speed", "max_motor_torque"}));
  JointDef d = jointCommon(o, JointType::Revolute);
  d.anchor_a = o.vec("anchor", Vec2::Zero());
  d.enable_limit = o.has("lower_angle") || o.has("upper_angle");
  d.lower = o.number("lower_angle", 0.0);
  d.upper = o.number("upper_angle", 0.0);
  d.enable_motor = o.has("motor_speed") || o.has("max_motor_torque");
  d.motor_speed = o.number("motor_speed", 0.0);
  d.max_motor_torque = o.number("max_motor_torque", 0.0);
  springOf(o, d);
  return pushJoint(L, d);
}

// Prismatic and wheel: an axis, translation limits, a motor, a spring.
JointDef axial(const Options& o, JointType type) {
  JointDef d = jointCommon(o, type);
  d.anchor_a = o.vec("anchor", Vec2::Zero());
  d.axis = o.vec("axis", d.axis);
  d.enable_limit = o.has("lower") || o.has("upper");
  d.lower = o.number("lower", 0.0);
  d.upper = o.number("upper", 0.0);
  d.enable_motor = o.has("motor_speed") || o.has("max_motor_force") || o.has("max_motor_torque");
  d.motor_speed = o.number("motor_speed", 0.0);
  d.max_motor_force = o.number("max_motor_force", 0.0);
  d.max_motor_torque = o.number("max_motor_torque", 0.0);
  springOf(o, d);
  return d;
}
int addPrismatic(lua_State* L) {
  const Options o(L, 2, with(with(kJointCommon, kSpringOptions), {"anchor", "axis", "lower", "upper", "motor_speed", "max_motor_force"}));
  return pushJoint(L, axial(o, JointType::Prismatic));
}
int addWheel(lua_State* L) {
  const Options o(L, 2, with(with(kJointCommon, kSpringOptions), {"anchor", "axis", "lower", "upper", "motor_speed", "max_motor_torque"}));
  return pushJoint(L, axial(o, JointType::Wheel));
}

int addDistance(lua_State* L) {
  const Options o(L, 2, with(with(kJointCommon, kSpringOptions), {"anchor_a", "anchor_b", "length", "min_length", "max_length", "max_spring_force"}));
  JointDef d = jointCommon(o, JointType::Distance);
  d.anchor_a = o.vec("anchor_a", Vec2::Zero());
  d.anchor_b = o.vec("anchor_b", Vec2::Zero());
  if (d.a.isNull()) std::swap(d.anchor_a, d.anchor_b);  // the scene's anchor_a is on its body a
  d.length = o.number("length", d.length);
  d.enable_limit = o.has("min_length") || o.has("max_length");
  d.min_length = o.number("min_length", d.min_length);
  d.max_length = o.number("max_length", d.max_length);
  springOf(o, d);
  d.max_spring_force = o.number("max_spring_force", d.max_spring_force);
  return pushJoint(L, d);
}

int addWeld(lua_State* L) {
  const Options o(L, 2, with(kJointCommon, {"anchor", "linear_hertz", "linear_damping", "angular_hertz", "angular_damping"}));
  JointDef d = jointCommon(o, JointType::Weld);
  d.anchor_a = o.vec("anchor", Vec2::Zero());
  d.linear_hertz = o.number("linear_hertz", 0.0);
  d.linear_damping = o.number("linear_damping", 0.0);
  d.angular_hertz = o.number("angular_hertz", 0.0);
  d.angular_damping = o.number("angular_damping", 0.0);
  return pushJoint(L, d);
}

int addMotorJoint(lua_State* L) {
  const Options o(L, 2, with(kJointCommon, {"anchor", "linear_offset", "angular_offset", "max_force", "max_torque",
                                      "motor_hertz", "motor_damping", "linear_velocity", "angular_velocity"}));
  JointDef d = jointCommon(o, JointType::Motor);
  d.anchor_a = o.vec("anchor", Vec2::Zero());
  d.use_offsets = o.has("linear_offset") || o.has("angular_offset");
  d.linear_offset = o.vec("linear_offset", Vec2::Zero());
  d.angular_offset = o.number("angular_offset", 0.0);
  d.max_force = o.number("max_force", 0.0);
  d.max_torque = o.number("max_torque", 0.0);
  d.motor_hertz = o.number("motor_hertz", d.motor_hertz);
  d.motor_damping = o.number("motor_damping", d.motor_damping);
  d.linear_velocity = o.vec("linear_velocity", Vec2::Zero());
  d.angular_velocity = o.number("angular_velocity", 0.0);
  return pushJoint(L, d);
}

int addFrictionJoint(lua_State* L) {
  const Options o(L, 2, with(kJointCommon, {"anchor", "max_force", "max_torque"}));
  JointDef d = jointCommon(o, JointType::Friction);
  d.anchor_a = o.vec("anchor", Vec2::Zero());
  d.max_force = o.number("max_force", 0.0);
  d.max_torque = o.number("max_torque", 0.0);
  return pushJoint(L, d);
}

int addPulley(lua_State* L) {
  const Options o(L, 2, with(kJointCommon, {"anchor_a", "anchor_b", "ground_a", "ground_b", "ratio"}));
  JointDef d = jointCommon(o, JointType::Pulley);
  d.anchor_a = o.vec("anchor_a", Vec2::Zero());
  d.anchor_b = o.vec("anchor_b", Vec2::Zero());
  d.ground_a = o.vec("ground_a", Vec2::Zero());
  d.ground_b = o.vec("ground_b", Vec2::Zero());
  d.ratio = o.number("ratio", d.ratio);
  return pushJoint(L, d);
}

int addGear(lua_State* L) {
  const Options o(L, 2, {"joint_a", "joint_b", "ratio", "collide_connected", "break_force", "break_torque", "name"});
  JointDef d = jointCommon(o, JointType::Gear);
  d.joint_a = o.handle<JointId>("joint_a", kJointMeta);
  d.joint_b = o.handle<JointId>("joint_b", kJointMeta);
  d.ratio = o.number("ratio", d.ratio);
  return pushJoint(L, d);
}

// Springs and dampers: the options the bindings have today.
int addSpring(lua_State* L) {
  const Options o(L, 2, {"a", "b", "anchor", "local_a", "local_b", "stiffness", "rest_length", "damping"});
  SpringDef d;
  d.a = o.handle<BodyId>("a", kBodyMeta);
  if (o.has("b")) d.b = o.handle<BodyId>("b", kBodyMeta);
  d.anchor = o.vec("anchor", Vec2::Zero());
  d.local_a = o.vec("local_a", Vec2::Zero());
  d.local_b = o.vec("local_b", Vec2::Zero());
  d.stiffness = o.number("stiffness", 0.0);
  if (o.has("rest_length")) d.rest_length = o.number("rest_length", 0.0);
  d.damping = o.number("damping", 0.0);
  worldOf(L).addSpring(d);
  return 0;
}
int addDamper(lua_State* L) {
  const Options o(L, 2, {"body", "coefficient", "angular_coefficient"});
  DamperDef d;
  d.body = o.handle<BodyId>("body", kBodyMeta);
  d.coefficient = o.number("coefficient", 0.0);
  d.angular_coefficient = o.number("angular_coefficient", 0.0);
  worldOf(L).addDamper(d);
  return 0;
}

void pushWorld(lua_State* L) {
  const luaL_Reg methods[] = {
      {"add_circle", guarded<addCircle>},     {"add_box", guarded<addBox>},
      {"add_polygon", guarded<addPolygon>},   {"add_capsule", guarded<addCapsule>},
      {"add_segment", guarded<addSegment>},   {"add_chain", guarded<addChain>},
      {"add_revolute", guarded<addRevolute>}, {"add_prismatic", guarded<addPrismatic>},
      {"add_distance", guarded<addDistance>}, {"add_weld", guarded<addWeld>},
      {"add_wheel", guarded<addWheel>},       {"add_motor_joint", guarded<addMotorJoint>},
      {"add_friction_joint", guarded<addFrictionJoint>}, {"add_pulley", guarded<addPulley>},
      {"add_gear", guarded<addGear>},         {"add_spring", guarded<addSpring>},
      {"add_damper", guarded<addDamper>},     {nullptr, nullptr}};
  luaL_newlib(L, methods);
}

}  // namespace

World loadWithDouble(const std::filesystem::path& saved_file) {
  World world;
  lua_State* L = luaL_newstate();
  struct Close {
    lua_State* L;
    ~Close() { lua_close(L); }
  } close{L};
  luaL_openlibs(L);
  lua_pushlightuserdata(L, &world);
  lua_setfield(L, LUA_REGISTRYINDEX, kWorldKey);
  luaL_newmetatable(L, kBodyMeta);
  lua_pushcfunction(L, guarded<bodyIndex>);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, guarded<bodyNewIndex>);
  lua_setfield(L, -2, "__newindex");
  luaL_newmetatable(L, kJointMeta);
  lua_pop(L, 2);
  // require("saved_world") finds scripts/saved_world.lua.
  lua_getglobal(L, "package");
  lua_pushstring(L, (lua::scriptsDirectory() / "?.lua").c_str());
  lua_setfield(L, -2, "path");
  lua_pop(L, 1);
  const auto check = [&](int status) {
    if (status != LUA_OK) throw std::runtime_error(lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error)");
  };
  check(luaL_dofile(L, saved_file.c_str()));
  lua_getglobal(L, "PopulateWorld");
  pushWorld(L);
  check(lua_pcall(L, 1, 0, 0));
  return world;
}

}  // namespace rigidlab::sandbox_test

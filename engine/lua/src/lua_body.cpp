// Body handles in Lua: fields (read, and write where it makes sense) and methods.
//
//   read/write  position (body origin), angle, velocity, angular_velocity, mass, static, name,
//               restitution, friction, static_friction
//   read only   id, center (world centre of mass), inertia, density, shape ("circle"|"polygon"),
//               radius (circles), vertices (polygons, body coordinates), removed
//   methods     body:apply_impulse(j [, point])          point: world, default the centre of mass
//               body:apply_force(f [, point [, duration]])  duration default: the next step only
// A misspelt field is an error naming the closest valid one.
#include <algorithm>

#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

using api::kBodyReadable;
using api::kBodyWritable;

World& worldOf(lua_State* L, const LuaBody& b, std::string_view function) { return liveWorld(L, *b.scene, function); }

const LuaBody& selfBody(lua_State* L, const sol::stack_object& self, std::string_view function) {
  const LuaBody* b = toHandle<LuaBody>(L, self.stack_index());
  if (!b)
    fail(L, function, "call it as body:" + std::string(function) + "(...), with a colon; got " + describe(self) +
                          " as the body");
  return *b;
}

double numberArg(lua_State* L, std::string_view function, std::string_view what, const sol::stack_object& v) {
  if (v.get_type() != sol::type::number) fail(L, function, std::string(what) + " must be a number, got " + describe(v));
  const double x = v.as<double>();
  if (!std::isfinite(x)) fail(L, function, std::string(what) + " must be finite, got " + formatNumber(x));
  return x;
}

Vec2 vecArg(lua_State* L, std::string_view function, std::string_view what, const sol::object& v) {
  const auto p = toVec(L, v);
  if (!p) fail(L, function, std::string(what) + " must be a vector {x, y} or vec2(x, y), got " + describe(v));
  if (!isFinite(*p)) fail(L, function, std::string(what) + " must be finite, got " + formatVec(*p));
  return *p;
}

int applyImpulse(lua_State* L) {
  sol::stack_object self(L, 1), j(L, 2), p(L, 3);
  const LuaBody& b = selfBody(L, self, "apply_impulse");
  requireIdle(L, *b.scene, "apply_impulse");
  const BodyId id = liveBody(L, b, "apply_impulse");
  World& w = worldOf(L, b, "apply_impulse");
  const Vec2 impulse = vecArg(L, "apply_impulse", "impulse", j);
  const Vec2 point = isMissing(p) ? w.body(id).center : vecArg(L, "apply_impulse", "point", p);
  try {
    w.applyImpulse(id, impulse, point);
  } catch (const InputError& e) {
    fail(L, "apply_impulse", e.what());
  }
  return 0;
}

int applyForce(lua_State* L) {
  sol::stack_object self(L, 1), f(L, 2), p(L, 3), d(L, 4);
  const LuaBody& b = selfBody(L, self, "apply_force");
  requireIdle(L, *b.scene, "apply_force");
  const BodyId id = liveBody(L, b, "apply_force");
  World& w = worldOf(L, b, "apply_force");
  const Vec2 force = vecArg(L, "apply_force", "force", f);
  std::optional<Vec2> local;  // a world point is attached to the body where it is now
  if (!isMissing(p)) local = w.body(id).xf.applyInverse(vecArg(L, "apply_force", "point", p));
  double duration = World::kNextStep;
  if (!isMissing(d)) {
    duration = numberArg(L, "apply_force", "duration", d);
    if (!(duration > 0)) fail(L, "apply_force", "duration must be > 0, got " + formatNumber(duration));
  }
  try {
    w.addForce(std::make_unique<ConstantForce>(force, local), id, {}, duration);
  } catch (const InputError& e) {
    fail(L, "apply_force", e.what());
  }
  return 0;
}

sol::object bodyIndex(lua_State* L, const LuaBody& self, const sol::stack_object& key) {
  if (key.get_type() != sol::type::string) fail(L, "body", "fields are named by strings, got " + describe(key));
  const std::string k = key.as<std::string>();
  if (k == "removed") return sol::make_object(L, !worldOf(L, self, "body.removed").isValid(self.id));
  if (k == "id") return sol::make_object(L, self.uid);
  if (k == "apply_impulse" || k == "apply_force") {
    lua_pushcfunction(L, k == "apply_impulse" ? guarded<applyImpulse> : guarded<applyForce>);
    return sol::stack::pop<sol::object>(L);
  }
  if (std::find(kBodyReadable.begin(), kBodyReadable.end(), k) == kBodyReadable.end()) {
    const std::string hint = closestName(k, kBodyReadable);
    fail(L, "body", "has no field '" + k + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
  }
  const BodyId id = liveBody(L, self, "body." + k);
  const Body& b = worldOf(L, self, "body." + k).body(id);
  if (k == "position") return makeVec(L, b.position());
  if (k == "angle") return sol::make_object(L, b.angle);
  if (k == "velocity") return makeVec(L, b.velocity);
  if (k == "angular_velocity") return sol::make_object(L, b.angular_velocity);
  if (k == "mass") return sol::make_object(L, b.mass);
  if (k == "inertia") return sol::make_object(L, b.inertia);
  if (k == "density") return sol::make_object(L, b.density);
  if (k == "center") return makeVec(L, b.center);
  if (k == "static") return sol::make_object(L, b.isStatic());
  if (k == "awake") return sol::make_object(L, !b.isStatic() && b.awake);
  if (k == "name") return sol::make_object(L, b.name);
  if (b.shapes.empty()) return sol::make_object(L, sol::lua_nil);
  const BodyShape& first = worldOf(L, self, "body." + k).shape(b.shapes.front());
  const Shape& shape = first.geometry;
  if (k == "restitution") return sol::make_object(L, first.material.restitution);
  if (k == "friction") return sol::make_object(L, first.material.friction);
  if (k == "static_friction") return sol::make_object(L, first.material.static_friction);
  if (k == "shape") return sol::make_object(L, shape.type == ShapeType::Polygon ? "polygon" : shapeTypeName(shape.type));
  if (k == "radius") return shape.type == ShapeType::Circle ? sol::make_object(L, shape.radius) : sol::make_object(L, sol::lua_nil);
  // vertices
  if (shape.type != ShapeType::Polygon) return sol::make_object(L, sol::lua_nil);
  lua_createtable(L, static_cast<int>(shape.vertices.size()), 0);
  for (size_t i = 0; i < shape.vertices.size(); ++i) {
    pushVec(L, shape.vertices[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return sol::stack::pop<sol::object>(L);
}

void bodyNewIndex(lua_State* L, const LuaBody& self, const sol::stack_object& key, const sol::stack_object& value) {
  if (key.get_type() != sol::type::string) fail(L, "body", "fields are named by strings, got " + describe(key));
  const std::string k = key.as<std::string>();
  const std::string function = "body." + k;
  if (std::find(kBodyWritable.begin(), kBodyWritable.end(), k) == kBodyWritable.end()) {
    if (std::find(kBodyReadable.begin(), kBodyReadable.end(), k) != kBodyReadable.end()) fail(L, function, "is read-only");
    const std::string hint = closestName(k, kBodyWritable);
    fail(L, "body", "has no field '" + k + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
  }
  requireIdle(L, *self.scene, function);
  const BodyId id = liveBody(L, self, function);
  World& w = worldOf(L, self, function);
  const Body& b = w.body(id);
  try {
    if (k == "position") {
      w.setTransform(id, vecArg(L, function, "value", value), b.angle);
    } else if (k == "angle") {
      w.setTransform(id, b.position(), numberArg(L, function, "value", value));
    } else if (k == "velocity") {
      w.setVelocity(id, vecArg(L, function, "value", value));
    } else if (k == "angular_velocity") {
      w.setAngularVelocity(id, numberArg(L, function, "value", value));
    } else if (k == "mass") {
      const double m = numberArg(L, function, "value", value);
      if (!(m > 0)) fail(L, function, "must be > 0, got " + formatNumber(m));
      w.setMass(id, m);
    } else if (k == "static") {
      if (value.get_type() != sol::type::boolean) fail(L, function, "must be true or false, got " + describe(value));
      w.setType(id, value.as<bool>() ? BodyType::Static : BodyType::Dynamic);
    } else if (k == "awake") {
      if (value.get_type() != sol::type::boolean) fail(L, function, "must be true or false, got " + describe(value));
      if (value.as<bool>()) w.wake(id);  // bodies fall asleep on their own; a script can only wake them
    } else if (k == "name") {
      if (value.get_type() != sol::type::string) fail(L, function, "must be a string, got " + describe(value));
      std::string name = boundedString(L, value.stack_index(), function, "", kNameBytes);
      const size_t old_size = b.name.size();
      if (name.size() > old_size) self.scene->host->charge(L, function, name.size() - old_size);
      self.scene->host->release(old_size - std::min(old_size, name.size()));
      w.setName(id, std::move(name));
    } else {
      Material m = b.shapes.empty() ? Material{} : w.shape(b.shapes.front()).material;
      const double x = numberArg(L, function, "value", value);
      if (k == "restitution") m.restitution = x;
      if (k == "friction") m.friction = x;
      if (k == "static_friction") m.static_friction = x;
      w.setMaterial(id, m);
    }
  } catch (const InputError& e) {
    // The core names its own field ("restitution must be between 0 and 1, got 2"); say which body field.
    fail(L, function, e.what());
  }
}

std::string bodyToString(const LuaBody& self) {
  if (!self.scene->world) return "body (id " + std::to_string(self.uid) + ", scene closed)";
  const World& w = *self.scene->world;
  if (!w.isValid(self.id)) return "body (removed, id " + std::to_string(self.uid) + ")";
  const Body& b = w.body(self.id);
  // The name as messages show it: escaped and shortened (scene_text.h).
  return "body " + (b.name.empty() ? "" : "'" + displayText(b.name, 40) + "' ") + "(id " + std::to_string(self.uid) + ")";
}

}  // namespace

namespace {

int bodyIndexMeta(lua_State* L) {
  bodyIndex(L, selfBody(L, sol::stack_object(L, 1), "body"), sol::stack_object(L, 2)).push(L);
  return 1;
}

int bodyNewIndexMeta(lua_State* L) {
  bodyNewIndex(L, selfBody(L, sol::stack_object(L, 1), "body"), sol::stack_object(L, 2), sol::stack_object(L, 3));
  return 0;
}

int bodyToStringMeta(lua_State* L) {
  const std::string text = bodyToString(selfBody(L, sol::stack_object(L, 1), "tostring"));
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

int bodyEqualMeta(lua_State* L) {
  const LuaBody *a = toHandle<LuaBody>(L, 1), *b = toHandle<LuaBody>(L, 2);
  lua_pushboolean(L, a && b && a->scene == b->scene && a->uid == b->uid);
  return 1;
}

}  // namespace

void registerBodyType(lua_State* L) {
  registerHandleType(L, LuaBody::kMetatable, guarded<bodyIndexMeta>, guarded<bodyNewIndexMeta>, guarded<bodyToStringMeta>,
                     guarded<bodyEqualMeta>);
}

sol::object bodyHandle(lua_State* L, Scene::Impl& scene, BodyId id) {
  const uint32_t uid = scene.world->body(id).uid;
  sol::object cached = scene.handles.raw_get<sol::object>(uid);
  if (cached.valid() && cached.get_type() != sol::type::lua_nil) return cached;
  pushHandle(L, LuaBody{&scene, id, uid});
  sol::object handle = sol::stack::pop<sol::object>(L);
  scene.handles.raw_set(uid, handle);
  return handle;
}

BodyId liveBody(lua_State* L, const LuaBody& body, std::string_view function) {
  if (!liveWorld(L, *body.scene, function).isValid(body.id))
    fail(L, function, "body (id " + std::to_string(body.uid) + ") was removed from the world");
  return body.id;
}

BodyId bodyOption(lua_State* L, Scene::Impl& scene, std::string_view function, std::string_view key,
                  const sol::object& value) {
  value.push(L);
  const LuaBody* handle = toHandle<LuaBody>(L, -1);
  lua_pop(L, 1);
  if (!handle)
    fail(L, function, std::string(key) + " must be a body (from world:add_box, add_circle, ...), got " + describe(value));
  const LuaBody& b = *handle;
  if (b.scene != &scene) fail(L, function, std::string(key) + " is a body of another scene");
  return liveBody(L, b, function);
}

std::string describeHandle(lua_State* L, int index) {
  if (const LuaBody* b = toHandle<LuaBody>(L, index)) return bodyToString(*b);
  if (const LuaForceHandle* f = toHandle<LuaForceHandle>(L, index)) return std::string("a ") + f->kind;
  if (toHandle<LuaWorld>(L, index)) return "the world";
  if (toHandle<LuaDraw>(L, index)) return "the draw object";
  return "a userdata";
}

}  // namespace rigidlab::lua

// Body handles in Lua: fields (read, and write where it makes sense) and methods.
//
//   read/write  position (body origin), angle, velocity, angular_velocity, mass, inertia, type, static,
//               name, awake, linear_damping, angular_damping, gravity_scale, gravity (nil: the
//               world's), sleeping_allowed, fixed_rotation, bullet, enabled, user_data; and for all
//               its shapes restitution, friction, static_friction, sensor, category, mask, group
//   read only   id, center (world centre of mass), local_center, density, shapes, removed, world;
//               for a one-shape body shape ("circle" | "polygon" | "capsule" | ...), radius, vertices
//   methods     body:apply_impulse(j [, point])          point: world, default the centre of mass
//               body:apply_force(f [, point [, duration]])  duration default: the next step only
//               body:apply_torque(t [, duration]), body:apply_angular_impulse(j)
//               body:world_point(p), local_point(p), world_vector(v), local_vector(v), velocity_at(p)
//               body:reset_mass(), body:add_shape{...} (lua_shape.cpp), body:set_target{position,
//               angle, time}, body:joints() (lua_joint.cpp), body:contacts() (lua_contact.cpp)
// A misspelt field is an error naming the closest valid one.
#include <algorithm>

#include "api_names.h"
#include "bindings.h"
#include "budget.h"
#include "lua_args.h"
#include "lua_body_args.h"
#include "lua_contact.h"
#include "lua_joint.h"
#include "lua_shape.h"
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

double numberArg(lua_State* L, std::string_view function, std::string_view what, const sol::object& v) {
  return checkNumber(L, function, what, v, Range::Finite);
}

Vec2 vecArg(lua_State* L, std::string_view function, std::string_view what, const sol::object& v) {
  return checkVec(L, function, what, v);
}

// The optional `duration` argument of apply_force and apply_torque: > 0 seconds, default the next
// step only.
double durationArg(lua_State* L, std::string_view function, const sol::stack_object& d) {
  if (isMissing(d)) return World::kNextStep;
  const double duration = numberArg(L, function, "duration", d);
  if (!(duration > 0)) fail(L, function, "duration must be > 0, got " + formatNumber(duration));
  return duration;
}

// A method that acts on the body: its handle checked, the world not inside a step, the body alive.
struct ActedOn {
  World& world;
  BodyId id;
};
ActedOn actedOn(lua_State* L, const char* function) {
  const LuaBody& b = selfBody(L, sol::stack_object(L, 1), function);
  requireIdle(L, *b.scene, function);
  const BodyId id = liveBody(L, b, function);
  return {worldOf(L, b, function), id};
}

// A constant force and torque on the body for `duration` (apply_force, apply_torque).
void addConstantForce(lua_State* L, const char* function, const ActedOn& on, const Vec2& force,
                      const std::optional<Vec2>& local, double torque, double duration) {
  try {
    on.world.addForce(std::make_unique<ConstantForce>(force, local, torque), on.id, {}, duration);
  } catch (const InputError& e) {
    fail(L, function, e.what());
  }
}

int applyImpulse(lua_State* L) {
  const ActedOn on = actedOn(L, "apply_impulse");
  sol::stack_object j(L, 2), p(L, 3);
  const Vec2 impulse = vecArg(L, "apply_impulse", "impulse", j);
  const Vec2 point = isMissing(p) ? on.world.body(on.id).center : vecArg(L, "apply_impulse", "point", p);
  try {
    on.world.applyImpulse(on.id, impulse, point);
  } catch (const InputError& e) {
    fail(L, "apply_impulse", e.what());
  }
  return 0;
}

int applyForce(lua_State* L) {
  const ActedOn on = actedOn(L, "apply_force");
  sol::stack_object f(L, 2), p(L, 3), d(L, 4);
  const Vec2 force = vecArg(L, "apply_force", "force", f);
  std::optional<Vec2> local;  // a world point is attached to the body where it is now
  if (!isMissing(p)) local = on.world.body(on.id).xf.applyInverse(vecArg(L, "apply_force", "point", p));
  addConstantForce(L, "apply_force", on, force, local, 0.0, durationArg(L, "apply_force", d));
  return 0;
}

int applyTorque(lua_State* L) {
  const ActedOn on = actedOn(L, "apply_torque");
  sol::stack_object t(L, 2), d(L, 3);
  const double torque = numberArg(L, "apply_torque", "torque", t);
  addConstantForce(L, "apply_torque", on, Vec2::Zero(), std::nullopt, torque, durationArg(L, "apply_torque", d));
  return 0;
}

int applyAngularImpulse(lua_State* L) {
  const ActedOn on = actedOn(L, "apply_angular_impulse");
  on.world.applyAngularImpulse(on.id, numberArg(L, "apply_angular_impulse", "impulse", sol::stack_object(L, 2)));
  return 0;
}

// body:world_point(p) and the other frame helpers: the body's transform now (origin, angle).
enum class Frame { WorldPoint, LocalPoint, WorldVector, LocalVector, VelocityAt };
template <Frame F>
int frameHelper(lua_State* L) {
  static constexpr const char* kNames[] = {"world_point", "local_point", "world_vector", "local_vector", "velocity_at"};
  const char* function = kNames[static_cast<int>(F)];
  const LuaBody& b = selfBody(L, sol::stack_object(L, 1), function);
  const Body& body = worldOf(L, b, function).body(liveBody(L, b, function));
  const bool vector = F == Frame::WorldVector || F == Frame::LocalVector;
  const Vec2 x = vecArg(L, function, vector ? "vector" : "point", sol::stack_object(L, 2));
  switch (F) {
    case Frame::WorldPoint: pushVec(L, body.xf.apply(x)); break;
    case Frame::LocalPoint: pushVec(L, body.xf.applyInverse(x)); break;
    case Frame::WorldVector: pushVec(L, body.xf.q.apply(x)); break;
    case Frame::LocalVector: pushVec(L, body.xf.q.applyInverse(x)); break;
    case Frame::VelocityAt: pushVec(L, body.pointVelocity(x)); break;  // v + ω × (p − c), p world
  }
  return 1;
}

int resetMass(lua_State* L) {
  const ActedOn on = actedOn(L, "reset_mass");
  try {
    on.world.resetMass(on.id);
  } catch (const InputError& e) {
    failCore(L, "reset_mass", e);
  }
  return 0;
}

int setTarget(lua_State* L) {
  const ActedOn on = actedOn(L, "set_target");
  World& w = on.world;
  const BodyId id = on.id;
  const Options o(L, "set_target", sol::stack_object(L, 2), api::kTargetOptions);
  const Body& body = w.body(id);
  const Vec2 position = o.vec("position", body.position());
  const double angle = o.number("angle", body.angle);
  const double time = o.positive("time");
  if (!body.isKinematic())
    fail(L, "set_target", std::string("moves kinematic bodies, and this one is ") + bodyTypeName(body.type) +
                              " (make it type = \"kinematic\")");
  try {
    w.setTarget(id, position, angle, time);
  } catch (const InputError& e) {
    failCore(L, "set_target", e);
  }
  return 0;
}

lua_CFunction bodyMethod(std::string_view name) {
  static const NamedFunction kMethods[] = {{"apply_impulse", guarded<applyImpulse>},
                                           {"apply_force", guarded<applyForce>},
                                           {"apply_torque", guarded<applyTorque>},
                                           {"apply_angular_impulse", guarded<applyAngularImpulse>},
                                           {"world_point", guarded<frameHelper<Frame::WorldPoint>>},
                                           {"local_point", guarded<frameHelper<Frame::LocalPoint>>},
                                           {"world_vector", guarded<frameHelper<Frame::WorldVector>>},
                                           {"local_vector", guarded<frameHelper<Frame::LocalVector>>},
                                           {"velocity_at", guarded<frameHelper<Frame::VelocityAt>>},
                                           {"reset_mass", guarded<resetMass>},
                                           {"add_shape", addShapeMethod},
                                           {"set_target", guarded<setTarget>},
                                           {"joints", bodyJointsMethod},
                                           {"contacts", bodyContactsMethod}};
  return lookUp(kMethods, name);
}

// The fields a body has for its one shape (the others of kShapeWritable stand for a property all
// its shapes share).
bool isOneShapeField(std::string_view k) { return k == "shape" || k == "radius" || k == "vertices"; }

sol::object oneShapeField(lua_State* L, const World& w, const Body& b, const std::string& k) {
  if (b.shapes.empty()) return sol::make_object(L, sol::lua_nil);
  if (b.shapes.size() > 1)
    fail(L, "body." + k, "the body has " + std::to_string(b.shapes.size()) + " shapes; read body.shapes[i]." +
                             (k == "shape" ? "kind" : k));
  const Shape& shape = w.shape(b.shapes.front()).geometry;
  if (k == "shape") return sol::make_object(L, shapeTypeName(shape.type));
  if (k == "radius")
    return shape.type == ShapeType::Circle || shape.type == ShapeType::Capsule ? sol::make_object(L, shape.radius)
                                                                               : sol::make_object(L, sol::lua_nil);
  if (shape.type != ShapeType::Polygon) return sol::make_object(L, sol::lua_nil);
  lua_createtable(L, static_cast<int>(shape.vertices.size()), 0);
  for (size_t i = 0; i < shape.vertices.size(); ++i) {
    pushVec(L, shape.vertices[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return sol::stack::pop<sol::object>(L);
}

// The value all the body's shapes share; a compound body whose shapes differ has none.
sol::object sharedShapeProperty(lua_State* L, const World& w, const Body& b, const std::string& k) {
  if (b.shapes.empty()) return sol::make_object(L, sol::lua_nil);
  const sol::object first = shapeProperty(L, w.shape(b.shapes.front()), k);
  for (size_t i = 1; i < b.shapes.size(); ++i) {
    const sol::object other = shapeProperty(L, w.shape(b.shapes[i]), k);
    first.push(L);
    other.push(L);
    const bool same = lua_rawequal(L, -1, -2);
    lua_pop(L, 2);
    if (!same)
      fail(L, "body." + k, "the body's " + std::to_string(b.shapes.size()) + " shapes differ in " + k + " (shape 1: " +
                               describe(first) + ", shape " + std::to_string(i + 1) + ": " + describe(other) +
                               "); read body.shapes[i]." + k);
  }
  return first;
}

sol::object shapesList(lua_State* L, Scene::Impl& scene, const Body& b) {
  pushHandles(L, b.shapes, [&](ShapeId id) { return shapeHandle(L, scene, id); });
  return sol::stack::pop<sol::object>(L);
}

sol::object bodyIndex(lua_State* L, const LuaBody& self, const sol::stack_object& key) {
  const std::string k = fieldName(L, "body", key);
  if (k == "removed") return sol::make_object(L, !worldOf(L, self, "body.removed").isValid(self.id));
  if (k == "id") return sol::make_object(L, self.uid);
  if (k == "world") return self.scene->world_handle;
  if (const lua_CFunction f = bodyMethod(k)) {
    lua_pushcfunction(L, f);
    return sol::stack::pop<sol::object>(L);
  }
  if (std::find(kBodyReadable.begin(), kBodyReadable.end(), k) == kBodyReadable.end()) noSuchField(L, "body", k, kBodyReadable);
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
  if (k == "type") return sol::make_object(L, bodyTypeName(b.type));
  if (k == "local_center") return makeVec(L, b.local_center);
  if (k == "linear_damping") return sol::make_object(L, b.linear_damping);
  if (k == "angular_damping") return sol::make_object(L, b.angular_damping);
  if (k == "gravity_scale") return sol::make_object(L, b.gravity_scale);
  if (k == "gravity") return b.own_gravity ? makeVec(L, b.gravity) : sol::make_object(L, sol::lua_nil);
  if (k == "sleeping_allowed") return sol::make_object(L, b.sleeping_allowed);
  if (k == "fixed_rotation") return sol::make_object(L, b.fixed_rotation);
  if (k == "bullet") return sol::make_object(L, b.bullet);
  if (k == "enabled") return sol::make_object(L, b.enabled);
  if (k == "user_data") return self.scene->user_data.raw_get<sol::object>(self.uid);
  const World& w = worldOf(L, self, "body." + k);
  if (k == "shapes") return shapesList(L, *self.scene, b);
  if (isOneShapeField(k)) return oneShapeField(L, w, b, k);
  return sharedShapeProperty(L, w, b, k);
}

void bodyNewIndex(lua_State* L, const LuaBody& self, const sol::stack_object& key, const sol::stack_object& value) {
  const std::string k = fieldName(L, "body", key);
  const std::string function = "body." + k;
  requireWritable(L, "body", k, kBodyReadable, kBodyWritable);
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
      const Vec2 v = vecArg(L, function, "value", value);
      if (b.isStatic() && v != Vec2::Zero())
        fail(L, function, "a static body cannot move, got " + formatVec(v) +
                              ": make it kinematic (body.type = \"kinematic\") to give it a velocity");
      w.setVelocity(id, v);
    } else if (k == "angular_velocity") {
      const double omega = numberArg(L, function, "value", value);
      if (b.isStatic() && omega != 0.0)
        fail(L, function, "a static body cannot turn, got " + formatNumber(omega) +
                              ": make it kinematic (body.type = \"kinematic\") to give it an angular velocity");
      w.setAngularVelocity(id, omega);
    } else if (k == "mass") {
      const double m = numberArg(L, function, "value", value);
      if (!(m > 0)) fail(L, function, "must be > 0, got " + formatNumber(m));
      w.setMass(id, m);
    } else if (k == "inertia") {
      w.setInertia(id, checkNumber(L, function, "", value, Range::Positive));
    } else if (k == "gravity") {
      w.setBodyGravity(id, isMissing(value) ? std::nullopt : std::optional(vecArg(L, function, "value", value)));
    } else if (k == "sleeping_allowed") {
      w.setSleepingAllowed(id, checkBool(L, function, "", value));
    } else if (k == "static") {
      w.setType(id, checkBool(L, function, "", value) ? BodyType::Static : BodyType::Dynamic);
    } else if (k == "type") {
      w.setType(id, bodyType(L, function, "", value));
    } else if (k == "awake") {
      if (checkBool(L, function, "", value)) w.wake(id);  // bodies fall asleep on their own; a script can only wake them
    } else if (k == "linear_damping") {
      w.setLinearDamping(id, checkNumber(L, function, "", value, Range::NonNegative));
    } else if (k == "angular_damping") {
      w.setAngularDamping(id, checkNumber(L, function, "", value, Range::NonNegative));
    } else if (k == "gravity_scale") {
      w.setGravityScale(id, checkNumber(L, function, "", value, Range::Finite));
    } else if (k == "fixed_rotation") {
      w.setFixedRotation(id, checkBool(L, function, "", value));
    } else if (k == "bullet") {
      w.setBullet(id, checkBool(L, function, "", value));
    } else if (k == "enabled") {
      w.setEnabled(id, checkBool(L, function, "", value));
    } else if (k == "user_data") {
      self.scene->user_data.raw_set(self.uid, sol::object(value));  // any value, kept as it is
    } else if (k == "name") {
      if (value.get_type() != sol::type::string) fail(L, function, "must be a string, got " + describe(value));
      std::string name = boundedString(L, value.stack_index(), function, "", kNameBytes);
      const size_t old_size = b.name.size();
      if (name.size() > old_size) self.scene->host->charge(L, function, name.size() - old_size);
      self.scene->host->release(old_size - std::min(old_size, name.size()));
      w.setName(id, std::move(name));
    } else {  // a property of every shape
      if (b.shapes.empty()) fail(L, function, "the body has no shapes (add one with body:add_shape{...})");
      if (k == "sensor") {
        w.setBodySensor(id, checkBool(L, function, "", value));  // one mass update, not one per shape
      } else {
        const std::vector<ShapeId> shapes = b.shapes;
        for (const ShapeId s : shapes) {
          setShapeProperty(L, w, s, function, k, value);
          Budget::check(L);  // a body of many shapes: stopped within one shape of its budget
        }
      }
    }
  } catch (const InputError& e) {
    failCore(L, function, e);  // the core names its own field ("a body with a segment ... cannot be dynamic")
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

}  // namespace

void registerBodyType(lua_State* L) {
  registerHandleType(L, LuaBody::kMetatable, guarded<bodyIndexMeta>, guarded<bodyNewIndexMeta>, guarded<handleToString<LuaBody, bodyToString>>,
                     guarded<handlesEqual<LuaBody, &LuaBody::uid>>);
}

sol::object bodyHandle(lua_State* L, Scene::Impl& scene, BodyId id) {
  const uint32_t uid = scene.world->body(id).uid;
  return cachedHandle(L, scene.handles, uid, LuaBody{&scene, id, uid});
}

void pushBodyHandle(lua_State* L, Scene::Impl& scene, BodyId id) {
  const uint32_t uid = scene.world->body(id).uid;
  pushCachedHandle(L, scene.handles, uid, LuaBody{&scene, id, uid});
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
  if (const LuaShape* s = toHandle<LuaShape>(L, index)) return "a " + describeShape(*s);
  if (const LuaJoint* j = toHandle<LuaJoint>(L, index)) return "a " + describeJoint(*j);
  if (const LuaForceHandle* f = toHandle<LuaForceHandle>(L, index)) return std::string("a ") + f->kind;
  if (toHandle<LuaWorld>(L, index)) return "the world";
  if (toHandle<LuaDraw>(L, index)) return "the draw object";
  return "a userdata";
}

}  // namespace rigidlab::lua

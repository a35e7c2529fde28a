// The `world` object scenes receive in PopulateWorld and the hooks (OnStep, Check, OnKey, OnMouse, ...).
//
//   fields   gravity (vec2), integrator (string), dt, solver, iterations, substeps, sleeping,
//            exact_joints: read and write; time, step_count, title, locked (true inside a step: in
//            a force or a pre_solve function), controls (world.controls, scene_controls.cpp): read only
//   methods  add_spring, add_damper, add_force, bodies, find, remove, step, kinetic_energy,
//            potential_energy here; the body functions (add_box, ...) in lua_world_bodies.cpp, the
//            joint functions (add_revolute, ..., joints, find_joint) in lua_joint_create.cpp
// Forces, springs and dampers are returned as handles with `kind`, `removed` and `remove()`.
#include <algorithm>

#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"
#include "lua_events.h"
#include "lua_force.h"
#include "lua_query.h"
#include "lua_shape.h"
#include "lua_snapshot.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

using api::kWorldFields;
using api::kWorldMethods;

void pushForceHandle(lua_State* L, Scene::Impl& scene, ForceId id, const char* kind) {
  pushHandle(L, LuaForceHandle{&scene, id, kind});
}

int addSpring(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "add_spring");
  const Options o(L, "add_spring", sol::stack_object(L, 2),
                  api::kSpringOptions);
  SpringDef d;
  d.a = bodyOption(L, scene, "add_spring", "a", o.get("a"));
  if (o.has("b") == o.has("anchor"))
    o.fail(o.has("b") ? "b" : "anchor", o.has("b") ? "and anchor cannot both be given: a spring ends at a body (b) or at a fixed point (anchor)"
                                                   : "is required (or b): a spring ends at a body (b) or at a fixed point (anchor)");
  if (o.has("b")) {
    d.b = bodyOption(L, scene, "add_spring", "b", o.get("b"));
    if (d.b == d.a) o.fail("b", "must be a different body than a");
  } else {
    d.anchor = o.vec("anchor");
  }
  if (o.has("local_b") && !o.has("b")) o.fail("local_b", "needs b (a spring to an anchor has no second body)");
  d.local_a = o.vec("local_a", Vec2::Zero());
  d.local_b = o.vec("local_b", Vec2::Zero());
  d.stiffness = o.nonNegative("stiffness");
  if (o.has("rest_length")) d.rest_length = o.nonNegative("rest_length");
  d.damping = o.nonNegative("damping", 0.0);
  ForceId id;
  try {
    id = scene.world->addSpring(d);
  } catch (const InputError& e) {
    fail(L, "add_spring", e.what());
  }
  pushForceHandle(L, scene, id, "spring");
  return 1;
}

int addDamper(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "add_damper");
  const Options o(L, "add_damper", sol::stack_object(L, 2), api::kDamperOptions);
  DamperDef d;
  d.body = bodyOption(L, scene, "add_damper", "body", o.get("body"));
  d.coefficient = o.nonNegative("coefficient");
  d.angular_coefficient = o.nonNegative("angular_coefficient", 0.0);
  ForceId id;
  try {
    id = scene.world->addDamper(d);
  } catch (const InputError& e) {
    fail(L, "add_damper", e.what());
  }
  pushForceHandle(L, scene, id, "damper");
  return 1;
}

int addForce(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "add_force");
  const Options o(L, "add_force", sol::stack_object(L, 2), api::kForceOptions);
  const BodyId body = bodyOption(L, scene, "add_force", "body", o.get("body"));
  const sol::object fn = o.get("evaluate");
  if (fn.get_type() != sol::type::function)
    o.fail("evaluate", fn.get_type() == sol::type::lua_nil ? "is required: a function(s) returning fx, fy [, torque]"
                                                           : "must be a function(s) returning fx, fy [, torque], got " + describe(fn));
  const double duration = o.has("duration") ? o.positive("duration") : World::kForever;
  std::optional<Vec2> point;
  if (o.has("point")) point = o.vec("point");
  BodyId other;
  if (o.has("other")) {
    other = bodyOption(L, scene, "add_force", "other", o.get("other"));
    if (other == body) o.fail("other", "must be a different body than body");
  }
  ForceId id;
  try {
    auto force = std::make_unique<LuaForce>(*scene.host, fn.as<sol::function>(), point, !other.isNull());
    id = scene.world->addForce(std::move(force), body, other, duration);
  } catch (const InputError& e) {
    fail(L, "add_force", e.what());
  }
  pushForceHandle(L, scene, id, "lua force");
  return 1;
}

int bodies(lua_State* L) {
  Scene::Impl& scene = selfWorld(L, "bodies");
  pushHandles(L, scene.world->bodyIds(), [&](BodyId id) { return bodyHandle(L, scene, id); });
  return 1;
}

int find(lua_State* L) {
  Scene::Impl& scene = selfWorld(L, "find");
  const auto id = scene.world->findBody(std::string_view(stringArg(L, 2, "find", "name")));
  if (!id) return 0;
  bodyHandle(L, scene, *id).push(L);
  return 1;
}

int remove(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "remove");
  sol::stack_object what(L, 2);
  try {
    if (const LuaBody* body = toHandle<LuaBody>(L, 2)) {
      const LuaBody& b = *body;
      if (b.scene != &scene) fail(L, "remove", "the body belongs to another scene");
      const BodyId id = liveBody(L, b, "remove");
      const size_t bytes = hostBytes(*scene.world, scene.world->body(id));
      for (const ShapeId s : scene.world->body(id).shapes) {
        forgetShapeEvents(scene, s);
        forgetShapeUserData(scene, s);
      }
      scene.world->destroyBody(id);
      scene.host->release(bytes);
      scene.handles.raw_set(b.uid, sol::lua_nil);
      scene.user_data.raw_set(b.uid, sol::lua_nil);
    } else if (const LuaShape* shape = toHandle<LuaShape>(L, 2)) {
      if (shape->scene != &scene) fail(L, "remove", "the shape belongs to another scene");
      removeShape(L, scene, liveShape(L, *shape, "remove"));
    } else if (const LuaJoint* joint = toHandle<LuaJoint>(L, 2)) {
      if (joint->scene != &scene) fail(L, "remove", "the joint belongs to another scene");
      removeJoint(L, *joint, "remove");
    } else if (const LuaForceHandle* force = toHandle<LuaForceHandle>(L, 2)) {
      const LuaForceHandle& f = *force;
      if (!scene.world->isValid(f.id)) fail(L, "remove", std::string("the ") + f.kind + " was already removed (or has expired)");
      scene.world->removeForce(f.id);
    } else {
      fail(L, "remove", "expects a body, shape, joint, force, spring or damper, got " + describe(what));
    }
  } catch (const InputError& e) {
    fail(L, "remove", e.what());
  }
  return 0;
}

int step(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "step");
  sol::stack_object dt(L, 2);
  double h = scene.settings.dt;
  if (!isMissing(dt)) {
    if (dt.get_type() != sol::type::number) fail(L, "step", "dt must be a number, got " + describe(dt));
    h = dt.as<double>();
    if (!(h > 0) || !std::isfinite(h)) fail(L, "step", "dt must be > 0, got " + formatNumber(h));
  }
  try {
    scene.world->step(h);
  } catch (const InputError& e) {
    fail(L, "step", e.what());
  }
  noteJointBreaks(scene);
  return 0;
}

int kineticEnergy(lua_State* L) {
  lua_pushnumber(L, selfWorld(L, "kinetic_energy").world->kineticEnergy());
  return 1;
}

int potentialEnergy(lua_State* L) {
  lua_pushnumber(L, selfWorld(L, "potential_energy").world->potentialEnergy());
  return 1;
}

lua_CFunction ownMethod(std::string_view name) {
  static const NamedFunction kMethods[] = {
      {"add_spring", guarded<addSpring>}, {"add_damper", guarded<addDamper>}, {"add_force", guarded<addForce>},
      {"bodies", guarded<bodies>},        {"find", guarded<find>},            {"remove", guarded<remove>},
      {"step", guarded<step>},            {"kinetic_energy", guarded<kineticEnergy>},
      {"potential_energy", guarded<potentialEnergy>}};
  return lookUp(kMethods, name);
}

sol::object method(lua_State* L, std::string_view name) {
  lua_CFunction f = bodyWorldMethod(name);
  if (!f) f = jointWorldMethod(name);
  if (!f) f = queryWorldMethod(name);
  if (!f) f = ownMethod(name);
  if (!f) f = snapshotWorldMethod(name);
  if (!f) return sol::make_object(L, sol::lua_nil);
  lua_pushcfunction(L, f);
  return sol::stack::pop<sol::object>(L);
}

void unknownField(lua_State* L, const std::string& k) {
  std::vector<std::string_view> all = joined({&kWorldFields, &api::kWorldModFields, &kWorldMethods});
  noSuchField(L, "world", k, all);
}

sol::object worldIndex(lua_State* L, const LuaWorld& self, const sol::stack_object& key) {
  const std::string k = fieldName(L, "world", key);
  const World& w = liveWorld(L, *self.scene, "world");
  if (k == "gravity") return makeVec(L, w.settings().gravity);
  if (k == "integrator") return sol::make_object(L, std::string(integratorName(w.settings().integrator)));
  if (k == "dt") return sol::make_object(L, self.scene->settings.dt);
  if (k == "solver") return sol::make_object(L, std::string(contactSolverName(w.settings().contact_solver)));
  if (k == "iterations") return sol::make_object(L, w.settings().iterations);
  if (k == "substeps") return sol::make_object(L, w.settings().substeps);
  if (k == "sleeping") return sol::make_object(L, w.settings().sleeping);
  if (k == "exact_joints") return sol::make_object(L, w.settings().exact_joints);
  if (k == "time") return sol::make_object(L, w.time());
  if (k == "step_count") return sol::make_object(L, w.stepCount());
  if (k == "title") return sol::make_object(L, self.scene->settings.title);
  if (k == "locked") return sol::make_object(L, w.isStepping());
  if (k == "controls") {  // scene_controls.cpp
    pushControls(L, *self.scene);
    return sol::stack::pop<sol::object>(L);
  }
  sol::object m = method(L, k);
  if (m.get_type() == sol::type::lua_nil) unknownField(L, k);
  return m;
}

void worldNewIndex(lua_State* L, const LuaWorld& self, const sol::stack_object& key, const sol::stack_object& value) {
  const std::string k = fieldName(L, "world", key);
  const std::string function = "world." + k;
  World& w = liveWorld(L, *self.scene, function);
  if (std::find(kWorldFields.begin(), kWorldFields.end(), k) != kWorldFields.end()) requireIdle(L, *self.scene, function);
  const auto number = [&] {
    if (value.get_type() != sol::type::number) fail(L, function, "must be a number, got " + describe(value));
    return value.as<double>();
  };
  try {
    if (k == "gravity") {
      const auto g = toVec(L, value);
      if (!g) fail(L, function, "must be a vector {x, y} or vec2(x, y), got " + describe(value));
      w.setGravity(*g);
    } else if (k == "integrator") {
      const auto i = value.is<std::string>() ? parseIntegrator(value.as<std::string>()) : std::nullopt;
      if (!i) fail(L, function, "must be one of " + integratorNames() + ", got " + describe(value));
      w.setIntegrator(*i);
    } else if (k == "dt") {
      const double dt = number();
      if (!(dt > 0) || !std::isfinite(dt)) fail(L, function, "must be > 0, got " + formatNumber(dt));
      self.scene->settings.dt = dt;
    } else if (k == "iterations") {
      const double n = number();
      if (n != std::floor(n) || n < 1 || n > 10000)
        fail(L, function, "must be a whole number between 1 and 10000, got " + describe(value));
      w.setIterations(static_cast<int>(n));
    } else if (k == "solver") {
      const auto s = value.is<std::string>() ? parseContactSolver(value.as<std::string>()) : std::nullopt;
      if (!s) fail(L, function, "must be one of " + contactSolverNames() + ", got " + describe(value));
      w.setContactSolver(*s);
    } else if (k == "substeps") {
      const double n = number();
      if (n != std::floor(n) || n < 1 || n > 64)
        fail(L, function, "must be a whole number between 1 and 64, got " + describe(value));
      w.setSubsteps(static_cast<int>(n));
    } else if (k == "sleeping") {
      if (value.get_type() != sol::type::boolean) fail(L, function, "must be true or false, got " + describe(value));
      w.setSleeping(value.as<bool>());
    } else if (k == "exact_joints") {
      if (value.get_type() != sol::type::boolean) fail(L, function, "must be true or false, got " + describe(value));
      w.setExactJoints(value.as<bool>());
    } else if (std::find(kWorldFields.begin(), kWorldFields.end(), k) != kWorldFields.end() || k == "controls" ||
               std::find(kWorldMethods.begin(), kWorldMethods.end(), k) != kWorldMethods.end()) {
      fail(L, function, "is read-only");
    } else {
      unknownField(L, k);
    }
  } catch (const InputError& e) {
    fail(L, function, e.what());
  }
}

// --- force handles: kind, removed, remove()

const LuaForceHandle& selfForce(lua_State* L, std::string_view function) {
  const LuaForceHandle* f = toHandle<LuaForceHandle>(L, 1);
  if (!f) fail(L, function, "call it as handle:" + std::string(function) + "(), with a colon");
  return *f;
}

int removeForceHandle(lua_State* L) {
  const LuaForceHandle& f = selfForce(L, "remove");
  requireIdle(L, *f.scene, "remove");
  if (f.scene->world->isValid(f.id)) {
    try {
      f.scene->world->removeForce(f.id);
    } catch (const InputError& e) {
      fail(L, "remove", e.what());
    }
  }
  return 0;
}

int forceIndex(lua_State* L) {
  const LuaForceHandle& self = selfForce(L, "handle");
  sol::stack_object key(L, 2);
  const std::string k = key.is<std::string>() ? key.as<std::string>() : describe(key);
  if (k == "kind") {
    lua_pushstring(L, self.kind);
  } else if (k == "removed") {
    lua_pushboolean(L, !liveWorld(L, *self.scene, self.kind).isValid(self.id));
  } else if (k == "remove") {
    lua_pushcfunction(L, guarded<removeForceHandle>);
  } else {
    noSuchField(L, self.kind, k, {"kind", "removed", "remove"});
  }
  return 1;
}

int forceNewIndex(lua_State* L) {
  fail(L, selfForce(L, "handle").kind, "handles are read-only (use world:remove to remove it)");
}

int forceToString(lua_State* L) {
  lua_pushstring(L, selfForce(L, "tostring").kind);
  return 1;
}

const LuaWorld& selfWorldHandle(lua_State* L) {
  const LuaWorld* w = toHandle<LuaWorld>(L, 1);
  if (!w) fail(L, "world", "expects the world");
  return *w;
}

int worldIndexMeta(lua_State* L) {
  worldIndex(L, selfWorldHandle(L), sol::stack_object(L, 2)).push(L);
  return 1;
}

int worldNewIndexMeta(lua_State* L) {
  worldNewIndex(L, selfWorldHandle(L), sol::stack_object(L, 2), sol::stack_object(L, 3));
  return 0;
}

int worldToString(lua_State* L) {
  lua_pushliteral(L, "world");
  return 1;
}

}  // namespace

Scene::Impl& selfWorld(lua_State* L, std::string_view function) {
  const LuaWorld* world = toHandle<LuaWorld>(L, 1);
  if (!world)
    fail(L, function, "call it as world:" + std::string(function) + "(...), with a colon; got " + describe(L, 1) +
                          " as the world");
  Scene::Impl& scene = *world->scene;
  liveWorld(L, scene, function);
  return scene;
}

Scene::Impl& editedWorld(lua_State* L, std::string_view function) {
  Scene::Impl& scene = selfWorld(L, function);
  requireIdle(L, scene, function);
  return scene;
}

World& liveWorld(lua_State* L, Scene::Impl& scene, std::string_view function) {
  if (!scene.world) fail(L, function, "the scene is closed");
  return *scene.world;
}

void requireIdle(lua_State* L, Scene::Impl& scene, std::string_view function) {
  if (liveWorld(L, scene, function).isStepping())
    fail(L, function, "not allowed while the world is stepping (from inside a force)");
}

size_t hostBytes(const World& world, const Body& body) {
  // The body record, its shapes' records, vertices and normals, its name, and the world's per-body
  // and per-shape working arrays (some 40 vectors indexed by slot). Measured: 930 bytes of host
  // memory per circle (RSS of 200 000 circles less that of 100 000, less Lua's own growth).
  constexpr size_t kPerSlot = 560;
  size_t bytes = sizeof(Body) + kPerSlot + body.name.size();
  for (const ShapeId s : body.shapes) bytes += shapeHostBytes(world.shape(s));
  return bytes;
}

size_t shapeHostBytes(const BodyShape& shape) {
  return sizeof(BodyShape) + 2 * sizeof(Vec2) * shape.geometry.vertices.size();
}

void chargeJoint(lua_State* L, Scene::Impl& scene, std::string_view function, JointId id) {
  // The definition, the solver's record and per-joint lists (an estimate of the core's Joint).
  constexpr size_t kPerJoint = 1024;
  World& world = *scene.world;
  const size_t bytes = sizeof(JointDef) + kPerJoint + world.joint(id).name.size();
  // Gives back the charges of joints that are gone (removed with a body, broken, removed).
  const auto settle = [&] {
    std::erase_if(scene.joint_charges, [&](const std::pair<JointId, size_t>& c) {
      if (world.isValid(c.first)) return false;
      scene.host->release(c.second);
      return true;
    });
    scene.joint_charges_checked = scene.joint_charges.size();
  };
  // Settled in batches (amortised O(1) per joint), and before a charge would fail.
  if (scene.joint_charges.size() >= 2 * scene.joint_charges_checked + 64 ||
      scene.host->memoryUsed() + bytes > scene.host->limits().memory_bytes)
    settle();
  try {
    scene.host->charge(L, function, bytes);
  } catch (...) {
    world.destroyJoint(id);  // over the memory limit: as if it had not been made
    throw;
  }
  scene.joint_charges.emplace_back(id, bytes);
}

void registerWorldType(lua_State* L) {
  registerHandleType(L, LuaWorld::kMetatable, guarded<worldIndexMeta>, guarded<worldNewIndexMeta>, guarded<worldToString>,
                     nullptr);
  registerHandleType(L, LuaForceHandle::kMetatable, guarded<forceIndex>, guarded<forceNewIndex>, guarded<forceToString>,
                     guarded<handlesEqual<LuaForceHandle, &LuaForceHandle::id>>);
}

}  // namespace rigidlab::lua

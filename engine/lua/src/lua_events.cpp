// Events in Lua (lua_events.h): shape event options and fields, pre_solve functions run during the
// step, and the hook calls made after it.
#include "lua_events.h"

#include "api_names.h"
#include "lua_contact.h"
#include "lua_shape.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

bool isFunction(const sol::object& f) { return f.valid() && f.get_type() == sol::type::function; }

// A one_way direction: a finite vector that is not zero (the core normalises it).
Vec2 oneWay(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v) {
  const Vec2 n = checkVec(L, function, subject, v);
  if (!(n.norm() > 0.0))
    fail(L, function, (subject.empty() ? "" : std::string(subject) + " ") +
                          "must be a direction {nx, ny} (the side to stand on), got " + formatVec(n));
  return n;
}

void requirePreSolveFunction(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v,
                             bool nil_allowed) {
  if (v.get_type() == sol::type::function) return;
  fail(L, function, (subject.empty() ? "" : std::string(subject) + " ") +
                        "must be a function(contact) that returns false to disable the contact" +
                        (nil_allowed ? ", or nil" : "") + ", got " + describe(v));
}

uint64_t keyOf(ShapeId id) { return handleKey(id.index, id.generation); }

// Lua called from inside the world's step (pre_solve functions, ShouldCollide): under the step's
// Lua budget, a Lua error thrown as ScriptError naming `what` (the step is then undone).
template <typename Body>
void duringStep(Scene::Impl& s, std::string_view what, Body body) {
  ScriptHost& host = *s.host;
  const Budget::Scope budget(host.budget(), Budget::Kind::Force);
  const auto error = host.run([&] { body(host); });
  if (error) throw ScriptError(host.errorText(*error, what));
}

// A number a pre_solve function wrote into its contact table (field `k`: the table's metatable
// gives the contact's values, a write puts the field in the table itself), checked as the shape
// option of that name is; `was` if none was written.
double writtenNumber(lua_State* L, int table, const char* k, double was, Range range) {
  lua_pushstring(L, k);
  lua_rawget(L, table);
  const sol::object v = sol::stack::pop<sol::object>(L);
  if (v.get_type() == sol::type::lua_nil) return was;
  const double x = checkNumber(L, "pre_solve", std::string("contact.") + k, v, range);
  if (std::string_view(k) == "restitution" && x > 1.0)
    fail(L, "pre_solve", "contact.restitution must be between 0 and 1, got " + formatNumber(x));
  return x;
}

// What the pre_solve functions wrote into the contact table (api::kPreSolveWritable), for this
// step: friction (and static_friction with it unless that is written too), restitution,
// tangent_speed; enabled = false disables the contact as returning false does.
bool readPreSolveWrites(lua_State* L, int table, ContactInfo& c) {
  const double friction = writtenNumber(L, table, "friction", c.friction, Range::NonNegative);
  const double static_friction = writtenNumber(L, table, "static_friction", c.static_friction, Range::NonNegative);
  if (static_friction != c.static_friction) c.static_friction = static_friction;
  else if (friction != c.friction) c.static_friction = friction;  // one friction, as LÖVE and Box2D have
  c.friction = friction;
  c.restitution = writtenNumber(L, table, "restitution", c.restitution, Range::NonNegative);
  c.tangent_speed = writtenNumber(L, table, "tangent_speed", c.tangent_speed, Range::Finite);
  lua_pushliteral(L, "enabled");
  lua_rawget(L, table);
  const bool disabled = lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1);
  lua_pop(L, 1);
  return !disabled;
}

// The pre-solve callback of the scene's world: the pre_solve functions of the contact's shapes, in
// the order a, b, each given the same contact table; the first that returns false disables the
// contact (and the other is not asked). What they wrote into the table's writable fields
// (readPreSolveWrites) holds for this step. Runs inside the step, under the step's Lua budget.
bool runPreSolve(Scene::Impl& s, ContactInfo& c) {
  lua_State* L = s.host->L();
  bool enabled = true;
  duringStep(s, "pre_solve", [&](ScriptHost& host) {
    const int top = lua_gettop(L);
    pushContact(L, s, contactView(*s.world, c));
    for (const ShapeId id : {c.shape_a, c.shape_b}) {
      if (!enabled) break;
      s.pre_solve_functions.push(L);
      lua_rawgeti(L, -1, static_cast<lua_Integer>(keyOf(id)));
      lua_remove(L, -2);
      if (lua_type(L, -1) != LUA_TFUNCTION) {
        lua_pop(L, 1);
        continue;
      }
      lua_pushvalue(L, top + 1);
      ++host.calls;
      lua_call(L, 1, 1);
      enabled = !(lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1));
      lua_pop(L, 1);
    }
    enabled = readPreSolveWrites(L, top + 1, c) && enabled;
    lua_settop(L, top);
  });
  return enabled;
}

// Keeps `f` as the pre_solve function of shape `id` (nil: none) and flags the shape for the core.
void keepPreSolve(lua_State* L, Scene::Impl& scene, ShapeId id, const sol::object& f) {
  const bool on = f.get_type() == sol::type::function;
  if (!scene.pre_solve_functions.valid()) {
    if (!on) return;
    scene.pre_solve_functions = sol::table(L, sol::create);
    scene.world->setPreSolve([&scene](ContactInfo& c) { return runPreSolve(scene, c); });
  }
  scene.pre_solve_functions.raw_set(static_cast<lua_Integer>(keyOf(id)), on ? f : sol::make_object(L, sol::lua_nil));
  scene.world->setShapePreSolve(id, on);
}

}  // namespace

void readShapeEventOptions(const Options& o, ShapeDef& def) {
  if (!o.hasAny(api::kShapeEventOptions)) return;
  def.contact_events = o.boolean("contact_events", false);
  def.hit_speed = o.nonNegative("hit_speed", def.hit_speed);
  def.hit_events = o.boolean("hit_events", o.has("hit_speed"));
  if (o.has("one_way")) def.one_way = oneWay(o.L(), o.function(), "one_way", o.get("one_way"));
  if (o.has("pre_solve")) {
    requirePreSolveFunction(o.L(), o.function(), "pre_solve", o.get("pre_solve"), false);
    def.pre_solve = true;
  }
}

void attachShapeEvents(lua_State* L, Scene::Impl& scene, const Options& o, ShapeId id) {
  if (!o.hasAny(api::kShapeEventOptions)) return;
  ShapeDef d;
  readShapeEventOptions(o, d);  // checked already, before the shape was made
  World& w = *scene.world;
  w.setShapeEvents(id, d.contact_events, d.hit_events, d.hit_speed);
  if (d.one_way) w.setShapeOneWay(id, d.one_way);
  if (o.has("pre_solve")) keepPreSolve(L, scene, id, o.get("pre_solve"));
}

bool pushShapeEventField(lua_State* L, Scene::Impl& scene, const BodyShape& s, std::string_view k) {
  if (k == "contact_events") {
    lua_pushboolean(L, s.contact_events);
  } else if (k == "hit_events") {
    lua_pushboolean(L, s.hit_events);
  } else if (k == "hit_speed") {
    lua_pushnumber(L, s.hit_speed);
  } else if (k == "one_way") {
    if (s.one_way) pushVec(L, *s.one_way);
    else lua_pushnil(L);
  } else if (k == "pre_solve") {
    if (scene.pre_solve_functions.valid()) scene.pre_solve_functions.raw_get<sol::object>(static_cast<lua_Integer>(keyOf(s.id))).push(L);
    else lua_pushnil(L);
  } else {
    return false;
  }
  return true;
}

bool setShapeEventField(lua_State* L, Scene::Impl& scene, ShapeId id, std::string_view function, std::string_view k,
                        const sol::object& value) {
  World& w = *scene.world;
  const BodyShape& s = w.shape(id);
  try {
    if (k == "contact_events") {
      w.setShapeEvents(id, checkBool(L, function, "", value), s.hit_events, s.hit_speed);
    } else if (k == "hit_events") {
      w.setShapeEvents(id, s.contact_events, checkBool(L, function, "", value), s.hit_speed);
    } else if (k == "hit_speed") {
      w.setShapeEvents(id, s.contact_events, s.hit_events, checkNumber(L, function, "", value, Range::NonNegative));
    } else if (k == "one_way") {
      w.setShapeOneWay(id, isMissing(value) ? std::nullopt : std::optional(oneWay(L, function, "", value)));
    } else if (k == "pre_solve") {
      if (!isMissing(value)) requirePreSolveFunction(L, function, "", value, true);
      keepPreSolve(L, scene, id, value);
    } else {
      return false;
    }
  } catch (const InputError& e) {
    failCore(L, function, e);
  }
  return true;
}

void forgetShapeEvents(Scene::Impl& scene, ShapeId id) {
  if (scene.pre_solve_functions.valid()) scene.pre_solve_functions.raw_set(static_cast<lua_Integer>(keyOf(id)), sol::lua_nil);
}

const std::vector<EventHook>& eventHooks() {
  static const std::vector<EventHook> hooks = {{"OnContactBegin", &Scene::Impl::on_contact_begin},
                                               {"OnContactEnd", &Scene::Impl::on_contact_end},
                                               {"OnHit", &Scene::Impl::on_hit},
                                               {"OnSensorBegin", &Scene::Impl::on_sensor_begin},
                                               {"OnSensorEnd", &Scene::Impl::on_sensor_end},
                                               {"OnJointBreak", &Scene::Impl::on_joint_break}};
  return hooks;
}

namespace {

// The world's collision filter for a scene that defines ShouldCollide(shape_a, shape_b): called
// during the step (broad_phase.cpp), once per pair whose boxes begin to overlap, under the step's
// Lua budget as pre_solve functions are; false keeps the pair apart while their boxes overlap.
bool runShouldCollide(Scene::Impl& s, ShapeId a, ShapeId b) {
  lua_State* L = s.host->L();
  bool collide = true;
  duringStep(s, "ShouldCollide", [&](ScriptHost& host) {
    const int top = lua_gettop(L);
    s.should_collide.push(L);
    pushShapeHandle(L, s, a);
    pushShapeHandle(L, s, b);
    ++host.calls;
    lua_call(L, 2, 1);
    collide = !(lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1));
    lua_settop(L, top);
  });
  return collide;
}

}  // namespace

void installShouldCollide(Scene::Impl& scene) {
  if (!isFunction(scene.should_collide)) return;
  scene.world->setShouldCollide([&scene](ShapeId a, ShapeId b) { return runShouldCollide(scene, a, b); });
}

std::vector<std::string> unraisedEventWarnings(const Scene::Impl& scene) {
  const World& w = *scene.world;
  bool contact = false, hit = false;
  for (const BodyId id : w.bodyIds())
    for (const ShapeId s : w.body(id).shapes) {
      contact = contact || w.shape(s).contact_events;
      hit = hit || w.shape(s).hit_events;
    }
  std::vector<std::string> out;
  const auto warn = [&](const char* hook, const sol::object& f, bool raised, const char* option) {
    if (!isFunction(f) || raised) return;
    out.push_back(std::string("warning: ") + hook + " is defined, but no shape has " + option +
                  " = true, so it is never called: give " + option +
                  " = true to the shapes whose contacts it wants (unlike Box2D v3, rigidlab raises contact "
                  "events only for the shapes that ask, so a scene without them pays nothing)");
  };
  warn("OnContactBegin", scene.on_contact_begin, contact, "contact_events");
  warn("OnContactEnd", scene.on_contact_end, contact, "contact_events");
  warn("OnHit", scene.on_hit, hit, "hit_events");
  return out;
}

void pushEventCalls(Scene::Impl& s, std::vector<EventCall>& calls) {
  calls.clear();
  const bool contacts = isFunction(s.on_contact_begin) || isFunction(s.on_contact_end) || isFunction(s.on_hit);
  const bool sensors = isFunction(s.on_sensor_begin) || isFunction(s.on_sensor_end);
  const bool joints = isFunction(s.on_joint_break);
  if (!contacts && !sensors && !joints) return;
  lua_State* L = s.host->L();
  const World& w = *s.world;
  using Kind = World::ContactEvent::Kind;
  const std::vector<World::ContactEvent>& contact_events = w.contactEvents();
  lua_createtable(L, contacts ? static_cast<int>(contact_events.size()) : 0, 0);
  const int args = lua_gettop(L);
  int n = 0;  // arguments in the table
  const auto keep = [&] { lua_rawseti(L, args, ++n); return n; };
  if (contacts) {
    // The hook of each kind looked up once, not per event.
    const sol::object* hook[3] = {nullptr, nullptr, nullptr};
    for (int k = 0; k < 3; ++k)
      if (isFunction(s.*eventHooks()[k].slot)) hook[k] = &(s.*eventHooks()[k].slot);
    calls.reserve(contact_events.size());
    ContactPusher pusher(L, s);
    for (const World::ContactEvent& e : contact_events) {
      const int k = e.kind == Kind::Begin ? 0 : e.kind == Kind::End ? 1 : 2;
      if (!hook[k]) continue;
      pusher.push(contactView(e));
      calls.push_back({hook[k], eventHooks()[k].name, keep(), 0});
    }
    pusher.done();
  }
  if (sensors) {
    for (const World::SensorEvent& e : w.sensorEvents()) {
      const EventHook& h = eventHooks()[e.begin ? 3 : 4];
      if (!isFunction(s.*h.slot)) continue;
      pushShapeHandle(L, s, e.sensor);
      const int sensor = keep();
      pushShapeHandle(L, s, e.visitor);
      calls.push_back({&(s.*h.slot), h.name, sensor, keep()});
    }
  }
  if (joints) {
    // The core has removed a broken joint by now: its handle is made from what the break kept.
    for (const World::JointBreakInfo& b : w.jointBreaks()) {
      pushCachedHandle(L, s.joint_handles, handleKey(b.id.index, b.id.generation), LuaJoint{&s, b.id, b.def.type});
      calls.push_back({&s.on_joint_break, "OnJointBreak", keep(), 0});
    }
  }
}

}  // namespace rigidlab::lua

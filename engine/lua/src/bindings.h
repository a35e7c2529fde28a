// Internal glue shared by the binding files: the scene's state and the Lua-side handle types.
// The glue holds no physics: it validates, converts and calls the core.
#pragma once

#include <memory>
#include <new>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "rigidlab/lua/scene.h"
#include "script_host.h"

namespace rigidlab::lua {

struct LuaDraw;

struct Scene::Impl {
  ~Impl();  // closes in order (scene_loader.cpp): the world, the Lua references, the state
  std::unique_ptr<ScriptHost> host;
  std::unique_ptr<World> world;  // null while the scene closes: handles then refuse to work
  SceneSettings settings;
  std::filesystem::path file;
  std::string name;  // what messages show as the file name
  sol::object on_step, check, on_key, on_draw, exact;  // the hook functions, or nil
  sol::table handles;       // body uid → its Lua handle, so the same body is always the same object
  sol::table user_data;     // body uid → body.user_data (any Lua value; the engine never reads it)
  // Shape and joint key (handleKey) → shape.user_data, joint.user_data. Set (or cleared) when a
  // shape or joint is made, so a reused slot starts without the old one's; a joint's stays
  // readable after it broke (OnJointBreak).
  sol::table shape_user_data, joint_user_data;
  // Shape and joint key (handleKey) → handle, weak-valued: the same shape or joint is the same
  // object while a script holds it (usable as a table key), and a forgotten one costs nothing.
  sol::table shape_handles, joint_handles;
  // Joints that broke in a step (handleKey), so a handle still says `broken` after the core removed
  // the joint (noteJointBreaks).
  std::set<uint64_t> broken_joints;
  // Host memory charged for joints. The core removes joints on its own (with their bodies, when
  // they break), so the charges of joints that no longer exist are given back in batches
  // (chargeJoint).
  std::vector<std::pair<JointId, size_t>> joint_charges;
  size_t joint_charges_checked = 0;  // joint_charges.size() after the last pass
  sol::object world_handle; // the `world` passed to hooks
  sol::object draw_handle;  // the `draw` passed to OnDraw
  LuaDraw* draw = nullptr;  // draw_handle's object
  // --- events (lua_events.cpp): the event hooks, or nil; the shapes' pre_solve functions (shape
  // key → function), made on first use, so a scene without them holds nothing for events.
  sol::object on_contact_begin, on_contact_end, on_hit, on_sensor_begin, on_sensor_end, on_joint_break;
  sol::table pre_solve_functions;
  sol::object should_collide;  // ShouldCollide, or nil (the world's collision filter calls it)
  double event_seconds = 0.0, event_cpu_seconds = 0.0;  // Scene::eventSeconds, eventCpuSeconds

  // --- sandbox mod hooks (scene_controls.cpp, lua_mouse_event.cpp)
  sol::object on_mouse, on_control;  // OnMouse, OnControl, or nil
  std::vector<double> control_values;  // current values of settings.controls (sliders; 0 for buttons)

  // world:snapshot()'s, by the index their handles hold (lua_snapshot.cpp)
  std::vector<WorldSnapshot> snapshots;
  sol::object save_state, load_state;  // SaveState, LoadState (scene_state.h), or nil
};

// Handles are full userdata holding these plain structs, with metatables of the host's own
// (handles.cpp), not sol2 usertypes: a handle's metatable holds only __index, __newindex,
// __tostring, __eq, __name and __metatable = false (getmetatable(handle) is false), and no __gc,
// for a handle needs no finalizer (the structs are trivially destructible). So no finalizer
// exists in a scene's state at all, and no key of a handle reaches a binding's internals.

// A body as Lua sees it (`world:add_box{}` returns one). Stale after world:remove(body).
struct LuaBody {
  static constexpr const char* kMetatable = "rigidlab.body";
  Scene::Impl* scene;
  BodyId id;
  uint32_t uid;
};

// A shape of a body (`body:add_shape{}` returns one). Stale after shape:remove() or its body's removal.
struct LuaShape {
  static constexpr const char* kMetatable = "rigidlab.shape";
  Scene::Impl* scene;
  ShapeId id;
};

// A joint (`world:add_revolute{}` returns one). Stale once removed or broken.
struct LuaJoint {
  static constexpr const char* kMetatable = "rigidlab.joint";
  Scene::Impl* scene;
  JointId id;
  JointType type;  // kept: `kind` stays readable after the joint is gone
};

// The key of a shape or joint in the handle caches and broken_joints: generation and slot index.
inline uint64_t handleKey(uint32_t index, uint32_t generation) { return (uint64_t{generation} << 32) | index; }

// A force, spring or damper as Lua sees it.
struct LuaForceHandle {
  static constexpr const char* kMetatable = "rigidlab.force";
  Scene::Impl* scene;
  ForceId id;
  const char* kind;  // "spring", "damper", "lua force": a string literal
};

struct LuaWorld {
  static constexpr const char* kMetatable = "rigidlab.world";
  Scene::Impl* scene;
};

// The `draw` argument of OnDraw; usable only during that call, which it counts (Scene::DrawReport).
struct LuaDraw {
  static constexpr const char* kMetatable = "rigidlab.draw";
  OverlayDraw* target = nullptr;
  Scene::DrawReport report;
  size_t text_bytes = 0;
  // draw.screen: a second handle that draws through this one (its target and allowance) in pixels.
  LuaDraw* main = nullptr;       // set in the screen handle: the draw object it belongs to
  int screen_ref = LUA_NOREF;    // set in the main handle: registry reference of the screen handle
};

// Pushes the `draw` handle of OnDraw (made with its draw.screen) and sets `main` to it.
void pushDrawHandles(lua_State* L, LuaDraw*& main);

// The handle of type T at `index`, or nullptr if the value is something else.
template <typename T>
T* toHandle(lua_State* L, int index) {
  return static_cast<T*>(luaL_testudata(L, index, T::kMetatable));
}

// Pushes a new handle holding `value`.
template <typename T>
void pushHandle(lua_State* L, const T& value) {
  static_assert(std::is_trivially_destructible_v<T>, "a handle must need no finalizer (no __gc)");
  new (lua_newuserdatauv(L, sizeof(T), 0)) T(value);
  luaL_setmetatable(L, T::kMetatable);
}

// The handle of `value` in `cache` under `key`, made and kept there on first use: the same body,
// shape or joint is the same Lua object while the cache holds it.
template <typename T>
sol::object cachedHandle(lua_State* L, sol::table& cache, uint64_t key, const T& value) {
  sol::object cached = cache.raw_get<sol::object>(key);
  if (cached.valid() && cached.get_type() != sol::type::lua_nil) return cached;
  pushHandle(L, value);
  sol::object handle = sol::stack::pop<sol::object>(L);
  cache.raw_set(key, handle);
  return handle;
}

// cachedHandle pushed onto the stack, with no registry reference made on the way (the event
// hooks' arguments are built in bulk), from the cache at stack index `cache` (absolute).
template <typename T>
void pushCachedHandleAt(lua_State* L, int cache, uint64_t key, const T& value) {
  if (lua_rawgeti(L, cache, static_cast<lua_Integer>(key)) != LUA_TNIL) return;
  lua_pop(L, 1);
  pushHandle(L, value);
  lua_pushvalue(L, -1);
  lua_rawseti(L, cache, static_cast<lua_Integer>(key));
}
template <typename T>
void pushCachedHandle(lua_State* L, const sol::table& cache, uint64_t key, const T& value) {
  cache.push(L);
  pushCachedHandleAt(L, lua_gettop(L), key, value);
  lua_remove(L, -2);
}

// __eq of a handle type: two handles of one scene naming the same thing (T::*Key: uid, id).
template <typename T, auto Key>
int handlesEqual(lua_State* L) {
  const T *a = toHandle<T>(L, 1), *b = toHandle<T>(L, 2);
  lua_pushboolean(L, a && b && a->scene == b->scene && a->*Key == b->*Key);
  return 1;
}

// __tostring of a handle type: Describe(handle), e.g. "revolute joint 'hinge'".
template <typename T, std::string (*Describe)(const T&)>
int handleToString(lua_State* L) {
  const T* handle = toHandle<T>(L, 1);
  const std::string text = handle ? Describe(*handle) : std::string("?");
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

// Pushes a list {handle(ids[1]), ...}.
template <typename Id, typename Handle>
void pushHandles(lua_State* L, const std::vector<Id>& ids, Handle handle) {
  lua_createtable(L, static_cast<int>(ids.size()), 0);
  for (size_t i = 0; i < ids.size(); ++i) {
    handle(ids[i]).push(L);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

// A method by name, from a table of them; nullptr if `name` is none of them.
struct NamedFunction {
  std::string_view name;
  lua_CFunction function;
};
template <size_t N>
lua_CFunction lookUp(const NamedFunction (&table)[N], std::string_view name) {
  for (const NamedFunction& f : table)
    if (f.name == name) return f.function;
  return nullptr;
}

// Creates the metatable `name` in the registry with the given metamethods (nullptr: none) and
// __metatable = false.
void registerHandleType(lua_State* L, const char* name, lua_CFunction index, lua_CFunction new_index,
                        lua_CFunction to_string, lua_CFunction equal);

void registerBodyType(lua_State* L);
void registerWorldType(lua_State* L);
void registerDrawType(lua_State* L);
void registerShapeType(lua_State* L);
void registerJointType(lua_State* L);
// A table whose values are weak (the handle caches).
sol::table makeWeakTable(lua_State* L);

// The handle of a live body (created on first use, then cached in Scene::Impl::handles).
sol::object bodyHandle(lua_State* L, Scene::Impl& scene, BodyId id);
void pushBodyHandle(lua_State* L, Scene::Impl& scene, BodyId id);  // the same, pushed
// The body a handle designates; fails "<function>: <what> was removed" for a stale one.
BodyId liveBody(lua_State* L, const LuaBody& body, std::string_view function);
// The body named by option `key`, which must hold a body handle of this scene.
BodyId bodyOption(lua_State* L, Scene::Impl& scene, std::string_view function, std::string_view key,
                  const sol::object& value);

// The scene of `world:<function>(...)`, whose argument 1 must be the world (called with a colon);
// editedWorld also refuses while the world steps (requireIdle).
Scene::Impl& selfWorld(lua_State* L, std::string_view function);
Scene::Impl& editedWorld(lua_State* L, std::string_view function);

// The scene's world; fails "<function>: the scene is closed" while it closes.
World& liveWorld(lua_State* L, Scene::Impl& scene, std::string_view function);
// Fails "<function>: not allowed while the world is stepping (from inside a force)" during a step:
// the API's edits are refused then (World::isStepping).
void requireIdle(lua_State* L, Scene::Impl& scene, std::string_view function);
// Host memory a body takes (its record, per-body working arrays, shapes and name), charged against
// the scene's memory limit while it exists (ScriptHost::charge): the body's own part plus each
// shape's (shapeHostBytes), so that adding and removing shapes charges and releases their part.
size_t hostBytes(const World& world, const Body& body);
size_t shapeHostBytes(const BodyShape& shape);
// Charges the host memory of a joint just made; over the limit, the joint is destroyed again and
// the call fails as for bodies.
void chargeJoint(lua_State* L, Scene::Impl& scene, std::string_view function, JointId id);

// Joints: the world's and a body's joint functions (lua_world_joints.cpp); world:remove(joint) and
// what a step broke (lua_joint.cpp).
lua_CFunction jointWorldMethod(std::string_view name);  // add_revolute, ..., joints, find_joint; or nullptr
int bodyJointsMethod(lua_State* L);                     // body:joints()
void removeJoint(lua_State* L, const LuaJoint& joint, std::string_view function);
void noteJointBreaks(Scene::Impl& scene);  // after every step of the scene's world

// Body creation (lua_world_bodies.cpp): world:add_box, add_circle, add_polygon, add_capsule,
// add_segment, add_chain, add_body; or nullptr.
lua_CFunction bodyWorldMethod(std::string_view name);

bool isVec2Table(lua_State* L, int index);

// --- sandbox mod hooks
// Reads scene.keys and scene.controls of the scene table `o` into `settings` (scene_controls.cpp).
class Options;
void readModSettings(const Options& o, SceneSettings& settings);
// The starting values of the scene's controls: the defaults, or `given` (clamped) by name.
std::vector<double> initialControlValues(const SceneSettings& settings, const std::map<std::string, double>& given);
// world.controls: a handle reading and setting the sliders by name (scene_controls.cpp).
void registerControlsType(lua_State* L);
void pushControls(lua_State* L, Scene::Impl& scene);
// The event table of OnMouse(world, event) (lua_mouse_event.cpp).
void pushMouseEvent(lua_State* L, const MouseEvent& event);
// "body 'ball' (id 3)", "a spring", ... for messages.
std::string describeHandle(lua_State* L, int index);

}  // namespace rigidlab::lua

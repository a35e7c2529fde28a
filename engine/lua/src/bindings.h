// Internal glue shared by the binding files: the scene's state and the Lua-side handle types.
// The glue holds no physics: it validates, converts and calls the core.
#pragma once

#include <memory>
#include <string>

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
  sol::object world_handle; // the `world` passed to hooks
  sol::object draw_handle;  // the `draw` passed to OnDraw
  LuaDraw* draw = nullptr;  // draw_handle's object
};

// A body as Lua sees it (`world:add_box{}` returns one). Stale after world:remove(body).
struct LuaBody {
  Scene::Impl* scene;
  BodyId id;
  uint32_t uid;
};

// A force, spring or damper as Lua sees it.
struct LuaForceHandle {
  Scene::Impl* scene;
  ForceId id;
  std::string kind;
};

struct LuaWorld {
  Scene::Impl* scene;
};

// The `draw` argument of OnDraw; usable only during that call, which it counts (Scene::DrawReport).
struct LuaDraw {
  OverlayDraw* target = nullptr;
  Scene::DrawReport report;
  size_t text_bytes = 0;
};

void registerBodyType(sol::state& lua);
void registerWorldType(sol::state& lua);
void registerDrawType(sol::state& lua);

// The handle of a live body (created on first use, then cached in Scene::Impl::handles).
sol::object bodyHandle(lua_State* L, Scene::Impl& scene, BodyId id);
// The body a handle designates; fails "<function>: <what> was removed" for a stale one.
BodyId liveBody(lua_State* L, const LuaBody& body, std::string_view function);
// The body named by option `key`, which must hold a body handle of this scene.
BodyId bodyOption(lua_State* L, Scene::Impl& scene, std::string_view function, std::string_view key,
                  const sol::object& value);

// The scene's world; fails "<function>: the scene is closed" while it closes.
World& liveWorld(lua_State* L, Scene::Impl& scene, std::string_view function);
// Fails "<function>: not allowed while the world is stepping (from inside a force)" during a step:
// the API's edits are refused then (World::isStepping).
void requireIdle(lua_State* L, Scene::Impl& scene, std::string_view function);
// Host memory a body takes (its record, per-body working arrays, shape and name), charged against
// the scene's memory limit while it exists (ScriptHost::charge).
size_t hostBytes(const World& world, const Body& body);

bool isVec2Table(lua_State* L, int index);
// "body 'ball' (id 3)", "a spring", ... for messages.
std::string describeHandle(lua_State* L, int index);

}  // namespace rigidlab::lua

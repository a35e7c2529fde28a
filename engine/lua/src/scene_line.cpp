// Where the main chunk sets the global `scene` (scene_line.h).
#include "scene_line.h"

#include <lua.hpp>

#include <string_view>

#include "script_host.h"

namespace rigidlab::lua {
namespace {

constexpr const char* kWatchKey = "rigidlab.scene_watch";  // the metatable put on _G
constexpr const char* kLineKey = "rigidlab.scene_line";

// __newindex(t, k, v) of the globals while the main chunk runs.
int sceneAssignment(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 3);
  if (lua_type(L, 2) == LUA_TSTRING && std::string_view(lua_tostring(L, 2)) == "scene")
    recordSceneLine(L, sceneLocation(L));
  lua_rawset(L, 1);
  return 0;
}

// Pushes _G's metatable if it is the host's watcher, else nothing; returns whether it pushed.
bool pushWatcher(lua_State* L) {
  lua_pushglobaltable(L);
  if (!lua_getmetatable(L, -1)) {
    lua_pop(L, 1);
    return false;
  }
  lua_getfield(L, LUA_REGISTRYINDEX, kWatchKey);
  const bool ours = !lua_isnil(L, -1) && lua_rawequal(L, -1, -2);
  lua_pop(L, 2);  // the registry's copy and _G's metatable
  if (!ours) lua_pop(L, 1);
  return ours;  // _G left on the stack
}

}  // namespace

void watchSceneLine(lua_State* L) {
  lua_pushglobaltable(L);
  lua_createtable(L, 0, 2);
  lua_pushcfunction(L, guarded<sceneAssignment>);
  lua_setfield(L, -2, "__newindex");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");  // getmetatable(_G) is false: no way to reach __newindex
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, kWatchKey);
  lua_setmetatable(L, -2);
  lua_pop(L, 1);
}

void unwatchSceneLine(lua_State* L) {
  if (pushWatcher(L)) {
    lua_pushnil(L);
    lua_setmetatable(L, -2);
    lua_pop(L, 1);
  }
  lua_pushnil(L);
  lua_setfield(L, LUA_REGISTRYINDEX, kWatchKey);
}

void releaseGlobals(lua_State* L) {
  if (!pushWatcher(L)) return;
  lua_pushnil(L);
  lua_setmetatable(L, -2);
  lua_pop(L, 1);
}

void recordSceneLine(lua_State* L, const std::string& at) {
  lua_getfield(L, LUA_REGISTRYINDEX, kWatchKey);
  const bool watching = !lua_isnil(L, -1);
  lua_pop(L, 1);
  if (!watching) return;
  lua_pushlstring(L, at.data(), at.size());
  lua_setfield(L, LUA_REGISTRYINDEX, kLineKey);
}

std::string sceneLine(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kLineKey);
  std::string at = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "";
  lua_pop(L, 1);
  return at;
}

}  // namespace rigidlab::lua

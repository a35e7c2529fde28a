// The metatables of the host's handles (bindings.h): made with the C API so that nothing but the
// metamethods the bindings define is in them.
#include "bindings.h"

namespace rigidlab::lua {

void registerHandleType(lua_State* L, const char* name, lua_CFunction index, lua_CFunction new_index,
                        lua_CFunction to_string, lua_CFunction equal) {
  luaL_newmetatable(L, name);  // also sets __name, which Lua's own messages show ("a rigidlab.body value")
  const std::pair<const char*, lua_CFunction> methods[] = {
      {"__index", index}, {"__newindex", new_index}, {"__tostring", to_string}, {"__eq", equal}};
  for (const auto& [event, f] : methods) {
    if (!f) continue;
    lua_pushcfunction(L, f);
    lua_setfield(L, -2, event);
  }
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");  // getmetatable(handle) is false; setmetatable refuses it
  lua_pop(L, 1);
}

sol::table makeWeakTable(lua_State* L) {
  lua_newtable(L);
  lua_createtable(L, 0, 2);
  lua_pushliteral(L, "v");
  lua_setfield(L, -2, "__mode");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  return sol::stack::pop<sol::table>(L);
}

}  // namespace rigidlab::lua

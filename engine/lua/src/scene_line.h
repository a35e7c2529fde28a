// The line where a scene's main chunk sets the global `scene`, so that errors in its settings
// point at it ("box.lua:3: scene: dt must be > 0, got 0"). While the main chunk runs, _G has a
// metatable of the host's whose __newindex notes the line of an assignment to `scene`; the
// prelude's rawset notes it too (rawset(_G, "scene", {...}) bypasses __newindex). The metatable is
// locked (getmetatable(_G) is false), and steps aside if the scene sets a metatable of its own on
// _G (the prelude's setmetatable calls releaseGlobals).
#pragma once

#include <string>

struct lua_State;

namespace rigidlab::lua {

void watchSceneLine(lua_State* L);    // before the main chunk
void unwatchSceneLine(lua_State* L);  // after it: _G's metatable goes, if it is still the host's
// Notes `at` ("<file>:<line>: ") as where `scene` was set, if the main chunk is running.
void recordSceneLine(lua_State* L, const std::string& at);
void releaseGlobals(lua_State* L);
// What was noted: "<file>:<line>: " or "".
std::string sceneLine(lua_State* L);

}  // namespace rigidlab::lua

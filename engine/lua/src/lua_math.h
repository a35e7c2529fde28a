// math.sin, cos, tan, asin, acos and atan for scenes: the core's portable functions
// (rigidlab/portable_math.h) in place of the C library's, so that a scene that builds its terrain
// or aims with them gives the same bits on every machine. math.exp, math.log and the ^ operator
// stay the C library's (docs/physics.md, "Same bits on every machine").
#pragma once

struct lua_State;

namespace rigidlab::lua {

// Replaces the functions in the math table (which must be open).
void installPortableMath(lua_State* L);

}  // namespace rigidlab::lua

// Portable trigonometry for scenes (lua_math.h).
#include "lua_math.h"

#include <cmath>

#include <lua.hpp>

#include "rigidlab/portable_math.h"

namespace rigidlab::lua {
namespace {

int mathSin(lua_State* L) {
  lua_pushnumber(L, portableSin(luaL_checknumber(L, 1)));
  return 1;
}

int mathCos(lua_State* L) {
  lua_pushnumber(L, portableCos(luaL_checknumber(L, 1)));
  return 1;
}

int mathTan(lua_State* L) {
  double s = 0.0, c = 0.0;
  portableSinCos(luaL_checknumber(L, 1), s, c);
  lua_pushnumber(L, s / c);
  return 1;
}

// asin x = atan2(x, √((1 − x)(1 + x))), acos x = atan2(√((1 − x)(1 + x)), x): the product form
// keeps 1 − x² accurate near ±1; outside [−1, 1] the root is NaN, as asin and acos are there.
double rootOneMinusSquare(double x) { return std::sqrt((1.0 - x) * (1.0 + x)); }

int mathAsin(lua_State* L) {
  const double x = luaL_checknumber(L, 1);
  lua_pushnumber(L, std::fabs(x) > 1.0 ? std::nan("") : portableAtan2(x, rootOneMinusSquare(x)));
  return 1;
}

int mathAcos(lua_State* L) {
  const double x = luaL_checknumber(L, 1);
  lua_pushnumber(L, std::fabs(x) > 1.0 ? std::nan("") : portableAtan2(rootOneMinusSquare(x), x));
  return 1;
}

// math.atan(y [, x]): Lua 5.4's, with x = 1 when left out.
int mathAtan(lua_State* L) {
  const double y = luaL_checknumber(L, 1);
  const double x = luaL_optnumber(L, 2, 1.0);
  lua_pushnumber(L, portableAtan2(y, x));
  return 1;
}

}  // namespace

void installPortableMath(lua_State* L) {
  static const luaL_Reg kFunctions[] = {{"sin", mathSin},   {"cos", mathCos},   {"tan", mathTan}, {"asin", mathAsin},
                                        {"acos", mathAcos}, {"atan", mathAtan}, {nullptr, nullptr}};
  lua_getglobal(L, "math");
  luaL_setfuncs(L, kFunctions, 0);
  lua_pop(L, 1);
}

}  // namespace rigidlab::lua

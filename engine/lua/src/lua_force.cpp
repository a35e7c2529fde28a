#include "lua_force.h"

#include <cmath>

#include "lua_args.h"
#include "rigidlab/debug_draw.h"
#include "rigidlab/error.h"

namespace rigidlab::lua {

LuaForce::LuaForce(ScriptHost& host, const sol::function& evaluate, std::optional<Vec2> local_point, bool two_body)
    : host_(host), L_(host.L()), local_point_(local_point), two_body_(two_body) {
  evaluate.push(L_);
  lua_Debug ar;
  lua_pushvalue(L_, -1);
  lua_getinfo(L_, ">S", &ar);
  if (ar.linedefined > 0) {
    defined_at_ = std::string(ar.short_src) + ":" + std::to_string(ar.linedefined);
  } else {
    // A C function (evaluate = math.floor) has no line of its own: name the add_force call.
    defined_at_ = where(L_, 0);
    if (defined_at_.ends_with(": ")) defined_at_.resize(defined_at_.size() - 2);
    if (defined_at_.empty()) defined_at_ = "?";
  }
  function_ref_ = luaL_ref(L_, LUA_REGISTRYINDEX);
  state_ = makeState();
  if (two_body_) other_ = makeState();
  // Fill the tables once here, inside the add_force call: every key then exists, so refilling them
  // in evaluate() (outside any protected call) never allocates and cannot hit the memory cap.
  const BodyState zero;
  pushState(state_, zero, 0.0);
  lua_pop(L_, 1);
  if (two_body_) {
    pushState(other_, zero, 0.0);
    lua_pop(L_, 1);
  }
}

LuaForce::~LuaForce() {
  for (int ref : {function_ref_, state_.table, state_.position, state_.velocity, state_.center, other_.table,
                  other_.position, other_.velocity, other_.center})
    luaL_unref(L_, LUA_REGISTRYINDEX, ref);
}

LuaForce::StateRefs LuaForce::makeState() {
  StateRefs refs;
  lua_createtable(L_, 0, 8);
  refs.table = luaL_ref(L_, LUA_REGISTRYINDEX);
  for (int* ref : {&refs.position, &refs.velocity, &refs.center}) {
    pushVec(L_, Vec2::Zero());
    *ref = luaL_ref(L_, LUA_REGISTRYINDEX);
  }
  return refs;
}

void LuaForce::pushState(const StateRefs& refs, const BodyState& s, double time) {
  lua_State* L = L_;
  lua_rawgeti(L, LUA_REGISTRYINDEX, refs.table);
  const auto setVec = [&](int ref, const char* name, const Vec2& v) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    lua_pushnumber(L, v.x());
    lua_setfield(L, -2, "x");
    lua_pushnumber(L, v.y());
    lua_setfield(L, -2, "y");
    lua_setfield(L, -2, name);  // also puts it back if the script replaced s.<name>
  };
  setVec(refs.position, "position", s.position);
  setVec(refs.velocity, "velocity", s.velocity);
  setVec(refs.center, "center", s.center);
  const auto setNumber = [&](const char* name, double x) {
    lua_pushnumber(L, x);
    lua_setfield(L, -2, name);
  };
  setNumber("angle", s.angle);
  setNumber("angular_velocity", s.angular_velocity);
  setNumber("mass", s.mass);
  setNumber("inertia", s.inertia);
  setNumber("time", time);
}

void LuaForce::evaluate(const ForceInput& in, ForceOutput& out) {
  lua_State* L = L_;
  // Inside Scene::step this only counts (the step's window is armed at its first Lua force); a
  // World::step called directly gives each evaluation its own window.
  const Budget::Scope budget(host_.budget(), Budget::Kind::Force);
  const int top = lua_gettop(L);
  lua_pushcfunction(L, messageHandler);
  lua_rawgeti(L, LUA_REGISTRYINDEX, function_ref_);
  pushState(state_, in.a, in.time);
  int nargs = 1;
  if (two_body_ && in.b) {
    pushState(other_, *in.b, in.time);
    nargs = 2;
  }
  ++host_.calls;
  if (const int status = lua_pcall(L, nargs, 3, top + 1); status != LUA_OK) {
    std::string message = status == LUA_ERRMEM ? "not enough memory (the scene's limit is " +
                                                     std::to_string(host_.limits().memory_bytes >> 20) + " MiB)"
                          : lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "error";
    lua_settop(L, top);
    // An error raised inside a C function called directly as evaluate has no Lua line to point at.
    if (!hasLocation(message)) message = defined_at_ + ": " + message;
    throw ScriptError(host_.errorText(std::move(message), "evaluate"));
  }
  double v[3] = {0.0, 0.0, 0.0};
  static constexpr const char* kNames[3] = {"fx", "fy", "torque"};
  for (int i = 0; i < 3; ++i) {
    const int index = top + 2 + i;
    const int type = lua_type(L, index);
    if (type == LUA_TNUMBER) {
      v[i] = lua_tonumber(L, index);
    } else if (!(i == 2 && type == LUA_TNIL)) {
      const std::string got = describe(L, index);
      lua_settop(L, top);
      throw ScriptError(defined_at_ + ": evaluate: must return fx, fy [, torque] as numbers; " + kNames[i] +
                        " is " + got);
    }
    if (!std::isfinite(v[i])) {
      lua_settop(L, top);
      throw ScriptError(defined_at_ + ": evaluate: returned a non-finite " + kNames[i] + ": " + formatNumber(v[i]) +
                        " (body id " + std::to_string(in.a.uid) + ", t = " + formatNumber(in.time) + " s)");
    }
  }
  lua_settop(L, top);
  const Vec2 f(v[0], v[1]);
  out.a = local_point_ ? atPoint(in.a, f, in.a.worldPoint(*local_point_)) : Wrench{f, 0.0};
  out.a.torque += v[2];
  last_force_ = f;
}

void LuaForce::draw(DebugDraw& dd, const BodyState& a, const BodyState*) const {
  drawForceArrow(dd, local_point_ ? a.worldPoint(*local_point_) : a.center, last_force_, a.mass);
}

}  // namespace rigidlab::lua

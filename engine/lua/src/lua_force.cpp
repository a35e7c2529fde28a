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
  // in evaluate() allocates nothing unless the script removed one.
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
  // No metamethod of the script's may run here: a state table the script gave a metatable is
  // filled with raw sets; one without (the usual case) with lua_setfield, which then never calls
  // a metamethod and is faster (0.55 against 0.65 µs per evaluation of forces.spring). The vec2
  // tables keep the prelude's metatable (locked; no __newindex). A key the script removed is put
  // back, which may allocate: this runs inside ScriptHost::run.
  lua_State* L = L_;
  lua_rawgeti(L, LUA_REGISTRYINDEX, refs.table);
  const bool plain = !lua_getmetatable(L, -1);
  if (!plain) lua_pop(L, 1);
  const auto set = [&](const char* name) {
    if (plain) {
      lua_setfield(L, -2, name);
    } else {
      lua_pushstring(L, name);
      lua_insert(L, -2);
      lua_rawset(L, -3);
    }
  };
  const auto setVec = [&](int ref, const char* name, const Vec2& v) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    lua_pushnumber(L, v.x());
    lua_setfield(L, -2, "x");
    lua_pushnumber(L, v.y());
    lua_setfield(L, -2, "y");
    set(name);  // also puts it back if the script replaced s.<name>
  };
  setVec(refs.position, "position", s.position);
  setVec(refs.velocity, "velocity", s.velocity);
  setVec(refs.center, "center", s.center);
  const auto setNumber = [&](const char* name, double x) {
    lua_pushnumber(L, x);
    set(name);
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
  ++host_.calls;
  double v[3] = {0.0, 0.0, 0.0};
  const auto error = host_.run([&] {
    lua_rawgeti(L, LUA_REGISTRYINDEX, function_ref_);
    pushState(state_, in.a, in.time);
    int nargs = 1;
    if (two_body_ && in.b) {
      pushState(other_, *in.b, in.time);
      nargs = 2;
    }
    lua_call(L, nargs, 3);
    static constexpr const char* kNames[3] = {"fx", "fy", "torque"};
    for (int i = 0; i < 3; ++i) {
      const int index = i - 3;
      const int type = lua_type(L, index);
      if (type == LUA_TNUMBER) {
        v[i] = lua_tonumber(L, index);
      } else if (!(i == 2 && type == LUA_TNIL)) {
        throw ScriptError(defined_at_ + ": evaluate: must return fx, fy [, torque] as numbers; " + kNames[i] +
                          " is " + describe(L, index));
      }
      if (!std::isfinite(v[i]))
        throw ScriptError(defined_at_ + ": evaluate: returned a non-finite " + kNames[i] + ": " + formatNumber(v[i]) +
                          " (body id " + std::to_string(in.a.uid) + ", t = " + formatNumber(in.time) + " s)");
    }
  });
  if (error) {
    // An error raised inside a C function called directly as evaluate has no Lua line to point at.
    std::string message = hasLocation(*error) ? *error : defined_at_ + ": " + *error;
    throw ScriptError(host_.errorText(std::move(message), "evaluate"));
  }
  const Vec2 f(v[0], v[1]);
  out.a = local_point_ ? atPoint(in.a, f, in.a.worldPoint(*local_point_)) : Wrench{f, 0.0};
  out.a.torque += v[2];
  last_force_ = f;
}

void LuaForce::draw(DebugDraw& dd, const BodyState& a, const BodyState*) const {
  drawForceArrow(dd, local_point_ ? a.worldPoint(*local_point_) : a.center, last_force_, a.mass);
}

}  // namespace rigidlab::lua

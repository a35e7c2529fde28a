// A force written in Lua: `world:add_force{ body = b, evaluate = function(s) ... end }`.
//
// evaluate(s [, o]) is called at every integrator stage (four times per step with RK4) with the
// body's state at that stage: s.position, s.velocity, s.center (vec2), s.angle,
// s.angular_velocity, s.mass, s.inertia, s.time. With `other = b2`, o is b2's state at the same
// stage. It returns fx, fy [, torque] (N, N·m). Per the style guide (lesson 5) one evaluation costs
// one protected call: the state tables are created once per force and refilled in place, so a call
// allocates nothing. The tables are therefore only valid during the call.
#pragma once

#include <optional>
#include <string>

#include "bindings.h"
#include "rigidlab/force.h"

namespace rigidlab::lua {

class LuaForce final : public Force {
 public:
  // `evaluate` must be a function of the scene's state; `local_point` (body coordinates) is where
  // the force applies (default: the centre of mass).
  LuaForce(ScriptHost& host, const sol::function& evaluate, std::optional<Vec2> local_point, bool two_body);
  ~LuaForce() override;

  void evaluate(const ForceInput& in, ForceOutput& out) override;
  void draw(DebugDraw& dd, const BodyState& a, const BodyState* b) const override;
  std::string_view kind() const override { return "lua force"; }

 private:
  struct StateRefs {
    int table = LUA_NOREF, position = LUA_NOREF, velocity = LUA_NOREF, center = LUA_NOREF;
  };
  StateRefs makeState();
  void pushState(const StateRefs& refs, const BodyState& s, double time);

  ScriptHost& host_;
  lua_State* L_;
  int function_ref_ = LUA_NOREF;
  StateRefs state_, other_;
  std::optional<Vec2> local_point_;
  bool two_body_;
  std::string defined_at_;  // "<file>:<line>" of the evaluate function, for messages
  Vec2 last_force_ = Vec2::Zero();
};

}  // namespace rigidlab::lua

// The `draw` object of OnDraw(draw): overlays in world coordinates, drawn by the sandbox.
//   draw:line(a, b [, color])   draw:circle(center, radius [, color])   draw:text(position, text [, color])
// color: {r, g, b [, a]} with components in 0..1; default white.
#include "bindings.h"
#include "lua_args.h"
#include "rigidlab/error.h"

namespace rigidlab::lua {
namespace {

OverlayDraw& target(lua_State* L, std::string_view function) {
  sol::stack_object self(L, 1);
  if (!self.is<LuaDraw>()) fail(L, function, "call it as draw:" + std::string(function) + "(...), with a colon");
  OverlayDraw* t = self.as<const LuaDraw&>().target;
  if (!t) fail(L, function, "the draw object can only be used during OnDraw");
  return *t;
}

Vec2 point(lua_State* L, std::string_view function, std::string_view what, int index) {
  sol::stack_object v(L, index);
  const auto p = toVec(L, v);
  if (!p || !isFinite(*p)) fail(L, function, std::string(what) + " must be a finite vector {x, y}, got " + describe(v));
  return *p;
}

Color color(lua_State* L, std::string_view function, int index) {
  sol::stack_object v(L, index);
  if (isMissing(v)) return {};
  bool ok = v.get_type() == sol::type::table;
  float c[4] = {1, 1, 1, 1};
  if (ok) {
    sol::table t = v.as<sol::table>();
    const size_t n = t.size();
    ok = n == 3 || n == 4;
    for (size_t i = 1; ok && i <= n; ++i) {
      const sol::object x = t.raw_get<sol::object>(i);
      ok = x.get_type() == sol::type::number && x.as<double>() >= 0 && x.as<double>() <= 1;
      if (ok) c[i - 1] = static_cast<float>(x.as<double>());
    }
  }
  if (!ok) fail(L, function, "color must be {r, g, b [, a]} with values in 0..1, got " + describe(v));
  return {c[0], c[1], c[2], c[3]};
}

int line(lua_State* L) {
  OverlayDraw& t = target(L, "line");
  t.line(point(L, "line", "a", 2), point(L, "line", "b", 3), color(L, "line", 4));
  return 0;
}

int circle(lua_State* L) {
  OverlayDraw& t = target(L, "circle");
  const Vec2 c = point(L, "circle", "center", 2);
  sol::stack_object r(L, 3);
  if (r.get_type() != sol::type::number || !(r.as<double>() > 0) || !std::isfinite(r.as<double>()))
    fail(L, "circle", "radius must be a number > 0, got " + describe(r));
  t.circle(c, r.as<double>(), color(L, "circle", 4));
  return 0;
}

int text(lua_State* L) {
  OverlayDraw& t = target(L, "text");
  const Vec2 p = point(L, "text", "position", 2);
  sol::stack_object s(L, 3);
  if (s.get_type() != sol::type::string && s.get_type() != sol::type::number)
    fail(L, "text", "text must be a string, got " + describe(s));
  t.text(p, s.as<std::string>(), color(L, "text", 4));
  return 0;
}

sol::object drawIndex(sol::this_state ts, const LuaDraw&, sol::stack_object key) {
  lua_State* L = ts;
  const std::string k = key.is<std::string>() ? key.as<std::string>() : describe(key);
  lua_CFunction f = k == "line" ? guarded<line> : k == "circle" ? guarded<circle> : k == "text" ? guarded<text> : nullptr;
  if (!f) {
    const std::string hint = closestName(k, {"line", "circle", "text"});
    fail(L, "draw", "has no function '" + k + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
  }
  lua_pushcfunction(L, f);
  return sol::stack::pop<sol::object>(L);
}

}  // namespace

void registerDrawType(sol::state& lua) {
  lua.new_usertype<LuaDraw>("rigidlab.draw", sol::no_constructor, sol::meta_function::index, &drawIndex);
  lua["rigidlab.draw"] = sol::lua_nil;
}

}  // namespace rigidlab::lua

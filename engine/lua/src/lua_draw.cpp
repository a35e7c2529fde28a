// The `draw` object of OnDraw(draw): overlays in world coordinates, drawn by the sandbox.
//   draw:line(a, b [, color])   draw:circle(center, radius [, color])   draw:text(position, text [, color])
// color: {r, g, b [, a]} with components in 0..1; default white.
#include <algorithm>

#include "bindings.h"
#include "lua_args.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

LuaDraw& self(lua_State* L, std::string_view function) {
  LuaDraw* handle = toHandle<LuaDraw>(L, 1);
  if (!handle) fail(L, function, "call it as draw:" + std::string(function) + "(...), with a colon");
  LuaDraw& d = *handle;
  if (!d.target) fail(L, function, "the draw object can only be used during OnDraw");
  return d;
}

// Counts a call against the frame's allowance (Scene::DrawReport): false once `count` has reached
// `max`, and the report says the output was truncated. The arguments are still checked, so a
// mistake is found whatever the allowance.
bool allowed(LuaDraw& d, int& count, int max) {
  if (count >= max) {
    d.report.truncated = true;
    return false;
  }
  ++count;
  return true;
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
    v.push(L);
    const size_t n = lua_rawlen(L, -1);  // raw: a __len of the script's must not run in the host
    lua_pop(L, 1);
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
  LuaDraw& d = self(L, "line");
  const Vec2 a = point(L, "line", "a", 2), b = point(L, "line", "b", 3);
  const Color c = color(L, "line", 4);
  if (allowed(d, d.report.lines, Scene::kMaxDrawLines)) d.target->line(a, b, c);
  return 0;
}

int circle(lua_State* L) {
  LuaDraw& d = self(L, "circle");
  const Vec2 c = point(L, "circle", "center", 2);
  sol::stack_object r(L, 3);
  if (r.get_type() != sol::type::number || !(r.as<double>() > 0) || !std::isfinite(r.as<double>()))
    fail(L, "circle", "radius must be a number > 0, got " + describe(r));
  const Color k = color(L, "circle", 4);
  if (allowed(d, d.report.circles, Scene::kMaxDrawCircles)) d.target->circle(c, r.as<double>(), k);
  return 0;
}

int text(lua_State* L) {
  LuaDraw& d = self(L, "text");
  const Vec2 p = point(L, "text", "position", 2);
  const int type = lua_type(L, 3);
  if (type != LUA_TSTRING && type != LUA_TNUMBER) fail(L, "text", "text must be a string, got " + describe(L, 3));
  const Color c = color(L, "text", 4);
  if (!allowed(d, d.report.texts, Scene::kMaxDrawTexts)) return 0;
  size_t length = 0;
  const char* s = lua_tolstring(L, 3, &length);
  // Only what is drawn is copied: kDrawTextBytes per text, kMaxDrawTextBytes per frame.
  const size_t room = Scene::kMaxDrawTextBytes - std::min(d.text_bytes, Scene::kMaxDrawTextBytes);
  const size_t taken = std::min({length, kDrawTextBytes, room});
  if (taken < length) d.report.truncated = true;
  if (taken == 0) return 0;
  d.text_bytes += taken;
  d.target->text(p, displayText(std::string_view(s, taken), kDrawTextBytes + 3, "\n"), c);
  return 0;
}

int drawIndex(lua_State* L) {
  sol::stack_object key(L, 2);
  const std::string k = key.is<std::string>() ? key.as<std::string>() : describe(key);
  lua_CFunction f = k == "line" ? guarded<line> : k == "circle" ? guarded<circle> : k == "text" ? guarded<text> : nullptr;
  if (!f) {
    const std::string hint = closestName(k, {"line", "circle", "text"});
    fail(L, "draw", "has no function '" + k + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
  }
  lua_pushcfunction(L, f);
  return 1;
}

}  // namespace

void registerDrawType(lua_State* L) { registerHandleType(L, LuaDraw::kMetatable, guarded<drawIndex>, nullptr, nullptr, nullptr); }

}  // namespace rigidlab::lua

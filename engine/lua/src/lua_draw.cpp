// The `draw` object of OnDraw(draw, world): overlays in world coordinates, drawn by the sandbox.
//   draw:line(a, b [, color])   draw:circle(center, radius [, color [, fill]])   draw:text(position, text [, color])
//   draw:polygon(points [, color [, fill]])   draw:capsule(a, b, radius [, color [, fill]])
// color, fill: {r, g, b [, a]} with components in 0..1; color default white, no fill by default.
// draw.screen has the same functions in pixels from the window's top-left corner, y down (a HUD
// that stays put when the camera moves); it shares draw's allowance per frame. The arguments stay
// positional, as the first three functions have always taken them.
#include <algorithm>

#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

// The draw object a call draws through (draw.screen's is draw's) and whether its coordinates are
// pixels.
struct Drawing {
  LuaDraw& d;
  bool screen;
  Vec2 place(const Vec2& p) const { return screen ? d.target->screenToWorld(p) : p; }
  double length(double r) const { return screen ? r * d.target->metresPerPixel() : r; }
};

Drawing self(lua_State* L, std::string_view function) {
  LuaDraw* handle = toHandle<LuaDraw>(L, 1);
  if (!handle) fail(L, function, "call it as draw:" + std::string(function) + "(...), with a colon");
  LuaDraw& d = handle->main ? *handle->main : *handle;
  if (!d.target) fail(L, function, "the draw object can only be used during OnDraw");
  return {d, handle->main != nullptr};
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

std::optional<Color> optionalColor(lua_State* L, std::string_view function, std::string_view what, int index) {
  sol::stack_object v(L, index);
  if (isMissing(v)) return std::nullopt;
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
  if (!ok) fail(L, function, std::string(what) + " must be {r, g, b [, a]} with values in 0..1, got " + describe(v));
  return Color{c[0], c[1], c[2], c[3]};
}

Color color(lua_State* L, std::string_view function, int index) {
  return optionalColor(L, function, "color", index).value_or(Color{});
}

double radius(lua_State* L, std::string_view function, int index) {
  sol::stack_object r(L, index);
  if (r.get_type() != sol::type::number || !(r.as<double>() > 0) || !std::isfinite(r.as<double>()))
    fail(L, function, "radius must be a number > 0, got " + describe(r));
  return r.as<double>();
}

int line(lua_State* L) {
  const Drawing x = self(L, "line");
  LuaDraw& d = x.d;
  const Vec2 a = point(L, "line", "a", 2), b = point(L, "line", "b", 3);
  const Color c = color(L, "line", 4);
  if (allowed(d, d.report.lines, Scene::kMaxDrawLines)) d.target->line(x.place(a), x.place(b), c);
  return 0;
}

int circle(lua_State* L) {
  const Drawing x = self(L, "circle");
  LuaDraw& d = x.d;
  const Vec2 c = point(L, "circle", "center", 2);
  const double r = radius(L, "circle", 3);
  const Color k = color(L, "circle", 4);
  const std::optional<Color> fill = optionalColor(L, "circle", "fill", 5);
  if (!allowed(d, d.report.circles, Scene::kMaxDrawCircles)) return 0;
  if (fill) d.target->disc(x.place(c), x.length(r), k, *fill);
  else d.target->circle(x.place(c), x.length(r), k);
  return 0;
}

int polygon(lua_State* L) {
  const Drawing x = self(L, "polygon");
  LuaDraw& d = x.d;
  std::vector<Vec2> points =
      checkPoints(L, "polygon", "points", sol::object(sol::stack_object(L, 2)), 3, Scene::kMaxDrawPolygonPoints);
  const Color k = color(L, "polygon", 3);
  const std::optional<Color> fill = optionalColor(L, "polygon", "fill", 4);
  if (!allowed(d, d.report.shapes, Scene::kMaxDrawShapes)) return 0;
  for (Vec2& p : points) p = x.place(p);
  d.target->polygon(points, k, fill);
  return 0;
}

int capsule(lua_State* L) {
  const Drawing x = self(L, "capsule");
  LuaDraw& d = x.d;
  const Vec2 a = point(L, "capsule", "a", 2), b = point(L, "capsule", "b", 3);
  const double r = radius(L, "capsule", 4);
  const Color k = color(L, "capsule", 5);
  const std::optional<Color> fill = optionalColor(L, "capsule", "fill", 6);
  if (allowed(d, d.report.shapes, Scene::kMaxDrawShapes)) d.target->capsule(x.place(a), x.place(b), x.length(r), k, fill);
  return 0;
}

int text(lua_State* L) {
  const Drawing x = self(L, "text");
  LuaDraw& d = x.d;
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
  d.target->text(x.place(p), displayText(std::string_view(s, taken), kDrawTextBytes + 3, "\n"), c);
  return 0;
}

int drawIndex(lua_State* L) {
  sol::stack_object key(L, 2);
  const std::string k = key.is<std::string>() ? key.as<std::string>() : describe(key);
  if (k == "screen") {  // draw.screen: the same functions in pixels
    const LuaDraw* handle = toHandle<LuaDraw>(L, 1);
    const LuaDraw* main = handle && handle->main ? handle->main : handle;
    if (main && main->screen_ref != LUA_NOREF) {
      lua_rawgeti(L, LUA_REGISTRYINDEX, main->screen_ref);
      return 1;
    }
  }
  static constexpr NamedFunction kFunctions[] = {{"line", guarded<line>},       {"circle", guarded<circle>},
                                                 {"text", guarded<text>},       {"polygon", guarded<polygon>},
                                                 {"capsule", guarded<capsule>}};
  lua_CFunction f = lookUp(kFunctions, k);
  if (!f) {
    const std::string hint = closestName(k, api::kDrawFunctions);
    fail(L, "draw", "has no function '" + k + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
  }
  lua_pushcfunction(L, f);
  return 1;
}

}  // namespace

void registerDrawType(lua_State* L) { registerHandleType(L, LuaDraw::kMetatable, guarded<drawIndex>, nullptr, nullptr, nullptr); }

void pushDrawHandles(lua_State* L, LuaDraw*& main) {
  pushHandle(L, LuaDraw{});
  main = toHandle<LuaDraw>(L, -1);
  LuaDraw screen;
  screen.main = main;
  pushHandle(L, screen);
  main->screen_ref = luaL_ref(L, LUA_REGISTRYINDEX);  // lives as long as the state
}

}  // namespace rigidlab::lua

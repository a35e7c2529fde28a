#include "lua_args.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "bindings.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {

std::string where(lua_State* L, int level) {
  // The first Lua function at or above `level` that has a current line (C functions, like assert
  // or pcall, have none) and is the scene's: the host's own chunks (named "=...", like the
  // prelude's pcall and load wrappers) are passed over.
  lua_Debug ar;
  for (int l = level; l < level + 8 && lua_getstack(L, l, &ar); ++l) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline > 0 && ar.source[0] != '=') return std::string(ar.short_src) + ":" + std::to_string(ar.currentline) + ": ";
  }
  return "";
}

void fail(lua_State* L, std::string_view function, const std::string& message) {
  const std::string text = where(L) + std::string(function) + ": " + message;
  hostOf(L).markApiError(text);
  throw ScriptError(text);
}

std::string describe(lua_State* L, int index) {
  index = lua_absindex(L, index);
  switch (lua_type(L, index)) {
    case LUA_TNONE:
    case LUA_TNIL: return "nil";
    case LUA_TBOOLEAN: return lua_toboolean(L, index) ? "true" : "false";
    case LUA_TNUMBER:
      if (lua_isinteger(L, index)) return std::to_string(lua_tointeger(L, index));
      return formatNumber(lua_tonumber(L, index));
    case LUA_TSTRING: {
      size_t len = 0;
      const char* s = lua_tolstring(L, index, &len);
      std::string text = displayText(std::string_view(s, std::min<size_t>(len, 48)), 40);
      if (const size_t cut = text.find("... ("); cut != std::string::npos) text.resize(cut);
      return "\"" + text + (len > 40 ? "...\" (" + std::to_string(len) + " bytes)" : "\"");
    }
    case LUA_TTABLE: {
      sol::object value(L, index);
      if (const auto v = toVec(L, value); v && isVec2Table(L, index)) return "vec2" + formatVec(*v);
      return "a table";
    }
    case LUA_TFUNCTION: return "a function";
    case LUA_TUSERDATA: return describeHandle(L, index);
    default: return std::string("a ") + lua_typename(L, lua_type(L, index));
  }
}

std::string describe(const sol::object& value) {
  lua_State* L = value.lua_state();
  if (!L) return "nil";
  value.push(L);
  std::string text = describe(L, -1);
  lua_pop(L, 1);
  return text;
}

std::string closestName(std::string_view name, const std::vector<std::string_view>& candidates) {
  // Optimal string alignment distance: Levenshtein plus swaps of two neighbouring letters.
  const auto distance = [](std::string_view a, std::string_view b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
      for (size_t j = 1; j <= b.size(); ++j) {
        d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
        if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    return d[a.size()][b.size()];
  };
  const auto lower = [](std::string_view s) {
    std::string l(s);
    for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return l;
  };
  if (name.size() < 4 || name.size() > 64) return "";
  std::string best;
  size_t best_distance = SIZE_MAX;
  for (std::string_view c : candidates) {
    size_t d = distance(name, c);
    const size_t allowed = std::max(name.size(), c.size()) / 5;
    if (lower(name) == lower(c)) d = 0;
    else if (c.starts_with(name)) d = std::min(d, allowed);  // a name cut short: always a candidate
    else if (d > allowed) continue;
    if (d < best_distance) {
      best_distance = d;
      best = std::string(c);
    }
  }
  return best;
}

bool isVec2Table(lua_State* L, int index) {
  const int ref = hostOf(L).vec2_metatable_ref;
  if (ref == LUA_NOREF || !lua_getmetatable(L, index)) return false;
  lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
  const bool same = lua_rawequal(L, -1, -2);
  lua_pop(L, 2);
  return same;
}

std::optional<Vec2> toVec(lua_State* L, const sol::object& value) {
  if (value.get_type() != sol::type::table) return std::nullopt;
  value.push(L);
  const int t = lua_gettop(L);
  std::optional<Vec2> result;
  lua_pushliteral(L, "x");
  lua_rawget(L, t);
  lua_pushliteral(L, "y");
  lua_rawget(L, t);
  if (lua_type(L, -2) == LUA_TNUMBER && lua_type(L, -1) == LUA_TNUMBER) {
    result = Vec2(lua_tonumber(L, -2), lua_tonumber(L, -1));
  } else if (lua_isnil(L, -2) && lua_isnil(L, -1) && lua_rawlen(L, t) == 2) {
    lua_rawgeti(L, t, 1);
    lua_rawgeti(L, t, 2);
    if (lua_type(L, -2) == LUA_TNUMBER && lua_type(L, -1) == LUA_TNUMBER) result = Vec2(lua_tonumber(L, -2), lua_tonumber(L, -1));
    lua_pop(L, 2);
  }
  lua_settop(L, t - 1);
  return result;
}

void pushVec(lua_State* L, const Vec2& v) {
  lua_createtable(L, 0, 2);
  lua_pushnumber(L, v.x());
  lua_setfield(L, -2, "x");
  lua_pushnumber(L, v.y());
  lua_setfield(L, -2, "y");
  lua_rawgeti(L, LUA_REGISTRYINDEX, hostOf(L).vec2_metatable_ref);
  lua_setmetatable(L, -2);
}

sol::object makeVec(lua_State* L, const Vec2& v) {
  pushVec(L, v);
  return sol::stack::pop<sol::object>(L);
}

// ---------------------------------------------------------------------------------------------

Options::Options(lua_State* L, std::string_view function, const sol::object& arg, std::vector<std::string_view> known)
    : L_(L), function_(function) {
  if (arg.get_type() != sol::type::table)
    lua::fail(L, function, "expects a table of named options, e.g. " + std::string(function) + "{ " +
                               std::string(known.front()) + " = ... }, got " + describe(arg));
  table_ = arg.as<sol::table>();
  // Unknown keys are errors, so a typo is never silently ignored. Reported in sorted order, so
  // the message does not depend on Lua's randomised table order.
  std::vector<std::string> unknown;
  table_.push(L);
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      const std::string key = describe(L, -2);
      lua_pop(L, 3);
      lua::fail(L, function, "options must be named (name = value), got a value at position " + key);
    }
    const std::string key = lua_tostring(L, -2);
    if (std::find(known.begin(), known.end(), key) == known.end()) unknown.push_back(key);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (!unknown.empty()) {
    std::sort(unknown.begin(), unknown.end());
    const std::string suggestion = closestName(unknown.front(), known);
    lua::fail(L, function, "unknown option '" + unknown.front() + "'" +
                               (suggestion.empty() ? "" : " (did you mean '" + suggestion + "'?)"));
  }
}

bool Options::has(std::string_view key) const { return get(key).get_type() != sol::type::lua_nil; }

sol::object Options::get(std::string_view key) const { return table_.raw_get<sol::object>(key); }

void Options::fail(std::string_view key, const std::string& message) const {
  lua::fail(L_, function_, std::string(key) + " " + message);
}

sol::object Options::required(std::string_view key) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) fail(key, "is required");
  return v;
}

double Options::number(std::string_view key, std::optional<double> fallback) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) {
    if (!fallback) fail(key, "is required");
    return *fallback;
  }
  if (v.get_type() != sol::type::number) fail(key, "must be a number, got " + describe(v));
  const double x = v.as<double>();
  if (!std::isfinite(x)) fail(key, "must be finite, got " + formatNumber(x));
  return x;
}

double Options::positive(std::string_view key, std::optional<double> fallback) const {
  const double x = number(key, fallback);
  if (!(x > 0)) fail(key, "must be > 0, got " + formatNumber(x));
  return x;
}

double Options::nonNegative(std::string_view key, std::optional<double> fallback) const {
  const double x = number(key, fallback);
  if (!(x >= 0)) fail(key, "must be >= 0, got " + formatNumber(x));
  return x;
}

double Options::inRange(std::string_view key, double lo, double hi, std::optional<double> fallback) const {
  const double x = number(key, fallback);
  if (x < lo || x > hi) fail(key, "must be between " + formatNumber(lo) + " and " + formatNumber(hi) + ", got " + formatNumber(x));
  return x;
}

int Options::integer(std::string_view key, int lo, int hi, std::optional<int> fallback) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) {
    if (!fallback) fail(key, "is required");
    return *fallback;
  }
  v.push(L_);
  const bool is_int = lua_isinteger(L_, -1) || (lua_type(L_, -1) == LUA_TNUMBER && std::floor(lua_tonumber(L_, -1)) == lua_tonumber(L_, -1));
  const double x = lua_type(L_, -1) == LUA_TNUMBER ? lua_tonumber(L_, -1) : 0.0;
  lua_pop(L_, 1);
  if (!is_int) fail(key, "must be a whole number, got " + describe(v));
  if (x < lo || x > hi) fail(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " + describe(v));
  return static_cast<int>(x);
}

Vec2 Options::vec(std::string_view key, std::optional<Vec2> fallback) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) {
    if (!fallback) fail(key, "is required");
    return *fallback;
  }
  const std::optional<Vec2> p = toVec(L_, v);
  if (!p) fail(key, "must be a vector {x, y} or vec2(x, y), got " + describe(v));
  if (!isFinite(*p)) fail(key, "must be finite, got " + formatVec(*p));
  return *p;
}

bool Options::boolean(std::string_view key, bool fallback) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) return fallback;
  if (v.get_type() != sol::type::boolean) fail(key, "must be true or false, got " + describe(v));
  return v.as<bool>();
}

std::string Options::string(std::string_view key, std::optional<std::string> fallback, size_t max_bytes) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) {
    if (!fallback) fail(key, "is required");
    return *fallback;
  }
  if (v.get_type() != sol::type::string) fail(key, "must be a string, got " + describe(v));
  v.push(L_);
  const size_t length = lua_rawlen(L_, -1);
  lua_pop(L_, 1);
  if (length > max_bytes)
    fail(key, "must be at most " + std::to_string(max_bytes) + " bytes long, got " + std::to_string(length));
  return v.as<std::string>();
}

std::string boundedString(lua_State* L, int index, std::string_view function, std::string_view what, size_t max_bytes) {
  size_t length = 0;
  const char* s = lua_tolstring(L, index, &length);
  const std::string subject = what.empty() ? "" : std::string(what) + " ";
  if (!s) fail(L, function, subject + "must be a string, got " + describe(L, index));
  if (length > max_bytes)
    fail(L, function, subject + "must be at most " + std::to_string(max_bytes) + " bytes long, got " + std::to_string(length));
  return std::string(s, length);
}

}  // namespace rigidlab::lua

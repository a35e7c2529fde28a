#include "lua_args.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "bindings.h"
#include "porting_names.h"
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

std::string fieldName(lua_State* L, std::string_view what, const sol::object& key) {
  if (key.get_type() != sol::type::string) fail(L, what, "fields are named by strings, got " + describe(key));
  return key.as<std::string>();
}

namespace {

// What to say after an unknown name: " (did you mean 'x'?)" for `meant` (a similar function's
// name) or a typo (closestName), " (rigidlab calls it 'x')" for a name of LÖVE or Box2D
// (porting_names.h), or "".
std::string suggestion(std::string_view name, const std::vector<std::string_view>& candidates, std::string meant) {
  if (!meant.empty()) return " (did you mean '" + meant + "'?)";
  if (const std::string ported = portingSuggestion(name, candidates); !ported.empty()) return " (" + ported + ")";
  meant = closestName(name, candidates);
  return meant.empty() ? "" : " (did you mean '" + meant + "'?)";
}

}  // namespace

void noSuchField(lua_State* L, std::string_view what, const std::string& k, const std::vector<std::string_view>& names,
                 std::string hint) {
  fail(L, what, "has no field '" + k + "'" + suggestion(k, names, std::move(hint)));
}

void requireWritable(lua_State* L, std::string_view what, const std::string& k,
                     const std::vector<std::string_view>& readable, const std::vector<std::string_view>& writable) {
  if (std::find(writable.begin(), writable.end(), k) != writable.end()) return;
  if (std::find(readable.begin(), readable.end(), k) != readable.end()) fail(L, std::string(what) + "." + k, "is read-only");
  noSuchField(L, what, k, writable);
}

std::string stringArg(lua_State* L, int index, std::string_view function, std::string_view what) {
  if (lua_type(L, index) != LUA_TSTRING) fail(L, function, std::string(what) + " must be a string, got " + describe(L, index));
  size_t length = 0;
  const char* s = lua_tolstring(L, index, &length);
  return std::string(s, length);
}

std::vector<std::string_view> joined(std::initializer_list<const std::vector<std::string_view>*> lists) {
  std::vector<std::string_view> all;
  for (const auto* list : lists) all.insert(all.end(), list->begin(), list->end());
  return all;
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

void pushVec(lua_State* L, const Vec2& v, int metatable) {
  lua_createtable(L, 0, 2);
  lua_pushnumber(L, v.x());
  lua_setfield(L, -2, "x");
  lua_pushnumber(L, v.y());
  lua_setfield(L, -2, "y");
  lua_pushvalue(L, metatable);
  lua_setmetatable(L, -2);
}

void pushVec(lua_State* L, const Vec2& v) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, hostOf(L).vec2_metatable_ref);
  pushVec(L, v, lua_gettop(L));
  lua_remove(L, -2);
}

sol::object makeVec(lua_State* L, const Vec2& v) {
  pushVec(L, v);
  return sol::stack::pop<sol::object>(L);
}

// ---------------------------------------------------------------------------------------------

Options::Options(lua_State* L, std::string_view function, const sol::object& arg, std::vector<std::string_view> known,
                 const Synonyms& synonyms)
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
    std::string meant;
    for (const auto& [name, synonym] : synonyms)
      if (name == unknown.front()) meant = std::string(synonym);
    lua::fail(L, function, "unknown option '" + unknown.front() + "'" + suggestion(unknown.front(), known, meant));
  }
}

bool Options::has(std::string_view key) const { return get(key).get_type() != sol::type::lua_nil; }

bool Options::hasAny(const std::vector<std::string_view>& keys) const {
  table_.push(L_);
  bool any = false;
  for (std::string_view key : keys) {
    lua_pushlstring(L_, key.data(), key.size());
    any = lua_rawget(L_, -2) != LUA_TNIL;
    lua_pop(L_, 1);
    if (any) break;
  }
  lua_pop(L_, 1);
  return any;
}

sol::object Options::get(std::string_view key) const { return table_.raw_get<sol::object>(key); }

void Options::fail(std::string_view key, const std::string& message) const {
  lua::fail(L_, function_, std::string(key) + " " + message);
}

sol::object Options::required(std::string_view key) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) fail(key, "is required");
  return v;
}

namespace {

// "<subject> <message>", or the message alone for a field write (no subject).
std::string about(std::string_view subject, const std::string& message) {
  return subject.empty() ? message : std::string(subject) + " " + message;
}

}  // namespace

double checkNumber(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v, Range range) {
  if (v.get_type() != sol::type::number) fail(L, function, about(subject, "must be a number, got " + describe(v)));
  const double x = v.as<double>();
  const bool infinity_allowed = range == Range::PositiveOrInfinity || range == Range::NonNegativeOrInfinity;
  if (!std::isfinite(x) && !(infinity_allowed && x == INFINITY))
    fail(L, function, about(subject, "must be finite" + std::string(infinity_allowed ? " or math.huge" : "") + ", got " + formatNumber(x)));
  if ((range == Range::Positive || range == Range::PositiveOrInfinity) && !(x > 0))
    fail(L, function, about(subject, "must be > 0, got " + formatNumber(x)));
  if ((range == Range::NonNegative || range == Range::NonNegativeOrInfinity) && !(x >= 0))
    fail(L, function, about(subject, "must be >= 0, got " + formatNumber(x)));
  return x;
}

Vec2 checkVec(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v) {
  const std::optional<Vec2> p = toVec(L, v);
  if (!p) fail(L, function, about(subject, "must be a vector {x, y} or vec2(x, y), got " + describe(v)));
  if (!isFinite(*p)) fail(L, function, about(subject, "must be finite, got " + formatVec(*p)));
  return *p;
}

bool checkBool(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v) {
  if (v.get_type() != sol::type::boolean) fail(L, function, about(subject, "must be true or false, got " + describe(v)));
  return v.as<bool>();
}

int64_t checkInteger(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v,
                     int64_t lo, int64_t hi) {
  v.push(L);
  const bool is_int = lua_isinteger(L, -1);
  const bool whole = is_int || (lua_type(L, -1) == LUA_TNUMBER && std::floor(lua_tonumber(L, -1)) == lua_tonumber(L, -1));
  const lua_Integer i = is_int ? lua_tointeger(L, -1) : 0;
  const double x = lua_type(L, -1) == LUA_TNUMBER ? lua_tonumber(L, -1) : 0.0;
  lua_pop(L, 1);
  if (!whole) fail(L, function, about(subject, "must be a whole number, got " + describe(v)));
  if (is_int ? (i < lo || i > hi) : (x < static_cast<double>(lo) || x > static_cast<double>(hi)))
    fail(L, function, about(subject, "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " + describe(v)));
  return is_int ? i : static_cast<int64_t>(x);
}

uint64_t checkBits(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v) {
  v.push(L);
  const int type = lua_type(L, -1);
  const bool is_int = lua_isinteger(L, -1);
  const lua_Integer i = is_int ? lua_tointeger(L, -1) : 0;
  const double x = type == LUA_TNUMBER ? lua_tonumber(L, -1) : 0.0;
  lua_pop(L, 1);
  if (is_int) return static_cast<uint64_t>(i);
  constexpr double kTwo63 = 9223372036854775808.0;
  if (type != LUA_TNUMBER || std::floor(x) != x || x < -kTwo63 || x >= 2 * kTwo63)
    fail(L, function, about(subject, "must be an integer set of bits (e.g. 1 << 3, 0x8 or -1 for all 64), got " + describe(v)));
  return x >= kTwo63 ? static_cast<uint64_t>(x - kTwo63) + (uint64_t{1} << 63)
                     : static_cast<uint64_t>(static_cast<int64_t>(x));
}

std::string checkChoice(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v,
                        const std::vector<std::string_view>& names) {
  if (v.get_type() == sol::type::string) {
    const std::string s = v.as<std::string>();
    if (std::find(names.begin(), names.end(), s) != names.end()) return s;
  }
  std::string list;
  for (size_t i = 0; i < names.size(); ++i)
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("\"" + std::string(names[i]) + "\"");
  fail(L, function, about(subject, "must be " + list + ", got " + describe(v)));
}

std::vector<Vec2> checkPoints(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v,
                              size_t min, size_t max) {
  if (v.get_type() != sol::type::table)
    fail(L, function, about(subject, "must be a list of points {{x, y}, ...}, got " + describe(v)));
  // The raw length: `#` would run a __len metamethod of the script's inside the host.
  v.push(L);
  const size_t n = lua_rawlen(L, -1);
  lua_pop(L, 1);
  if (n > max) fail(L, function, about(subject, "has " + std::to_string(n) + " points, at most " + std::to_string(max) + " are allowed"));
  if (n < min) fail(L, function, about(subject, "needs at least " + std::to_string(min) + " points, got " + std::to_string(n)));
  const sol::table t = v.as<sol::table>();
  std::vector<Vec2> points;
  points.reserve(n);
  for (size_t i = 1; i <= n; ++i) {
    const sol::object p = t.raw_get<sol::object>(i);
    const auto q = toVec(L, p);
    const std::string element = std::string(subject) + "[" + std::to_string(i) + "]";
    if (!q) fail(L, function, element + " must be a point {x, y}, got " + describe(p));
    if (!isFinite(*q)) fail(L, function, element + " must be finite, got " + formatVec(*q));
    points.push_back(*q);
  }
  return points;
}

double Options::number(std::string_view key, std::optional<double> fallback) const {
  return number(key, Range::Finite, fallback);
}

double Options::number(std::string_view key, Range range, std::optional<double> fallback) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) {
    if (!fallback) fail(key, "is required");
    return *fallback;
  }
  return checkNumber(L_, function_, key, v, range);
}

double Options::positive(std::string_view key, std::optional<double> fallback) const {
  return number(key, Range::Positive, fallback);
}

double Options::nonNegative(std::string_view key, std::optional<double> fallback) const {
  return number(key, Range::NonNegative, fallback);
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
  return static_cast<int>(checkInteger(L_, function_, key, v, lo, hi));
}

Vec2 Options::vec(std::string_view key, std::optional<Vec2> fallback) const {
  sol::object v = get(key);
  if (v.get_type() == sol::type::lua_nil) {
    if (!fallback) fail(key, "is required");
    return *fallback;
  }
  return checkVec(L_, function_, key, v);
}

uint64_t Options::bits(std::string_view key, uint64_t fallback) const {
  sol::object v = get(key);
  return v.get_type() == sol::type::lua_nil ? fallback : checkBits(L_, function_, key, v);
}

std::string Options::choice(std::string_view key, const std::vector<std::string_view>& names, std::string_view fallback) const {
  sol::object v = get(key);
  return v.get_type() == sol::type::lua_nil ? std::string(fallback) : checkChoice(L_, function_, key, v, names);
}

std::vector<Vec2> Options::points(std::string_view key, size_t min, size_t max) const {
  return checkPoints(L_, function_, key, required(key), min, max);
}

bool Options::boolean(std::string_view key, bool fallback) const {
  sol::object v = get(key);
  return v.get_type() == sol::type::lua_nil ? fallback : checkBool(L_, function_, key, v);
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

namespace {

bool wordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

}  // namespace

void failCore(lua_State* L, std::string_view function, const InputError& e,
              const std::vector<std::pair<std::string_view, std::string_view>>& renames) {
  // Word by word, so that renames may swap names (anchor_a <-> anchor_b) and "lower" never matches
  // inside "lower_angle".
  const std::string in = e.what();
  std::string out;
  std::string field = e.field();
  for (const auto& [from, to] : renames)
    if (field == from) field = std::string(to);
  for (size_t i = 0; i < in.size();) {
    if (!wordChar(in[i])) {
      out += in[i++];
      continue;
    }
    size_t j = i;
    while (j < in.size() && wordChar(in[j])) ++j;
    std::string word = in.substr(i, j - i);
    for (const auto& [from, to] : renames)
      if (word == from) {
        word = std::string(to);
        break;
      }
    out += word;
    i = j;
  }
  bool mentioned = field.empty();
  for (size_t at = out.find(field); !mentioned && at != std::string::npos; at = out.find(field, at + 1))
    mentioned = (at == 0 || !wordChar(out[at - 1])) && (at + field.size() == out.size() || !wordChar(out[at + field.size()]));
  fail(L, function, mentioned ? out : field + ": " + out);
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

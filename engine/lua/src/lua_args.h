// Reading and validating what scripts pass to the API (the Lua boundary: validation lives here).
//
// Messages follow LÖVE's lead: they name the function, the field and the bad value, and carry the
// location of the Lua line that made the call, e.g.
//   scenes/box.lua:12: add_circle: radius must be > 0, got -1
//   scenes/box.lua:14: add_box: unknown option 'widht' (did you mean 'width'?)
// Tables are read with raw access, so a script's metamethods never run inside the host.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigidlab/error.h"
#include "rigidlab/lua/closest_name.h"
#include "rigidlab/math.h"
#include "script_host.h"

namespace rigidlab::lua {

// The exception bound functions throw; sol2's trampoline turns it into a Lua error carrying the
// message (no C++ object is alive when the Lua error is raised).
class ScriptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "<file>:<line>: " of the Lua code `level` frames up (1: the caller of the running C function).
std::string where(lua_State* L, int level = 1);
// Throws ScriptError("<where><function>: <message>").
[[noreturn]] void fail(lua_State* L, std::string_view function, const std::string& message);

// True for nil and for an argument that was not passed at all (LUA_TNONE).
inline bool isMissing(const sol::object& v) {
  return v.get_type() == sol::type::lua_nil || v.get_type() == sol::type::none;
}
inline bool isMissing(const sol::stack_object& v) {
  return v.get_type() == sol::type::lua_nil || v.get_type() == sol::type::none;
}

// A string argument of at most `max_bytes` bytes (the length is checked before anything is
// copied); fails "<function>: <what> must be at most N bytes long, got M".
std::string boundedString(lua_State* L, int index, std::string_view function, std::string_view what, size_t max_bytes);

// A value as messages show it: -1, 0.5, nan, true, nil, "text", a table, a function, a body.
// Strings are shortened to 40 bytes and their control characters escaped (scene_text.h).
std::string describe(const sol::object& value);
std::string describe(lua_State* L, int index);

// The names of several lists in one (a function's accepted options).
std::vector<std::string_view> joined(std::initializer_list<const std::vector<std::string_view>*> lists);

// Handle fields: the name of `handle.<key>`, or fails "<what>: fields are named by strings, got
// 5"; "<what>: has no field 'x' (did you mean 'y'?)" with closestName's suggestion or `hint`; and
// for a write "<what>.<k>: is read-only" unless `k` is writable (or has no field, as above).
std::string fieldName(lua_State* L, std::string_view what, const sol::object& key);
[[noreturn]] void noSuchField(lua_State* L, std::string_view what, const std::string& k,
                              const std::vector<std::string_view>& names, std::string hint = "");
void requireWritable(lua_State* L, std::string_view what, const std::string& k,
                     const std::vector<std::string_view>& readable, const std::vector<std::string_view>& writable);
// Argument `index`, a string: fails "<function>: <what> must be a string, got 5".
std::string stringArg(lua_State* L, int index, std::string_view function, std::string_view what);

// A vector from a vec2 table, {x = , y = } or {x, y}; nullopt if the value is none of these.
std::optional<Vec2> toVec(lua_State* L, const sol::object& value);
// Pushes a new vec2 table.
void pushVec(lua_State* L, const Vec2& v);
// The same with the vec2 metatable at stack index `metatable` (absolute): for vectors in bulk.
void pushVec(lua_State* L, const Vec2& v, int metatable);
sol::object makeVec(lua_State* L, const Vec2& v);

// Checks of one value, shared by options (`subject` is the option's name: "add_box: width must be
// > 0, got -1") and field writes (`subject` is empty: "body.mass: must be > 0, got -1").
enum class Range {
  Finite,                 // any finite number
  Positive,               // > 0
  NonNegative,            // >= 0
  PositiveOrInfinity,     // > 0, math.huge allowed (break_force: "never")
  NonNegativeOrInfinity,  // >= 0, math.huge allowed (max_length: "no limit")
};
double checkNumber(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v, Range range);
Vec2 checkVec(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v);  // finite
bool checkBool(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v);
// A whole number between lo and hi (a float with a whole value is accepted).
int64_t checkInteger(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v,
                     int64_t lo, int64_t hi);
// A 64-bit set of bits (collision category and mask): any Lua integer, taken as its 64 bits (-1 is
// every bit, 1 << 63 the top one), or a float with a whole value in [-2^63, 2^64) (2^3 is 8.0).
uint64_t checkBits(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v);
// One of `names`, e.g. type = "kinematic"; the message lists them.
std::string checkChoice(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v,
                        const std::vector<std::string_view>& names);
// A list of at least `min` and at most `max` finite points {{x, y}, ...}, read raw; a bad element is
// named "<subject>[i]".
std::vector<Vec2> checkPoints(lua_State* L, std::string_view function, std::string_view subject, const sol::object& v,
                              size_t min, size_t max);

// A core InputError as an error of `function`. The core names its fields mostly as the Lua API
// does; `renames` maps the others (whole words of the message: {"lower", "lower_angle"}). A message
// that does not mention its field gets it in front ("velocity: a static body cannot move ...").
[[noreturn]] void failCore(lua_State* L, std::string_view function, const InputError& e,
                           const std::vector<std::pair<std::string_view, std::string_view>>& renames = {});

// A table of named options, checked against the names a function accepts.
class Options {
 public:
  // Fails unless `arg` is a table whose keys are all in `known` (unknown: "unknown option 'x'",
  // with closestName's suggestion, or the one `synonyms` gives for a name of a similar function:
  // {"lower_angle", "lower"} for a prismatic joint).
  using Synonyms = std::vector<std::pair<std::string_view, std::string_view>>;
  Options(lua_State* L, std::string_view function, const sol::object& arg, std::vector<std::string_view> known,
          const Synonyms& synonyms = {});

  bool has(std::string_view key) const;
  // Whether any of `keys` is given: raw lookups that make no Lua object (a check that costs about
  // as little as the options it skips when none is given).
  bool hasAny(const std::vector<std::string_view>& keys) const;
  sol::object get(std::string_view key) const;

  double number(std::string_view key, std::optional<double> fallback = std::nullopt) const;  // finite
  double positive(std::string_view key, std::optional<double> fallback = std::nullopt) const;  // > 0
  double nonNegative(std::string_view key, std::optional<double> fallback = std::nullopt) const;  // ≥ 0
  double inRange(std::string_view key, double lo, double hi, std::optional<double> fallback = std::nullopt) const;
  int integer(std::string_view key, int lo, int hi, std::optional<int> fallback = std::nullopt) const;
  // Finite numbers in `range`; the ...OrInfinity ranges also take math.huge.
  double number(std::string_view key, Range range, std::optional<double> fallback = std::nullopt) const;
  Vec2 vec(std::string_view key, std::optional<Vec2> fallback = std::nullopt) const;  // finite
  bool boolean(std::string_view key, bool fallback) const;
  uint64_t bits(std::string_view key, uint64_t fallback) const;  // checkBits
  std::string choice(std::string_view key, const std::vector<std::string_view>& names, std::string_view fallback) const;
  // checkPoints; required.
  std::vector<Vec2> points(std::string_view key, size_t min, size_t max) const;
  // At most `max_bytes` long: a longer string is refused before the host copies it.
  std::string string(std::string_view key, std::optional<std::string> fallback = std::nullopt,
                     size_t max_bytes = SIZE_MAX) const;

  // Fails with "<function>: <key> <message>".
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  const std::string& function() const { return function_; }
  lua_State* L() const { return L_; }

 private:
  sol::object required(std::string_view key) const;

  lua_State* L_;
  std::string function_;
  sol::table table_;
};

}  // namespace rigidlab::lua

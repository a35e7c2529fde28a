// The script host: one sandboxed Lua 5.4 state per scene (reliability.md §1.5).
//
// - libraries: base (without dofile, loadfile; load is text-only; collectgarbage only "count"),
//   math (math.random seeded by the host, so runs repeat), string (without dump), table. No io, os,
//   package, debug, coroutine.
// - every chunk is loaded as text: a binary chunk is refused before the parser sees it.
// - setmetatable refuses __gc; the string metatable is locked (getmetatable("") is false).
// - print() goes to the host's log; require() is the host's: it reads only `<name>.lua` files from
//   the scene's directory and the module directories, as text, into the same state.
// - all memory goes through a counting allocator with a cap (ScriptLimits::memory_bytes; the scene
//   may lower it with scene.memory_limit).
// - every call into Lua runs under a wall-clock budget (budget.h); pcall/xpcall are wrapped so they
//   cannot swallow the budget error. C functions the hook cannot interrupt are capped
//   (caps.h, installGuards in script_host.cpp): string.find/match/gmatch/gsub refuse a pattern
//   whose worst-case matching work on the subject exceeds kPatternWorkLimit; table.sort of more
//   than kNativeSortLimit elements compares through a Lua function (so the budget can stop it);
//   table.move moves at most kMoveLimit elements per call; string.rep fills by doubling; load()
//   takes chunks of at most ScriptLimits::source_bytes.
// Every call from C++ into Lua is a protected call; no Lua error unwinds through C++ frames.
#pragma once

#define SOL_ALL_SAFETIES_ON 1
#include <sol/sol.hpp>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "budget.h"
#include "caps.h"
#include "rigidlab/lua/scene.h"

namespace rigidlab::lua {


class ScriptHost {
 public:
  ScriptHost(const SceneOptions& options, std::filesystem::path scene_dir);
  ~ScriptHost();
  ScriptHost(const ScriptHost&) = delete;
  ScriptHost& operator=(const ScriptHost&) = delete;

  sol::state& lua() { return *lua_; }
  lua_State* L() { return lua_->lua_state(); }

  // Reads a script file (size-capped). Throws SceneError("<name>: cannot read: <reason>").
  std::string readSource(const std::filesystem::path& file, const std::string& name) const;
  // Compiles `source` as a text chunk named `name` (messages show "<name>:<line>:").
  // Throws SceneError with Lua's syntax error message.
  sol::protected_function compile(std::string_view source, const std::string& name);
  // A protected function whose errors come back as one clean message (see errorText).
  sol::protected_function protect(const sol::object& function);
  // The message of a failed protected call: "<file>:<line>: <context>: <what>". `context` is the
  // function being run ("PopulateWorld", "Check", ...); it is not repeated when the error came
  // from a rigidlab API function, whose messages already name themselves.
  std::string errorText(const sol::protected_function_result& result, std::string_view context);
  std::string errorText(std::string message, std::string_view context);

  // The scene's wall-clock budget (budget.h).
  Budget& budget() { return *budget_; }
  const ScriptLimits& limits() const { return options_.limits; }
  // Lowers the memory cap (scene.memory_limit); never raises it.
  void lowerMemoryLimit(size_t bytes) { options_.limits.memory_bytes = std::min(options_.limits.memory_bytes, bytes); }

  void log(const std::string& line) const;
  const std::vector<std::filesystem::path>& requiredFiles() const { return required_; }
  size_t memoryUsed() const { return used_; }

  // Called by API functions just before throwing their (already located) message, so errorText
  // does not prefix a context a second time.
  void markApiError(const std::string& message) { last_api_error_ = message; }
  long calls = 0;  // protected calls made into Lua (hooks, forces)

  // Registry keys of the vec2 metatable (set by the prelude).
  int vec2_metatable_ref = LUA_NOREF;

  // require(name): the host's module loader (see the file comment). Called from Lua.
  int requireModule(lua_State* L);

 private:
  static void* allocate(void* ud, void* ptr, size_t old_size, size_t new_size);
  void installGuards();
  void runPrelude();

  SceneOptions options_;
  std::filesystem::path scene_dir_;
  size_t used_ = 0;
  std::vector<std::filesystem::path> required_;
  std::string last_api_error_;
  std::unique_ptr<sol::state> lua_;
  std::unique_ptr<Budget> budget_;
};

// Message handler for protected calls (lua_pcall's msgh): keeps a string error as it is and
// describes any other error object without running its metamethods.
int messageHandler(lua_State* L);
// True if an error message starts with a "<chunk>:<line>:" location (before its first newline).
bool hasLocation(const std::string& message);

// The host that owns a Lua state (stored in its registry).
ScriptHost& hostOf(lua_State* L);

// Wraps a raw lua_CFunction so that a C++ exception it throws becomes a Lua error carrying the
// exception's message. (Lua is built as C++: its own errors are exceptions too, of another type,
// and pass through untouched.) A C++ exception must never reach Lua's machinery directly.
template <lua_CFunction F>
int guarded(lua_State* L) {
  try {
    return F(L);
  } catch (const std::exception& e) {
    lua_pushstring(L, e.what());
  }
  return lua_error(L);
}

}  // namespace rigidlab::lua

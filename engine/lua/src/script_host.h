// The script host: one sandboxed Lua 5.4 state per scene (docs/design/reliability.md §1.5).
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
// - every call into Lua runs under a CPU-time budget (budget.h); pcall/xpcall are wrapped so they
//   cannot swallow the budget error. C functions the hook cannot interrupt are capped
//   (caps.h, installGuards in script_host.cpp): string.find/match/gmatch/gsub refuse a pattern
//   whose worst-case matching work on the subject exceeds kPatternWorkLimit; table.sort of more
//   than kNativeSortLimit elements compares through a Lua function (so the budget can stop it);
//   table.move moves at most kMoveLimit elements per call; string.rep fills by doubling; load()
//   takes chunks of at most kLoadChunkLimit bytes, strings or the total a reader function returns.
// - the host's metatables (of _G while the main chunk runs, of the handles) are locked, and no
//   finalizer (__gc) exists in the state.
// - pairs/next visit keys in an order that does not depend on Lua's per-process hash seed
//   (ordered_pairs.h).
// Every use of the state from C++ is inside a protected call (run()); no Lua error unwinds
// through C++ frames unprotected.
#pragma once

#define SOL_ALL_SAFETIES_ON 1
#include <sol/sol.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "block_pool.h"
#include "budget.h"
#include "caps.h"
#include "rigidlab/lua/scene.h"

namespace rigidlab::lua {


// Every block of a scene's Lua state is preceded by a header holding its serial number, the order
// in which the blocks were allocated: ordered_pairs.cpp orders table and function keys by it,
// which a program's allocations make the same in every run. 8 bytes keep the alignment Lua needs
// (LUAI_MAXALIGN: doubles, pointers, 64-bit integers; sol2 aligns its own objects in userdata).
// They count against the memory cap: about 10 % more for a scene of small tables.
inline constexpr size_t kBlockHeader = 8;
inline uint64_t blockSerial(const void* block) {
  uint64_t serial;
  std::memcpy(&serial, static_cast<const char*>(block) - kBlockHeader, sizeof serial);
  return serial;
}

class ScriptHost {
 public:
  ScriptHost(const SceneOptions& options, std::filesystem::path scene_dir);
  ~ScriptHost();
  ScriptHost(const ScriptHost&) = delete;
  ScriptHost& operator=(const ScriptHost&) = delete;

  sol::state& lua() { return *lua_; }
  lua_State* L() { return lua_->lua_state(); }

  // Runs `body` inside a protected call whose message handler locates errors (messageHandler).
  // Every use of the state from C++ goes through here: any Lua error raised while `body` runs —
  // in a script it calls, or in the host's own pushes and reads (a memory error while pushing a
  // key, a finalizer's) — ends the call and comes back as its message; nothing unwinds past it
  // unprotected. A C++ exception `body` throws is rethrown unchanged once the call has ended.
  // Returns nullopt, or the error as raised ("<file>:<line>: ..."); a memory error gets the
  // location of the scene's Lua line that was running when the allocation was refused.
  template <typename F>
  std::optional<std::string> run(F&& body) {
    using Body = std::remove_reference_t<F>;
    return runErased([](void* f) { (*static_cast<Body*>(f))(); }, const_cast<void*>(static_cast<const void*>(&body)));
  }

  // Reads a script file (size-capped). Throws SceneError("<name>: cannot read: <reason>").
  std::string readSource(const std::filesystem::path& file, const std::string& name) const;
  // Compiles `source` as a text chunk named `name` (messages show "<name>:<line>:") and pushes it.
  // Throws SceneError with Lua's syntax error message. Call it inside run() (or from Lua).
  void pushChunk(std::string_view source, const std::string& name);
  // The message of a failed call: "<file>:<line>: <context>: <what>". `context` is the function
  // being run ("PopulateWorld", "Check", ...); it is not repeated when the error came from a
  // rigidlab API function, whose messages already name themselves. Shortened to kMessageBytes
  // and with control characters escaped (display.h), so any error is safe to print.
  // `budget_spent`: whether the call's budget window ran out, when the window has closed since
  // (default: asks the open window).
  std::string errorText(std::string message, std::string_view context, std::optional<bool> budget_spent = std::nullopt);

  // The scene's CPU-time budget (budget.h).
  Budget& budget() { return *budget_; }
  const ScriptLimits& limits() const { return options_.limits; }
  // Lowers the memory cap (scene.memory_limit); never raises it.
  void lowerMemoryLimit(size_t bytes) { options_.limits.memory_bytes = std::min(options_.limits.memory_bytes, bytes); }
  // Memory the host keeps for the scene outside Lua (bodies and their names) counts against the
  // same cap: charge() raises a Lua "not enough memory" error past it (call it from Lua's side of
  // the boundary, i.e. from an API function); release() gives the bytes back.
  void charge(lua_State* L, std::string_view function, size_t bytes);
  void release(size_t bytes) { used_ -= std::min(used_, bytes); }

  void log(const std::string& line) const;
  const std::vector<std::filesystem::path>& requiredFiles() const { return required_; }
  size_t memoryUsed() const { return used_; }
  // The message for a refused allocation: "not enough memory (the scene's limit is N MiB)".
  std::string memoryMessage() const;

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
  std::optional<std::string> runErased(void (*invoke)(void*), void* body);
  void installGuards();
  void runPrelude();

  SceneOptions options_;
  std::filesystem::path scene_dir_;
  std::vector<std::filesystem::path> allowed_dirs_;  // scene_dir_ and the module directories, resolved
  size_t used_ = 0;
  lua_State* state_ = nullptr;  // once lua_newstate has returned
  uint64_t serial_ = 0;         // blocks allocated so far (kBlockHeader)
  BlockPool pool_;              // the small blocks (before lua_: it outlives the state)
  std::string memory_error_at_;  // "<file>:<line>: " of the Lua line whose allocation was refused
  std::vector<std::filesystem::path> required_;
  std::string last_api_error_;
  std::unique_ptr<sol::state> lua_;
  std::unique_ptr<Budget> budget_;
};

// "<file>:<line>: " of the innermost Lua frame of the scene's own code (chunks whose name does
// not start with '='), or "".
std::string sceneLocation(lua_State* L);

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

#include "script_host.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "lua_args.h"

extern const char kPreludeSource[];

namespace rigidlab::lua {
namespace {

constexpr const char* kHostKey = "rigidlab.host";
constexpr const char* kLoadedKey = "rigidlab.loaded";

// print(...): tab-separated like Lua's own, to the host's log.
int luaPrint(lua_State* L) {
  const int n = lua_gettop(L);
  std::string line;
  for (int i = 1; i <= n; ++i) {
    size_t len = 0;
    const char* s = luaL_tolstring(L, i, &len);  // may call __tostring: an error unwinds cleanly
    if (i > 1) line += '\t';
    line.append(s, len);
    lua_pop(L, 1);
  }
  hostOf(L).log(line);
  return 0;
}

int luaRequire(lua_State* L) { return hostOf(L).requireModule(L); }

int luaDescribe(lua_State* L) {
  const std::string text = describe(L, 1);
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

int luaRegisterVec2(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_pushvalue(L, 1);
  hostOf(L).vec2_metatable_ref = luaL_ref(L, LUA_REGISTRYINDEX);
  return 0;
}

bool hasLocation(const std::string& message) {
  // "<chunk>:<digits>:" before the first newline
  const size_t end = message.find('\n');
  for (size_t colon = message.find(':'); colon != std::string::npos && colon < end;
       colon = message.find(':', colon + 1)) {
    size_t i = colon + 1;
    while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
    if (i > colon + 1 && i < message.size() && message[i] == ':') return true;
  }
  return false;
}

}  // namespace

// A non-string error object is described, never converted with its own __tostring (which could
// loop or fail while we format the error).
// A message without a location (assert's "assertion failed!", error(msg, 0), error({...})) gets the
// location of the Lua line that raised it.
int messageHandler(lua_State* L) {
  std::string text;
  if (lua_type(L, 1) == LUA_TSTRING) {
    text = lua_tostring(L, 1);
    if (hasLocation(text)) {
      lua_settop(L, 1);
      return 1;
    }
  } else {
    text = "error object is " + describe(L, 1);
  }
  text = where(L, 1) + text;
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

ScriptHost& hostOf(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kHostKey);
  auto* host = static_cast<ScriptHost*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return *host;
}

void* ScriptHost::allocate(void* ud, void* ptr, size_t old_size, size_t new_size) {
  auto* self = static_cast<ScriptHost*>(ud);
  const size_t old = ptr ? old_size : 0;  // for a new block old_size encodes the object type
  if (new_size == 0) {
    std::free(ptr);
    self->used_ -= old;
    return nullptr;
  }
  // Refusing an allocation makes Lua collect garbage, retry, then raise "not enough memory".
  if (new_size > old && self->used_ - old + new_size > self->options_.limits.memory_bytes) return nullptr;
  void* p = std::realloc(ptr, new_size);
  if (p) self->used_ = self->used_ - old + new_size;
  return p;
}

ScriptHost::ScriptHost(const SceneOptions& options, std::filesystem::path scene_dir)
    : options_(options), scene_dir_(std::move(scene_dir)) {
  if (options_.module_dirs.empty()) options_.module_dirs.push_back(scriptsDirectory());
  lua_ = std::make_unique<sol::state>(sol::default_at_panic, &ScriptHost::allocate, this);
  lua_State* L = lua_->lua_state();
  lua_pushlightuserdata(L, this);
  lua_setfield(L, LUA_REGISTRYINDEX, kHostKey);
  lua_newtable(L);
  lua_setfield(L, LUA_REGISTRYINDEX, kLoadedKey);

  // Only these libraries; never open_libraries() without arguments (it opens io, os, package...).
  lua_->open_libraries(sol::lib::base, sol::lib::math, sol::lib::string, sol::lib::table);
  lua_pushcfunction(L, guarded<luaPrint>);
  lua_setglobal(L, "print");
  lua_pushcfunction(L, guarded<luaRequire>);
  lua_setglobal(L, "require");
  // The string metatable cannot be read or replaced: getmetatable("") is false.
  lua_pushliteral(L, "");
  lua_getmetatable(L, -1);
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 2);
  // Runs repeat: the generator starts from the same seed every time (reliability.md D2).
  (*lua_)["math"]["randomseed"](20261121);
  runPrelude();
}

ScriptHost::~ScriptHost() { lua_.reset(); }  // closes the state while the allocator's counter lives

void ScriptHost::runPrelude() {
  sol::state& lua = *lua_;
  sol::protected_function prelude = compile(kPreludeSource, "=prelude");
  sol::table api = lua.create_table();
  lua_State* L = lua.lua_state();
  lua_pushcfunction(L, guarded<luaDescribe>);
  api["describe"] = sol::stack::pop<sol::object>(L);
  lua_pushcfunction(L, guarded<luaRegisterVec2>);
  api["register_vec2"] = sol::stack::pop<sol::object>(L);
  auto result = prelude(api);
  if (!result.valid()) throw SceneError("prelude: " + errorText(result, "prelude"));
}

std::string ScriptHost::readSource(const std::filesystem::path& file, const std::string& name) const {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw SceneError(name + ": cannot read: " + ec.message());
  if (size > options_.limits.source_bytes)
    throw SceneError(name + ": file is " + std::to_string(size) + " bytes, larger than the limit of " +
                     std::to_string(options_.limits.source_bytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(name + ": cannot read: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

sol::protected_function ScriptHost::compile(std::string_view source, const std::string& name) {
  lua_State* L = lua_->lua_state();
  const std::string chunkname = name.starts_with("=") ? name : "@" + name;
  // Mode "t": a precompiled (binary) chunk is refused before the parser runs (reliability.md §0.2).
  const int status = luaL_loadbufferx(L, source.data(), source.size(), chunkname.c_str(), "t");
  if (status != LUA_OK) {
    std::string message = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "cannot load";
    lua_pop(L, 1);
    if (message.find("attempt to load a binary chunk") != std::string::npos)
      message = name + ": binary (precompiled) chunks are not allowed; load Lua source text";
    throw SceneError(message);
  }
  sol::function chunk(L, -1);
  lua_pop(L, 1);
  return protect(chunk);
}

sol::protected_function ScriptHost::protect(const sol::object& function) {
  lua_State* L = lua_->lua_state();
  lua_pushcfunction(L, messageHandler);
  sol::reference handler = sol::stack::pop<sol::reference>(L);
  return sol::protected_function(function, handler);
}

std::string ScriptHost::errorText(const sol::protected_function_result& result, std::string_view context) {
  std::string message;
  if (result.status() == sol::call_status::memory) {
    message = "not enough memory (the scene's limit is " + std::to_string(options_.limits.memory_bytes >> 20) + " MiB)";
  } else {
    // Read the error from the stack: sol2 refuses to convert a failed result to anything else.
    lua_State* L = result.lua_state();
    const int index = result.stack_index();
    message = lua_type(L, index) == LUA_TSTRING ? lua_tostring(L, index) : "error object is " + describe(L, index);
  }
  return errorText(std::move(message), context);
}

std::string ScriptHost::errorText(std::string message, std::string_view context) {
  if (message == last_api_error_ || context.empty()) return message;  // already "<where><function>: ..."
  if (hasLocation(message)) {
    // Insert the context after "<file>:<line>: ".
    const size_t colon = message.find(": ");
    if (colon != std::string::npos) return message.substr(0, colon + 2) + std::string(context) + ": " + message.substr(colon + 2);
  }
  return std::string(context) + ": " + message;
}

void ScriptHost::log(const std::string& line) const {
  if (options_.log) {
    options_.log(line);
  } else {
    std::fprintf(stderr, "%s\n", line.c_str());
  }
}

int ScriptHost::requireModule(lua_State* L) {
  const std::string name = luaL_checkstring(L, 1);
  lua_getfield(L, LUA_REGISTRYINDEX, kLoadedKey);
  lua_getfield(L, -1, name.c_str());
  if (!lua_isnil(L, -1)) return 1;
  lua_pop(L, 1);

  // Module names are dotted identifiers: "forces.spring" → forces/spring.lua. No paths, no "..".
  const bool valid = !name.empty() && name.find_first_not_of(
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") == std::string::npos &&
      name.find("..") == std::string::npos && name.front() != '.';
  if (!valid) fail(L, "require", "module name must look like \"forces.spring\", got " + describe(L, 1));
  std::string relative = name;
  for (char& c : relative)
    if (c == '.') c = '/';
  relative += ".lua";

  std::vector<std::filesystem::path> dirs{scene_dir_};
  dirs.insert(dirs.end(), options_.module_dirs.begin(), options_.module_dirs.end());
  std::filesystem::path found;
  std::string looked;
  for (const auto& dir : dirs) {
    const auto candidate = dir / relative;
    if (std::filesystem::is_regular_file(candidate)) {
      found = candidate;
      break;
    }
    looked += (looked.empty() ? "" : ", ") + (dir.empty() ? std::string(".") : dir.string());
  }
  if (found.empty()) fail(L, "require", "module '" + name + "' not found (looked for " + relative + " in " + looked + ")");

  const std::string display = found.lexically_normal().string();
  sol::protected_function chunk = compile(readSource(found, display), display);
  if (std::find(required_.begin(), required_.end(), found) == required_.end()) required_.push_back(found);
  ++calls;
  auto result = chunk(name);
  if (!result.valid()) {
    const std::string message = errorText(result, "require '" + name + "'");
    markApiError(message);
    throw ScriptError(message);
  }
  sol::object value = result;
  lua_getfield(L, LUA_REGISTRYINDEX, kLoadedKey);
  if (value.get_type() == sol::type::lua_nil) {
    lua_pushboolean(L, 1);
  } else {
    value.push(L);
  }
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, name.c_str());
  return 1;
}

}  // namespace rigidlab::lua

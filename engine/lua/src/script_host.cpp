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
#include "lua_math.h"
#include "ordered_pairs.h"
#include "rigidlab/lua/bounded_file.h"
#include "rigidlab/lua/scene_text.h"
#include "scene_line.h"

extern const char kPreludeSource[];

namespace rigidlab::lua {
namespace {

constexpr const char* kLoadedKey = "rigidlab.loaded";

// print(...): tab-separated like Lua's own, to the host's log; at most kPrintBytes of it, with
// control characters other than newline and tab escaped (a scene's "\27[2J" must not reach a
// terminal).
int luaPrint(lua_State* L) {
  const int n = lua_gettop(L);
  std::string line;
  size_t total = 0;
  for (int i = 1; i <= n; ++i) {
    size_t len = 0;
    const char* s = luaL_tolstring(L, i, &len);  // may call __tostring: an error unwinds cleanly
    if (i > 1) line += '\t';
    total += len + (i > 1);
    // Only what can be shown is copied (a 100 MB argument is not).
    if (line.size() <= kPrintBytes) line.append(s, std::min(len, kPrintBytes + 1));
    lua_pop(L, 1);
  }
  std::string shown = displayText(line, kPrintBytes, "\n\t");
  if (total > line.size() && !shown.ends_with(" more bytes)"))
    shown += "... (" + std::to_string(total - line.size()) + " more bytes)";
  hostOf(L).log(shown);
  return 0;
}

int luaRequire(lua_State* L) { return hostOf(L).requireModule(L); }

// The real path: links resolved as far as the path exists (std::filesystem::weakly_canonical).
std::filesystem::path resolved(const std::filesystem::path& p) {
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(p.empty() ? std::filesystem::path(".") : p, ec);
  auto real = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : real;
}

// True if `file` lies below `dir` (both resolved).
bool isInside(const std::filesystem::path& file, const std::filesystem::path& dir) {
  auto f = file.begin();
  for (auto d = dir.begin(); d != dir.end(); ++d, ++f) {
    if (d->empty()) continue;  // a trailing separator
    if (f == file.end() || *f != *d) return false;
  }
  return f != file.end();
}

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


// --- Caps on C functions the budget hook cannot interrupt (script_host.h, docs/security.md).

// Index just past a character class "[...]" starting at p[i] == '[' (lstrlib's classEnd).
size_t skipSet(std::string_view p, size_t i) {
  ++i;
  if (i < p.size() && p[i] == '^') ++i;
  do {
    if (i >= p.size()) return p.size();
    if (p[i++] == '%' && i < p.size()) ++i;
  } while (i < p.size() && p[i] != ']');
  return i + 1;
}

// string.find/match/gmatch/gsub: argument 1 the subject, 2 the pattern; upvalue 1 the original.
template <int Which>  // 0 find, 1 match, 2 gmatch, 3 gsub
int patternGuard(lua_State* L) {
  static constexpr const char* kNames[] = {"string.find", "string.match", "string.gmatch", "string.gsub"};
  size_t n = 0, m = 0;
  luaL_checklstring(L, 1, &n);
  const char* p = luaL_checklstring(L, 2, &m);
  const bool plain = Which == 0 && lua_toboolean(L, 4);
  const double work = patternWork(std::string_view(p, m), std::string_view(lua_tostring(L, 1), n), plain, Which != 2);
  if (work > kPatternWorkLimit) {
    char amount[32];
    std::snprintf(amount, sizeof amount, "%.2g", work);
    fail(L, kNames[Which], "pattern " + describe(L, 2) + " is too costly for a subject of " + std::to_string(n) +
                               " bytes (worst case " + amount + " matching steps, the limit is 5e+07; use a "
                               "simpler pattern or a shorter string)");
  }
  const int nargs = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, nargs, LUA_MULTRET);
  return lua_gettop(L);
}

// table.sort(t [, comp]): above kNativeSortLimit elements a missing or C comparator is replaced by
// a Lua function (upvalue 2: less-than; upvalue 3: a wrapper factory), so the budget hook can stop
// the sort. Same order: Lua's `<` is what the built-in comparison does.
int sortGuard(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  const lua_Integer n = luaL_len(L, 1);
  const bool native = lua_isnoneornil(L, 2) || lua_iscfunction(L, 2);
  if (n > kNativeSortLimit && native) {
    if (lua_isnoneornil(L, 2)) {
      lua_settop(L, 1);
      lua_pushvalue(L, lua_upvalueindex(2));
    } else {
      lua_settop(L, 2);
      lua_pushvalue(L, lua_upvalueindex(3));
      lua_insert(L, 2);
      lua_call(L, 1, 1);  // wrap(comp)
    }
  }
  const int nargs = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, nargs, 0);
  return 0;
}

// table.move(a1, f, e, t [, a2]) loops in C over e - f + 1 elements, nil or not.
int moveGuard(lua_State* L) {
  const lua_Integer f = luaL_checkinteger(L, 2), e = luaL_checkinteger(L, 3);
  if (e >= f && (f <= 0 ? e >= LUA_MAXINTEGER + f : e - f >= kMoveLimit))
    fail(L, "table.move", "moves at most " + std::to_string(kMoveLimit) + " elements per call, asked for " +
                              (f <= 0 && e >= LUA_MAXINTEGER + f ? std::string("more") : std::to_string(e - f + 1)));
  const int nargs = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, nargs, LUA_MULTRET);
  return lua_gettop(L);
}

// string.rep(s, n [, sep]) filled by doubling copies: time linear in the result (which the
// memory cap bounds), not in n (Lua's loop copies `s` n times, ~1 ns each for 1-byte pieces).
int repGuard(lua_State* L) {
  size_t l = 0, lsep = 0;
  const char* s = luaL_checklstring(L, 1, &l);
  const lua_Integer n = luaL_checkinteger(L, 2);
  const char* sep = luaL_optlstring(L, 3, "", &lsep);
  if (n <= 0 || l + lsep == 0) {
    lua_pushliteral(L, "");
    return 1;
  }
  const size_t unit = l + lsep;
  constexpr size_t kMax = static_cast<size_t>(LUA_MAXINTEGER) / 2;
  if (unit > kMax / static_cast<size_t>(n)) return luaL_error(L, "resulting string too large");
  const size_t total = unit * static_cast<size_t>(n) - lsep;
  luaL_Buffer b;
  char* out = luaL_buffinitsize(L, &b, total);
  size_t filled = std::min(l, total);
  std::memcpy(out, s, filled);
  if (filled < total) {
    std::memcpy(out + filled, sep, std::min(lsep, total - filled));
    filled = std::min(unit, total);
  }
  while (filled < total) {  // out[0, filled) is whole periods of `unit`
    const size_t c = std::min(filled, total - filled);
    std::memcpy(out + filled, out, c);
    filled += c;
  }
  luaL_pushresultsize(&b, total);
  return 1;
}

// rigidlab.record_scene_line(): called by the prelude's rawset when the main chunk sets the
// global `scene` with rawset, so errors in the settings still point at a line.
int luaRecordSceneLine(lua_State* L) {
  recordSceneLine(L, sceneLocation(L));
  return 0;
}

// rigidlab.release_globals(): the scene replaces the metatable of _G (prelude's setmetatable):
// the host's recorder of the `scene` line (scene_loader.cpp), locked, steps aside.
int luaReleaseGlobals(lua_State* L) {
  releaseGlobals(L);
  return 0;
}

int luaBudgetCheck(lua_State* L) { return Budget::check(L); }
int luaBudgetExpired(lua_State* L) {
  lua_pushboolean(L, Budget::expiredOn(L));
  return 1;
}

}  // namespace

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

namespace {

// Lua's character classes (lstrlib.c match_class / singlematch), to measure how long a run of
// subject characters a repeated pattern item can take.
bool classMatches(unsigned char c, char cl) {
  bool res;
  switch (std::tolower(static_cast<unsigned char>(cl))) {
    case 'a': res = std::isalpha(c); break;
    case 'c': res = std::iscntrl(c); break;
    case 'd': res = std::isdigit(c); break;
    case 'g': res = std::isgraph(c); break;
    case 'l': res = std::islower(c); break;
    case 'p': res = std::ispunct(c); break;
    case 's': res = std::isspace(c); break;
    case 'u': res = std::isupper(c); break;
    case 'w': res = std::isalnum(c); break;
    case 'x': res = std::isxdigit(c); break;
    default: return static_cast<unsigned char>(cl) == c;
  }
  if (std::isupper(static_cast<unsigned char>(cl))) res = !res;
  return res;
}

// Does subject character c match the single-character item p[begin, end)?
bool itemMatches(unsigned char c, std::string_view p, size_t begin, size_t end) {
  const char first = p[begin];
  if (first == '.') return true;
  if (first == '%') return begin + 1 < end && classMatches(c, p[begin + 1]);
  if (first != '[') return static_cast<unsigned char>(first) == c;
  size_t i = begin + 1;
  bool negate = false;
  if (i < end && p[i] == '^') negate = true, ++i;
  const size_t close = end - 1;  // the ']'
  bool found = false;
  while (i < close && !found) {
    if (p[i] == '%' && i + 1 < close) {
      found = classMatches(c, p[i + 1]);
      i += 2;
    } else if (i + 2 < close && p[i + 1] == '-') {
      found = static_cast<unsigned char>(p[i]) <= c && c <= static_cast<unsigned char>(p[i + 2]);
      i += 3;
    } else {
      found = static_cast<unsigned char>(p[i]) == c;
      ++i;
    }
  }
  return found != negate;
}

// Longest run of consecutive subject characters that the item p[begin, end) matches.
double longestRun(std::string_view subject, std::string_view p, size_t begin, size_t end) {
  size_t best = 0, run = 0;
  for (unsigned char c : subject) {
    run = itemMatches(c, p, begin, end) ? run + 1 : 0;
    best = std::max(best, run);
  }
  return static_cast<double>(best);
}

}  // namespace

double patternWork(std::string_view p, std::string_view subject, bool plain, bool anchor) {
  const double n = static_cast<double>(subject.size()), m = static_cast<double>(p.size());
  if (plain || p.find_first_of("^$*+?.([%-") == std::string_view::npos)
    return std::max(1.0, n - m + 1) * std::max(1.0, m);  // lmemfind: memcmp at each candidate start
  size_t i = 0;
  bool anchored = false;
  if (anchor && p[0] == '^') {
    anchored = true;
    i = 1;
  }
  int repeats = 0, optionals = 0;  // items with * + - (or %b, back-references); items with ?
  double items = 0;
  double splits = 1;  // Π (longest run the repeated item can take + 1)
  while (i < p.size()) {
    const char c = p[i];
    if (c == '(' || c == ')' || (c == '$' && i + 1 == p.size())) {
      ++i;
      continue;
    }
    if (c == '%' && i + 1 < p.size()) {
      const char d = p[i + 1];
      if (d == 'b') {  // %bxy: scans up to the subject's end at each try
        ++repeats, ++items, i += 4, splits *= n + 1;
        continue;
      }
      if (d == 'f') {  // %f[set]: one comparison
        i = (i + 2 < p.size() && p[i + 2] == '[') ? skipSet(p, i + 2) : i + 2;
        ++items;
        continue;
      }
      if (d >= '0' && d <= '9') {  // back-reference: compares up to a capture's length
        ++repeats, ++items, i += 2, splits *= n + 1;
        continue;
      }
    }
    const size_t begin = i;
    i = c == '%' ? std::min(i + 2, p.size()) : c == '[' ? std::min(skipSet(p, i), p.size()) : i + 1;
    ++items;
    if (i < p.size()) {
      if (p[i] == '*' || p[i] == '+' || p[i] == '-') {
        splits *= longestRun(subject, p, begin, i) + 1;
        ++repeats, ++i;
      } else if (p[i] == '?') {
        ++optionals, ++i;
      }
    }
  }
  // Each start position (one if anchored) tries the ways of splitting the subject among the
  // repeated items: at most C(n + k, k) for k of them, and at most the product of the runs each
  // can take; each try costs about k + 1 steps, and every optional item doubles the tries.
  double ways = 1;
  for (int k = 1; k <= repeats && ways < 1e300; ++k) ways *= (n + k) / k;
  const double starts = anchored ? 1.0 : n + 1;
  return starts * std::max(1.0, items) * std::min(ways, splits) * (repeats + 1) *
         std::pow(2.0, std::min(optionals, 64));
}

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
  // The state's extra space (LUA_EXTRASPACE, copied into every coroutine the state makes) holds
  // the host: a pointer read, where the registry lookup it replaced cost a string comparison.
  ScriptHost* host;
  std::memcpy(&host, lua_getextraspace(L), sizeof host);
  return *host;
}

std::string sceneLocation(lua_State* L) {
  lua_Debug frame;
  for (int level = 0; lua_getstack(L, level, &frame); ++level) {
    if (!lua_getinfo(L, "Sl", &frame) || frame.currentline <= 0 || frame.source[0] == '=') continue;
    return std::string(frame.short_src) + ":" + std::to_string(frame.currentline) + ": ";
  }
  return "";
}

void* ScriptHost::allocate(void* ud, void* ptr, size_t old_size, size_t new_size) {
  auto* self = static_cast<ScriptHost*>(ud);
  // Lua sees the memory after the header (kBlockHeader); both count against the cap.
  char* block = ptr ? static_cast<char*>(ptr) - kBlockHeader : nullptr;
  const size_t old = ptr ? old_size + kBlockHeader : 0;  // for a new block old_size encodes the object type
  BlockPool& pool = self->pool_;
  const auto release = [&](char* b, size_t bytes) {
    if (BlockPool::holds(bytes)) pool.give(b, bytes);
    else std::free(b);
  };
  if (new_size == 0) {
    if (block) release(block, old);
    self->used_ -= old;
    return nullptr;
  }
  const size_t size = new_size + kBlockHeader;
  // Refusing an allocation makes Lua collect garbage, retry, then raise "not enough memory". The
  // scene's line that asked for it is noted each time (the last refusal is the one that raises):
  // Lua's memory error carries no location and its message handler does not run for it.
  if (new_size > SIZE_MAX - kBlockHeader || (size > old && self->used_ - old + size > self->options_.limits.memory_bytes)) {
    if (self->state_) self->memory_error_at_ = sceneLocation(self->state_);
    return nullptr;
  }
  char* p;
  if (block && (BlockPool::holds(old) ? BlockPool::holds(size) && BlockPool::sameClass(old, size) : !BlockPool::holds(size))) {
    p = BlockPool::holds(size) ? block : static_cast<char*>(std::realloc(block, size));  // stays where it is
  } else {
    p = static_cast<char*>(BlockPool::holds(size) ? pool.take(size) : std::malloc(size));
    if (!p) {
      // Lua counts on a block that shrinks never failing: the old one is large enough, and is
      // given back later as a block of the new size (to the pool, if that size is the pool's:
      // then, out of memory anyway, the C library never gets it back).
      if (!block || size > old) return nullptr;
      self->used_ = self->used_ - old + size;
      return ptr;
    }
    if (block) {
      std::memcpy(p, block, std::min(old, size));
      release(block, old);
    }
  }
  if (!p) return nullptr;  // realloc of a large block
  if (!block) {
    const uint64_t serial = ++self->serial_;
    std::memcpy(p, &serial, sizeof serial);
  }
  self->used_ = self->used_ - old + size;
  return p + kBlockHeader;
}

void ScriptHost::charge(lua_State* L, std::string_view function, size_t bytes) {
  if (used_ + bytes > options_.limits.memory_bytes)
    fail(L, function, memoryMessage() + "; bodies, shapes, joints and their names count against it");
  used_ += bytes;
}

std::string ScriptHost::memoryMessage() const {
  return "not enough memory (the scene's limit is " + std::to_string(options_.limits.memory_bytes >> 20) + " MiB)";
}

namespace {

struct ProtectedBody {
  void (*invoke)(void*);
  void* body;
  std::exception_ptr exception;
};

// The C function run() calls under lua_pcall. A C++ exception from the body is kept and a Lua
// error raised in its place (Lua, built as C++, would catch it with catch (...) and lose it);
// Lua's own errors pass through to the pcall.
int protectedBody(lua_State* L) {
  auto* p = static_cast<ProtectedBody*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  bool thrown = false;
  try {
    p->invoke(p->body);
  } catch (const std::exception&) {
    p->exception = std::current_exception();
    thrown = true;
  }
  if (thrown) {
    lua_pushliteral(L, "(host exception)");
    return lua_error(L);
  }
  return 0;
}

}  // namespace

std::optional<std::string> ScriptHost::runErased(void (*invoke)(void*), void* body) {
  lua_State* L = this->L();
  const int top = lua_gettop(L);
  memory_error_at_.clear();
  if (!lua_checkstack(L, 3)) return memoryMessage();  // lua_checkstack itself is protected
  ProtectedBody p{invoke, body, nullptr};
  lua_pushcfunction(L, messageHandler);
  lua_pushcfunction(L, protectedBody);
  lua_pushlightuserdata(L, &p);
  const int status = lua_pcall(L, 1, 0, top + 1);
  std::optional<std::string> error;
  if (status == LUA_ERRMEM) {
    error = memory_error_at_ + memoryMessage();
  } else if (status != LUA_OK) {
    error = lua_type(L, -1) == LUA_TSTRING ? std::string(lua_tostring(L, -1)) : "error object is " + describe(L, -1);
  }
  lua_settop(L, top);
  if (p.exception) std::rethrow_exception(p.exception);
  return error;
}

ScriptHost::ScriptHost(const SceneOptions& options, std::filesystem::path scene_dir)
    : options_(options), scene_dir_(std::move(scene_dir)) {
  if (options_.module_dirs.empty()) options_.module_dirs.push_back(scriptsDirectory());
  // require() reads only below these, whatever links lead elsewhere (requireModule).
  for (const auto& dir : std::vector{scene_dir_}) allowed_dirs_.push_back(resolved(dir));
  for (const auto& dir : options_.module_dirs) allowed_dirs_.push_back(resolved(dir));
  lua_ = std::make_unique<sol::state>(sol::default_at_panic, &ScriptHost::allocate, this);
  lua_State* L = lua_->lua_state();
  state_ = L;
  const auto error = run([&] {
    ScriptHost* self = this;
    static_assert(LUA_EXTRASPACE >= sizeof self, "hostOf keeps the host in the state's extra space");
    std::memcpy(lua_getextraspace(L), &self, sizeof self);
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
    // Runs repeat: the generator starts from the same seed every time (docs/design/reliability.md D2).
    lua_getglobal(L, "math");
    lua_getfield(L, -1, "randomseed");
    lua_pushinteger(L, 20261121);
    lua_call(L, 1, 0);
    lua_pop(L, 1);
    installPortableMath(L);  // the same bits on every machine (lua_math.h)
    installGuards();
    installOrderedPairs(L);
    runPrelude();
  });
  if (error) throw SceneError("cannot set up the scene's Lua state: " + *error);
  // From here on every call into the state runs under a budget window (budget.h).
  budget_ = std::make_unique<Budget>(L, options_.limits.hook_seconds, options_.limits.force_seconds);
}

ScriptHost::~ScriptHost() {
  budget_.reset();
  // Closing runs the finalizers of what is left, and Lua runs finalizers with its hooks off, so no
  // budget could stop one: none exists. setmetatable refuses __gc (one added to a metatable later
  // is never called) and handles have none (bindings.h).
  lua_.reset();  // while the allocator's counter lives
}

void ScriptHost::installGuards() {
  lua_State* L = lua_->lua_state();
  static const std::pair<const char*, lua_CFunction> kPatterns[] = {
      {"find", guarded<patternGuard<0>>}, {"match", guarded<patternGuard<1>>},
      {"gmatch", guarded<patternGuard<2>>}, {"gsub", guarded<patternGuard<3>>}};
  lua_getglobal(L, "string");
  for (const auto& [name, guard] : kPatterns) {
    lua_getfield(L, -1, name);
    lua_pushcclosure(L, guard, 1);
    lua_setfield(L, -2, name);
  }
  lua_pushcfunction(L, guarded<repGuard>);
  lua_setfield(L, -2, "rep");
  lua_pop(L, 1);

  lua_getglobal(L, "table");
  lua_getfield(L, -1, "move");
  lua_pushcclosure(L, guarded<moveGuard>, 1);
  lua_setfield(L, -2, "move");
  lua_getfield(L, -1, "sort");
  static constexpr std::string_view kComparators =
      "return function(a, b) return a < b end, function(f) return function(a, b) return f(a, b) end end";
  if (luaL_loadbufferx(L, kComparators.data(), kComparators.size(), "=table.sort", "t") != LUA_OK)
    throw SceneError("table.sort guard: " + std::string(lua_tostring(L, -1)));
  lua_call(L, 0, 2);
  lua_pushcclosure(L, guarded<sortGuard>, 3);
  lua_setfield(L, -2, "sort");
  lua_pop(L, 1);
}

void ScriptHost::runPrelude() {
  lua_State* L = lua_->lua_state();
  pushChunk(kPreludeSource, "=prelude");
  lua_createtable(L, 0, 8);
  static const std::pair<const char*, lua_CFunction> kApi[] = {
      {"describe", guarded<luaDescribe>},
      {"register_vec2", guarded<luaRegisterVec2>},
      {"budget_check", luaBudgetCheck},
      {"budget_expired", luaBudgetExpired},
      {"record_scene_line", guarded<luaRecordSceneLine>},
      {"release_globals", guarded<luaReleaseGlobals>}};
  for (const auto& [name, f] : kApi) {
    lua_pushcfunction(L, f);
    lua_setfield(L, -2, name);
  }
  lua_pushinteger(L, static_cast<lua_Integer>(std::min(options_.limits.source_bytes, kLoadChunkLimit)));
  lua_setfield(L, -2, "source_limit");
  lua_call(L, 1, 0);
}

std::string ScriptHost::readSource(const std::filesystem::path& file, const std::string& name) const {
  try {
    return readBoundedFile(file, options_.limits.source_bytes, name, "a module file");
  } catch (const std::runtime_error& e) {
    throw SceneError(e.what());
  }
}

void ScriptHost::pushChunk(std::string_view source, const std::string& name) {
  lua_State* L = lua_->lua_state();
  const std::string chunkname = name.starts_with("=") ? name : "@" + name;
  // Mode "t": a precompiled (binary) chunk is refused before the parser runs (docs/design/reliability.md §0.2).
  const int status = luaL_loadbufferx(L, source.data(), source.size(), chunkname.c_str(), "t");
  if (status == LUA_OK) return;
  std::string message = status == LUA_ERRMEM                ? name + ": " + memoryMessage()
                        : lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1)
                                                         : "cannot load";
  lua_pop(L, 1);
  if (message.find("attempt to load a binary chunk") != std::string::npos)
    message = name + ": binary (precompiled) chunks are not allowed; load Lua source text";
  throw SceneError(errorText(std::move(message), ""));
}

std::string ScriptHost::errorText(std::string message, std::string_view context, std::optional<bool> budget_spent) {
  // A spent budget explains whatever error the call ended with (the hook's, or one it caused).
  if (budget_ && budget_spent.value_or(budget_->expired())) message = budget_->raised().empty() ? budget_->message() : budget_->raised();
  // Shown on terminals and in the sandbox: escaped and shortened (scene_text.h).
  message = displayText(message, kMessageBytes, "\n\t");
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
  size_t length = 0;
  const char* text = luaL_checklstring(L, 1, &length);
  const std::string name(text, length);  // all of it: a name cut at a NUL would load another module
  // Module names are dotted identifiers: "forces.spring" → forces/spring.lua. No paths, no "..",
  // no NUL or other control characters.
  const bool valid = !name.empty() && name.find_first_not_of(
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") == std::string::npos &&
      name.find("..") == std::string::npos && name.front() != '.';
  if (!valid) fail(L, "require", "module name must look like \"forces.spring\", got " + describe(L, 1));
  lua_getfield(L, LUA_REGISTRYINDEX, kLoadedKey);
  lua_getfield(L, -1, name.c_str());
  if (!lua_isnil(L, -1)) return 1;
  lua_pop(L, 1);
  std::string relative = name;
  for (char& c : relative)
    if (c == '.') c = '/';
  relative += ".lua";

  std::vector<std::filesystem::path> dirs{scene_dir_};
  dirs.insert(dirs.end(), options_.module_dirs.begin(), options_.module_dirs.end());
  std::filesystem::path found, real;
  std::string looked;
  for (size_t d = 0; d < dirs.size() && found.empty(); ++d) {
    const auto candidate = dirs[d] / relative;
    if (std::filesystem::is_regular_file(candidate)) {
      // The real file, links resolved, must lie inside one of the allowed folders (also resolved):
      // a link in a mod's folder must not lead to /etc/os-release.
      real = resolved(candidate);
      if (!std::any_of(allowed_dirs_.begin(), allowed_dirs_.end(), [&](const auto& dir) { return isInside(real, dir); }))
        fail(L, "require", "module '" + name + "' (" + candidate.lexically_normal().string() +
                               ") is a link to a file outside the scene's folder and the module folders: refused");
      found = candidate;
    } else {
      looked += (looked.empty() ? "" : ", ") + (dirs[d].empty() ? std::string(".") : dirs[d].string());
    }
  }
  if (found.empty()) fail(L, "require", "module '" + name + "' not found (looked for " + relative + " in " + looked + ")");

  const std::string display = found.lexically_normal().string();
  std::string source;
  try {
    source = readSource(real, display);  // the file checked, not the link again
  } catch (const SceneError& e) {
    fail(L, "require", e.what());  // "require: forces/big.lua: the file is ... bytes, more than the limit ..."
  }
  if (std::find(required_.begin(), required_.end(), found) == required_.end()) required_.push_back(found);
  ++calls;
  lua_pushcfunction(L, messageHandler);
  const int handler = lua_gettop(L);
  pushChunk(source, display);
  lua_pushlstring(L, name.data(), name.size());
  if (const int status = lua_pcall(L, 1, 1, handler); status != LUA_OK) {
    const std::string raised = status == LUA_ERRMEM ? memory_error_at_ + memoryMessage()
                               : lua_type(L, -1) == LUA_TSTRING ? std::string(lua_tostring(L, -1))
                                                                : "error object is " + describe(L, -1);
    const std::string message = errorText(raised, "require '" + name + "'");
    markApiError(message);
    throw ScriptError(message);
  }
  lua_getfield(L, LUA_REGISTRYINDEX, kLoadedKey);
  if (lua_isnil(L, -2)) {
    lua_pushboolean(L, 1);
  } else {
    lua_pushvalue(L, -2);
  }
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, name.c_str());
  return 1;
}

}  // namespace rigidlab::lua

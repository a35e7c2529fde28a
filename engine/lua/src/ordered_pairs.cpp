// Iteration in an order that is the same in every process (ordered_pairs.h).
#include "ordered_pairs.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "bindings.h"
#include "budget.h"
#include "lua_args.h"

namespace rigidlab::lua {
namespace {

constexpr const char* kSnapshotsKey = "rigidlab.next_snapshots";  // weak table: t → sorted keys

enum Rank : uint8_t { kNumber, kString, kBoolean, kObject, kHandle, kCFunction, kOther };

// A key reduced to what its place in the order needs. 24 bytes: a snapshot of n keys costs 24 n
// bytes of C++ memory while it is sorted (Lua already holds the keys themselves).
struct SortKey {
  uint64_t a = 0, b = 0;  // number: the value's bits (b: 1 if an integer); string: pointer, length;
                          // object: serial; handle: kind, id; C function: library name, offset
  uint32_t index = 0;     // position in the unsorted list
  Rank rank = kOther;
};

SortKey keyOf(lua_State* L, int index) {
  index = lua_absindex(L, index);
  SortKey k;
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      k.rank = kNumber;
      if (lua_isinteger(L, index)) {
        const lua_Integer i = lua_tointeger(L, index);
        std::memcpy(&k.a, &i, sizeof i);
        k.b = 1;
      } else {
        const lua_Number d = lua_tonumber(L, index);
        std::memcpy(&k.a, &d, sizeof d);
      }
      return k;
    case LUA_TSTRING: {
      size_t len = 0;
      const char* s = lua_tolstring(L, index, &len);
      k.rank = kString;
      k.a = reinterpret_cast<uintptr_t>(s);
      k.b = len;
      return k;
    }
    case LUA_TBOOLEAN:
      k.rank = kBoolean;
      k.a = lua_toboolean(L, index);
      return k;
    case LUA_TTABLE:
      k.rank = kObject;
      k.a = blockSerial(lua_topointer(L, index));
      return k;
    case LUA_TFUNCTION:
      if (!lua_iscfunction(L, index) || lua_getupvalue(L, index, 1)) {
        if (lua_iscfunction(L, index)) lua_pop(L, 1);  // the upvalue: a C closure is an object too
        k.rank = kObject;
        k.a = blockSerial(lua_topointer(L, index));
      } else {
        // A light C function is no allocation: its address, relative to its library's, is fixed.
        const void* f = reinterpret_cast<const void*>(lua_tocfunction(L, index));
        Dl_info info{};
        k.rank = kCFunction;
        if (dladdr(f, &info) && info.dli_fname) {
          k.a = reinterpret_cast<uintptr_t>(info.dli_fname);
          k.b = reinterpret_cast<uintptr_t>(f) - reinterpret_cast<uintptr_t>(info.dli_fbase);
        } else {
          k.b = reinterpret_cast<uintptr_t>(f);
        }
      }
      return k;
    case LUA_TUSERDATA: {
      k.rank = kHandle;
      if (const LuaBody* b = toHandle<LuaBody>(L, index)) {
        k.a = 1, k.b = b->uid;
      } else if (const LuaForceHandle* f = toHandle<LuaForceHandle>(L, index)) {
        k.a = 2, k.b = static_cast<uint64_t>(f->id.index) << 32 | f->id.generation;
      } else if (toHandle<LuaWorld>(L, index)) {
        k.a = 3;
      } else if (toHandle<LuaDraw>(L, index)) {
        k.a = 4;
      } else {
        k.rank = kOther;
        k.a = reinterpret_cast<uintptr_t>(lua_topointer(L, index));
      }
      return k;
    }
    default:  // threads and light userdata: a scene cannot make them
      k.a = reinterpret_cast<uintptr_t>(lua_topointer(L, index));
      return k;
  }
}

// Numbers: integers and floats compared by value (a float key never has an integral value that
// fits an integer: Lua stores those as integers).
bool numberBefore(const SortKey& x, const SortKey& y) {
  const auto integer = [](const SortKey& k) {
    lua_Integer i;
    std::memcpy(&i, &k.a, sizeof i);
    return i;
  };
  const auto real = [](const SortKey& k) {
    lua_Number d;
    std::memcpy(&d, &k.a, sizeof d);
    return d;
  };
  if (x.b && y.b) return integer(x) < integer(y);
  if (!x.b && !y.b) return real(x) < real(y);
  // i < d for an integer i and a float d: exact, without converting i to a double.
  const auto intBefore = [](lua_Integer i, lua_Number d) {
    if (d >= 0x1p63) return true;
    if (d < -0x1p63) return false;
    const auto f = static_cast<lua_Integer>(std::floor(d));
    return i < f || (i == f && static_cast<lua_Number>(f) < d);
  };
  const auto floatBefore = [&](lua_Number d, lua_Integer i) { return !intBefore(i, d) && !(static_cast<lua_Number>(i) == d); };
  return x.b ? intBefore(integer(x), real(y)) : floatBefore(real(x), integer(y));
}

bool before(const SortKey& x, const SortKey& y) {
  if (x.rank != y.rank) return x.rank < y.rank;
  switch (x.rank) {
    case kNumber: return numberBefore(x, y);
    case kString: {
      const int c = std::memcmp(reinterpret_cast<const char*>(x.a), reinterpret_cast<const char*>(y.a), std::min(x.b, y.b));
      return c < 0 || (c == 0 && x.b < y.b);
    }
    case kCFunction: {
      const char* lx = reinterpret_cast<const char*>(x.a);
      const char* ly = reinterpret_cast<const char*>(y.a);
      const int c = (lx && ly) ? std::strcmp(lx, ly) : (lx != nullptr) - (ly != nullptr);
      return c < 0 || (c == 0 && x.b < y.b);
    }
    default: return x.a < y.a || (x.a == y.a && x.b < y.b);
  }
}

void requireTable(lua_State* L, const char* function) {
  if (lua_type(L, 1) != LUA_TTABLE) fail(L, function, "expects a table, got " + describe(L, 1));
}

// Pushes {k1, k2, ...}: the keys of the table at `t`, in order.
void pushSortedKeys(lua_State* L, int t) {
  t = lua_absindex(L, t);
  int n = 0;
  lua_pushnil(L);
  while (lua_next(L, t)) {
    lua_pop(L, 1);
    if (++n % kBudgetEvery == 0) Budget::check(L);
  }
  lua_createtable(L, n, 0);
  const int unsorted = lua_gettop(L);
  std::vector<SortKey> keys;
  keys.reserve(static_cast<size_t>(n));
  lua_pushnil(L);
  while (lua_next(L, t)) {
    lua_pop(L, 1);
    lua_pushvalue(L, -1);
    lua_rawseti(L, unsorted, static_cast<lua_Integer>(keys.size() + 1));
    SortKey k = keyOf(L, -1);  // a string's bytes stay put: the table holds it
    k.index = static_cast<uint32_t>(keys.size() + 1);
    keys.push_back(k);
    if (keys.size() % kBudgetEvery == 0) Budget::check(L);
  }
  // Sorting 2 million string keys took 6 s in this one C call: the budget is looked at while
  // sorting (and every kBudgetEvery keys).
  budgetedSort(L, keys.begin(), keys.end(), before);
  lua_createtable(L, n, 0);
  for (size_t i = 0; i < keys.size(); ++i) {
    lua_rawgeti(L, unsorted, keys[i].index);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    if ((i + 1) % kBudgetEvery == 0) Budget::check(L);
  }
  lua_remove(L, unsorted);
}

// The iterator pairs() returns. Upvalues: the sorted keys, the table, the position reached.
int pairsStep(lua_State* L) {
  lua_Integer position = lua_tointeger(L, lua_upvalueindex(3));
  for (;;) {
    if (lua_rawgeti(L, lua_upvalueindex(1), ++position) == LUA_TNIL) return 1;  // the end (keeps position)
    lua_pushvalue(L, -1);
    if (lua_rawget(L, lua_upvalueindex(2)) != LUA_TNIL) break;  // removed since the snapshot: skip
    lua_pop(L, 2);
  }
  lua_pushinteger(L, position);
  lua_replace(L, lua_upvalueindex(3));
  return 2;
}

int orderedPairs(lua_State* L) {
  if (lua_type(L, 1) == LUA_TTABLE && luaL_getmetafield(L, 1, "__pairs") != LUA_TNIL) {
    lua_pushvalue(L, 1);
    lua_call(L, 1, 3);
    return 3;
  }
  requireTable(L, "pairs");
  lua_settop(L, 1);
  pushSortedKeys(L, 1);
  lua_pushvalue(L, 1);
  lua_pushinteger(L, 0);
  lua_pushcclosure(L, pairsStep, 3);
  lua_pushvalue(L, 1);
  lua_pushnil(L);
  return 3;
}

// Index (1-based) of the key at `key` in the sorted list at `list`, or 0.
lua_Integer findKey(lua_State* L, int list, int key) {
  const SortKey k = keyOf(L, key);
  lua_Integer lo = 1, hi = static_cast<lua_Integer>(lua_rawlen(L, list));
  while (lo <= hi) {
    const lua_Integer mid = lo + (hi - lo) / 2;
    lua_rawgeti(L, list, mid);
    const SortKey m = keyOf(L, -1);
    const bool less = before(m, k), equal = !less && !before(k, m);
    lua_pop(L, 1);
    if (equal) return mid;
    if (less) lo = mid + 1;
    else hi = mid - 1;
  }
  return 0;
}

int orderedNext(lua_State* L) {
  requireTable(L, "next");
  lua_settop(L, 2);
  lua_getfield(L, LUA_REGISTRYINDEX, kSnapshotsKey);  // 3
  if (lua_isnil(L, 2)) {
    // A new traversal: forget t's snapshot, find the smallest key.
    lua_pushvalue(L, 1);
    lua_pushnil(L);
    lua_rawset(L, 3);
    lua_pushnil(L);  // 4: the best key so far
    lua_pushnil(L);
    bool any = false;
    SortKey best;
    while (lua_next(L, 1)) {
      lua_pop(L, 1);
      const SortKey k = keyOf(L, -1);
      if (!any || before(k, best)) {
        lua_pushvalue(L, -1);
        lua_replace(L, 4);
        best = keyOf(L, 4);
        any = true;
      }
    }
    if (!any) return 1;  // nil: empty
    lua_pushvalue(L, 4);
    lua_pushvalue(L, 4);
    lua_rawget(L, 1);
    return 2;
  }
  // The key after k: from t's snapshot, taken now if there is none or k is not in it.
  lua_pushvalue(L, 1);
  lua_rawget(L, 3);  // 4
  lua_Integer at = lua_isnil(L, 4) ? 0 : findKey(L, 4, 2);
  if (at == 0) {
    lua_pop(L, 1);
    pushSortedKeys(L, 1);
    lua_pushvalue(L, 1);
    lua_pushvalue(L, -2);
    lua_rawset(L, 3);
    at = findKey(L, 4, 2);
    if (at == 0) fail(L, "next", "invalid key to 'next': " + describe(L, 2) + " is not in the table");
  }
  for (lua_Integer i = at + 1;; ++i) {
    if (lua_rawgeti(L, 4, i) == LUA_TNIL) return 1;  // the end
    lua_pushvalue(L, -1);
    if (lua_rawget(L, 1) != LUA_TNIL) return 2;
    lua_pop(L, 2);
  }
}

}  // namespace

void installOrderedPairs(lua_State* L) {
  lua_createtable(L, 0, 0);
  lua_createtable(L, 0, 1);
  lua_pushliteral(L, "k");
  lua_setfield(L, -2, "__mode");  // a snapshot lives as long as its table
  lua_setmetatable(L, -2);
  lua_setfield(L, LUA_REGISTRYINDEX, kSnapshotsKey);
  lua_pushcfunction(L, guarded<orderedPairs>);
  lua_setglobal(L, "pairs");
  lua_pushcfunction(L, guarded<orderedNext>);
  lua_setglobal(L, "next");
}

}  // namespace rigidlab::lua

// The encoding of a scene's saved state (scene_state.h). Little-endian, one tag byte per value:
//
//   "RLSS" u8 version (1), then the value:
//   nil | false | true                     the tag alone
//   integer                                 8 bytes (two's complement)
//   float                                   the double's 8 bytes, raw
//   string                                  u64 length, bytes
//   table / vec2 table                      u64 pair count, then key, value, ... in key order
//   table seen before                       u64 its number (tables are numbered 0, 1, ... as first written)
//   body                                    u32 slot, u32 generation, u32 uid
//   shape                                   u32 slot, u32 generation
//   joint                                   u32 slot, u32 generation, u8 joint type
//   force                                   u32 slot, u32 generation, u8 kind (spring, damper, lua force)
//   world                                   the tag alone
//
// Keys are sorted by class (booleans, integers, floats, strings, handles) and then by value, so the
// bytes do not depend on the order a table was filled in nor on Lua's hashing. Tables are read
// raw: no metamethod of the script runs inside the host.
#include "scene_state.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "budget.h"
#include "lua_args.h"
#include "lua_snapshot.h"

namespace rigidlab::lua {

namespace {

constexpr char kMagic[] = "RLSS";
constexpr size_t kMagicBytes = 4;
constexpr uint8_t kFormat = 1;

enum Tag : uint8_t {
  kNil,
  kFalse,
  kTrue,
  kInteger,
  kFloat,
  kString,
  kTable,
  kVec2Table,
  kTableRef,
  kBody,
  kShape,
  kJoint,
  kForce,
  kWorld,
  kTags
};

// LuaForceHandle::kind is one of these literals (lua_world.cpp); a file stores its position.
constexpr const char* kForceKinds[] = {"spring", "damper", "lua force"};

constexpr const char* kAllowed =
    "only nil, booleans, numbers, strings, tables and body/shape/joint/force handles can be saved";

void putRaw(std::string& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

// A key reduced to what its place in the order needs (the string's bytes stay in the Lua string,
// which the keys table anchors while the table is written).
struct SortKey {
  int cls = 0;  // 0 boolean, 1 integer, 2 float, 3 string, 4 handle
  lua_Integer integer = 0;  // boolean: 0/1; handle: tag
  double number = 0;
  std::string_view text;
  uint64_t slot = 0, generation = 0;
  int position = 0;  // in the keys table
};

bool before(const SortKey& a, const SortKey& b) {
  if (a.cls != b.cls) return a.cls < b.cls;
  switch (a.cls) {
    case 2: return a.number < b.number;  // never NaN: NaN is no table key
    case 3: return a.text < b.text;
    case 4:
      if (a.integer != b.integer) return a.integer < b.integer;
      if (a.slot != b.slot) return a.slot < b.slot;
      return a.generation < b.generation;
    default: return a.integer < b.integer;
  }
}

bool sameKey(const SortKey& a, const SortKey& b) { return !before(a, b) && !before(b, a); }

class Encoder {
 public:
  Encoder(lua_State* L, Scene::Impl& scene) : L_(L), scene_(scene) {}

  std::string run(int index) {
    out_.assign(kMagic, kMagicBytes);
    out_ += static_cast<char>(kFormat);
    value(lua_absindex(L_, index), 0);
    return std::move(out_);
  }

 private:
  // "state.enemies[3].think": the path of keys (their stack slots) from the returned value.
  // A deep one shows its first and last keys: state[1][1][1][1][1]...[1][1][1][1][1].
  std::string path() const {
    constexpr size_t kShown = 5;
    std::string p = "state";
    for (size_t i = 0; i < path_.size(); ++i) {
      if (path_.size() > 2 * kShown + 1 && i == kShown) {
        p += "...";
        i = path_.size() - kShown - 1;
        continue;
      }
      const int k = path_[i];
      if (lua_type(L_, k) == LUA_TSTRING) {
        size_t n = 0;
        const char* s = lua_tolstring(L_, k, &n);
        const std::string_view name(s, n);
        const bool identifier = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
                                std::all_of(name.begin(), name.end(), [](char c) {
                                  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                                });
        if (identifier && n <= 64) {
          p += ".";
          p += name;
          continue;
        }
      }
      p += "[" + describe(L_, k) + "]";
    }
    return p;
  }

  std::string describeValue(int index) const {
    if (toHandle<LuaSnapshot>(L_, index)) return "a snapshot (snapshots are kept in memory, not saved)";
    if (lua_type(L_, index) == LUA_TTHREAD) return "a coroutine";
    return describe(L_, index);
  }

  // "value at <path> is <what>": `what` describes the value at `index` and says what can be saved.
  [[noreturn]] void refuse(int index) const { refuse(describeValue(index) + "; " + kAllowed); }
  [[noreturn]] void refuse(const std::string& what) const {
    throw SceneStateError("value at " + path() + " is " + what);
  }

  void checkScene(int index, Scene::Impl* owner) const {
    if (owner != &scene_) refuse(describeValue(index) + " of another scene; " + kAllowed + " (of this scene)");
  }

  // A handle: its tag and id written (and its sort key filled, for keys); false if `index` holds
  // no handle this encoding knows.
  bool handle(int index, SortKey* key) {
    uint8_t tag;
    uint32_t slot, generation;
    std::string rest;
    if (const LuaBody* b = toHandle<LuaBody>(L_, index)) {
      checkScene(index, b->scene);
      tag = kBody, slot = b->id.index, generation = b->id.generation;
      putRaw(rest, b->uid, 4);
    } else if (const LuaShape* s = toHandle<LuaShape>(L_, index)) {
      checkScene(index, s->scene);
      tag = kShape, slot = s->id.index, generation = s->id.generation;
    } else if (const LuaJoint* j = toHandle<LuaJoint>(L_, index)) {
      checkScene(index, j->scene);
      tag = kJoint, slot = j->id.index, generation = j->id.generation;
      putRaw(rest, static_cast<uint8_t>(j->type), 1);
    } else if (const LuaForceHandle* f = toHandle<LuaForceHandle>(L_, index)) {
      checkScene(index, f->scene);
      tag = kForce, slot = f->id.index, generation = f->id.generation;
      uint8_t kind = 0;
      while (kind < std::size(kForceKinds) && std::strcmp(kForceKinds[kind], f->kind) != 0) ++kind;
      if (kind == std::size(kForceKinds)) refuse(index);
      putRaw(rest, kind, 1);
    } else if (const LuaWorld* w = toHandle<LuaWorld>(L_, index)) {
      checkScene(index, w->scene);
      tag = kWorld, slot = 0, generation = 0;
    } else {
      return false;
    }
    out_ += static_cast<char>(tag);
    if (tag != kWorld) {
      putRaw(out_, slot, 4);
      putRaw(out_, generation, 4);
      out_ += rest;
    }
    if (key) {
      key->cls = 4;
      key->integer = tag;
      key->slot = slot;
      key->generation = generation;
    }
    return true;
  }

  void value(int index, int depth) {
    if (++values_ % kBudgetEvery == 0) Budget::check(L_);  // millions of values: budget.h
    switch (lua_type(L_, index)) {
      case LUA_TNIL:
        out_ += static_cast<char>(kNil);
        return;
      case LUA_TBOOLEAN:
        out_ += static_cast<char>(lua_toboolean(L_, index) ? kTrue : kFalse);
        return;
      case LUA_TNUMBER:
        if (lua_isinteger(L_, index)) {
          out_ += static_cast<char>(kInteger);
          putRaw(out_, static_cast<uint64_t>(lua_tointeger(L_, index)), 8);
        } else {
          out_ += static_cast<char>(kFloat);
          putRaw(out_, std::bit_cast<uint64_t>(static_cast<double>(lua_tonumber(L_, index))), 8);
        }
        return;
      case LUA_TSTRING: {
        size_t n = 0;
        const char* s = lua_tolstring(L_, index, &n);
        out_ += static_cast<char>(kString);
        putRaw(out_, n, 8);
        out_.append(s, n);
        return;
      }
      case LUA_TTABLE:
        table(index, depth);
        return;
      case LUA_TUSERDATA:
        if (handle(index, nullptr)) return;
        refuse(index);
      default:
        refuse(index);
    }
  }

  void table(int t, int depth) {
    const void* id = lua_topointer(L_, t);
    if (const auto seen = tables_.find(id); seen != tables_.end()) {
      out_ += static_cast<char>(kTableRef);
      putRaw(out_, seen->second, 8);
      return;
    }
    bool vec2 = false;
    if (lua_getmetatable(L_, t)) {
      lua_pop(L_, 1);
      vec2 = isVec2Table(L_, t);
      if (!vec2) refuse("a table with a metatable; only plain tables and vec2 can be saved (a metatable's functions cannot)");
    }
    if (depth >= kMaxSceneStateDepth)
      refuse("a table nested " + std::to_string(depth) + " tables deep; at most " +
             std::to_string(kMaxSceneStateDepth) + " levels of tables can be saved");
    luaL_checkstack(L_, 6, "SaveState: the state is nested too deeply");
    const uint64_t number = tables_.size();
    tables_.emplace(id, number);

    // The keys into a table of their own (so their strings stay anchored), and their order.
    lua_newtable(L_);
    const int keys = lua_gettop(L_);
    std::vector<SortKey> order;
    lua_pushnil(L_);
    while (lua_next(L_, t) != 0) {
      lua_pop(L_, 1);  // the value
      if (++values_ % kBudgetEvery == 0) Budget::check(L_);
      const int k = lua_gettop(L_);
      SortKey key;
      switch (lua_type(L_, k)) {
        case LUA_TBOOLEAN:
          key.cls = 0, key.integer = lua_toboolean(L_, k);
          break;
        case LUA_TNUMBER:
          if (lua_isinteger(L_, k)) key.cls = 1, key.integer = lua_tointeger(L_, k);
          else key.cls = 2, key.number = lua_tonumber(L_, k);
          break;
        case LUA_TSTRING: {
          size_t n = 0;
          const char* s = lua_tolstring(L_, k, &n);
          key.cls = 3, key.text = std::string_view(s, n);
          break;
        }
        default: {
          // A handle: its sort key from the bytes it would write (written for real below).
          const size_t mark = out_.size();
          const bool known = lua_type(L_, k) == LUA_TUSERDATA && handle(k, &key);
          out_.resize(mark);
          if (!known)
            throw SceneStateError("key in " + path() + " is " + describeValue(k) +
                                  "; only booleans, numbers, strings and body/shape/joint/force handles can be "
                                  "saved as keys");
        }
      }
      key.position = static_cast<int>(order.size()) + 1;
      order.push_back(key);
      lua_pushvalue(L_, k);
      lua_rawseti(L_, keys, key.position);
    }
    budgetedSort(L_, order.begin(), order.end(), before);
    out_ += static_cast<char>(vec2 ? kVec2Table : kTable);
    putRaw(out_, order.size(), 8);
    for (size_t i = 0; i < order.size(); ++i) {
      lua_rawgeti(L_, keys, order[i].position);
      const int k = lua_gettop(L_);
      if (i > 0 && sameKey(order[i - 1], order[i]))
        throw SceneStateError("key in " + path() + ": two handles of the same object (" + describeValue(k) +
                              ") are keys of one table; it could not hold both after a restore");
      value(k, depth + 1);
      lua_pushvalue(L_, k);
      lua_rawget(L_, t);
      path_.push_back(k);
      value(lua_gettop(L_), depth + 1);
      path_.pop_back();
      lua_pop(L_, 2);
    }
    lua_pop(L_, 1);  // keys
  }

  lua_State* L_;
  uint64_t values_ = 0;  // values written or read, for the budget's checks
  Scene::Impl& scene_;
  std::string out_;
  std::vector<int> path_;
  std::unordered_map<const void*, uint64_t> tables_;
};

class Decoder {
 public:
  Decoder(lua_State* L, Scene::Impl& scene, std::string_view in) : L_(L), scene_(scene), in_(in) {}

  void run() {
    if (in_.size() < kMagicBytes + 1 || in_.substr(0, kMagicBytes) != std::string_view(kMagic, kMagicBytes))
      fail("it is not a saved scene state (no \"RLSS\" header)");
    pos_ = kMagicBytes;
    if (const uint64_t format = raw(1, "the format"); format != kFormat)
      fail("format " + std::to_string(format) + ", this program reads format " + std::to_string(kFormat));
    lua_newtable(L_);  // the tables read so far, by number
    tables_ = lua_gettop(L_);
    value(0);
    if (pos_ != in_.size()) fail("bytes left over after the value");
    lua_remove(L_, tables_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw SceneStateError("the saved state is corrupt: " + what + " (at byte " + std::to_string(pos_) + ")");
  }

  uint64_t raw(int bytes, const char* what) {
    if (in_.size() - pos_ < static_cast<size_t>(bytes)) fail(std::string("truncated, reading ") + what);
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= uint64_t{static_cast<unsigned char>(in_[pos_ + i])} << (8 * i);
    pos_ += bytes;
    return v;
  }
  // A count of things that follow, each at least one byte.
  uint64_t count(const char* what) {
    const uint64_t n = raw(8, what);
    if (n > in_.size() - pos_) fail(std::string(what) + " of " + std::to_string(n) + " cannot fit in what is left");
    return n;
  }

  void value(int depth) {
    if (++values_ % kBudgetEvery == 0) Budget::check(L_);
    luaL_checkstack(L_, 6, "LoadState: the state is nested too deeply");
    const uint64_t tag = raw(1, "a value's kind");
    switch (tag) {
      case kNil: lua_pushnil(L_); return;
      case kFalse: lua_pushboolean(L_, 0); return;
      case kTrue: lua_pushboolean(L_, 1); return;
      case kInteger: lua_pushinteger(L_, static_cast<lua_Integer>(raw(8, "an integer"))); return;
      case kFloat: lua_pushnumber(L_, std::bit_cast<double>(raw(8, "a number"))); return;
      case kString: {
        const uint64_t n = count("a string's length");
        lua_pushlstring(L_, in_.data() + pos_, n);
        pos_ += n;
        return;
      }
      case kTable:
      case kVec2Table: table(tag == kVec2Table, depth); return;
      case kTableRef: {
        const uint64_t n = raw(8, "a table's number");
        if (n >= tables_read_) fail("a reference to table " + std::to_string(n) + " of " + std::to_string(tables_read_));
        lua_rawgeti(L_, tables_, static_cast<lua_Integer>(n) + 1);
        return;
      }
      case kBody: {
        BodyId id;
        id.index = static_cast<uint32_t>(raw(4, "a body's slot"));
        id.generation = static_cast<uint32_t>(raw(4, "a body's generation"));
        const auto uid = static_cast<uint32_t>(raw(4, "a body's uid"));
        const World& w = *scene_.world;
        if (w.isValid(id) && w.body(id).uid == uid) pushBodyHandle(L_, scene_, id);
        else pushHandle(L_, LuaBody{&scene_, id, uid});  // removed when saved (or since): stale
        return;
      }
      case kShape: {
        ShapeId id;
        id.index = static_cast<uint32_t>(raw(4, "a shape's slot"));
        id.generation = static_cast<uint32_t>(raw(4, "a shape's generation"));
        pushCachedHandle(L_, scene_.shape_handles, handleKey(id.index, id.generation), LuaShape{&scene_, id});
        return;
      }
      case kJoint: {
        JointId id;
        id.index = static_cast<uint32_t>(raw(4, "a joint's slot"));
        id.generation = static_cast<uint32_t>(raw(4, "a joint's generation"));
        const uint64_t type = raw(1, "a joint's type");
        if (type >= static_cast<uint64_t>(kJointTypes)) fail("joint type " + std::to_string(type));
        pushCachedHandle(L_, scene_.joint_handles, handleKey(id.index, id.generation),
                         LuaJoint{&scene_, id, static_cast<JointType>(type)});
        return;
      }
      case kForce: {
        ForceId id;
        id.index = static_cast<uint32_t>(raw(4, "a force's slot"));
        id.generation = static_cast<uint32_t>(raw(4, "a force's generation"));
        const uint64_t kind = raw(1, "a force's kind");
        if (kind >= std::size(kForceKinds)) fail("force kind " + std::to_string(kind));
        pushHandle(L_, LuaForceHandle{&scene_, id, kForceKinds[kind]});
        return;
      }
      case kWorld: scene_.world_handle.push(L_); return;
      default: fail("a value of kind " + std::to_string(tag));
    }
  }

  void table(bool vec2, int depth) {
    if (depth >= kMaxSceneStateDepth) fail("tables nested more than " + std::to_string(kMaxSceneStateDepth) + " deep");
    const uint64_t n = count("a table's size");
    lua_newtable(L_);
    const int t = lua_gettop(L_);
    lua_pushvalue(L_, t);
    lua_rawseti(L_, tables_, static_cast<lua_Integer>(++tables_read_));
    for (uint64_t i = 0; i < n; ++i) {
      value(depth + 1);
      if (lua_isnil(L_, -1) || (lua_type(L_, -1) == LUA_TNUMBER && lua_tonumber(L_, -1) != lua_tonumber(L_, -1)))
        fail("a table key that is nil or NaN");
      value(depth + 1);
      lua_rawset(L_, t);
    }
    if (vec2) {
      lua_rawgeti(L_, LUA_REGISTRYINDEX, hostOf(L_).vec2_metatable_ref);
      lua_setmetatable(L_, t);
    }
  }

  lua_State* L_;
  uint64_t values_ = 0;  // values written or read, for the budget's checks
  Scene::Impl& scene_;
  std::string_view in_;
  size_t pos_ = 0;
  int tables_ = 0;
  uint64_t tables_read_ = 0;
};

}  // namespace

std::string encodeSceneState(lua_State* L, Scene::Impl& scene, int index) {
  const int top = lua_gettop(L);
  std::string bytes = Encoder(L, scene).run(index);
  lua_settop(L, top);
  return bytes;
}

void pushSceneState(lua_State* L, Scene::Impl& scene, std::string_view bytes) {
  const int top = lua_gettop(L);
  try {
    Decoder(L, scene, bytes).run();
  } catch (...) {
    lua_settop(L, top);
    throw;
  }
}

}  // namespace rigidlab::lua

// Snapshots from Lua: world:snapshot(), world:restore(s) (lua_snapshot.cpp).
#pragma once

#include <cstdint>
#include <string_view>

#include "bindings.h"

namespace rigidlab::lua {

// A snapshot as Lua sees it: the index of a WorldSnapshot in Scene::Impl::snapshots.
struct LuaSnapshot {
  static constexpr const char* kMetatable = "rigidlab.snapshot";
  Scene::Impl* scene;
  uint32_t index;
};

// Snapshots a scene may take: each is kept (and charged) until the scene closes.
inline constexpr size_t kMaxSnapshots = 100000;

void registerSnapshotType(lua_State* L);
lua_CFunction snapshotWorldMethod(std::string_view name);  // snapshot, restore; or nullptr
// World::restore and the Lua side's mending (the file comment of lua_snapshot.cpp). Call it inside
// a protected call; SnapshotError leaves everything as it was.
void restoreScene(lua_State* L, Scene::Impl& scene, const WorldSnapshot& snapshot);

}  // namespace rigidlab::lua

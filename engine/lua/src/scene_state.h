// A scene's own state in a snapshot (docs/lua-api.md "Snapshots"): the value SaveState(world)
// returns, as bytes for WorldSnapshot::appData, and back.
//
// The encoding is deterministic: the same state gives the same bytes whatever order its tables
// were filled in (keys are written sorted: booleans, integers, floats, strings, then handles by
// kind, slot and generation). Numbers keep their subtype and floats their 64 bits (-0.0, NaN
// payloads). A table reached twice (shared, or in a cycle) is written once and then referred to,
// so the restored value shares it the same way. Body, shape, joint and force handles and the world
// are written as ids (slot, generation; a body's uid too): read back after the world's restore,
// they are the handles of the restored objects (the same Lua objects the API returns for them, so
// they work as table keys). A vec2 keeps its metatable. Anything else is refused, naming the path:
//   value at state.enemies[3].think is a function; only nil, booleans, numbers, strings, tables
//   and body/shape/joint/force handles can be saved
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "bindings.h"

namespace rigidlab::lua {

// A value that cannot be saved, or bytes that are not an encoded state. The message has no
// location and no hook name: the caller adds them.
class SceneStateError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Tables nested deeper than this are refused (the encoder and decoder recurse).
inline constexpr int kMaxSceneStateDepth = 100;

// The value at stack `index` as bytes (never empty: nil is one byte). Call it inside a protected
// call (it pushes and may raise a Lua memory error); leaves the stack as it was.
std::string encodeSceneState(lua_State* L, Scene::Impl& scene, int index);

// Pushes the value `bytes` hold, with its handles naming the objects of scene's world as it is now
// (call it after the world's restore). Inside a protected call.
void pushSceneState(lua_State* L, Scene::Impl& scene, std::string_view bytes);

}  // namespace rigidlab::lua

// world:snapshot() and world:restore(s) (docs/lua-api.md "Snapshots"), and Scene::snapshot and
// Scene::restore for the program and the sandbox.
//
// A snapshot handle is a plain struct like the other handles (no finalizer may exist in a scene's
// state, bindings.h): it names a WorldSnapshot kept in Scene::Impl::snapshots until the scene
// closes, whose memory is charged against the scene's limit. Restoring puts the world back
// (World::restore) and then mends the Lua side: body handles and user_data of bodies that no longer
// exist are forgotten (a handle a script still holds is stale and says so), joints alive again are
// no longer `broken`, and the host memory charged for bodies follows the bodies. The scene's Lua
// variables are its own: a scene that defines SaveState(world) has the value it returns encoded
// (scene_state.h) into the snapshot's application data, and LoadState(world, value) gets it back
// after the world's restore. SaveState runs before the world is copied, so that the handles it
// returns name objects the snapshot holds.
#include "lua_snapshot.h"

#include <cstdio>
#include <set>

#include "api_names.h"
#include "lua_args.h"
#include "scene_state.h"

namespace rigidlab::lua {

namespace {

size_t bodiesHostBytes(const World& w) {
  size_t n = 0;
  for (BodyId id : w.bodyIds()) n += hostBytes(w, w.body(id));
  return n;
}

const LuaSnapshot& selfSnapshot(lua_State* L, std::string_view what) {
  const LuaSnapshot* s = toHandle<LuaSnapshot>(L, 1);
  if (!s) fail(L, what, "expects a snapshot (call it with a colon), got " + describe(L, 1));
  return *s;
}

int snapshotIndex(lua_State* L) {
  const LuaSnapshot& self = selfSnapshot(L, "snapshot");
  sol::stack_object key(L, 2);
  const std::string k = fieldName(L, "snapshot", key);
  const WorldSnapshot& s = self.scene->snapshots.at(self.index);
  if (k == "time") {
    lua_pushnumber(L, s.time());
  } else if (k == "step_count") {
    lua_pushinteger(L, s.stepCount());
  } else if (k == "bytes") {
    lua_pushinteger(L, static_cast<lua_Integer>(s.memoryBytes()));
  } else {
    noSuchField(L, "snapshot", k, api::kSnapshotFields);
  }
  return 1;
}

int snapshotNewIndex(lua_State* L) {
  selfSnapshot(L, "snapshot");
  sol::stack_object key(L, 2);
  const std::string k = fieldName(L, "snapshot", key);
  requireWritable(L, "snapshot", k, api::kSnapshotFields, {});
  return 0;
}

std::string describeSnapshot(const LuaSnapshot& s) {
  const WorldSnapshot& w = s.scene->snapshots.at(s.index);
  return "snapshot at t = " + formatNumber(w.time()) + " s (step " + std::to_string(w.stepCount()) + ")";
}

bool defined(const sol::object& f) { return f.valid() && f.get_type() == sol::type::function; }

// "<file>:<line>: " where hook `f` is defined: encoding errors happen after it has returned, and
// a bad value is made there.
std::string definedAt(lua_State* L, const sol::object& f) {
  f.push(L);
  lua_Debug ar;
  lua_getinfo(L, ">S", &ar);
  if (ar.linedefined <= 0) return "";
  return std::string(ar.short_src) + ":" + std::to_string(ar.linedefined) + ": ";
}

// Throws ScriptError("<where hook is defined>: <hook>: <message>"), located and marked like an
// API function's error (so no context is added a second time).
[[noreturn]] void failHook(lua_State* L, const sol::object& hook, std::string_view name, const std::string& message) {
  const std::string text = definedAt(L, hook) + std::string(name) + ": " + message;
  hostOf(L).markApiError(text);
  throw ScriptError(text);
}

// SaveState(world)'s value, encoded; "" if the scene defines no SaveState. Inside a protected call.
std::string saveState(lua_State* L, Scene::Impl& scene) {
  if (!defined(scene.save_state)) return {};
  scene.save_state.push(L);
  scene.world_handle.push(L);
  lua_call(L, 1, 1);
  std::string bytes;
  try {
    bytes = encodeSceneState(L, scene, -1);
  } catch (const SceneStateError& e) {
    failHook(L, scene.save_state, "SaveState", e.what());
  }
  lua_pop(L, 1);
  return bytes;
}

// LoadState(world, value) with the value the snapshot carries (nil if it carries none), after the
// world's restore. Inside a protected call.
void loadState(lua_State* L, Scene::Impl& scene, const WorldSnapshot& snapshot) {
  if (!defined(scene.load_state)) return;
  scene.load_state.push(L);
  scene.world_handle.push(L);
  if (snapshot.appData().empty()) {
    lua_pushnil(L);
  } else {
    try {
      pushSceneState(L, scene, snapshot.appData());
    } catch (const SceneStateError& e) {
      failHook(L, scene.load_state, "LoadState", e.what());
    }
  }
  lua_call(L, 2, 0);
}

int snapshotMethod(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "snapshot");
  if (scene.snapshots.size() >= kMaxSnapshots)
    fail(L, "snapshot", "a scene may keep at most " + std::to_string(kMaxSnapshots) +
                            " snapshots (each is kept until the scene closes)");
  std::string state = saveState(L, scene);
  WorldSnapshot s = scene.world->snapshot();
  s.setAppData(std::move(state));
  s.setLabel(scene.file.empty() ? scene.name : scene.file.string());
  scene.host->charge(L, "snapshot", s.memoryBytes());
  scene.snapshots.push_back(std::move(s));
  pushHandle(L, LuaSnapshot{&scene, static_cast<uint32_t>(scene.snapshots.size() - 1)});
  return 1;
}

int restoreMethod(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "restore");
  const LuaSnapshot* s = toHandle<LuaSnapshot>(L, 2);
  if (!s) fail(L, "restore", "snapshot must be a snapshot (from world:snapshot()), got " + describe(L, 2));
  if (s->scene != &scene)
    fail(L, "restore", "snapshot was taken in another scene (" + s->scene->name + "), not in " + scene.name);
  const WorldSnapshot& snapshot = scene.snapshots.at(s->index);
  try {
    restoreScene(L, scene, snapshot);
  } catch (const SnapshotError& e) {
    fail(L, "restore", e.what());
  }
  loadState(L, scene, snapshot);
  return 0;
}

}  // namespace

void restoreScene(lua_State* L, Scene::Impl& scene, const WorldSnapshot& snapshot) {
  World& w = *scene.world;
  const size_t before = bodiesHostBytes(w);
  w.restore(snapshot);
  scene.host->release(before);
  // Handles and user_data of bodies that are gone: forgotten, so a body made after this restore
  // (which may get the uid of one made after the snapshot) gets its own.
  std::set<uint32_t> live;
  for (BodyId id : w.bodyIds()) live.insert(w.body(id).uid);
  for (sol::table* t : {&scene.handles, &scene.user_data}) {
    std::vector<uint32_t> gone;
    for (const auto& [key, value] : *t) {
      if (key.get_type() != sol::type::number) continue;
      const auto uid = key.as<uint32_t>();
      if (!live.count(uid)) gone.push_back(uid);
    }
    for (uint32_t uid : gone) t->raw_set(uid, sol::lua_nil);
  }
  // The same for shapes' and joints' user_data, by their keys.
  std::set<uint64_t> live_keys;
  for (BodyId id : w.bodyIds())
    for (ShapeId s : w.body(id).shapes) live_keys.insert(handleKey(s.index, s.generation));
  for (JointId j : w.jointIds()) live_keys.insert(handleKey(j.index, j.generation));
  for (sol::table* t : {&scene.shape_user_data, &scene.joint_user_data}) {
    std::vector<lua_Integer> gone;
    for (const auto& [key, value] : *t)
      if (key.get_type() == sol::type::number && !live_keys.count(static_cast<uint64_t>(key.as<lua_Integer>())))
        gone.push_back(key.as<lua_Integer>());
    for (lua_Integer key : gone) t->raw_set(key, sol::lua_nil);
  }
  for (JointId j : w.jointIds()) scene.broken_joints.erase(handleKey(j.index, j.generation));
  scene.host->charge(L, "restore", bodiesHostBytes(w));
}

void registerSnapshotType(lua_State* L) {
  registerHandleType(L, LuaSnapshot::kMetatable, guarded<snapshotIndex>, guarded<snapshotNewIndex>,
                     guarded<handleToString<LuaSnapshot, describeSnapshot>>,
                     guarded<handlesEqual<LuaSnapshot, &LuaSnapshot::index>>);
}

lua_CFunction snapshotWorldMethod(std::string_view name) {
  if (name == "snapshot") return guarded<snapshotMethod>;
  if (name == "restore") return guarded<restoreMethod>;
  return nullptr;
}

namespace {

// A hook call from C++ (Scene::snapshot, Scene::restore) as scene_loader.cpp makes the others:
// under the hook's budget, a Lua error located and named ("<file>:<line>: SaveState: ...").
template <typename F>
void callHook(Scene::Impl& s, std::string_view name, F body) {
  ++s.host->calls;
  std::optional<std::string> error;
  {
    const Budget::Scope budget(s.host->budget(), Budget::Kind::Hook);
    try {
      error = s.host->run(body);
    } catch (const ScriptError& e) {  // an encoding error, already located
      error = e.what();
    }
    if (error) error = s.host->errorText(std::move(*error), name);
  }
  if (error) throw SceneError(*error);
}

}  // namespace

WorldSnapshot Scene::snapshot() const {
  Scene::Impl& scene = *impl_;
  std::string state;
  if (defined(scene.save_state)) callHook(scene, "SaveState", [&] { state = saveState(scene.host->L(), scene); });
  WorldSnapshot s = impl_->world->snapshot();
  s.setAppData(std::move(state));
  // The scene's dt is the scene's, not the world's: the label carries it, exactly (%a).
  char dt[64];
  std::snprintf(dt, sizeof dt, "%a", impl_->settings.dt);
  s.setLabel("scene: " + (impl_->file.empty() ? impl_->name : impl_->file.string()) + "\ndt: " + dt + "\n");
  return s;
}

void Scene::restore(const WorldSnapshot& snapshot) {
  Scene::Impl& s = *impl_;
  std::optional<std::string> snapshot_error;
  const auto error = s.host->run([&] {
    try {
      restoreScene(s.host->L(), s, snapshot);
    } catch (const SnapshotError& e) {
      snapshot_error = e.what();
    }
  });
  if (snapshot_error) throw SceneError(s.name + ": " + *snapshot_error);
  if (error) throw SceneError(s.host->errorText(*error, "restore"));
  if (defined(s.load_state)) callHook(s, "LoadState", [&] { loadState(s.host->L(), s, snapshot); });
}

}  // namespace rigidlab::lua

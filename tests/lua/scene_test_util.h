// Loading a scene from a string in tests, and the one message a broken scene ends with.
#pragma once

#include <memory>
#include <string>

#include "rigidlab/lua/scene.h"

namespace lua_test {

inline std::unique_ptr<rigidlab::lua::Scene> load(const std::string& source, rigidlab::lua::SceneOptions options = {}) {
  if (!options.log) options.log = [](const std::string&) {};
  return rigidlab::lua::Scene::loadString(source, "test.lua", options);
}

// The message of the SceneError that loading (and, if given, stepping) the scene throws.
inline std::string errorOf(const std::string& source, int steps = 0) {
  try {
    auto scene = load(source);
    for (int i = 0; i < steps; ++i) scene->step();
    scene->runCheck();
  } catch (const rigidlab::lua::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace lua_test

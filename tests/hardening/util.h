// Helpers shared by the hardening tests.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "rigidlab/lua/scene.h"

namespace hardening {

using rigidlab::lua::Scene;
using rigidlab::lua::SceneError;
using rigidlab::lua::SceneOptions;

inline SceneOptions quiet(SceneOptions o = {}) {
  if (!o.log) o.log = [](const std::string&) {};
  return o;
}

inline std::unique_ptr<Scene> load(const std::string& source, SceneOptions options = {}) {
  return Scene::loadString(source, "test.lua", quiet(std::move(options)));
}

// Runs f; returns the SceneError's message ("(no error)" if none) and the wall time in ms.
struct Outcome {
  std::string message;
  double ms = 0;
};

inline Outcome timed(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  Outcome o{"(no error)", 0};
  try {
    f();
  } catch (const SceneError& e) {
    o.message = e.what();
  }
  o.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return o;
}

inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace hardening

// Benchmark scenes for `rigidlab bench`. Each builds a world (in C++, or through a Lua scene when
// it measures Lua) and says how many steps to time.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"
#include "rigidlab/world.h"

namespace rigidlab::app {

// A world to step: either owned directly or inside a Lua scene.
struct BenchWorld {
  std::unique_ptr<World> world;
  std::unique_ptr<lua::Scene> scene;
  World& get() { return scene ? scene->world() : *world; }
  long luaCalls() const { return scene ? scene->luaCalls() : 0; }
};

struct BenchScene {
  std::string name;
  std::string description;
  int steps = 600;
  double dt = 1.0 / 60.0;
  std::function<BenchWorld()> build;
};

const std::vector<BenchScene>& benchScenes();

}  // namespace rigidlab::app

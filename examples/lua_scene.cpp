// A Lua scene run from a user's own program (rigidlab::lua): loads the file given on the command
// line (default: the installed scripts/scenes/pyramid.lua), steps it for its `scene.duration`, runs
// its Check if it has one, and prints its highest body.
#include <cmath>
#include <cstdio>
#include <exception>

#include "rigidlab/lua/scene.h"

int main(int argc, char** argv) {
  using namespace rigidlab;
  const std::filesystem::path file =
      argc > 1 ? std::filesystem::path(argv[1]) : lua::scriptsDirectory() / "scenes" / "pyramid.lua";
  try {
    const auto scene = lua::Scene::loadFile(file);
    const long steps = std::lround(scene->settings().duration / scene->settings().dt);
    for (long i = 0; i < steps; ++i) scene->step();
    if (scene->hasCheck()) scene->runCheck();  // throws SceneError if the scene's checks fail
    const World& world = scene->world();
    const Body* top = nullptr;
    for (BodyId id : world.bodyIds())
      if (const Body& b = world.body(id); b.isDynamic() && (!top || b.position().y() > top->position().y())) top = &b;
    std::printf("%s: %zu bodies after %.2f s%s\n", file.filename().string().c_str(), world.bodyIds().size(),
                world.time(), scene->hasCheck() ? ", Check passed" : "");
    if (top) std::printf("  highest: '%s' at (%.3f, %.3f) m\n", top->name.c_str(), top->position().x(), top->position().y());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}

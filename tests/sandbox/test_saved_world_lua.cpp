// The saved-file round trip through the real Lua bindings: format 3 files (every shape kind, body
// option and joint kind) opened by rigidlab itself, as the sandbox's saves are;
// test_scene_writer.cpp runs the same files through the scene API double.
#include <doctest/doctest.h>
#include <unistd.h>

#include <fstream>

#include "rigidlab/lua/scene.h"
#include "rigidlab/lua/scene_writer.h"
#include "saved_worlds.h"

using namespace rigidlab;
using namespace rigidlab::lua;
using namespace rigidlab::sandbox_test;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    char name[] = "/tmp/rigidlab-saved-lua-XXXXXX";
    path = ::mkdtemp(name);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

TEST_CASE("saved world through the Lua bindings: every kind, saved after running, opens as the same world") {
  World w = everyKindWorld();
  for (int i = 0; i < 90; ++i) w.step(1.0 / 60.0);
  TempDir dir;
  saveScene(w, SceneSettings{}, dir.path / "every_kind.lua");
  auto scene = Scene::loadFile(dir.path / "every_kind.lua");
  checkSameWorld(w, scene->world(), 1e-12);
}

TEST_CASE("saved world through the Lua bindings: saved before it runs, it steps bit for bit like the original") {
  World a = everyKindWorld();
  TempDir dir;
  SceneSettings settings;
  saveScene(a, settings, dir.path / "fresh.lua");
  auto scene = Scene::loadFile(dir.path / "fresh.lua");
  World& b = scene->world();
  checkSameWorld(a, b, 0.0);
  int diverged = -1;
  for (int i = 1; i <= 240 && diverged < 0; ++i) {
    a.step(settings.dt);
    scene->step();
    if (bodyHash(a) != bodyHash(b) || jointHash(a) != jointHash(b)) diverged = i;
  }
  CHECK(diverged == -1);
}

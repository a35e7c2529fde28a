// Placeholder entry point until the Lua layer lands: runs a built-in scene headless.
#include <cstdio>

#include "rigidlab/world.h"

int main() {
  using namespace rigidlab;
  World world;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = makeBox(40, 1);
  ground.position = {0, -0.5};
  world.createBody(ground);
  BodyDef box;
  box.shape = makeBox(1, 1);
  box.position = {0, 4};
  box.angle = 0.3;
  BodyId id = world.createBody(box);
  for (int i = 0; i < 600; ++i) world.step(1.0 / 60.0);
  const Body& b = world.body(id);
  std::printf("t=%.3f box at (%.4f, %.4f) angle %.4f\n", world.time(), b.position().x(), b.position().y(), b.angle);
}

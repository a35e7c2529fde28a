// A world in C++ alone (rigidlab::core, no Lua): a box dropped on the ground, stepped for two
// seconds at 60 Hz, its height printed every half second. It comes to rest on the ground: its
// centre 0.5 m above it (half its 1 m side), to within the contact solver's slop.
#include <cstdio>

#include "rigidlab/world.h"

int main() {
  using namespace rigidlab;
  World world;  // gravity (0, -9.80665) m/s², RK4, the auto contact solver

  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = makeBox(20.0, 1.0);  // 20 m wide, 1 m thick, its top at y = 0
  ground.position = {0.0, -0.5};
  world.createBody(ground);

  BodyDef box;
  box.shape = makeBox(1.0, 1.0);
  box.position = {0.0, 4.0};
  box.angle = 0.3;
  box.density = 2.0;  // kg/m²
  const BodyId id = world.createBody(box);

  for (int step = 1; step <= 120; ++step) {
    world.step(1.0 / 60.0);
    if (step % 30 == 0) {
      const Body& b = world.body(id);
      std::printf("t = %.2f s  box at (%.3f, %.3f) m, angle %.3f rad\n", world.time(), b.position().x(),
                  b.position().y(), b.angle);
    }
  }
  const double y = world.body(id).position().y();
  return y > 0.45 && y < 0.55 ? 0 : 1;  // resting on the ground
}

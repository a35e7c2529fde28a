// Opens a saved scene file through the scene API double (scene_api_double.h) and prints what it
// built, one line: "bodies N joints M shapes S1 S2 ...". For build_test.sh, which checks a file
// the sandbox saved with shapes and joints before rigidlab's own bindings for them are merged.
#include <cstdio>
#include <exception>

#include "scene_api_double.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: open_saved FILE.lua\n");
    return 2;
  }
  try {
    const rigidlab::World w = rigidlab::sandbox_test::loadWithDouble(argv[1]);
    std::printf("bodies %d joints %zu shapes", w.bodyCount(), w.jointIds().size());
    for (const rigidlab::BodyId id : w.bodyIds()) std::printf(" %zu", w.body(id).shapes.size());
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "open_saved: %s\n", e.what());
    return 1;
  }
  return 0;
}

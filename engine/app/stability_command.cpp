// rigidlab stability: placeholder until the stability lab lands (issue 5). It says so and fails.
#include <cstdio>

#include "cli.h"
#include "commands.h"

namespace rigidlab::app {

int stabilityCommand(const std::vector<std::string>&) {
  std::fprintf(stderr, "rigidlab stability: not built yet in this version\n");
  return kExitSceneError;
}

}  // namespace rigidlab::app

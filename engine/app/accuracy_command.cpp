// rigidlab accuracy: placeholder until the accuracy lab lands (issue 5). It says so and fails.
#include <cstdio>

#include "cli.h"
#include "commands.h"

namespace rigidlab::app {

int accuracyCommand(const std::vector<std::string>&) {
  std::fprintf(stderr, "rigidlab accuracy: not built yet in this version\n");
  return kExitSceneError;
}

}  // namespace rigidlab::app

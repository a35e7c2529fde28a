// The version line (version.h).
#include "version.h"

namespace rigidlab::app {

std::string versionLine(const VersionInfo& info) {
  std::string line = std::string("rigidlab ") + info.version + " (" + info.build_type + " build";
  if (*info.commit) line += std::string(", commit ") + info.commit + (info.modified ? ", modified" : "");
  return line + ")";
}

}  // namespace rigidlab::app

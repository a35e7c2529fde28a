// The program's version (the CMake project's), its build type and the git commit it was built
// from; the record is written at build time (cmake/RigidlabVersion.cmake).
#pragma once

#include <string>

namespace rigidlab::app {

struct VersionInfo {
  const char* version;     // "0.2.0"
  const char* build_type;  // "Release", "Debug", ...
  const char* commit;      // 12 hex digits; "" when not built from a git checkout
  bool modified;           // the checkout had uncommitted changes to tracked files
};
extern const VersionInfo kVersion;

// `rigidlab --version`: "rigidlab 0.2.0 (Release build, commit 0123456789ab)", with
// ", modified" after the commit when the tree had changes, and no commit when it is unknown.
std::string versionLine(const VersionInfo& info = kVersion);

}  // namespace rigidlab::app

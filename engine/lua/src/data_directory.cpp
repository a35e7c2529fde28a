// Run-time file lookup (data_directory.h).
#include "rigidlab/lua/data_directory.h"

#include <cstdlib>
#include <system_error>

// Defined in a program that links the installed package: rigidlabConfig.cmake compiles it in
// (cmake/rigidlabConfig.cmake.in), returning that package's share/rigidlab. Weak, so that the
// rigidlab program and the build tree's test programs, which have none, link without it.
extern "C" __attribute__((weak)) const char* rigidlab_package_data_directory();

namespace rigidlab::lua {

std::filesystem::path dataDirectory(std::string_view name, const char* env_var) {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv(env_var); env && *env) return env;
  std::error_code ec;
  fs::path configured = fs::path(RIGIDLAB_INSTALL_DATADIR) / "rigidlab" / name;
  if (rigidlab_package_data_directory) {
    configured = fs::path(rigidlab_package_data_directory()) / name;
    if (fs::is_directory(configured, ec)) return configured;
  }
  const fs::path relative = fs::path("share") / "rigidlab" / name;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    fs::path dir = exe.parent_path();
    for (int up = 0; up <= 4 && !dir.empty(); ++up, dir = dir.parent_path()) {
      if (fs::is_directory(dir / relative, ec)) return dir / relative;
      if (dir == dir.root_path()) break;
    }
  }
  return configured;
}

}  // namespace rigidlab::lua

// Run-time file lookup (data_directory.h).
#include "rigidlab/lua/data_directory.h"

#include <cstdlib>
#include <system_error>

namespace rigidlab::lua {

std::filesystem::path dataDirectory(std::string_view name, const char* env_var) {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv(env_var); env && *env) return env;
  const fs::path relative = fs::path("share") / "rigidlab" / name;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    fs::path dir = exe.parent_path();
    for (int up = 0; up <= 4 && !dir.empty(); ++up, dir = dir.parent_path()) {
      if (fs::is_directory(dir / relative, ec)) return dir / relative;
      if (dir == dir.root_path()) break;
    }
  }
  return fs::path(RIGIDLAB_INSTALL_DATADIR) / "rigidlab" / name;
}

}  // namespace rigidlab::lua

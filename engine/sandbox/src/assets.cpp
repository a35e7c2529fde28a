// Run-time asset lookup (assets.h).
#include "assets.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace rigidlab::sandbox {

std::filesystem::path assetsDirectory() {
  if (const char* env = std::getenv("RIGIDLAB_ASSETS"); env && *env) return env;
  return RIGIDLAB_ASSETS_DIR;
}

std::optional<std::string> readTextFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rigidlab::sandbox

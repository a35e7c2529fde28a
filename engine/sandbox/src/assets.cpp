// Run-time asset lookup (assets.h).
#include "assets.h"

#include <fstream>
#include <sstream>

#include "rigidlab/lua/data_directory.h"

namespace rigidlab::sandbox {

std::filesystem::path assetsDirectory() { return lua::dataDirectory("assets", "RIGIDLAB_ASSETS"); }

std::optional<std::string> readTextFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rigidlab::sandbox

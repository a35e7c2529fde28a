#include "text_file.h"

#include <fstream>
#include <stdexcept>
#include <system_error>

#include "rigidlab/lua/bounded_file.h"

namespace rigidlab::app {

std::string readFile(const std::filesystem::path& file, size_t limit, const std::string& what) {
  return lua::readBoundedFile(file, limit, file.string(), what);
}

void writeFile(const std::filesystem::path& file, const std::string& text, Folders folders) {
  const std::filesystem::path parent = file.parent_path();
  std::error_code error;
  if (!parent.empty()) {
    if (folders == Folders::Make) {
      std::filesystem::create_directories(parent, error);
      if (error) throw std::runtime_error(parent.string() + ": " + error.message());
    } else if (!std::filesystem::is_directory(parent, error)) {
      throw std::runtime_error(file.string() + ": cannot write the file: the folder " + parent.string() +
                               " does not exist");
    }
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write the file");
}

}  // namespace rigidlab::app

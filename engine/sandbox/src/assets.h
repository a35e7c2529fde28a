// Finding the sandbox's run-time files (shaders): $RIGIDLAB_ASSETS if set, else the source tree's
// assets/ that this binary was built from (compile-time RIGIDLAB_ASSETS_DIR).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace rigidlab::sandbox {

std::filesystem::path assetsDirectory();
// The whole file, or nothing if it cannot be read.
std::optional<std::string> readTextFile(const std::filesystem::path& file);

}  // namespace rigidlab::sandbox

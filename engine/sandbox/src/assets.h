// Finding the sandbox's run-time files (shaders, font): $RIGIDLAB_ASSETS if set, else this
// installation's assets (rigidlab/lua/data_directory.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace rigidlab::sandbox {

std::filesystem::path assetsDirectory();
// The whole file, or nothing if it cannot be read.
std::optional<std::string> readTextFile(const std::filesystem::path& file);

}  // namespace rigidlab::sandbox

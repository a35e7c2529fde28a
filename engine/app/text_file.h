// Whole text files in and out, with errors that name the file.
#pragma once

#include <filesystem>
#include <string>

namespace rigidlab::app {

// Throws std::runtime_error("<file>: cannot read the file").
std::string readFile(const std::filesystem::path& file);
// Creates the parent folders; throws std::runtime_error("<file>: <reason>").
void writeFile(const std::filesystem::path& file, const std::string& text);

}  // namespace rigidlab::app

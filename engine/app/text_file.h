// Whole files in and out, with errors that name the file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace rigidlab::app {

// The whole file, if it holds at most `limit` bytes (checked before reading, and while reading:
// lua/bounded_file.h). Throws std::runtime_error("<file>: cannot read the file (<reason>)") or
// lua::FileTooLarge("<file>: the file is N bytes, more than the limit of M MiB for <what>").
std::string readFile(const std::filesystem::path& file, size_t limit, const std::string& what);

// Whether writeFile may make the file's missing parent folders: an output path the user gives
// must name a folder that exists (a typo must not make folders, at the root or elsewhere); the
// folders the program owns (golden/ beside a scene, --diff-dir, --junit's) are made.
enum class Folders { MustExist, Make };

// Throws std::runtime_error("<file>: <reason>").
void writeFile(const std::filesystem::path& file, const std::string& text, Folders folders = Folders::MustExist);

}  // namespace rigidlab::app

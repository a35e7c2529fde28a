// Finding rigidlab's run-time files (Lua scripts, the sandbox's shaders and font) wherever the
// program or library was built or installed, without a path compiled in from the build machine.
#pragma once

#include <filesystem>
#include <string_view>

namespace rigidlab::lua {

// The directory `name` ("scripts" or "assets") of this installation:
//   1. $<env_var> if it is set and not empty (a user's own copy);
//   2. in a program of a user's own built with find_package(rigidlab): share/rigidlab/<name> of
//      the package it was built against, wherever that was installed (the libraries are static and
//      cannot find themselves at run time, so the package config compiles its place into the
//      program);
//   3. share/rigidlab/<name> in the running executable's directory or one of its four parents:
//      an install puts the program in <prefix>/bin and the files in <prefix>/share/rigidlab; a
//      build tree links <build>/share/rigidlab to the sources, for the program in <build> and the
//      test programs in <build>/tests/...;
//   4. <install prefix>/share/rigidlab/<name>, the prefix this library was configured for.
// Returns the package's (2) or else the configured (4) place when none exists, so error messages
// name a concrete place.
std::filesystem::path dataDirectory(std::string_view name, const char* env_var);

}  // namespace rigidlab::lua

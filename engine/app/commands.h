// The subcommands of the rigidlab program, one file each.
#pragma once

#include <string>
#include <vector>

namespace rigidlab::app {

int runCommand(const std::vector<std::string>& args);    // run_command.cpp
int checkCommand(const std::vector<std::string>& args);  // run_command.cpp
int benchCommand(const std::vector<std::string>& args);  // bench_command.cpp
int accuracyCommand(const std::vector<std::string>& args);   // accuracy_command.cpp
int stabilityCommand(const std::vector<std::string>& args);  // stability_command.cpp
int testCommand(const std::vector<std::string>& args);       // test_command.cpp
// The headless stand-in for the sandbox: a few seconds of the scene and its summary.
int headlessPreview(const std::string& scene, const std::string& reason);  // run_command.cpp

}  // namespace rigidlab::app

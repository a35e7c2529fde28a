// Command-line parsing shared by the subcommands: --name value, --name=value, flags, positionals.
// Usage errors throw UsageError; main() prints them with a pointer to --help and exits with 2.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rigidlab::app {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The candidate `given` is probably a typo of (the Lua API's rule, lua/closest_name.h, with short
// names allowed one edit), or "": for "did you mean ...?".
std::string suggestion(std::string_view given, const std::vector<std::string>& candidates);

class Args {
 public:
  // `command` names the subcommand in messages ("run: unknown option --tmie (did you mean
  // --time?)"); empty for the program's own options. `valued`: options that take a value;
  // `flags`: options that do not.
  Args(std::string command, const std::vector<std::string>& argv, std::vector<std::string> valued,
       std::vector<std::string> flags);

  bool flag(const std::string& name) const;
  std::optional<std::string> value(const std::string& name) const;
  std::optional<double> number(const std::string& name) const;          // finite
  std::optional<long> integer(const std::string& name, long min) const;  // ≥ min
  const std::vector<std::string>& positional() const { return positional_; }
  bool help() const { return help_; }

 private:
  std::string command_;  // "run: ", or empty
  std::vector<std::pair<std::string, std::string>> values_;
  std::vector<std::string> flags_set_;
  std::vector<std::string> positional_;
  bool help_ = false;
};

// Exit codes of every subcommand.
inline constexpr int kExitOk = 0;
inline constexpr int kExitSceneError = 1;  // scene error, failed Check, failed gate
inline constexpr int kExitUsage = 2;
// rigidlab run: the run finished and Check passed (or there is none), but it blew up: the NaN
// firewall froze a body, or the energy became non-finite (unless scene.expect_incidents).
inline constexpr int kExitIncidents = 3;

}  // namespace rigidlab::app

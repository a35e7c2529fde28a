#include "cli.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "rigidlab/lua/closest_name.h"

namespace rigidlab::app {

std::string suggestion(std::string_view given, const std::vector<std::string>& candidates) {
  const std::vector<std::string_view> names(candidates.begin(), candidates.end());
  // Short words too: a command line's names are few, so a near one is worth naming.
  return lua::closestName(given, names, {.min_length = 2, .min_edits = 1});
}

Args::Args(std::string command, const std::vector<std::string>& argv, std::vector<std::string> valued,
           std::vector<std::string> flags)
    : command_(command.empty() ? "" : command + ": ") {
  const auto known = [](const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "--help" || a == "-h") {
      help_ = true;
      continue;
    }
    if (!a.starts_with("--") || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    const size_t eq = name.find('=');
    const bool has_inline = eq != std::string::npos;
    if (has_inline) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (known(valued, name)) {
      if (!has_inline) {
        if (i + 1 >= argv.size()) throw UsageError(command_ + "--" + name + " needs a value");
        value = argv[++i];
      }
      values_.emplace_back(name, value);
    } else if (known(flags, name)) {
      if (has_inline) throw UsageError(command_ + "--" + name + " takes no value");
      flags_set_.push_back(name);
    } else {
      std::vector<std::string> all = valued;
      all.insert(all.end(), flags.begin(), flags.end());
      all.push_back("help");
      const std::string hint = suggestion(name, all);
      throw UsageError(command_ + "unknown option --" + name + (hint.empty() ? "" : " (did you mean --" + hint + "?)"));
    }
  }
}

bool Args::flag(const std::string& name) const {
  return std::find(flags_set_.begin(), flags_set_.end(), name) != flags_set_.end();
}

std::optional<std::string> Args::value(const std::string& name) const {
  std::optional<std::string> found;
  for (const auto& [k, v] : values_)
    if (k == name) found = v;  // the last one wins
  return found;
}

std::optional<double> Args::number(const std::string& name) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(v->c_str(), &end);
  if (v->empty() || *end != '\0' || !std::isfinite(x))
    throw UsageError(command_ + "--" + name + " must be a number, got '" + *v + "'");
  return x;
}

std::optional<long> Args::integer(const std::string& name, long min) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  char* end = nullptr;
  const long x = std::strtol(v->c_str(), &end, 10);
  if (v->empty() || *end != '\0' || x < min)
    throw UsageError(command_ + "--" + name + " must be a whole number >= " + std::to_string(min) + ", got '" + *v + "'");
  return x;
}

}  // namespace rigidlab::app

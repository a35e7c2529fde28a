// JSON values for `rigidlab bench`, which reads its scenes' and the peer programs' output lines:
// parsed by nlohmann::json, held as this small tree, written compactly by dump().
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rigidlab::app {

struct JsonValue {
  enum class Type { Null, Bool, Number, String, Array, Object } type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<JsonValue> array;
  std::map<std::string, JsonValue> object;

  const JsonValue* get(const std::string& key) const;  // nullptr if absent or not an object
  std::optional<double> num(const std::string& key) const;
  std::optional<std::string> str(const std::string& key) const;
  std::string dump() const;  // compact JSON; numbers as %.6g (null when not finite)
};

// nullopt if `text` is not one valid JSON value.
std::optional<JsonValue> parseJson(const std::string& text);

}  // namespace rigidlab::app

#include "json_value.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "report.h"

namespace rigidlab::app {
namespace {

// nlohmann::json (Debian's nlohmann-json3-dev) parses; the bench code reads the small tree below.
JsonValue convert(const nlohmann::json& j) {
  JsonValue v;
  switch (j.type()) {
    case nlohmann::json::value_t::boolean:
      v.type = JsonValue::Type::Bool;
      v.boolean = j.get<bool>();
      break;
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float:
      v.type = JsonValue::Type::Number;
      v.number = j.get<double>();
      break;
    case nlohmann::json::value_t::string:
      v.type = JsonValue::Type::String;
      v.string = j.get<std::string>();
      break;
    case nlohmann::json::value_t::array:
      v.type = JsonValue::Type::Array;
      for (const auto& e : j) v.array.push_back(convert(e));
      break;
    case nlohmann::json::value_t::object:
      v.type = JsonValue::Type::Object;
      for (const auto& [key, e] : j.items()) v.object[key] = convert(e);
      break;
    default:  // null (and the binary and discarded kinds, which text never gives)
      break;
  }
  return v;
}

}  // namespace

const JsonValue* JsonValue::get(const std::string& key) const {
  if (type != Type::Object) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &it->second;
}

std::optional<double> JsonValue::num(const std::string& key) const {
  const JsonValue* v = get(key);
  if (!v || v->type != Type::Number) return std::nullopt;
  return v->number;
}

std::optional<std::string> JsonValue::str(const std::string& key) const {
  const JsonValue* v = get(key);
  if (!v || v->type != Type::String) return std::nullopt;
  return v->string;
}

std::string JsonValue::dump() const {
  switch (type) {
    case Type::Null: return "null";
    case Type::Bool: return boolean ? "true" : "false";
    case Type::Number: {
      char buf[64];
      std::snprintf(buf, sizeof buf, std::isfinite(number) ? "%.6g" : "null", number);
      return buf;
    }
    case Type::String: return jsonString(string);
    case Type::Array: {
      std::string s = "[";
      for (size_t i = 0; i < array.size(); ++i) s += (i ? ", " : "") + array[i].dump();
      return s + "]";
    }
    case Type::Object: {
      std::string s = "{";
      bool first = true;
      for (const auto& [k, v] : object) {
        s += (first ? "" : ", ") + jsonString(k) + ": " + v.dump();
        first = false;
      }
      return s + "}";
    }
  }
  return "null";
}

std::optional<JsonValue> parseJson(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return std::nullopt;
  return convert(j);
}

}  // namespace rigidlab::app

#include "json_value.h"

#include <cmath>
#include <cstdio>

#include "report.h"

#include <cctype>
#include <cstdlib>

namespace rigidlab::app {
namespace {

struct Parser {
  const std::string& s;
  size_t i = 0;
  void ws() {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  }
  bool lit(const char* word) {
    const std::string w(word);
    if (s.compare(i, w.size(), w) != 0) return false;
    i += w.size();
    return true;
  }
  bool str(std::string& out) {
    if (i >= s.size() || s[i] != '"') return false;
    for (++i; i < s.size() && s[i] != '"'; ++i) {
      if (s[i] == '\\' && i + 1 < s.size()) {
        const char e = s[++i];
        out += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
      } else {
        out += s[i];
      }
    }
    if (i >= s.size()) return false;
    ++i;
    return true;
  }
  bool value(JsonValue& v) {
    ws();
    if (i >= s.size()) return false;
    const char c = s[i];
    if (c == '{') {
      v.type = JsonValue::Type::Object;
      ++i;
      ws();
      if (i < s.size() && s[i] == '}') return ++i, true;
      for (;;) {
        ws();
        std::string key;
        if (!str(key)) return false;
        ws();
        if (i >= s.size() || s[i] != ':') return false;
        ++i;
        if (!value(v.object[key])) return false;
        ws();
        if (i < s.size() && s[i] == ',') {
          ++i;
          continue;
        }
        if (i < s.size() && s[i] == '}') return ++i, true;
        return false;
      }
    }
    if (c == '[') {
      v.type = JsonValue::Type::Array;
      ++i;
      ws();
      if (i < s.size() && s[i] == ']') return ++i, true;
      for (;;) {
        v.array.emplace_back();
        if (!value(v.array.back())) return false;
        ws();
        if (i < s.size() && s[i] == ',') {
          ++i;
          continue;
        }
        if (i < s.size() && s[i] == ']') return ++i, true;
        return false;
      }
    }
    if (c == '"') {
      v.type = JsonValue::Type::String;
      return str(v.string);
    }
    if (lit("true")) return v.type = JsonValue::Type::Bool, v.boolean = true, true;
    if (lit("false")) return v.type = JsonValue::Type::Bool, v.boolean = false, true;
    if (lit("null")) return v.type = JsonValue::Type::Null, true;
    char* end = nullptr;
    v.number = std::strtod(s.c_str() + i, &end);
    if (end == s.c_str() + i) return false;
    v.type = JsonValue::Type::Number;
    i = static_cast<size_t>(end - s.c_str());
    return true;
  }
};

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
  Parser p{text};
  JsonValue v;
  if (!p.value(v)) return std::nullopt;
  p.ws();
  if (p.i != text.size()) return std::nullopt;
  return v;
}

}  // namespace rigidlab::app

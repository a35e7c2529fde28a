// The editor annotations (scripts/meta/rigidlab.lua) must describe exactly the API the bindings
// implement: every field, method and option name, in both directions.
#include <doctest/doctest.h>

#include <fstream>
#include <map>
#include <cctype>
#include <set>
#include <string>

#include "api_names.h"
#include "rigidlab/lua/scene.h"

using namespace rigidlab::lua;

namespace {

// The identifier at the start of `s` (letters, digits, underscores).
std::string identifier(std::string_view s) {
  size_t n = 0;
  while (n < s.size() && (std::isalnum(static_cast<unsigned char>(s[n])) || s[n] == '_')) ++n;
  return std::string(s.substr(0, n));
}

// class name → the names its ---@field lines and `function Class:name(` definitions declare.
std::map<std::string, std::set<std::string>> annotated() {
  std::ifstream in(scriptsDirectory() / "meta" / "rigidlab.lua");
  REQUIRE(in);
  std::map<std::string, std::set<std::string>> classes;
  std::string current, line;
  while (std::getline(in, line)) {
    const std::string_view l(line);
    if (l.starts_with("---@class rigidlab.")) {
      current = identifier(l.substr(19));
      classes[current];
    } else if (l.starts_with("---@field ") && !current.empty()) {
      classes[current].insert(identifier(l.substr(10)));
    } else if (l.starts_with("function ") && l.find(':') != std::string_view::npos) {
      const size_t colon = l.find(':');
      classes[identifier(l.substr(9))].insert(identifier(l.substr(colon + 1)));
    } else if (!l.starts_with("---")) {
      current.clear();
    }
  }
  return classes;
}

std::set<std::string> names(std::initializer_list<const std::vector<std::string_view>*> lists) {
  std::set<std::string> out;
  for (const auto* list : lists)
    for (std::string_view n : *list) out.insert(std::string(n));
  return out;
}

}  // namespace

TEST_CASE("the editor annotations list exactly the API's names") {
  const auto classes = annotated();
  CHECK(classes.at("Body") == names({&api::kBodyReadable}));
  CHECK(classes.at("World") == names({&api::kWorldFields, &api::kWorldMethods}));
  CHECK(classes.at("BodyOptions") == names({&api::kBodyOptions}));
  CHECK(classes.at("BoxOptions") == std::set<std::string>{"width", "height"});
  CHECK(classes.at("CircleOptions") == std::set<std::string>{"radius"});
  CHECK(classes.at("PolygonOptions") == std::set<std::string>{"vertices"});
  CHECK(classes.at("SpringOptions") == names({&api::kSpringOptions}));
  CHECK(classes.at("DamperOptions") == names({&api::kDamperOptions}));
  CHECK(classes.at("ForceOptions") == names({&api::kForceOptions}));
  CHECK(classes.at("SceneSettings") == names({&api::kSceneOptions}));
  CHECK(classes.at("Draw") == std::set<std::string>{"line", "circle", "text"});
  CHECK(classes.at("ExactState") == std::set<std::string>{"position", "velocity", "angle", "angular_velocity"});
  CHECK(classes.at("BodyState") ==
        std::set<std::string>{"position", "velocity", "center", "angle", "angular_velocity", "mass", "inertia", "time"});
}

// The editor annotations (scripts/meta/rigidlab.lua) must describe exactly the API the bindings
// implement: every field, method and option name, in both directions.
#include <doctest/doctest.h>

#include <algorithm>
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
// `writable` gets the fields whose comment says "(read/write)".
std::map<std::string, std::set<std::string>> annotated(std::map<std::string, std::set<std::string>>* writable = nullptr) {
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
      if (writable && l.ends_with("(read/write)")) (*writable)[current].insert(identifier(l.substr(10)));
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
  CHECK(classes.at("Shape") == names({&api::kShapeReadable}));
  CHECK(classes.at("World") == names({&api::kWorldFields, &api::kWorldMethods, &api::kWorldModFields}));
  CHECK(classes.at("BodyOptions") == names({&api::kBodyOptions}));
  CHECK(classes.at("ShapeOptions") == names({&api::kShapeOptions}));
  CHECK(classes.at("ShapedBodyOptions") == names({&api::kShapedBodyOptions}));
  CHECK(classes.at("BoxOptions") == names({&api::kBoxOptions}));
  CHECK(classes.at("CircleOptions") == names({&api::kCircleOptions}));
  CHECK(classes.at("PolygonOptions") == names({&api::kPolygonOptions}));
  CHECK(classes.at("CapsuleOptions") == names({&api::kCapsuleOptions}));
  CHECK(classes.at("SegmentOptions") == names({&api::kSegmentOptions}));
  CHECK(classes.at("ChainOptions") == names({&api::kChainOptions}));
  CHECK(classes.at("AddShapeOptions") == names({&api::kAddShapeOptions}));
  CHECK(classes.at("TargetOptions") == names({&api::kTargetOptions}));
  CHECK(classes.at("SpringOptions") == names({&api::kSpringOptions}));
  CHECK(classes.at("DamperOptions") == names({&api::kDamperOptions}));
  CHECK(classes.at("ForceOptions") == names({&api::kForceOptions}));
  CHECK(classes.at("SceneSettings") == names({&api::kSceneOptions, &api::kSceneModOptions}));
  CHECK(classes.at("JointOptions") == names({&api::kJointOptions}));
  CHECK(classes.at("RevoluteOptions") == names({&api::kRevoluteOptions}));
  CHECK(classes.at("PrismaticOptions") == names({&api::kPrismaticOptions}));
  CHECK(classes.at("DistanceOptions") == names({&api::kDistanceOptions}));
  CHECK(classes.at("WeldOptions") == names({&api::kWeldOptions}));
  CHECK(classes.at("WheelOptions") == names({&api::kWheelOptions}));
  CHECK(classes.at("MotorJointOptions") == names({&api::kMotorJointOptions}));
  CHECK(classes.at("FrictionJointOptions") == names({&api::kFrictionJointOptions}));
  CHECK(classes.at("PulleyOptions") == names({&api::kPulleyOptions}));
  CHECK(classes.at("GearOptions") == names({&api::kGearOptions}));
  CHECK(classes.at("Draw") == names({&api::kDrawFunctions}));
  CHECK(classes.at("Snapshot") == names({&api::kSnapshotFields}));
  CHECK(classes.at("MouseEvent") == names({&api::kMouseEventFields}));
  CHECK(classes.at("ControlOptions") == names({&api::kControlOptions}));
  CHECK(classes.at("ExactState") == std::set<std::string>{"position", "velocity", "angle", "angular_velocity"});
  CHECK(classes.at("BodyState") ==
        std::set<std::string>{"position", "velocity", "center", "angle", "angular_velocity", "mass", "inertia", "time"});

  // A joint handle: the common fields and every kind's own.
  std::set<std::string> joint = names({&api::kJointReadable});
  for (const auto* options : api::kJointKindOptions)
    for (std::string_view n : api::jointOwnFields(*options)) joint.insert(std::string(n));
  CHECK(classes.at("Joint") == joint);
}

TEST_CASE("the editor annotations mark exactly the writable fields (read/write)") {
  std::map<std::string, std::set<std::string>> writable;
  annotated(&writable);
  CHECK(writable.at("Body") == names({&api::kBodyWritable}));
  CHECK(writable.at("Shape") == names({&api::kShapeWritable}));
  std::set<std::string> joint = names({&api::kJointWritable});
  for (const auto* options : api::kJointKindOptions)
    for (std::string_view n : api::jointOwnFields(*options))
      if (std::find(api::kJointReadOnly.begin(), api::kJointReadOnly.end(), n) == api::kJointReadOnly.end())
        joint.insert(std::string(n));
  CHECK(writable.at("Joint") == joint);
}

// A scene's sandbox controls and keys: `scene.controls` (sliders and buttons of the sandbox's
// Controls panel), `scene.keys` (keys the scene takes from the sandbox's bindings), and
// `world.controls`, through which the scene reads and sets its sliders.
//   scene.controls = {{name = "wind", min = 0, max = 20, value = 5}, {name = "reset", kind = "button"}}
//   world.controls.wind          -- 5 headless (the default); what the slider says in the sandbox
//   world.controls.wind = 2      -- sets the slider (within its range)
// A button has no value: OnControl(world, name) is called when it is pressed (and when a slider
// was moved), between steps, so the world may be edited there.
#include <algorithm>
#include <cctype>

#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"

namespace rigidlab::lua {
namespace {

using Control = SceneSettings::Control;

constexpr size_t kMaxControls = 64;
constexpr size_t kMaxKeys = 64;
constexpr size_t kControlNameBytes = 64;
constexpr size_t kKeyNameBytes = 32;

// The elements 1..n of the list scene.<field> (read raw); fails "scene: <field> must be a list ..."
// otherwise.
std::vector<sol::object> listOf(lua_State* L, const std::string& field, const sol::object& v, size_t max,
                                std::string_view example) {
  if (v.get_type() != sol::type::table)
    fail(L, "scene", field + " must be a list, e.g. " + std::string(example) + ", got " + describe(v));
  v.push(L);
  const size_t n = lua_rawlen(L, -1);
  lua_pop(L, 1);
  if (n > max) fail(L, "scene", field + " has " + std::to_string(n) + " entries, at most " + std::to_string(max) + " are allowed");
  const sol::table t = v.as<sol::table>();
  std::vector<sol::object> items;
  for (size_t i = 1; i <= n; ++i) items.push_back(t.raw_get<sol::object>(i));
  return items;
}

bool isIdentifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

Control readControl(lua_State* L, const std::string& what, const sol::object& item) {
  const Options o(L, what, item, api::kControlOptions);
  Control c;
  c.name = o.string("name", std::nullopt, kControlNameBytes);
  if (!isIdentifier(c.name))
    o.fail("name", "must be a name of letters, digits and underscores (world.controls.<name>), got " + describe(o.get("name")));
  c.kind = o.choice("kind", api::kControlKinds, "slider") == "button" ? Control::Kind::Button : Control::Kind::Slider;
  if (c.kind == Control::Kind::Button) {
    for (const char* field : {"min", "max", "value"})
      if (o.has(field)) o.fail(field, "is for sliders; a button has none, got " + describe(o.get(field)));
    return c;
  }
  c.min = o.number("min");
  c.max = o.number("max");
  if (!(c.max > c.min)) o.fail("max", "must be greater than min (" + formatNumber(c.min) + "), got " + formatNumber(c.max));
  c.value = o.number("value", c.min);
  if (c.value < c.min || c.value > c.max)
    o.fail("value", "must be between min and max (" + formatNumber(c.min) + " and " + formatNumber(c.max) + "), got " +
                        formatNumber(c.value));
  return c;
}

// OnKey's names: lower case, as SDL names keys ("space", "a", "f1", "left shift").
std::string readKey(lua_State* L, const std::string& what, const sol::object& item) {
  const bool string = item.get_type() == sol::type::string;
  const std::string key = string ? item.as<std::string>() : std::string();
  const bool ok = string && !key.empty() && key.size() <= kKeyNameBytes &&
                  std::none_of(key.begin(), key.end(), [](char c) {
                    return std::isupper(static_cast<unsigned char>(c)) || std::iscntrl(static_cast<unsigned char>(c));
                  });
  if (!ok)
    fail(L, "scene", what + " must be a key name in lower case as OnKey receives it (\"space\", \"a\", \"f1\"), got " +
                         describe(item));
  return key;
}

int controlIndex(const Scene::Impl& s, std::string_view name) {
  for (size_t i = 0; i < s.settings.controls.size(); ++i)
    if (s.settings.controls[i].name == name) return static_cast<int>(i);
  return -1;
}

struct LuaControls {
  static constexpr const char* kMetatable = "rigidlab.controls";
  Scene::Impl* scene;
};

// The slider `world.controls.<key>` names; fails for a button or an unknown name.
size_t slider(lua_State* L, const Scene::Impl& s, const std::string& key) {
  const int i = controlIndex(s, key);
  if (i < 0) {
    std::vector<std::string_view> names;
    for (const Control& c : s.settings.controls) names.push_back(c.name);
    const std::string hint = closestName(key, names);
    fail(L, "world.controls", "has no control '" + key + "'" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)") +
                                  (names.empty() ? "; the scene table declares them: scene.controls = {{name = ...}}" : ""));
  }
  if (s.settings.controls[i].kind == Control::Kind::Button)
    fail(L, "world.controls." + key, "is a button, it has no value (OnControl(world, name) is called when it is pressed)");
  return static_cast<size_t>(i);
}

int controlsIndex(lua_State* L) {
  const LuaControls* c = toHandle<LuaControls>(L, 1);
  const std::string key = fieldName(L, "world.controls", sol::object(sol::stack_object(L, 2)));
  lua_pushnumber(L, c->scene->control_values[slider(L, *c->scene, key)]);
  return 1;
}

int controlsNewIndex(lua_State* L) {
  const LuaControls* c = toHandle<LuaControls>(L, 1);
  Scene::Impl& s = *c->scene;
  const std::string key = fieldName(L, "world.controls", sol::object(sol::stack_object(L, 2)));
  const size_t i = slider(L, s, key);
  const Control& control = s.settings.controls[i];
  const double v = checkNumber(L, "world.controls." + key, "", sol::object(sol::stack_object(L, 3)), Range::Finite);
  if (v < control.min || v > control.max)
    fail(L, "world.controls." + key, "must be between " + formatNumber(control.min) + " and " + formatNumber(control.max) +
                                         ", got " + formatNumber(v));
  s.control_values[i] = v;
  return 0;
}

int controlsToString(lua_State* L) {
  lua_pushliteral(L, "world.controls");
  return 1;
}

}  // namespace

void readModSettings(const Options& o, SceneSettings& settings) {
  lua_State* L = o.L();
  if (o.has("keys")) {
    const auto items = listOf(L, "keys", o.get("keys"), kMaxKeys, "{\"space\", \"a\"}");
    for (size_t i = 0; i < items.size(); ++i) settings.keys.push_back(readKey(L, "keys[" + std::to_string(i + 1) + "]", items[i]));
  }
  if (o.has("controls")) {
    const auto items = listOf(L, "controls", o.get("controls"), kMaxControls,
                              "{{name = \"wind\", min = 0, max = 20, value = 5}}");
    for (size_t i = 0; i < items.size(); ++i) {
      const std::string what = "scene.controls[" + std::to_string(i + 1) + "]";
      Control c = readControl(L, what, items[i]);
      for (const Control& earlier : settings.controls)
        if (earlier.name == c.name) fail(L, what, "name '" + c.name + "' is used by an earlier control");
      settings.controls.push_back(std::move(c));
    }
  }
}

std::vector<double> initialControlValues(const SceneSettings& settings, const std::map<std::string, double>& given) {
  std::vector<double> values;
  for (const Control& c : settings.controls) {
    double v = c.kind == Control::Kind::Button ? 0.0 : c.value;
    const auto it = given.find(c.name);
    if (c.kind == Control::Kind::Slider && it != given.end() && std::isfinite(it->second))
      v = std::clamp(it->second, c.min, c.max);
    values.push_back(v);
  }
  return values;
}

void registerControlsType(lua_State* L) {
  registerHandleType(L, LuaControls::kMetatable, guarded<controlsIndex>, guarded<controlsNewIndex>,
                     guarded<controlsToString>, nullptr);
}

void pushControls(lua_State* L, Scene::Impl& scene) { pushHandle(L, LuaControls{&scene}); }

// --- the C++ side (Scene)

double Scene::controlValue(size_t i) const { return i < impl_->control_values.size() ? impl_->control_values[i] : 0.0; }

void Scene::setControlValue(size_t i, double value) {
  const auto& controls = impl_->settings.controls;
  if (i >= controls.size() || controls[i].kind != Control::Kind::Slider || !std::isfinite(value)) return;
  impl_->control_values[i] = std::clamp(value, controls[i].min, controls[i].max);
}

std::map<std::string, double> Scene::controlValues() const {
  std::map<std::string, double> values;
  for (size_t i = 0; i < impl_->settings.controls.size(); ++i)
    if (impl_->settings.controls[i].kind == Control::Kind::Slider) values[impl_->settings.controls[i].name] = impl_->control_values[i];
  return values;
}

}  // namespace rigidlab::lua

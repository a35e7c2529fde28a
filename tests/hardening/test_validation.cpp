// Input validation as a property (reliability.md test plan V1, V2, S4): every option of every
// add_* function, of the `scene` table and every writable body field, given each value of a pool
// of bad (and good) values, either loads — when an oracle written separately from the loader says
// the value is valid — or fails with exactly one SceneError that names the function and the field.
// Never a crash, never a sol2 or C++ exception text. Misspelt option names are refused with the
// closest valid name suggested.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "api_names.h"
#include "util.h"

using namespace hardening;
using namespace rigidlab;

namespace {

// What an option accepts (the oracle).
enum class Accepts { Positive, NonNegative, Finite, Unit, Vector, Boolean, String, Body, OtherBody, Function, Integrator,
                     Iterations, MemoryMiB, Camera };

// A Lua value of the pool, with what the oracle needs to know about it.
struct Value {
  const char* lua;
  enum Type { Number, Integer, Text, Bool, Table, Func, BodyHandle } type;
  double x = 0;           // numbers
  bool vector = false;    // a table that is a finite {x, y} / {x = , y = } / vec2
  const char* text = "";  // strings
};

const double kNaN = std::nan("");
const double kInf = INFINITY;

const Value kPool[] = {
    {"0/0", Value::Number, kNaN},
    {"1/0", Value::Number, kInf},
    {"-1/0", Value::Number, -kInf},
    {"-1", Value::Integer, -1},
    {"0", Value::Integer, 0},
    {"-0.0", Value::Number, -0.0},
    {"1e-300", Value::Number, 1e-300},
    {"0.5", Value::Number, 0.5},
    {"1.5", Value::Number, 1.5},
    {"2", Value::Integer, 2},
    {"3", Value::Integer, 3},
    {"10001", Value::Integer, 10001},
    {"1e308", Value::Number, 1e308},
    {"2^53 + 1", Value::Number, 9007199254740992.0},
    {"math.maxinteger", Value::Integer, 9.2233720368547758e18},
    {"math.mininteger", Value::Integer, -9.2233720368547758e18},
    {"-1e-7", Value::Number, -1e-7},
    {"'1'", Value::Text, 0, false, "1"},
    {"'nan'", Value::Text, 0, false, "nan"},
    {"'rk4'", Value::Text, 0, false, "rk4"},
    {"'rk5'", Value::Text, 0, false, "rk5"},
    {"('x'):rep(100000)", Value::Text, 0, false, "x..."},
    {"true", Value::Bool},
    {"false", Value::Bool},
    {"{}", Value::Table},
    {"{1}", Value::Table},
    {"{1, 2}", Value::Table, 0, true},
    {"{1, 2, 3}", Value::Table},
    {"{x = 1}", Value::Table},
    {"{x = 1, y = -2}", Value::Table, 0, true},
    {"{0/0, 1}", Value::Table},
    {"{1, 1/0}", Value::Table},
    {"{x = 1, y = 0/0}", Value::Table},
    {"{'1', '2'}", Value::Table},
    {"vec2(1, 2)", Value::Table, 0, true},
    {"setmetatable({}, {__index = function() error('metamethod ran') end})", Value::Table},
    {"setmetatable({1, 2}, {__len = function() error('metamethod ran') end})", Value::Table, 0, true},
    {"function() return 0, 0 end", Value::Func},
    {"other", Value::BodyHandle},
    {"nil_body", Value::BodyHandle},  // the first body (for `other` this is the same body: invalid)
};

bool finiteNumber(const Value& v) { return (v.type == Value::Number || v.type == Value::Integer) && std::isfinite(v.x); }

bool valid(Accepts a, const Value& v) {
  switch (a) {
    case Accepts::Positive: return finiteNumber(v) && v.x > 0;
    case Accepts::NonNegative: return finiteNumber(v) && v.x >= 0;
    case Accepts::Finite: return finiteNumber(v);
    case Accepts::Unit: return finiteNumber(v) && v.x >= 0 && v.x <= 1;
    case Accepts::Vector: return v.type == Value::Table && v.vector;
    case Accepts::Boolean: return v.type == Value::Bool;
    case Accepts::String: return v.type == Value::Text && std::string(v.text) != "x...";  // names, titles: ≤ 256 bytes
    case Accepts::Body: return v.type == Value::BodyHandle;
    case Accepts::OtherBody: return v.type == Value::BodyHandle && std::string(v.lua) == "other";
    case Accepts::Function: return v.type == Value::Func;
    case Accepts::Integrator: return v.type == Value::Text && std::string(v.text) == "rk4";
    case Accepts::Iterations: return finiteNumber(v) && v.x == std::floor(v.x) && v.x >= 1 && v.x <= 10000;
    case Accepts::MemoryMiB: return finiteNumber(v) && v.x >= 1 && v.x <= 256;
    case Accepts::Camera: return false;  // tables of options: only {} or {center =, height =} would do
  }
  return false;
}

struct Option {
  const char* name;
  Accepts accepts;
};

// `call` builds the scene with $ replaced by "<name> = <value>" (the option under test).
struct Function {
  const char* name;     // as messages name it
  const char* call;     // Lua, inside PopulateWorld; `nil_body` and `other` are bodies
  std::vector<Option> options;
};

const std::vector<Option> kBodyOptions = {
    {"position", Accepts::Vector}, {"angle", Accepts::Finite}, {"velocity", Accepts::Vector},
    {"angular_velocity", Accepts::Finite}, {"mass", Accepts::Positive}, {"restitution", Accepts::Unit},
    {"friction", Accepts::NonNegative}, {"static_friction", Accepts::NonNegative}, {"static", Accepts::Boolean},
    {"name", Accepts::String}};

std::vector<Option> plus(std::vector<Option> a, std::vector<Option> b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const Function kFunctions[] = {
    {"add_box", "world:add_box{ width = 1, height = 1, $ }", plus(kBodyOptions, {{"width", Accepts::Positive}, {"height", Accepts::Positive}})},
    {"add_box", "world:add_box{ width = 1, height = 1, $ }", {{"density", Accepts::Positive}}},
    {"add_circle", "world:add_circle{ radius = 1, $ }", plus(kBodyOptions, {{"radius", Accepts::Positive}})},
    {"add_polygon", "world:add_polygon{ vertices = {{0, 0}, {1, 0}, {0, 1}}, $ }", kBodyOptions},
    {"add_spring", "world:add_spring{ a = nil_body, anchor = {0, 5}, stiffness = 1, $ }",
     {{"a", Accepts::Body}, {"local_a", Accepts::Vector}, {"stiffness", Accepts::NonNegative},
      {"rest_length", Accepts::NonNegative}, {"damping", Accepts::NonNegative}, {"anchor", Accepts::Vector}}},
    {"add_spring", "world:add_spring{ a = nil_body, stiffness = 1, $ }", {{"b", Accepts::OtherBody}}},
    {"add_spring", "world:add_spring{ a = nil_body, b = other, stiffness = 1, $ }", {{"local_b", Accepts::Vector}}},
    {"add_damper", "world:add_damper{ body = nil_body, coefficient = 1, $ }",
     {{"body", Accepts::Body}, {"coefficient", Accepts::NonNegative}, {"angular_coefficient", Accepts::NonNegative}}},
    {"add_force", "world:add_force{ body = nil_body, evaluate = function(s) return 0, 0 end, $ }",
     {{"body", Accepts::Body}, {"duration", Accepts::Positive}, {"point", Accepts::Vector}, {"other", Accepts::OtherBody}}},
    {"add_force", "world:add_force{ body = nil_body, $ }", {{"evaluate", Accepts::Function}}},
};

// A repeated key in a table constructor: the later value wins, so "$" can override a base option.
std::string scene(const std::string& call_line) {
  return "function PopulateWorld(world)\n"
         "  local nil_body = world:add_circle{ radius = 0.5, name = 'first' }\n"
         "  local other = world:add_circle{ radius = 0.5, position = {3, 0} }\n"
         "  " + call_line + "\nend";
}

std::string replace(std::string text, const std::string& what) {
  text.replace(text.find('$'), 1, what);
  return text;
}

// No text of the binding machinery or of C++ may reach the user.
bool clean(const std::string& m) {
  for (const char* bad : {"sol:", "stack index", "expected userdata", "std::", "basic_string", "bad_alloc", "what()",
                          "lua_", "metamethod ran", "nullptr", "terminate", "unknown error"})
    if (m.find(bad) != std::string::npos) return false;
  return m.find('\n') == std::string::npos;
}

std::string messageOf(const std::string& source, int steps = 0) {
  try {
    auto s = load(source);
    for (int i = 0; i < steps; ++i) s->step();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("validation: every option of every add_* function, given every pool value: loads iff valid, else names the field") {
  int accepted = 0, refused = 0;
  for (const Function& f : kFunctions) {
    for (const Option& o : f.options) {
      for (const Value& v : kPool) {
        const std::string source = scene(replace(f.call, std::string(o.name) + " = " + v.lua));
        CAPTURE(source);
        const std::string m = messageOf(source, 2);
        const std::string name = o.name;
        const bool size_or_mass = name == "width" || name == "height" || name == "radius" || name == "mass" ||
                                  name == "density";
        const bool side = name == "width" || name == "height";
        const bool extreme_size = size_or_mass && finiteNumber(v) && (side || v.x > 0.0) && (v.x < 1e-6 || v.x > 1e6);
        if (extreme_size) {
          // A box the core cannot represent (width/height beyond 1e8 : 1) is refused naming a side;
          // a body whose mass or inertia (or their inverses) would not be finite (radius 1e-300,
          // mass 1e308 on a small triangle) naming its mass.
          CHECK((m == "" || (m.starts_with("test.lua:4: " + std::string(f.name) + ": ") && clean(m) &&
                             (m.find("width") != std::string::npos || m.find("height") != std::string::npos ||
                              m.find(": mass and moment of inertia must be finite") != std::string::npos))));
        } else if (valid(o.accepts, v)) {
          CHECK(m == "");
          ++accepted;
        } else {
          // "test.lua:4: add_box: width must be > 0, got -1"
          CHECK(m.starts_with("test.lua:4: " + std::string(f.name) + ": " + o.name + " "));
          CHECK(clean(m));
          ++refused;
        }
      }
    }
  }
  MESSAGE(accepted << " valid values accepted, " << refused << " invalid values refused with the field named");
  CHECK(refused > 500);
}

TEST_CASE("validation: the scene table's settings, the same way") {
  const Option options[] = {{"dt", Accepts::Positive}, {"duration", Accepts::NonNegative}, {"gravity", Accepts::Vector},
                            {"title", Accepts::String}, {"integrator", Accepts::Integrator},
                            {"iterations", Accepts::Iterations}, {"memory_limit", Accepts::MemoryMiB}};
  for (const Option& o : options) {
    for (const Value& v : kPool) {
      if (v.type == Value::BodyHandle) continue;  // no bodies exist yet
      const std::string source = std::string("scene = { ") + o.name + " = " + v.lua + " }\nfunction PopulateWorld(world) end";
      CAPTURE(source);
      const std::string m = messageOf(source);
      if (valid(o.accepts, v)) {
        CHECK(m == "");
      } else {
        CHECK(m.starts_with(std::string("test.lua:1: scene: ") + o.name + " "));
        CHECK(clean(m));
      }
    }
  }
  for (const Value& v : kPool) {
    if (v.type == Value::BodyHandle) continue;
    for (const char* field : {"center", "height"}) {
      const std::string source =
          std::string("scene = { camera = { ") + field + " = " + v.lua + " } }\nfunction PopulateWorld(world) end";
      CAPTURE(source);
      const std::string m = messageOf(source);
      const bool ok = std::string(field) == "center" ? valid(Accepts::Vector, v) : valid(Accepts::Positive, v);
      if (ok) {
        CHECK(m == "");
      } else {
        CHECK(m.starts_with(std::string("test.lua:1: scene.camera: ") + field + " "));
        CHECK(clean(m));
      }
    }
  }
}

TEST_CASE("validation: writes to every writable body field, the same way") {
  const Option fields[] = {{"position", Accepts::Vector}, {"angle", Accepts::Finite}, {"velocity", Accepts::Vector},
                           {"angular_velocity", Accepts::Finite}, {"mass", Accepts::Positive},
                           {"static", Accepts::Boolean}, {"name", Accepts::String}, {"restitution", Accepts::Unit},
                           {"friction", Accepts::NonNegative}, {"static_friction", Accepts::NonNegative}};
  for (const Option& o : fields) {
    for (const Value& v : kPool) {
      const std::string source = scene(std::string("nil_body.") + o.name + " = " + v.lua);
      CAPTURE(source);
      const std::string m = messageOf(source, 1);
      if (valid(o.accepts, v)) {
        CHECK(m == "");
      } else {
        CHECK(m.starts_with(std::string("test.lua:4: body.") + o.name + ": "));
        CHECK(clean(m));
      }
    }
  }
}

TEST_CASE("validation: polygons: degenerate, too many points, NaN, concave, huge: refused by name or simulated finite") {
  const char* cases[] = {
      "{}", "{{0, 0}}", "{{0, 0}, {1, 0}}", "{{0, 0}, {1, 1}, {2, 2}}", "{{0, 0}, {10, 10}, {5, 5}, {3, 3}}",
      "{{0, 0}, {0, 0}, {0, 0}}", "{{0, 0}, {1, 0}, {0/0, 1}}", "{{0, 0}, {1, 0}, {1, 1/0}}",
      "{{0, 0}, {1, 0}, {1, 1}, {0.5, 0.2}, {0, 1}}", "{{0, 0}, {1, 1}, {1, 0}, {0, 1}}",
      "{{0, 0}, {1e-9, 0}, {0, 1e-9}}", "{{0, 0}, {1e300, 0}, {0, 1e300}}", "{{0, 0}, {1e154, 0}, {0, 1e154}}",
      "{{0, 0}, {0, 1}, {1, 0}}",  // clockwise: reversed, valid
      "(function() local t = {} for i = 1, 33 do local a = 2 * math.pi * i / 33 t[i] = {math.cos(a), math.sin(a)} end return t end)()",
      "(function() local t = {} for i = 1, 32 do local a = 2 * math.pi * i / 32 t[i] = {math.cos(a), math.sin(a)} end return t end)()",
      "{{0, 0}, {1, 0}, {0, 1}, 'x'}", "{{0, 0}, {1, 0}, {0, 1}, nil, {2, 2}}", "5", "'square'",
      "{{0, 0}, {1, 0}, {1 + 1e-15, 1e-15}, {0, 1}}",
  };
  for (const char* vertices : cases) {
    const std::string source = scene(std::string("world:add_polygon{ vertices = ") + vertices + ", position = {0, 3} }");
    CAPTURE(source);
    const std::string m = messageOf(source);
    if (m.empty()) {
      // Accepted: it must simulate with finite state and positive mass.
      auto s = load(source);
      for (int i = 0; i < 60; ++i) s->step();
      for (BodyId id : s->world().bodyIds()) {
        const Body& b = s->world().body(id);
        CHECK(std::isfinite(b.mass));
        CHECK(b.mass > 0);
        CHECK(isFinite(b.center));
        CHECK(isFinite(b.velocity));
      }
    } else {
      CHECK(m.starts_with("test.lua:4: add_polygon: "));
      CHECK(clean(m));
    }
  }
}

TEST_CASE("validation: misspelt option names are refused, suggesting the closest valid name") {
  std::mt19937 rng(7);
  const std::pair<const char*, std::vector<std::string_view>> functions[] = {
      {"world:add_box{ width = 1, height = 1, $ = 1 }", lua::api::kBodyOptions},
      {"world:add_spring{ a = nil_body, anchor = {0, 1}, stiffness = 1, $ = 1 }", lua::api::kSpringOptions},
      {"world:add_damper{ body = nil_body, coefficient = 1, $ = 1 }", lua::api::kDamperOptions},
      {"world:add_force{ body = nil_body, evaluate = function() return 0, 0 end, $ = 1 }", lua::api::kForceOptions},
  };
  int n = 0;
  for (const auto& [call, names] : functions) {
    for (std::string_view name : names) {
      for (int k = 0; k < 3; ++k) {
        std::string typo(name);
        const size_t i = rng() % typo.size();
        switch (k) {
          case 0: typo.erase(i, 1); break;                              // deletion
          case 1: typo.insert(i, 1, 'x'); break;                        // insertion
          default: if (i + 1 < typo.size()) std::swap(typo[i], typo[i + 1]); else typo += 'e'; break;  // transposition
        }
        if (typo.empty() || std::find(names.begin(), names.end(), typo) != names.end()) continue;
        const std::string source = scene(replace(call, typo));
        CAPTURE(source);
        const std::string m = messageOf(source);
        // Names of 5 letters or more are suggested whatever the slip; for shorter ones one letter is
        // a fifth of the name or more, so no suggestion is owed (lua_args.h closestName).
        CHECK(contains(m, "unknown option '" + typo + "'" + (name.size() >= 5 ? " (did you mean '" : "")));
        CHECK(clean(m));
        n += name.size() >= 5;
      }
    }
  }
  MESSAGE(n << " misspellings refused with a suggestion");
}

TEST_CASE("validation: tables with hostile metatables are read raw: no metamethod runs inside the host") {
  // __index/__len/__pairs that error would surface as "metamethod ran" if the host used them.
  const char* sources[] = {
      "scene = setmetatable({}, {__index = function() error('metamethod ran') end})\nfunction PopulateWorld(world) end",
      "function PopulateWorld(world)\n  world:add_circle(setmetatable({}, {__index = function() error('metamethod ran') end}))\nend",
      "function PopulateWorld(world)\n  world:add_circle(setmetatable({radius = 1}, {__pairs = function() error('metamethod ran') end}))\nend",
      "function PopulateWorld(world) world:add_circle{ radius = 1, name = 'b' } end\n"
      "function Exact(t) return setmetatable({}, {__index = function() error('metamethod ran') end}) end",
      "function PopulateWorld(world) world:add_circle{ radius = 1, name = 'b' } end\n"
      "function Exact(t) return { b = setmetatable({position = {0, 0}}, {__index = function() error('metamethod ran') end}) } end",
  };
  for (const char* text : sources) {
    const std::string source = text;
    CAPTURE(source);
    std::string m;
    try {
      auto s = load(source);
      s->exact(0.0);
    } catch (const SceneError& e) {
      m = e.what();
    }
    CAPTURE(m);
    CHECK(clean(m));
  }
}

TEST_CASE("validation: add_box with an extreme width names width, not vertices") {
  const std::string m = messageOf(scene("world:add_box{ width = 1e-300, height = 1 }"));
  MESSAGE(m);
  CHECK(m.starts_with("test.lua:4: add_box: width "));
}

TEST_CASE("validation: add_polygon reads vertices without running __len") {
  const std::string m = messageOf(scene(
      "world:add_polygon{ vertices = setmetatable({{0,0},{1,0},{0,1}}, {__len = function() error('metamethod ran') end}) }"));
  MESSAGE(m);
  CHECK(clean(m));
}

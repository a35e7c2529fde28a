// Input validation as a property (docs/design/reliability.md test plan V1, V2, S4): every option of every
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
                     Iterations, MemoryMiB, Camera,
                     PositiveOrInfinity, NonNegativeOrInfinity,  // math.huge too (break_force, max_length)
                     NonZero,     // finite and not 0 (a gear's ratio)
                     Zero,        // 0 only (a static body's angular velocity)
                     True,        // true only (static = true where the body must be static)
                     BodyType,    // "static" or "kinematic" ("dynamic" is not in the pool)
                     StaticType,  // "static" only (a chain's body)
                     Bits,        // any integer, or a float with a whole value in [-2^63, 2^64) (category, mask)
                     Int32,       // a whole number in [-2^31, 2^31) (group)
                     Any,         // every value (user_data)
                     Never };     // nothing in the pool (mass of a segment, a joint from a body, ...)

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
    {"'static'", Value::Text, 0, false, "static"},
    {"'kinematic'", Value::Text, 0, false, "kinematic"},
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
    case Accepts::PositiveOrInfinity: return (finiteNumber(v) && v.x > 0) || (v.type == Value::Number && v.x == kInf);
    case Accepts::NonNegativeOrInfinity: return (finiteNumber(v) && v.x >= 0) || (v.type == Value::Number && v.x == kInf);
    case Accepts::NonZero: return finiteNumber(v) && v.x != 0;
    case Accepts::Zero: return finiteNumber(v) && v.x == 0;
    case Accepts::True: return v.type == Value::Bool && std::string(v.lua) == "true";
    case Accepts::BodyType: return v.type == Value::Text && (std::string(v.text) == "static" || std::string(v.text) == "kinematic");
    case Accepts::StaticType: return v.type == Value::Text && std::string(v.text) == "static";
    case Accepts::Bits:
      return v.type == Value::Integer ||
             (v.type == Value::Number && std::isfinite(v.x) && v.x == std::floor(v.x) && v.x >= -0x1p63 && v.x < 0x1p64);
    case Accepts::Int32: return finiteNumber(v) && v.x == std::floor(v.x) && v.x >= -0x1p31 && v.x < 0x1p31;
    case Accepts::Any: return true;
    case Accepts::Never: return false;
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

// The body options of a moving body, and those of a body that must be static (a segment's or
// chain's default): no velocity but zero, and static = false or another type refused.
const std::vector<Option> kMovingOptions = {
    {"position", Accepts::Vector}, {"angle", Accepts::Finite}, {"velocity", Accepts::Vector},
    {"angular_velocity", Accepts::Finite}, {"name", Accepts::String}, {"linear_damping", Accepts::NonNegative},
    {"angular_damping", Accepts::NonNegative}, {"gravity_scale", Accepts::Finite}, {"fixed_rotation", Accepts::Boolean},
    {"bullet", Accepts::Boolean}, {"enabled", Accepts::Boolean}, {"user_data", Accepts::Any}, {"awake", Accepts::Boolean}};
const std::vector<Option> kStaticOptions = {
    {"position", Accepts::Vector}, {"angle", Accepts::Finite}, {"velocity", Accepts::Never},
    {"angular_velocity", Accepts::Zero}, {"name", Accepts::String}, {"linear_damping", Accepts::NonNegative},
    {"angular_damping", Accepts::NonNegative}, {"gravity_scale", Accepts::Finite}, {"fixed_rotation", Accepts::Boolean},
    {"bullet", Accepts::Boolean}, {"enabled", Accepts::Boolean}, {"user_data", Accepts::Any}, {"static", Accepts::True},
    {"awake", Accepts::Boolean}};
// The shape options (of body:add_shape, and of the one shape of add_box, ...) but density.
const std::vector<Option> kMaterialOptions = {
    {"restitution", Accepts::Unit}, {"friction", Accepts::NonNegative}, {"static_friction", Accepts::NonNegative},
    {"sensor", Accepts::Boolean}, {"category", Accepts::Bits}, {"mask", Accepts::Bits}, {"group", Accepts::Int32}};
// The event options of a shape (lua_events.cpp), options and shape fields alike: every vector of
// the pool is a direction (none is zero).
const std::vector<Option> kEventOptions = {
    {"contact_events", Accepts::Boolean}, {"hit_events", Accepts::Boolean}, {"hit_speed", Accepts::NonNegative},
    {"one_way", Accepts::Vector}, {"pre_solve", Accepts::Function}};

std::vector<Option> plus(std::vector<Option> a, std::vector<Option> b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const std::vector<Option> kBodyOptions =
    plus(plus(plus(kMovingOptions, kMaterialOptions), kEventOptions),
         {{"mass", Accepts::Positive}, {"static", Accepts::Boolean}, {"type", Accepts::BodyType}});
// Options every joint takes.
const std::vector<Option> kJointOptions = {{"collide_connected", Accepts::Boolean},
                                           {"break_force", Accepts::PositiveOrInfinity},
                                           {"break_torque", Accepts::PositiveOrInfinity},
                                           {"name", Accepts::String}};
// A joint's limit, motor and spring options.
const std::vector<Option> kMotorSpring = {
    {"enable_limit", Accepts::Boolean}, {"enable_motor", Accepts::Boolean}, {"enable_spring", Accepts::Boolean},
    {"motor_speed", Accepts::Finite}, {"spring_hertz", Accepts::NonNegative}, {"spring_damping", Accepts::NonNegative}};

const Function kFunctions[] = {
    {"add_box", "world:add_box{ width = 1, height = 1, $ }", plus(kBodyOptions, {{"width", Accepts::Positive}, {"height", Accepts::Positive}})},
    {"add_box", "world:add_box{ width = 1, height = 1, $ }", {{"density", Accepts::Positive}}},
    {"add_circle", "world:add_circle{ radius = 1, $ }", plus(kBodyOptions, {{"radius", Accepts::Positive}})},
    {"add_polygon", "world:add_polygon{ vertices = {{0, 0}, {1, 0}, {0, 1}}, $ }", plus(kBodyOptions, {{"concave", Accepts::Boolean}})},
    {"add_polygon", "world:add_polygon{ vertices = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, concave = true, $ }",
     plus(kBodyOptions, {{"density", Accepts::Positive}})},
    {"add_capsule", "world:add_capsule{ a = {0, 0}, b = {1, 0}, radius = 0.5, $ }",
     plus(kBodyOptions, {{"a", Accepts::Vector}, {"b", Accepts::Vector}, {"radius", Accepts::Positive}, {"density", Accepts::Positive}})},
    {"add_segment", "world:add_segment{ a = {0, 0}, b = {1, 0}, type = 'kinematic', $ }",
     plus(plus(plus(kMovingOptions, kMaterialOptions), kEventOptions), {{"a", Accepts::Vector}, {"b", Accepts::Vector}})},
    {"add_segment", "world:add_segment{ a = {0, 0}, b = {1, 0}, $ }",
     plus(kStaticOptions, {{"type", Accepts::BodyType}, {"mass", Accepts::Never}, {"density", Accepts::Never}})},
    {"add_chain", "world:add_chain{ points = {{0, 0}, {1, 0}, {1, 1}}, $ }",
     plus(plus(plus(kStaticOptions, kMaterialOptions), kEventOptions), {{"type", Accepts::StaticType}, {"loop", Accepts::Boolean},
                                                   {"mass", Accepts::Never}, {"density", Accepts::Never}})},
    {"add_body", "world:add_body{ $ }",
     plus(kMovingOptions, {{"static", Accepts::Boolean}, {"type", Accepts::BodyType}, {"mass", Accepts::Never},
                           {"density", Accepts::Never}, {"friction", Accepts::Never}, {"category", Accepts::Never},
                           {"contact_events", Accepts::Never}, {"one_way", Accepts::Never}, {"pre_solve", Accepts::Never}})},
    {"add_shape", "nil_body:add_shape{ shape = 'box', width = 1, height = 1, $ }",
     plus(plus(kMaterialOptions, kEventOptions), {{"width", Accepts::Positive}, {"height", Accepts::Positive}, {"offset", Accepts::Vector},
                             {"angle", Accepts::Finite}, {"density", Accepts::Positive}, {"shape", Accepts::Never},
                             {"radius", Accepts::Never}})},
    {"add_shape", "nil_body:add_shape{ shape = 'circle', radius = 1, $ }", {{"radius", Accepts::Positive}}},
    {"add_shape", "nil_body:add_shape{ shape = 'capsule', a = {0, 0}, b = {1, 0}, radius = 0.5, $ }",
     {{"a", Accepts::Vector}, {"b", Accepts::Vector}}},
    {"set_target", "kin:set_target{ time = 1, $ }",
     {{"position", Accepts::Vector}, {"angle", Accepts::Finite}, {"time", Accepts::Positive}}},
    {"add_revolute", "world:add_revolute{ a = nil_body, anchor = {0, 0}, lower_angle = -1e308, upper_angle = 1e308, max_motor_torque = 1, $ }",
     plus(plus(kJointOptions, kMotorSpring),
          {{"a", Accepts::Body}, {"b", Accepts::OtherBody}, {"anchor", Accepts::Vector}, {"lower_angle", Accepts::Finite},
           {"upper_angle", Accepts::Finite}, {"max_motor_torque", Accepts::NonNegative},
           {"reference_angle", Accepts::Finite}})},
    {"add_prismatic", "world:add_prismatic{ a = nil_body, anchor = {0, 0}, axis = {1, 0}, lower = -1e308, upper = 1e308, max_motor_force = 1, $ }",
     plus(plus(kJointOptions, kMotorSpring),
          {{"a", Accepts::Body}, {"b", Accepts::OtherBody}, {"anchor", Accepts::Vector}, {"axis", Accepts::Vector},
           {"lower", Accepts::Finite}, {"upper", Accepts::Finite}, {"max_motor_force", Accepts::NonNegative},
           {"reference_angle", Accepts::Finite}})},
    {"add_wheel", "world:add_wheel{ a = nil_body, anchor = {0, 0}, axis = {0, 1}, lower = -1e308, upper = 1e308, max_motor_torque = 1, $ }",
     plus(plus(kJointOptions, kMotorSpring),
          {{"a", Accepts::Body}, {"b", Accepts::OtherBody}, {"anchor", Accepts::Vector}, {"axis", Accepts::Vector},
           {"lower", Accepts::Finite}, {"upper", Accepts::Finite}, {"max_motor_torque", Accepts::NonNegative},
           {"reference_angle", Accepts::Finite}})},
    {"add_distance", "world:add_distance{ a = nil_body, anchor_b = {0, 5}, $ }",
     plus(kJointOptions,
          {{"a", Accepts::Body}, {"anchor_a", Accepts::Vector}, {"anchor_b", Accepts::Vector}, {"length", Accepts::NonNegative},
           {"min_length", Accepts::NonNegative}, {"max_length", Accepts::NonNegativeOrInfinity},
           {"max_spring_force", Accepts::NonNegativeOrInfinity}, {"enable_limit", Accepts::Boolean},
           {"enable_spring", Accepts::Boolean}, {"spring_hertz", Accepts::NonNegative}, {"spring_damping", Accepts::NonNegative}})},
    {"add_distance", "world:add_distance{ a = nil_body, $ }", {{"b", Accepts::OtherBody}}},
    {"add_weld", "world:add_weld{ a = nil_body, anchor = {0, 0}, $ }",
     plus(kJointOptions, {{"a", Accepts::Body}, {"b", Accepts::OtherBody}, {"anchor", Accepts::Vector},
                          {"linear_hertz", Accepts::NonNegative}, {"linear_damping", Accepts::NonNegative},
                          {"angular_hertz", Accepts::NonNegative}, {"angular_damping", Accepts::NonNegative},
           {"reference_angle", Accepts::Finite}})},
    {"add_motor_joint", "world:add_motor_joint{ a = nil_body, $ }",
     plus(kJointOptions, {{"a", Accepts::Body}, {"b", Accepts::OtherBody}, {"anchor", Accepts::Vector},
                          {"linear_offset", Accepts::Vector}, {"angular_offset", Accepts::Finite},
                          {"linear_velocity", Accepts::Vector}, {"angular_velocity", Accepts::Finite},
                          {"max_force", Accepts::NonNegative}, {"max_torque", Accepts::NonNegative},
                          {"motor_hertz", Accepts::NonNegative}, {"motor_damping", Accepts::NonNegative}})},
    {"add_friction_joint", "world:add_friction_joint{ a = nil_body, $ }",
     plus(kJointOptions, {{"a", Accepts::Body}, {"b", Accepts::OtherBody}, {"anchor", Accepts::Vector},
                          {"max_force", Accepts::NonNegative}, {"max_torque", Accepts::NonNegative}})},
    {"add_pulley", "world:add_pulley{ a = nil_body, b = other, ground_a = {0, 5}, ground_b = {3, 5}, $ }",
     plus(kJointOptions, {{"anchor_a", Accepts::Vector}, {"anchor_b", Accepts::Vector}, {"ground_a", Accepts::Vector},
                          {"ground_b", Accepts::Vector}, {"ratio", Accepts::Positive}})},
    {"add_gear", "world:add_gear{ joint_a = world:add_revolute{ a = nil_body, anchor = {0, 0} }, joint_b = world:add_revolute{ a = other, anchor = {3, 0} }, $ }",
     plus(kJointOptions, {{"ratio", Accepts::NonZero}, {"joint_a", Accepts::Never}, {"joint_b", Accepts::Never}})},
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
    // --- queries (lua_query.cpp)
    {"ray_cast", "world:ray_cast{ from = {0, 0}, to = {1, 0}, $ }",
     {{"from", Accepts::Vector}, {"to", Accepts::Vector}, {"category", Accepts::Bits}, {"mask", Accepts::Bits},
      {"sensors", Accepts::Boolean}}},
    {"ray_cast_all", "world:ray_cast_all{ from = {0, 0}, to = {1, 0}, $ }",
     {{"from", Accepts::Vector}, {"to", Accepts::Vector}, {"sensors", Accepts::Boolean}}},
    {"query_box", "world:query_box{ lower = {-1e9, -1e9}, upper = {1e9, 1e9}, $ }",
     {{"lower", Accepts::Vector}, {"upper", Accepts::Vector}, {"mask", Accepts::Bits}}},
    {"query_point", "world:query_point{ point = {0, 0}, $ }", {{"point", Accepts::Vector}, {"category", Accepts::Bits}}},
    {"overlap", "world:overlap{ shape = { shape = 'circle', radius = 1 }, $ }",
     {{"position", Accepts::Vector}, {"angle", Accepts::Finite}, {"shape", Accepts::Never}}},
    {"shape_cast", "world:shape_cast{ shape = { shape = 'box', width = 1, height = 1 }, from = {0, 5}, to = {0, 6}, $ }",
     {{"from", Accepts::Vector}, {"to", Accepts::Vector}, {"angle", Accepts::Finite}, {"shape", Accepts::Never}}},
    {"explode", "world:explode{ position = {0, 0}, $ }",
     {{"position", Accepts::Vector}, {"radius", Accepts::Positive}, {"falloff", Accepts::NonNegative},
      {"category", Accepts::Bits}, {"mask", Accepts::Bits}}},
    {"explode", "world:explode{ position = {0, 0}, radius = 0.1, $ }", {{"impulse", Accepts::NonNegative}}},
};

// A repeated key in a table constructor: the later value wins, so "$" can override a base option.
std::string scene(const std::string& call_line) {
  return "function PopulateWorld(world)\n"
         "  local nil_body = world:add_circle{ radius = 0.5, name = 'first' }\n"
         "  local other = world:add_circle{ radius = 0.5, position = {3, 0} }; local kin = world:add_box{ width = 1, height = 1, "
         "type = 'kinematic', position = {-3, 0} }\n"
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
        CAPTURE(m);
        const std::string name = o.name;
        const bool size_or_mass = name == "width" || name == "height" || name == "radius" || name == "mass" ||
                                  name == "density" || name == "falloff";
        const bool side = name == "width" || name == "height";
        const bool extreme_size = size_or_mass && o.accepts != Accepts::Never && finiteNumber(v) && (side || v.x > 0.0) && (v.x < 1e-6 || v.x > 1e6);
        if (extreme_size) {
          // A box the core cannot represent (width/height beyond 1e8 : 1) is refused naming a side;
          // a body whose mass or inertia (or their inverses) would not be finite (radius 1e-300,
          // mass 1e308 on a small triangle) naming its mass.
          // A size whose area, moment of inertia or square overflows (a radius of 1e308; explode's
          // reach) is refused naming that option.
          const std::string field = "test.lua:4: " + std::string(f.name) + ": ";
          CHECK((m == "" || (m.starts_with(field) && clean(m) &&
                             (m.find("width") != std::string::npos || m.find("height") != std::string::npos ||
                              m.starts_with(field + name + " ") ||
                              m.find(": mass and moment of inertia must be finite") != std::string::npos))));
        } else if (valid(o.accepts, v)) {
          CHECK(m == "");
          ++accepted;
        } else {
          // "test.lua:4: add_box: width must be > 0, got -1"; a table of options given as an option
          // names its own mistakes after it: "overlap: shape: radius must be > 0, got -1".
          const std::string field = "test.lua:4: " + std::string(f.name) + ": " + o.name;
          CHECK((m.starts_with(field + " ") || m.starts_with(field + ": ")));
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

// `handle.<field> = <value>` (after `setup`, on the same line) for every value of the pool:
// accepted iff valid, else an error of "<what>.<field>: ...".
void checkWrites(const char* what, const std::string& handle, const std::vector<Option>& fields,
                 const std::string& setup = "") {
  for (const Option& o : fields) {
    for (const Value& v : kPool) {
      const std::string source = scene(setup + handle + "." + o.name + " = " + v.lua);
      CAPTURE(source);
      const std::string m = messageOf(source, 1);
      CAPTURE(m);
      if (valid(o.accepts, v)) {
        CHECK(m == "");
      } else {
        CHECK(m.starts_with(std::string("test.lua:4: ") + what + "." + o.name + ": "));
        CHECK(clean(m));
      }
    }
  }
}

const std::vector<Option> kShapeFields = plus(plus(kMaterialOptions, kEventOptions), {{"density", Accepts::Positive}});

TEST_CASE("validation: writes to every writable body field, the same way") {
  checkWrites("body", "nil_body",
              plus(plus(kMovingOptions, kMaterialOptions),
                   {{"mass", Accepts::Positive}, {"static", Accepts::Boolean}, {"type", Accepts::BodyType}}));
}

TEST_CASE("validation: writes to every writable shape field, the same way") {
  checkWrites("shape", "nil_body.shapes[1]", kShapeFields);
}

TEST_CASE("validation: writes to every writable joint field of every kind, the same way") {
  const std::vector<Option> common = {{"collide_connected", Accepts::Boolean},
                                      {"break_force", Accepts::PositiveOrInfinity},
                                      {"break_torque", Accepts::PositiveOrInfinity},
                                      {"name", Accepts::String}};
  const std::pair<const char*, std::vector<Option>> joints[] = {
      {"world:add_revolute{ a = nil_body, anchor = {0, 0}, lower_angle = -1e308, upper_angle = 1e308 }",
       plus(plus(common, kMotorSpring),
            {{"lower_angle", Accepts::Finite}, {"upper_angle", Accepts::Finite}, {"max_motor_torque", Accepts::NonNegative}})},
      {"world:add_prismatic{ a = nil_body, anchor = {0, 0}, axis = {1, 0}, lower = -1e308, upper = 1e308 }",
       plus(kMotorSpring, {{"lower", Accepts::Finite}, {"upper", Accepts::Finite}, {"max_motor_force", Accepts::NonNegative}})},
      {"world:add_wheel{ a = nil_body, anchor = {0, 0}, axis = {0, 1}, lower = -1e308, upper = 1e308 }",
       plus(kMotorSpring, {{"lower", Accepts::Finite}, {"upper", Accepts::Finite}, {"max_motor_torque", Accepts::NonNegative}})},
      {"world:add_distance{ a = nil_body, b = other }",
       {{"enable_limit", Accepts::Boolean}, {"enable_spring", Accepts::Boolean}, {"min_length", Accepts::NonNegative},
        {"max_length", Accepts::NonNegativeOrInfinity}, {"max_spring_force", Accepts::NonNegativeOrInfinity},
        {"spring_hertz", Accepts::NonNegative}, {"spring_damping", Accepts::NonNegative}}},
      {"world:add_weld{ a = nil_body, anchor = {0, 0} }",
       {{"linear_hertz", Accepts::NonNegative}, {"linear_damping", Accepts::NonNegative},
        {"angular_hertz", Accepts::NonNegative}, {"angular_damping", Accepts::NonNegative}}},
      {"world:add_motor_joint{ a = nil_body }",
       {{"linear_offset", Accepts::Vector}, {"angular_offset", Accepts::Finite}, {"linear_velocity", Accepts::Vector},
        {"angular_velocity", Accepts::Finite}, {"max_force", Accepts::NonNegative}, {"max_torque", Accepts::NonNegative},
        {"motor_hertz", Accepts::NonNegative}, {"motor_damping", Accepts::NonNegative}}},
      {"world:add_friction_joint{ a = nil_body }", {{"max_force", Accepts::NonNegative}, {"max_torque", Accepts::NonNegative}}},
  };
  for (const auto& [make, fields] : joints) checkWrites("joint", "j", fields, "local j = " + std::string(make) + "; ");
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
      {"world:add_body{ $ = 1 }", lua::api::kBodyOptions},
      {"world:add_circle{ radius = 1, $ = 1 }", lua::api::kShapeOptions},
      {"world:add_capsule{ a = {0, 0}, b = {1, 0}, radius = 1, $ = 1 }", lua::api::kCapsuleOptions},
      {"world:add_chain{ points = {{0, 0}, {1, 0}}, $ = 1 }", lua::api::kChainOptions},
      {"world:add_polygon{ vertices = {{0, 0}, {1, 0}, {0, 1}}, $ = 1 }", lua::api::kPolygonOptions},
      {"nil_body:add_shape{ shape = 'circle', radius = 1, $ = 1 }", lua::api::kAddShapeOptions},
      {"kin:set_target{ time = 1, $ = 1 }", lua::api::kTargetOptions},
      {"world:add_revolute{ a = nil_body, anchor = {0, 0}, $ = 1 }", lua::api::kRevoluteOptions},
      {"world:add_revolute{ a = nil_body, anchor = {0, 0}, $ = 1 }", lua::api::kJointOptions},
      {"world:add_prismatic{ a = nil_body, anchor = {0, 0}, axis = {1, 0}, $ = 1 }", lua::api::kPrismaticOptions},
      {"world:add_distance{ a = nil_body, b = other, $ = 1 }", lua::api::kDistanceOptions},
      {"world:add_weld{ a = nil_body, anchor = {0, 0}, $ = 1 }", lua::api::kWeldOptions},
      {"world:add_wheel{ a = nil_body, anchor = {0, 0}, axis = {0, 1}, $ = 1 }", lua::api::kWheelOptions},
      {"world:add_motor_joint{ a = nil_body, $ = 1 }", lua::api::kMotorJointOptions},
      {"world:add_friction_joint{ a = nil_body, $ = 1 }", lua::api::kFrictionJointOptions},
      {"world:add_pulley{ a = nil_body, b = other, ground_a = {0, 5}, ground_b = {3, 5}, $ = 1 }", lua::api::kPulleyOptions},
      {"world:add_gear{ $ = 1 }", lua::api::kGearOptions},
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

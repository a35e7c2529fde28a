#include "porting_names.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace rigidlab::lua {
namespace {

// A foreign name (normalised: lower case, without '_', so frequencyHz, frequency_hz and FrequencyHz
// meet), the rigidlab names it may stand for, in order of preference (the first the function has
// is suggested), and what to say when the function has none of them (empty: nothing).
struct Ported {
  std::string_view foreign;
  std::array<std::string_view, 3> names;
  std::string_view otherwise;
};

// clang-format off
constexpr Ported kPorted[] = {
    // Joints: springs, motors, limits, anchors (LÖVE, Box2D 2.x and v3).
    {"frequency",            {"spring_hertz", "motor_hertz", "angular_hertz"}, ""},
    {"frequencyhz",          {"spring_hertz", "motor_hertz", "angular_hertz"}, ""},
    {"hertz",                {"spring_hertz", "motor_hertz", "angular_hertz"}, ""},
    {"springfrequency",      {"spring_hertz"}, ""},
    {"dampingratio",         {"spring_damping", "motor_damping", "angular_damping"}, ""},
    {"springdampingratio",   {"spring_damping"}, ""},
    {"stiffness",            {"spring_hertz", "linear_hertz", "motor_hertz"}, ""},
    {"target",               {"linear_offset"}, ""},
    {"correctionfactor",     {"motor_hertz"}, ""},
    {"lowertranslation",     {"lower"}, ""},
    {"uppertranslation",     {"upper"}, ""},
    {"lowerlimit",           {"lower_angle", "lower", "min_length"}, ""},
    {"upperlimit",           {"upper_angle", "upper", "max_length"}, ""},
    {"limits",               {"set_limits"}, ""},
    {"limitsenabled",        {"enable_limit"}, ""},
    {"enablelimits",         {"enable_limit"}, ""},
    {"motorenabled",         {"enable_motor"}, ""},
    {"springenabled",        {"enable_spring"}, ""},
    {"localaxisa",           {"axis"}, ""},
    {"localaxis",            {"axis"}, ""},
    {"bodya",                {"a"}, ""},
    {"bodyb",                {"b"}, ""},
    {"joint1",               {"joint_a"}, ""},
    {"joint2",               {"joint_b"}, ""},
    {"groundanchora",        {"ground_a"}, ""},
    {"groundanchorb",        {"ground_b"}, ""},
    {"groundanchors",        {"ground_a"}, ""},
    {"constant",             {"length"}, ""},
    {"maxlengths",           {}, "rigidlab's pulley has no maximum lengths (Box2D dropped them in version 2.2)"},
    {"anchors",              {"anchor_a"}, ""},
    {"anchor",               {"anchor_a"}, ""},
    {"jointangle",           {"angle"}, ""},
    {"jointspeed",           {"speed"}, ""},
    {"jointtranslation",     {"translation"}, ""},
    {"type",                 {"kind"}, ""},
    {"bodies",               {"a"}, ""},
    // Bodies.
    {"linearvelocity",       {"velocity"}, ""},
    {"rotation",             {"angle"}, ""},
    {"transform",            {"position"}, ""},
    {"x",                    {"position"}, ""},
    {"y",                    {"position"}, ""},
    {"worldcenter",          {"center"}, ""},
    {"massdata",             {"mass"}, ""},
    {"allowsleep",           {"sleeping_allowed", "sleeping"}, ""},
    {"enablesleep",          {"sleeping_allowed", "sleeping"}, ""},
    {"sleepallowed",         {"sleeping_allowed", "sleeping"}, ""},
    {"sleepingallowed",      {"sleeping_allowed", "sleeping"}, ""},
    {"active",               {"enabled"}, ""},
    {"fixturelist",          {"shapes"}, ""},
    {"fixtures",             {"shapes"}, ""},
    {"shapelist",            {"shapes"}, ""},
    {"jointlist",            {"joints"}, ""},
    {"contactlist",          {"contacts"}, ""},
    {"applylinearimpulse",   {"apply_impulse"}, ""},
    {"applylinearimpulsetocenter", {"apply_impulse"}, ""},
    {"applyforcetocenter",   {"apply_force"}, ""},
    {"linearvelocityfromworldpoint", {"velocity_at"}, ""},
    {"linearvelocityfromlocalpoint", {"velocity_at"}, ""},
    {"worldpointvelocity",   {"velocity_at"}, ""},
    {"localpointvelocity",   {"velocity_at"}, ""},
    {"worldpoints",          {"world_point"}, ""},
    {"localpoints",          {"local_point"}, ""},
    {"resetmassdata",        {"reset_mass"}, ""},
    {"applymassfromshapes",  {"reset_mass"}, ""},
    {"touching",             {"contacts"}, ""},
    {"destroy",              {"remove"}, "remove it with world:remove(...); the scene owns its world"},
    {"destroyed",            {"removed"}, ""},
    // Shapes (LÖVE's fixtures and shapes are one thing in rigidlab).
    {"fixture",              {"shape"}, ""},
    {"fixturea",             {"shape_a"}, ""},
    {"fixtureb",             {"shape_b"}, ""},
    {"categorybits",         {"category"}, ""},
    {"maskbits",             {"mask"}, ""},
    {"groupindex",           {"group"}, ""},
    {"filterdata",           {"category"}, ""},
    {"filter",               {"category"}, ""},
    {"shape",                {"kind"}, ""},
    {"boundingbox",          {"bounds"}, ""},
    {"aabb",                 {"bounds"}, ""},
    {"computeaabb",          {"bounds"}, ""},
    {"computemass",          {"mass"}, ""},
    {"points",               {"vertices"}, ""},
    {"point",                {"center"}, ""},
    {"vertexcount",          {"vertices"}, ""},
    {"nextvertex",           {"ghost2"}, ""},
    {"previousvertex",       {"ghost1"}, ""},
    {"childcount",           {}, "every rigidlab shape is one piece: a chain is one shape per segment (body.shapes)"},
    {"childedge",            {}, "a chain is one shape per segment: body.shapes[i]"},
    // The world.
    {"bodylist",             {"bodies"}, ""},
    {"bodycount",            {"bodies"}, ""},
    {"jointcount",           {"joints"}, ""},
    {"contactcount",         {"contacts"}, ""},
    {"update",               {"step"}, ""},
    {"queryboundingbox",     {"query_box"}, ""},
    {"queryaabb",            {"query_box"}, ""},
    {"overlapaabb",          {"query_box"}, ""},
    {"overlapshape",         {"overlap"}, ""},
    {"castray",              {"ray_cast"}, ""},
    {"raycastclosest",       {"ray_cast"}, ""},
    {"castshape",            {"shape_cast"}, ""},
    {"callbacks",            {}, "define the scene's hooks OnContactBegin, OnContactEnd and OnHit as global functions "
                                 "(and a shape's pre_solve function)"},
    {"contactfilter",        {}, "define the scene hook ShouldCollide(shape_a, shape_b) as a global function"},
    {"customfiltercallback", {}, "define the scene hook ShouldCollide(shape_a, shape_b) as a global function"},
    {"presolvecallback",     {"pre_solve"}, ""},
    {"translateorigin",      {}, "rigidlab has no origin shift: positions are doubles, precise far from the origin"},
    {"shiftorigin",          {}, "rigidlab has no origin shift: positions are doubles, precise far from the origin"},
    {"meter",                {}, "rigidlab works in metres: there is no pixel scale (scale where you draw)"},
    {"lengthunitspermeter",  {}, "rigidlab works in metres: there is no pixel scale (scale where you draw)"},
};
// clang-format on

std::string normalised(std::string_view name) {
  std::string n;
  for (char c : name)
    if (c != '_') n += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return n;
}

bool has(const std::vector<std::string_view>& candidates, std::string_view name) {
  return std::find(candidates.begin(), candidates.end(), name) != candidates.end();
}

// Without a Box2D v3 C prefix (b2Body_, b2World_, b2RevoluteJoint_, ...).
std::string_view withoutPrefix(std::string_view name) {
  if (name.starts_with("b2")) {
    const size_t underscore = name.find('_');
    if (underscore != std::string_view::npos && underscore + 1 < name.size()) return name.substr(underscore + 1);
  }
  return name;
}

// Without a get, set, is or has in front of a capital (getWorldPoint, IsBullet).
std::string_view withoutAccessor(std::string_view name) {
  for (std::string_view verb : {"get", "set", "is", "has", "Get", "Set", "Is", "Has"})
    if (name.starts_with(verb) && name.size() > verb.size() && std::isupper(static_cast<unsigned char>(name[verb.size()])))
      return name.substr(verb.size());
  return name;
}

// camelCase (or CamelCase) as snake_case: applyTorque → apply_torque, localAnchorA → local_anchor_a.
std::string snakeCase(std::string_view name) {
  std::string s;
  for (size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (std::isupper(c) && i > 0 && name[i - 1] != '_') s += '_';
    s += static_cast<char>(std::tolower(c));
  }
  return s;
}

}  // namespace

std::string portingSuggestion(std::string_view name, const std::vector<std::string_view>& candidates) {
  const std::string_view bare = withoutPrefix(name);
  for (const std::string_view form : {bare, withoutAccessor(bare)}) {
    const std::string key = normalised(form);
    for (const Ported& p : kPorted) {
      if (p.foreign != key) continue;
      for (std::string_view n : p.names)
        if (!n.empty() && has(candidates, n)) return "rigidlab calls it '" + std::string(n) + "'";
      if (!p.otherwise.empty()) return std::string(p.otherwise);
    }
    const std::string snake = snakeCase(form);
    if (snake != name && has(candidates, snake)) return "rigidlab calls it '" + snake + "'";
  }
  return "";
}

}  // namespace rigidlab::lua

#include "lua_body_args.h"

#include <algorithm>

#include "bindings.h"
#include "lua_events.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

const std::vector<std::string_view> kKindNames = {"circle", "box", "polygon", "capsule", "segment"};
const std::vector<std::string_view> kTypeNames = {"static", "kinematic", "dynamic"};

}  // namespace

ShapeKind shapeKind(const Options& o, std::string_view key) {
  if (!o.has(key)) o.fail(key, "is required: \"circle\", \"box\", \"polygon\", \"capsule\" or \"segment\"");
  const std::string name = o.choice(key, kKindNames, "");
  return static_cast<ShapeKind>(std::find(kKindNames.begin(), kKindNames.end(), name) - kKindNames.begin());
}

const char* shapeKindName(ShapeKind kind) { return kKindNames[static_cast<size_t>(kind)].data(); }

const std::vector<std::string_view>& geometryOptions(ShapeKind kind) {
  static const std::vector<std::string_view> circle = {"radius"}, box = {"width", "height"}, polygon = {"vertices"},
                                             capsule = {"a", "b", "radius"}, segment = {"a", "b"};
  switch (kind) {
    case ShapeKind::Circle:
      return circle;
    case ShapeKind::Box:
      return box;
    case ShapeKind::Polygon:
      return polygon;
    case ShapeKind::Capsule:
      return capsule;
    case ShapeKind::Segment:
      return segment;
  }
  return circle;
}

void refuseOtherGeometry(const Options& o, ShapeKind kind, std::string_view more) {
  const auto& own = geometryOptions(kind);
  std::string takes;
  for (std::string_view key : own) takes += (takes.empty() ? "" : ", ") + std::string(key);
  if (!more.empty()) takes += ", " + std::string(more);
  for (std::string_view key : {"radius", "width", "height", "vertices", "a", "b"})
    if (o.has(key) && std::find(own.begin(), own.end(), key) == own.end())
      o.fail(key, std::string("is not an option of a ") + shapeKindName(kind) + " shape (it takes " + takes + ")");
}

Shape readGeometry(const Options& o, ShapeKind kind) {
  lua_State* L = o.L();
  // The options are read before the core is called, so a missing or mistyped one is named as such.
  try {
    switch (kind) {
      case ShapeKind::Circle:
        return makeCircle(o.positive("radius"));
      case ShapeKind::Box: {
        const double w = o.positive("width"), h = o.positive("height");
        return makeBox(w, h);
      }
      case ShapeKind::Polygon: {
        const std::vector<Vec2> points = o.points("vertices", 0, kMaxPolygonVertices);
        return makePolygon(points);
      }
      case ShapeKind::Capsule: {
        const Vec2 a = o.vec("a"), b = o.vec("b");
        return makeCapsule(a, b, o.positive("radius"));
      }
      case ShapeKind::Segment: {
        const Vec2 a = o.vec("a"), b = o.vec("b");
        return makeSegment(a, b);
      }
    }
  } catch (const InputError& e) {
    // The core's hint for a concave outline, in the words of this function.
    const std::string hint = "(split concave shapes into convex pieces)";
    std::string text = e.what();
    if (const size_t at = text.find(hint); at != std::string::npos)
      text.replace(at, hint.size(),
                   o.function() == "add_polygon"
                       ? "(give concave = true to make the body of convex pieces)"
                       : "(a shape is convex: add one shape per convex piece, or make the body "
                         "with world:add_polygon{vertices = ..., concave = true})");
    failCore(L, o.function(), InputError(e.field(), text));  // names width, vertices[4], b, ... and the value
  }
  return {};
}

BodyType bodyType(lua_State* L, std::string_view function, std::string_view subject, const sol::object& value) {
  const std::string name = checkChoice(L, function, subject, value, kTypeNames);
  return name == "static" ? BodyType::Static : name == "kinematic" ? BodyType::Kinematic : BodyType::Dynamic;
}

BodyDef readBodyDef(const Options& o, BodyType fallback) {
  BodyDef d;
  if (o.has("type") && o.has("static"))
    o.fail("static", "and type cannot both be given (static = true is type = \"static\")");
  d.type = o.has("type")     ? bodyType(o.L(), o.function(), "type", o.get("type"))
           : o.has("static") ? (o.boolean("static", false) ? BodyType::Static : BodyType::Dynamic)
                             : fallback;
  d.position = o.vec("position", Vec2::Zero());
  d.angle = o.number("angle", 0.0);
  d.velocity = o.vec("velocity", Vec2::Zero());
  d.angular_velocity = o.number("angular_velocity", 0.0);
  if (d.type == BodyType::Static && d.velocity != Vec2::Zero())
    o.fail("velocity", "must be zero for a static body, got " + formatVec(d.velocity) +
                           " (a static body cannot move: make it type = \"kinematic\" to move it by its velocity)");
  if (d.type == BodyType::Static && d.angular_velocity != 0.0)
    o.fail("angular_velocity", "must be zero for a static body, got " + formatNumber(d.angular_velocity) +
                                   " (a static body cannot turn: make it type = \"kinematic\" to turn it)");
  d.linear_damping = o.nonNegative("linear_damping", 0.0);
  d.angular_damping = o.nonNegative("angular_damping", 0.0);
  d.gravity_scale = o.number("gravity_scale", 1.0);
  d.fixed_rotation = o.boolean("fixed_rotation", false);
  d.bullet = o.boolean("bullet", false);
  d.enabled = o.boolean("enabled", true);
  d.awake = o.boolean("awake", true);
  if (o.has("gravity")) d.gravity = o.vec("gravity");
  d.sleeping_allowed = o.boolean("sleeping_allowed", true);
  d.name = o.string("name", "", kNameBytes);
  return d;
}

Filter readFilter(const Options& o, const Filter& fallback) {
  Filter f;
  f.category = o.bits("category", fallback.category);
  f.mask = o.bits("mask", fallback.mask);
  f.group = static_cast<int32_t>(o.integer("group", INT32_MIN, INT32_MAX, fallback.group));
  return f;
}

ShapeDef readShapeOptions(const Options& o, bool area) {
  ShapeDef d;
  if (!area) {
    for (const char* key : {"density", "mass"})
      if (o.has(key)) o.fail(key, "cannot be given: a segment or chain has no area, so no density or mass");
  } else {
    d.density = o.positive("density", 1.0);
  }
  d.material.restitution = o.inRange("restitution", 0.0, 1.0, 0.0);
  d.material.friction = o.nonNegative("friction", 0.6);
  d.material.static_friction = o.nonNegative("static_friction", d.material.friction);
  d.sensor = o.boolean("sensor", false);
  d.filter = readFilter(o, Filter{});
  d.tangent_speed = o.number("tangent_speed", 0.0);
  d.rolling_resistance = o.nonNegative("rolling_resistance", 0.0);
  readShapeEventOptions(o, d);
  return d;
}

}  // namespace rigidlab::lua

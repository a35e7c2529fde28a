// The world functions that make bodies (docs/lua-api.md "Bodies"):
//
//   add_body      a body without shapes (add them with body:add_shape)
//   add_box, add_circle, add_capsule, add_segment
//                 a body with one shape; the shape options apply to it
//   add_polygon   one convex polygon, or with concave = true a compound body of convex pieces
//   add_chain     a static body with a chain of segments
//
// Every one takes the body options (lua_body_args.h) and returns the body's handle.
#include <string>

#include "api_names.h"
#include "bindings.h"
#include "lua_body_args.h"
#include "lua_events.h"
#include "lua_shape.h"
#include "rigidlab/error.h"

namespace rigidlab::lua {
namespace {

using namespace api;

// Outlines split into pieces in C++, which no budget can stop: ear clipping takes O(n³) at worst.
constexpr size_t kMaxConcavePoints = 256;
// A chain's segments are made in one call (and their host memory charged after it).
constexpr size_t kMaxChainPoints = 65536;

// Gives its shapes their event options, charges the body's host memory and keeps its user_data;
// over the memory limit the body is removed again, as if it had not been made.
void finishBody(lua_State* L, Scene::Impl& scene, const Options& o, BodyId id) {
  try {
    const bool surface = o.hasAny(kShapeSurfaceOptions);
    const double tangent_speed = o.number("tangent_speed", 0.0), rolling = o.nonNegative("rolling_resistance", 0.0);
    for (const ShapeId shape : scene.world->body(id).shapes) {
      attachShapeEvents(L, scene, o, shape);
      forgetShapeUserData(scene, shape);  // a slot used before: nothing of the old shape's
      if (surface) scene.world->setShapeSurface(shape, tangent_speed, rolling);
    }
    scene.host->charge(L, o.function(), hostBytes(*scene.world, scene.world->body(id)));
  } catch (...) {
    scene.world->destroyBody(id);
    throw;
  }
  if (o.has("user_data")) scene.user_data.raw_set(scene.world->body(id).uid, o.get("user_data"));
  bodyHandle(L, scene, id).push(L);
}

BodyId create(lua_State* L, World& world, std::string_view function, const BodyDef& d) {
  try {
    return world.createBody(d);
  } catch (const InputError& e) {
    failCore(L, function, e);  // the core names the field and the value
  }
}

// A segment or chain has no area, so it cannot be dynamic: refused naming the option that made it so.
void requireNotDynamic(const Options& o, const BodyDef& d, const char* what) {
  if (d.type != BodyType::Dynamic) return;
  const char* key = o.has("static") ? "static" : "type";
  o.fail(key, std::string(o.has("static") ? "= false" : "\"dynamic\"") + " is refused: a " + what +
                  " has no area, so only a static or kinematic body may have one (use a capsule or a thin box)");
}

// The body options, the shape options and mass (or density) of a body with one shape.
BodyId createOneShape(lua_State* L, Scene::Impl& scene, const Options& o, const Shape& shape) {
  const bool area = hasArea(shape.type);
  BodyDef d = readBodyDef(o, area ? BodyType::Dynamic : BodyType::Static);
  if (!area) requireNotDynamic(o, d, shapeTypeName(shape.type));
  if (o.has("mass") && o.has("density")) o.fail("mass", "and density cannot both be given (mass sets the density)");
  const ShapeDef s = readShapeOptions(o, area);
  d.shape = shape;
  if (o.has("mass")) d.mass = o.positive("mass");
  d.density = s.density;
  d.restitution = s.material.restitution;
  d.friction = s.material.friction;
  d.static_friction = s.material.static_friction;
  d.filter = s.filter;
  d.sensor = s.sensor;
  return create(L, *scene.world, o.function(), d);
}

// A body of several convex pieces with the same shape options. The mass, if given, is shared by
// the pieces in proportion to their areas, and the velocity is the centre of mass's, as for one shape.
BodyId createCompound(lua_State* L, Scene::Impl& scene, const Options& o,
                      const std::vector<std::vector<Vec2>>& pieces) {
  BodyDef d = readBodyDef(o, BodyType::Dynamic);
  if (o.has("mass") && o.has("density")) o.fail("mass", "and density cannot both be given (mass sets the density)");
  const std::optional<double> mass = o.has("mass") ? std::optional(o.positive("mass")) : std::nullopt;
  ShapeDef s = readShapeOptions(o, true);
  World& world = *scene.world;
  const BodyId id = create(L, world, o.function(), d);
  try {
    for (const std::vector<Vec2>& piece : pieces) {
      s.shape = makePolygon(piece);
      world.createShape(id, s);
    }
    if (mass) world.setMass(id, *mass);
    if (d.type != BodyType::Static) world.setVelocity(id, d.velocity);
  } catch (const InputError& e) {
    world.destroyBody(id);
    failCore(L, o.function(), e);
  }
  return id;
}

// add_box, add_circle, add_capsule, add_segment and add_polygon: the body options, the shape
// options and the kind's geometry; a polygon with concave = true is split into convex pieces.
template <ShapeKind Kind>
int addShaped(lua_State* L) {
  static constexpr const char* kFunctions[] = {"add_circle", "add_box", "add_polygon", "add_capsule", "add_segment"};
  static const std::vector<std::string_view>* const kGeometry[] = {&kCircleOptions, &kBoxOptions, &kPolygonOptions,
                                                                   &kCapsuleOptions, &kSegmentOptions};
  const char* function = kFunctions[static_cast<size_t>(Kind)];
  Scene::Impl& scene = editedWorld(L, function);
  const Options o(L, function, sol::stack_object(L, 2),
                  joined({&kBodyOptions, &kShapeOptions, &kShapedBodyOptions, kGeometry[static_cast<size_t>(Kind)]}));
  if (Kind != ShapeKind::Polygon || !o.boolean("concave", false)) {
    finishBody(L, scene, o, createOneShape(L, scene, o, readGeometry(o, Kind)));
    return 1;
  }
  const std::vector<Vec2> outline = o.points("vertices", 0, kMaxConcavePoints);
  std::vector<std::vector<Vec2>> pieces;
  try {
    pieces = decomposeConcave(outline);
  } catch (const InputError& e) {
    failCore(L, function, e);
  }
  // A convex outline given concave = true is one piece: a plain one-shape body.
  finishBody(L, scene, o,
             pieces.size() == 1 ? createOneShape(L, scene, o, makePolygon(pieces.front()))
                                : createCompound(L, scene, o, pieces));
  return 1;
}

int addChain(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "add_chain");
  const Options o(L, "add_chain", sol::stack_object(L, 2),
                  joined({&kBodyOptions, &kShapeOptions, &kShapedBodyOptions, &kChainOptions}));
  const bool loop = o.boolean("loop", false);
  World::ChainDef chain;
  chain.loop = loop;
  chain.points = o.points("points", loop ? 3 : 2, kMaxChainPoints);
  const BodyDef d = readBodyDef(o, BodyType::Static);
  if (d.type != BodyType::Static)
    o.fail(o.has("static") ? "static" : "type",
           std::string(o.has("static") ? "= false" : "\"" + std::string(bodyTypeName(d.type)) + "\"") +
               " is refused: a chain belongs to a static body (make a moving outline of capsules or polygons)");
  const ShapeDef s = readShapeOptions(o, false);
  chain.material = s.material;
  chain.filter = s.filter;
  chain.sensor = s.sensor;
  World& world = *scene.world;
  const BodyId id = create(L, world, "add_chain", d);
  try {
    world.createChain(id, chain);
  } catch (const InputError& e) {
    world.destroyBody(id);
    failCore(L, "add_chain", e);  // "points[3] repeats the point before it, (1, 0)"
  }
  finishBody(L, scene, o, id);
  return 1;
}

int addBody(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "add_body");
  // The shape options are known only to say where they belong.
  const Options o(L, "add_body", sol::stack_object(L, 2), joined({&kBodyOptions, &kShapeOptions, &kShapedBodyOptions}));
  for (const auto* list : {&kShapeOptions, &kShapedBodyOptions})
    for (std::string_view key : *list)
      if (o.has(key))
        o.fail(key,
               "is an option of a shape, and add_body makes a body without shapes: give it to body:add_shape{...}");
  finishBody(L, scene, o, create(L, *scene.world, "add_body", readBodyDef(o, BodyType::Dynamic)));
  return 1;
}

}  // namespace

lua_CFunction bodyWorldMethod(std::string_view name) {
  static const NamedFunction kMethods[] = {{"add_box", guarded<addShaped<ShapeKind::Box>>},
                                           {"add_circle", guarded<addShaped<ShapeKind::Circle>>},
                                           {"add_polygon", guarded<addShaped<ShapeKind::Polygon>>},
                                           {"add_capsule", guarded<addShaped<ShapeKind::Capsule>>},
                                           {"add_segment", guarded<addShaped<ShapeKind::Segment>>},
                                           {"add_chain", guarded<addChain>},
                                           {"add_body", guarded<addBody>}};
  return lookUp(kMethods, name);
}

}  // namespace rigidlab::lua

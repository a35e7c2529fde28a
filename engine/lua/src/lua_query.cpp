// The world's queries in Lua (lua_query.h). Every one takes a table of options with the filter
// category (default 1), mask (default all) and sensors (default false: sensors are not found), as
// World's QueryFilter has them; explode takes category and mask.
//
//   ray_cast{from, to}         nil or {body, shape, point, normal, fraction}: the closest hit
//   ray_cast_all{from, to}     every hit, by fraction (a shape once)
//   query_box{lower, upper}    the shapes overlapping the box (shapes, not bodies: a compound
//                              body's pieces are told apart; shape.body is the body)
//   query_point{point}         the shapes containing the point
//   overlap{shape, position, angle}     the shapes overlapping a circle, box, polygon or capsule
//   shape_cast{shape, from, to, angle}  nil or the first hit of that shape moved from → to:
//                              fraction is the time of impact along the way
//   explode{position, radius, falloff, impulse}   the bodies pushed, each once
// `shape` is a table like body:add_shape's: {shape = "circle", radius = 0.5}, {shape = "box",
// width =, height =}, {shape = "polygon", vertices =}, {shape = "capsule", a =, b =, radius =}.
#include "lua_query.h"

#include <cmath>

#include "api_names.h"
#include "lua_args.h"
#include "lua_body_args.h"
#include "lua_contact.h"
#include "lua_shape.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::lua {
namespace {

using namespace api;

QueryFilter readQueryFilter(const Options& o) {
  QueryFilter f;
  f.category = o.bits("category", f.category);
  f.mask = o.bits("mask", f.mask);
  f.sensors = o.boolean("sensors", f.sensors);
  return f;
}

// Two points of a query whose difference overflows (a ray from -1.7e308 to 1.7e308): refused naming
// the option, rather than a C++ name ("width must be > 0, got inf") or a silent miss.
void requireSpan(const Options& o, std::string_view key, std::string_view other, const Vec2& from, const Vec2& to,
                 std::string_view what) {
  const Vec2 d = to - from;
  if (!isFinite(d) || !std::isfinite(d.squaredNorm()))
    o.fail(key, "is too far from " + std::string(other) + ": " + std::string(what) + " overflows, got " +
                    std::string(other) + " " + formatVec(from) + " and " + std::string(key) + " " + formatVec(to));
}

// Runs a query of the core: its refusals are errors of `function`, naming the option.
template <typename F>
auto coreQuery(lua_State* L, std::string_view function, F&& query) {
  try {
    return query();
  } catch (const InputError& e) {
    failCore(L, function, e);
  }
}

// The options of `function`: its own and the filter's.
Options queryOptions(lua_State* L, std::string_view function, const std::vector<std::string_view>& own) {
  return Options(L, function, sol::stack_object(L, 2), joined({&own, &kQueryFilterOptions}));
}

void pushHit(lua_State* L, Scene::Impl& scene, const RayHit& h) {
  lua_createtable(L, 0, 5);
  bodyHandle(L, scene, h.body).push(L);
  lua_setfield(L, -2, "body");
  shapeHandle(L, scene, h.shape).push(L);
  lua_setfield(L, -2, "shape");
  pushVec(L, h.point);
  lua_setfield(L, -2, "point");
  pushVec(L, h.normal);
  lua_setfield(L, -2, "normal");
  lua_pushnumber(L, h.fraction);
  lua_setfield(L, -2, "fraction");
}


int pushShapes(lua_State* L, Scene::Impl& scene, const std::vector<ShapeId>& shapes) {
  pushHandles(L, shapes, [&](ShapeId id) { return shapeHandle(L, scene, id); });
  return 1;
}

// The `shape` option of overlap and shape_cast, in world coordinates of nothing yet (body
// coordinates of the query's placement). Messages read "overlap: shape: radius must be > 0, got -1".
Shape queryShape(const Options& outer) {
  const std::string function = outer.function() + ": shape";
  const sol::object value = outer.get("shape");
  if (value.get_type() != sol::type::table)
    outer.fail("shape", "must be a table like body:add_shape's, e.g. {shape = \"circle\", radius = 0.5}, got " +
                            describe(value));
  const Options o(outer.L(), function, value, kQueryShapeOptions);
  const ShapeKind kind = shapeKind(o, "shape");
  if (kind == ShapeKind::Segment)
    o.fail("shape", "\"segment\" cannot be used here: queries take a circle, box, polygon or capsule");
  refuseOtherGeometry(o, kind, "");
  return readGeometry(o, kind);
}

int rayCast(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "ray_cast");
  const Options o = queryOptions(L, "ray_cast", kRayCastOptions);
  const Vec2 from = o.vec("from"), to = o.vec("to");
  requireSpan(o, "to", "from", from, to, "the ray's length");
  const QueryFilter filter = readQueryFilter(o);
  return pushOptionalHit(L, scene, coreQuery(L, "ray_cast", [&] { return scene.world->rayCast(from, to, filter); }));
}

int rayCastAll(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "ray_cast_all");
  const Options o = queryOptions(L, "ray_cast_all", kRayCastOptions);
  const Vec2 from = o.vec("from"), to = o.vec("to");
  requireSpan(o, "to", "from", from, to, "the ray's length");
  const QueryFilter filter = readQueryFilter(o);
  const std::vector<RayHit> hits = coreQuery(L, "ray_cast_all", [&] { return scene.world->rayCastAll(from, to, filter); });
  lua_createtable(L, static_cast<int>(hits.size()), 0);
  for (size_t i = 0; i < hits.size(); ++i) {
    pushHit(L, scene, hits[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

int queryBox(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "query_box");
  const Options o = queryOptions(L, "query_box", kQueryBoxOptions);
  const Aabb box{o.vec("lower"), o.vec("upper")};
  if (box.upper.x() < box.lower.x() || box.upper.y() < box.lower.y())
    o.fail("upper", "must be above and right of lower (upper >= lower in x and y), got lower " +
                        formatVec(box.lower) + " and upper " + formatVec(box.upper));
  requireSpan(o, "upper", "lower", box.lower, box.upper, "the box's size");
  const QueryFilter filter = readQueryFilter(o);
  return pushShapes(L, scene, coreQuery(L, "query_box", [&] { return scene.world->queryBox(box, filter); }));
}

int queryPoint(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "query_point");
  const Options o = queryOptions(L, "query_point", kQueryPointOptions);
  const Vec2 point = o.vec("point");
  const QueryFilter filter = readQueryFilter(o);
  return pushShapes(L, scene, coreQuery(L, "query_point", [&] { return scene.world->queryPoint(point, filter); }));
}

int overlap(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "overlap");
  const Options o = queryOptions(L, "overlap", kOverlapOptions);
  const Shape shape = queryShape(o);
  const Transform xf{o.vec("position", Vec2::Zero()), Rot::fromAngle(o.number("angle", 0.0))};
  const QueryFilter filter = readQueryFilter(o);
  return pushShapes(L, scene, coreQuery(L, "overlap", [&] { return scene.world->overlap(shape, xf, filter); }));
}

int shapeCast(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "shape_cast");
  const Options o = queryOptions(L, "shape_cast", kShapeCastOptions);
  const Shape shape = queryShape(o);
  const Vec2 from = o.vec("from"), to = o.vec("to");
  requireSpan(o, "to", "from", from, to, "the cast's length");
  const Transform xf{from, Rot::fromAngle(o.number("angle", 0.0))};
  const QueryFilter filter = readQueryFilter(o);
  return pushOptionalHit(L, scene,
                         coreQuery(L, "shape_cast", [&] { return scene.world->shapeCast(shape, xf, to - from, filter); }));
}

int explode(lua_State* L) {
  Scene::Impl& scene = editedWorld(L, "explode");
  const Options o(L, "explode", sol::stack_object(L, 2), kExplodeOptions);
  ExplosionDef e;
  e.position = o.vec("position");
  e.radius = o.positive("radius", e.radius);
  e.falloff = o.nonNegative("falloff", e.falloff);
  e.impulse = o.nonNegative("impulse", e.impulse);
  // Distances are compared through their squares: a reach whose square overflows would miss bodies
  // whose distance from a far position overflows too, silently.
  if (!std::isfinite((e.radius + e.falloff) * (e.radius + e.falloff)))
    o.fail(e.falloff > e.radius ? "falloff" : "radius",
           "is too large: radius + falloff (" + formatNumber(e.radius + e.falloff) +
               ") must be below about 1e154 m (its square overflows)");
  e.filter.category = o.bits("category", e.filter.category);
  e.filter.mask = o.bits("mask", e.filter.mask);
  const std::vector<BodyId> pushed = coreQuery(L, "explode", [&] { return scene.world->explode(e); });
  pushHandles(L, pushed, [&](BodyId id) { return bodyHandle(L, scene, id); });
  return 1;
}

}  // namespace

int pushOptionalHit(lua_State* L, Scene::Impl& scene, const std::optional<RayHit>& h) {
  if (!h) return 0;  // nil
  pushHit(L, scene, *h);
  return 1;
}

lua_CFunction queryWorldMethod(std::string_view name) {
  static const NamedFunction kMethods[] = {
      {"ray_cast", guarded<rayCast>},     {"ray_cast_all", guarded<rayCastAll>}, {"query_box", guarded<queryBox>},
      {"query_point", guarded<queryPoint>}, {"overlap", guarded<overlap>},     {"shape_cast", guarded<shapeCast>},
      {"explode", guarded<explode>},      {"contact_events", contactEventsMethod},
      {"contacts", worldContactsMethod}};
  return lookUp(kMethods, name);
}

}  // namespace rigidlab::lua

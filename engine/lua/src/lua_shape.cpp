// Shape handles in Lua: body:add_shape{...} returns one, body.shapes lists them.
//
//   read        kind ("circle" | "polygon" | "capsule" | "segment" | "chain_segment"), body, mass,
//               area, inertia (about the shape's centroid), bounds ({lower, upper}, world), removed
//   read/write  the geometry, body coordinates: radius (circles, capsules), center (circles; the
//               centroid of the others, read only), vertices (polygons), a, b (capsules, segments,
//               chain segments), ghost1, ghost2 (chain segments: the chain's points around them);
//               density, restitution, friction, static_friction, sensor, category, mask, group,
//               tangent_speed, rolling_resistance, user_data; the event fields contact_events,
//               hit_events, hit_speed, one_way, pre_solve (lua_events.cpp)
//   methods     shape:remove(), shape:test_point(p), shape:ray_cast{from, to},
//               shape:distance(other) → distance, point on this shape, point on the other
// The shape properties of a body (body.friction, body.category, ...) read and write the same
// values for all of its shapes (shapeProperty, setShapeProperty).
#include "lua_shape.h"

#include <algorithm>

#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"
#include "lua_body_args.h"
#include "lua_events.h"
#include "lua_query.h"
#include "rigidlab/error.h"

namespace rigidlab::lua {
namespace {

using api::kShapeReadable;
using api::kShapeWritable;

const LuaShape& selfShape(lua_State* L, std::string_view function) {
  const LuaShape* s = toHandle<LuaShape>(L, 1);
  if (!s) fail(L, function, "call it as shape:" + std::string(function) + "(...), with a colon; got " + describe(L, 1));
  return *s;
}

int addShape(lua_State* L) {
  const LuaBody* handle = toHandle<LuaBody>(L, 1);
  if (!handle)
    fail(L, "add_shape", "call it as body:add_shape{...}, with a colon; got " + describe(L, 1) + " as the body");
  Scene::Impl& scene = *handle->scene;
  requireIdle(L, scene, "add_shape");
  const BodyId body = liveBody(L, *handle, "add_shape");
  const Options o(L, "add_shape", sol::stack_object(L, 2), joined({&api::kAddShapeOptions, &api::kShapeOptions}));
  const ShapeKind kind = shapeKind(o, "shape");
  refuseOtherGeometry(o, kind, "offset and angle");
  World& world = *scene.world;
  ShapeDef def = readShapeOptions(o, kind != ShapeKind::Segment);
  def.shape = readGeometry(o, kind);
  const Vec2 offset = o.vec("offset", Vec2::Zero());
  const double angle = o.number("angle", 0.0);
  if (kind == ShapeKind::Segment && world.body(body).isDynamic())
    o.fail("shape",
           "\"segment\" needs a static or kinematic body, and this one is dynamic: a segment has no area "
           "(use a capsule or a thin box)");
  ShapeId id;
  try {
    if (offset != Vec2::Zero() || angle != 0.0) def.shape = transformShape(def.shape, offset, angle);
    id = world.createShape(body, def);
  } catch (const InputError& e) {
    failCore(L, "add_shape", e);
  }
  scene.shape_user_data.raw_set(static_cast<lua_Integer>(handleKey(id.index, id.generation)),
                                o.has("user_data") ? o.get("user_data") : sol::make_object(L, sol::lua_nil));
  try {
    attachShapeEvents(L, scene, o, id);
    scene.host->charge(L, "add_shape", shapeHostBytes(world.shape(id)));
  } catch (...) {
    world.destroyShape(id);  // over the memory limit: as if it had not been made
    throw;
  }
  shapeHandle(L, scene, id).push(L);
  return 1;
}

int removeShapeMethod(lua_State* L) {
  const LuaShape& s = selfShape(L, "remove");
  requireIdle(L, *s.scene, "remove");
  if (liveWorld(L, *s.scene, "remove").isValid(s.id)) removeShape(L, *s.scene, s.id);
  return 0;  // removing a removed shape does nothing, as for forces
}

int testPoint(lua_State* L) {
  const LuaShape& self = selfShape(L, "test_point");
  const World& w = liveWorld(L, *self.scene, "test_point");
  const BodyShape& s = w.shape(liveShape(L, self, "test_point"));
  const Vec2 p = checkVec(L, "test_point", "point", sol::stack_object(L, 2));
  lua_pushboolean(L, containsPoint(s.geometry, w.body(s.body).xf, p));
  return 1;
}

int rayCast(lua_State* L) {
  const LuaShape& self = selfShape(L, "ray_cast");
  const World& w = liveWorld(L, *self.scene, "ray_cast");
  const ShapeId id = liveShape(L, self, "ray_cast");
  const Options o(L, "ray_cast", sol::stack_object(L, 2), api::kRayCastOptions);
  const Vec2 from = o.vec("from"), to = o.vec("to");
  return pushOptionalHit(L, *self.scene, w.shapeRayCast(id, from, to));
}

int distanceMethod(lua_State* L) {
  const LuaShape& self = selfShape(L, "distance");
  const World& w = liveWorld(L, *self.scene, "distance");
  const ShapeId id = liveShape(L, self, "distance");
  const LuaShape* other = toHandle<LuaShape>(L, 2);
  if (!other) fail(L, "distance", "other must be a shape (body.shapes[i], body:add_shape), got " + describe(L, 2));
  if (other->scene != self.scene) fail(L, "distance", "other is a shape of another scene");
  Vec2 on_self = Vec2::Zero(), on_other = Vec2::Zero();
  const double d = w.distanceBetween(id, liveShape(L, *other, "distance"), &on_self, &on_other);
  lua_pushnumber(L, d);
  pushVec(L, on_self);
  pushVec(L, on_other);
  return 3;
}

void pushBounds(lua_State* L, const Aabb& box) {
  lua_createtable(L, 0, 2);
  pushVec(L, box.lower);
  lua_setfield(L, -2, "lower");
  pushVec(L, box.upper);
  lua_setfield(L, -2, "upper");
}

// The shape's geometry with the field `k` set to `value` (shape.radius = ..., shape.vertices = ...),
// or a refusal naming what the kind has.
Shape changedGeometry(lua_State* L, const Shape& g, std::string_view function, std::string_view k, const sol::object& value) {
  const char* kind = shapeTypeName(g.type);
  const auto refuse = [&](const char* has) {
    fail(L, function, std::string("a ") + kind + " has no " + std::string(k) + " to set (it has " + has + ")");
  };
  const auto point = [&] { return checkVec(L, function, "", value); };
  switch (g.type) {
    case ShapeType::Circle:
      if (k == "radius") return makeCircle(checkNumber(L, function, "", value, Range::Positive), g.center);
      if (k == "center") return makeCircle(g.radius, point());
      refuse("radius, center");
      break;
    case ShapeType::Capsule:
      if (k == "radius") return makeCapsule(g.vertices[0], g.vertices[1], checkNumber(L, function, "", value, Range::Positive));
      if (k == "a") return makeCapsule(point(), g.vertices[1], g.radius);
      if (k == "b") return makeCapsule(g.vertices[0], point(), g.radius);
      if (k == "center") fail(L, function, "is read-only for a capsule: it is the middle of a and b");
      refuse("a, b, radius");
      break;
    case ShapeType::Polygon:
      if (k == "vertices") {
        const std::vector<Vec2> points = checkPoints(L, function, "", value, 0, kMaxPolygonVertices);
        return makePolygon(points);
      }
      if (k == "center") fail(L, function, "is read-only for a polygon: its centroid follows its vertices");
      refuse("vertices");
      break;
    case ShapeType::Segment:
      if (k == "a") return makeSegment(point(), g.vertices[1]);
      if (k == "b") return makeSegment(g.vertices[0], point());
      refuse("a, b");
      break;
    case ShapeType::ChainSegment:
      if (k == "a") return makeChainSegment(g.ghost1, point(), g.vertices[1], g.ghost2);
      if (k == "b") return makeChainSegment(g.ghost1, g.vertices[0], point(), g.ghost2);
      if (k == "ghost1") return makeChainSegment(point(), g.vertices[0], g.vertices[1], g.ghost2);
      if (k == "ghost2") return makeChainSegment(g.ghost1, g.vertices[0], g.vertices[1], point());
      refuse("a, b, ghost1, ghost2");
      break;
  }
  return g;
}

bool isGeometryField(std::string_view k) {
  return k == "radius" || k == "center" || k == "vertices" || k == "a" || k == "b" || k == "ghost1" || k == "ghost2";
}

void pushPoints(lua_State* L, const std::vector<Vec2>& points) {
  lua_createtable(L, static_cast<int>(points.size()), 0);
  for (size_t i = 0; i < points.size(); ++i) {
    pushVec(L, points[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

int shapeIndex(lua_State* L) {
  const LuaShape& self = selfShape(L, "shape");
  sol::stack_object key(L, 2);
  const std::string k = fieldName(L, "shape", key);
  const World& w = liveWorld(L, *self.scene, "shape." + k);
  if (k == "removed") {
    lua_pushboolean(L, !w.isValid(self.id));
    return 1;
  }
  if (k == "remove" || k == "test_point" || k == "ray_cast" || k == "distance") {
    lua_pushcfunction(L, k == "remove"       ? guarded<removeShapeMethod>
                         : k == "test_point" ? guarded<testPoint>
                         : k == "ray_cast"   ? guarded<rayCast>
                                             : guarded<distanceMethod>);
    return 1;
  }
  if (std::find(kShapeReadable.begin(), kShapeReadable.end(), k) == kShapeReadable.end())
    noSuchField(L, "shape", k, kShapeReadable);
  if (k == "user_data") {  // also of a removed shape: what the script gave it
    self.scene->shape_user_data.raw_get<sol::object>(static_cast<lua_Integer>(handleKey(self.id.index, self.id.generation))).push(L);
    return 1;
  }
  const BodyShape& s = w.shape(liveShape(L, self, "shape." + k));
  const Shape& g = s.geometry;
  const bool two_points =
      g.type == ShapeType::Capsule || g.type == ShapeType::Segment || g.type == ShapeType::ChainSegment;
  if (k == "kind") {
    lua_pushstring(L, shapeTypeName(g.type));
  } else if (k == "body") {
    bodyHandle(L, *self.scene, s.body).push(L);
  } else if (k == "radius") {
    if (g.type != ShapeType::Circle && g.type != ShapeType::Capsule) return 0;  // nil
    lua_pushnumber(L, g.radius);
  } else if (k == "center") {
    pushVec(L, g.type == ShapeType::Circle ? g.center
               : hasArea(g.type)           ? computeMass(g, 1.0).center
                                           : Vec2(0.5 * (g.vertices[0] + g.vertices[1])));
  } else if (k == "vertices") {
    if (g.type != ShapeType::Polygon) return 0;
    pushPoints(L, g.vertices);
  } else if (k == "a" || k == "b") {
    if (!two_points) return 0;
    pushVec(L, g.vertices[k == "a" ? 0 : 1]);
  } else if (k == "ghost1" || k == "ghost2") {
    if (g.type != ShapeType::ChainSegment) return 0;
    pushVec(L, k == "ghost1" ? g.ghost1 : g.ghost2);
  } else if (k == "mass") {
    lua_pushnumber(L, hasArea(g.type) ? computeMass(g, s.density).mass : 0.0);
  } else if (k == "area") {
    lua_pushnumber(L, hasArea(g.type) ? computeMass(g, 1.0).area : 0.0);
  } else if (k == "inertia") {
    lua_pushnumber(L, hasArea(g.type) ? computeMass(g, s.density).inertia : 0.0);
  } else if (k == "bounds") {
    pushBounds(L, computeAabb(g, w.body(s.body).xf));
  } else if (k == "tangent_speed" || k == "rolling_resistance") {
    lua_pushnumber(L, k == "tangent_speed" ? s.tangent_speed : s.rolling_resistance);
  } else if (!pushShapeEventField(L, *self.scene, s, k)) {
    shapeProperty(L, s, k).push(L);
  }
  return 1;
}

int shapeNewIndex(lua_State* L) {
  const LuaShape& self = selfShape(L, "shape");
  sol::stack_object key(L, 2);
  const std::string k = fieldName(L, "shape", key);
  const std::string function = "shape." + k;
  requireWritable(L, "shape", k, kShapeReadable, kShapeWritable);
  requireIdle(L, *self.scene, function);
  World& w = liveWorld(L, *self.scene, function);
  const ShapeId id = liveShape(L, self, function);
  const sol::stack_object value(L, 3);
  if (k == "user_data") {
    self.scene->shape_user_data.raw_set(static_cast<lua_Integer>(handleKey(id.index, id.generation)), sol::object(value));
    return 0;
  }
  try {
    const BodyShape& s = w.shape(id);
    if (isGeometryField(k)) {
      const Shape geometry = changedGeometry(L, s.geometry, function, k, value);
      w.setShapeGeometry(id, geometry);
      return 0;
    }
    if (k == "tangent_speed") {
      w.setShapeSurface(id, checkNumber(L, function, "", value, Range::Finite), s.rolling_resistance);
      return 0;
    }
    if (k == "rolling_resistance") {
      w.setShapeSurface(id, s.tangent_speed, checkNumber(L, function, "", value, Range::NonNegative));
      return 0;
    }
  } catch (const InputError& e) {
    failCore(L, function, e);
  }
  if (!setShapeEventField(L, *self.scene, id, function, k, value)) setShapeProperty(L, w, id, function, k, value);
  return 0;
}

}  // namespace

int addShapeMethod(lua_State* L) { return guarded<addShape>(L); }

sol::object shapeProperty(lua_State* L, const BodyShape& s, std::string_view name) {
  if (name == "density")
    return hasArea(s.geometry.type) ? sol::make_object(L, s.density) : sol::make_object(L, sol::lua_nil);
  if (name == "restitution") return sol::make_object(L, s.material.restitution);
  if (name == "friction") return sol::make_object(L, s.material.friction);
  if (name == "static_friction") return sol::make_object(L, s.material.static_friction);
  if (name == "sensor") return sol::make_object(L, s.sensor);
  // The bits as a Lua integer: the default mask, every bit, reads -1.
  if (name == "category") return sol::make_object(L, static_cast<lua_Integer>(s.filter.category));
  if (name == "mask") return sol::make_object(L, static_cast<lua_Integer>(s.filter.mask));
  if (name == "group") return sol::make_object(L, static_cast<lua_Integer>(s.filter.group));
  return sol::make_object(L, sol::lua_nil);
}

void setShapeProperty(lua_State* L, World& w, ShapeId id, std::string_view function, std::string_view name,
                      const sol::object& value) {
  const BodyShape& s = w.shape(id);
  Material m = s.material;
  Filter f = s.filter;
  try {
    if (name == "density") {
      if (!hasArea(s.geometry.type))
        fail(L, function, std::string("a ") + shapeTypeName(s.geometry.type) + " has no area, so no density");
      w.setShapeDensity(id, checkNumber(L, function, "", value, Range::Positive));
    } else if (name == "sensor") {
      w.setShapeSensor(id, checkBool(L, function, "", value));
    } else if (name == "category" || name == "mask" || name == "group") {
      if (name == "category") f.category = checkBits(L, function, "", value);
      if (name == "mask") f.mask = checkBits(L, function, "", value);
      if (name == "group") f.group = static_cast<int32_t>(checkInteger(L, function, "", value, INT32_MIN, INT32_MAX));
      w.setShapeFilter(id, f);
    } else {
      const double x = checkNumber(L, function, "", value, Range::NonNegative);
      if (name == "restitution" && x > 1.0) fail(L, function, "must be between 0 and 1, got " + formatNumber(x));
      if (name == "restitution") m.restitution = x;
      if (name == "friction") m.friction = x;
      if (name == "static_friction") m.static_friction = x;
      w.setShapeMaterial(id, m);
    }
  } catch (const InputError& e) {
    failCore(L, function, e);
  }
}

void registerShapeType(lua_State* L) {
  registerHandleType(L, LuaShape::kMetatable, guarded<shapeIndex>, guarded<shapeNewIndex>,
                     guarded<handleToString<LuaShape, describeShape>>, guarded<handlesEqual<LuaShape, &LuaShape::id>>);
}

sol::object shapeHandle(lua_State* L, Scene::Impl& scene, ShapeId id) {
  return cachedHandle(L, scene.shape_handles, handleKey(id.index, id.generation), LuaShape{&scene, id});
}

void pushShapeHandle(lua_State* L, Scene::Impl& scene, ShapeId id) {
  pushCachedHandle(L, scene.shape_handles, handleKey(id.index, id.generation), LuaShape{&scene, id});
}

ShapeId liveShape(lua_State* L, const LuaShape& shape, std::string_view function) {
  if (!liveWorld(L, *shape.scene, function).isValid(shape.id))
    fail(L, function, "the shape was removed (by shape:remove() or with its body)");
  return shape.id;
}

void forgetShapeUserData(Scene::Impl& scene, ShapeId id) {
  scene.shape_user_data.raw_set(static_cast<lua_Integer>(handleKey(id.index, id.generation)), sol::lua_nil);
}

void removeShape(lua_State* L, Scene::Impl& scene, ShapeId id) {
  World& w = liveWorld(L, scene, "remove");
  const size_t bytes = shapeHostBytes(w.shape(id));
  forgetShapeEvents(scene, id);
  forgetShapeUserData(scene, id);
  w.destroyShape(id);
  scene.host->release(bytes);
}

std::string describeShape(const LuaShape& shape) {
  const World* w = shape.scene->world.get();
  if (!w || !w->isValid(shape.id)) return "shape (removed)";
  return std::string(shapeTypeName(w->shape(shape.id).geometry.type)) + " shape";
}

}  // namespace rigidlab::lua

// Shapes attached to bodies: creation, removal, chains, and the body's mass summed over its shapes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rigidlab/error.h"
#include "rigidlab/world.h"
#include "shape_query.h"
#include "world_impl.h"

namespace rigidlab {

Shape WorldImpl::validatedShape(const Shape& s) {
  const auto two = [&](const char* kind) {
    if (s.vertices.size() != 2)
      throw InputError("vertices", std::string("a ") + kind + " has two points a and b, got " + std::to_string(s.vertices.size()));
  };
  switch (s.type) {
    case ShapeType::Circle: return makeCircle(s.radius, s.center);
    case ShapeType::Polygon: return makePolygon(s.vertices);  // re-validates and normalises a hand-built polygon
    case ShapeType::Capsule: two("capsule"); return makeCapsule(s.vertices[0], s.vertices[1], s.radius);
    case ShapeType::Segment: two("segment"); return makeSegment(s.vertices[0], s.vertices[1]);
    case ShapeType::ChainSegment:
      two("chain segment");
      return makeChainSegment(s.ghost1, s.vertices[0], s.vertices[1], s.ghost2);
  }
  throw InputError("shape", "unknown shape kind");
}

Material WorldImpl::validatedMaterial(double restitution, double friction, double static_friction) {
  requireNonNegative("restitution", restitution);
  if (restitution > 1.0)
    throw InputError("restitution", "restitution must be between 0 and 1, got " + formatNumber(restitution));
  return {restitution, requireNonNegative("friction", friction), requireNonNegative("static_friction", static_friction)};
}

BodyShape& WorldImpl::get(ShapeId id) {
  if (!isLive(id)) throw InputError("shape", "shape handle is not valid (the shape or its body was removed)");
  return shapes[id.index];
}

// Mass properties of the body from its shapes (docs/design/thesis.md §3; parallel-axis theorem):
//   M = Σ m_i,   C = Σ m_i c_i / M,   I = Σ (I_i + m_i |c_i − C|²)
// One shape: its own values, exactly. `field` and `value`: the input the densities came from, for
// the error message.
void WorldImpl::updateMass(Body& b, const char* field, double value) {
  double area = 0.0, mass = 0.0, inertia = 0.0;
  Vec2 center = Vec2::Zero();
  std::vector<MassData> parts;
  for (ShapeId s : b.shapes) {
    const BodyShape& shape = shapes[s.index];
    if (!hasArea(shape.geometry.type)) continue;
    parts.push_back(computeMass(shape.geometry, shape.density));
  }
  if (parts.size() == 1) {
    area = parts[0].area;
    mass = parts[0].mass;
    center = parts[0].center;
    inertia = parts[0].inertia;
  } else if (!parts.empty()) {
    for (const MassData& p : parts) {
      area += p.area;
      mass += p.mass;
      center += p.mass * p.center;
    }
    center /= mass;
    for (const MassData& p : parts) inertia += p.inertia + p.mass * (p.center - center).squaredNorm();
  }
  if (parts.empty()) {
    mass = 1.0;  // a body without area: a unit point mass, so that it can still be dynamic
    inertia = 1.0;
  }
  if (b.inertia_set) inertia = b.inertia;  // World::setInertia's, until the shapes change
  // A mass or inertia whose inverse is not finite (a denormal mass: 1/4.9e-324 = inf) or that
  // overflowed (density 1e308 on a large shape) would reach the solver as ∞ or 0·∞ = NaN.
  const auto usable = [](double x) { return std::isfinite(x) && x > 0.0 && std::isfinite(1.0 / x); };
  if (!usable(mass) || !usable(inertia) || !isFinite(center)) throw massError(field, mass, inertia, value);
  // The centre of mass may move (a shape added off-centre): the body keeps its origin and the
  // velocity of its material points, v_new = v + ω × (c_new − c_old). A finite position near the
  // largest double can still put it out of range: refused naming position (fuzz_world).
  const Vec2 new_center = b.xf.apply(center);
  if (!isFinite(new_center))
    throw InputError("position", "position " + formatVec(b.xf.p) + " puts the centre of mass out of range, at " +
                                     formatVec(new_center));
  if (b.isDynamic() || b.isKinematic()) b.velocity += cross(b.angular_velocity, new_center - b.center);
  b.center = new_center;
  if (parts.size() == 1) {
    b.density = shapes[b.shapes[0].index].density;
  } else if (!parts.empty()) {
    b.density = mass / area;
  }
  b.area = area;
  b.mass = mass;
  b.inertia = inertia;
  b.local_center = center;
  b.inv_mass = b.isDynamic() ? 1.0 / b.mass : 0.0;
  b.inv_inertia = b.isDynamic() && !b.fixed_rotation ? 1.0 / b.inertia : 0.0;
  b.min_inradius = std::numeric_limits<double>::infinity();
  b.max_extent = 0.0;
  for (ShapeId s : b.shapes) {
    const BodyShape& shape = shapes[s.index];
    if (shape.sensor) continue;
    b.min_inradius = std::min(b.min_inradius, shape.geometry.inradius);
    b.max_extent = std::max(b.max_extent, maxExtent(shape.geometry));
  }
}

InputError WorldImpl::massError(const char* field, double mass, double inertia, double value) {
  return InputError(field, "mass and moment of inertia must be finite with finite inverses, got " + formatNumber(mass) +
                               " kg and " + formatNumber(inertia) + " kg·m² (from " + field + " " + formatNumber(value) +
                               " and the shape's size)");
}

uint32_t WorldImpl::attachShape(uint32_t body, const ShapeDef& def, const char* field, double value, bool update_mass) {
  Body& b = bodies[body];
  BodyShape s;
  s.geometry = validatedShape(def.shape);
  if (b.isDynamic() && !hasArea(s.geometry.type))
    throw InputError("shape", std::string("a ") + shapeTypeName(s.geometry.type) +
                                  " has no area, so only static and kinematic bodies may have one (use a capsule or a thin box)");
  s.density = hasArea(s.geometry.type) ? requirePositive("density", def.density) : def.density;
  s.material = validatedMaterial(def.material.restitution, def.material.friction, def.material.static_friction);
  s.filter = def.filter;
  s.default_filter = def.filter == Filter{};
  s.sensor = def.sensor;
  s.contact_events = def.contact_events;
  s.hit_events = def.hit_events;
  s.hit_speed = requireNonNegative("hit_speed", def.hit_speed);
  if (def.one_way) {
    requireFinite("one_way", *def.one_way);
    if (!(def.one_way->norm() > 0.0)) throw InputError("one_way", "one_way must be a direction, got " + formatVec(*def.one_way));
    s.one_way = def.one_way->normalized();
  }
  s.pre_solve = def.pre_solve;
  s.tangent_speed = requireFinite("tangent_speed", def.tangent_speed);
  s.rolling_resistance = requireNonNegative("rolling_resistance", def.rolling_resistance);
  s.body = b.id;
  uint32_t index;
  if (!free_shapes.empty()) {
    index = free_shapes.back();
    free_shapes.pop_back();
    s.id = {index, shapes[index].id.generation + 1};
    shapes[index] = std::move(s);
    shape_alive[index] = 1;
  } else {
    index = static_cast<uint32_t>(shapes.size());
    s.id = {index, 0};
    shapes.push_back(std::move(s));
    shape_alive.push_back(1);
  }
  b.shapes.push_back(shapes[index].id);
  b.inertia_set = false;  // the mass is the shapes' again
  countShape(shapes[index], +1);
  ++layout_version;
  shapesEdited();
  ++static_version;
  if (!update_mass) return index;
  try {
    updateMass(b, field, value);
  } catch (...) {
    b.shapes.pop_back();
    releaseShape(index);
    throw;
  }
  return index;
}

void WorldImpl::releaseShape(uint32_t index) {
  countShape(shapes[index], -1);
  if (index < sensor_overlaps.size()) sensor_overlaps[index].clear();
  shape_alive[index] = 0;
  ++layout_version;
  shapesEdited();
  const ShapeId old = shapes[index].id;
  shapes[index] = BodyShape{};
  shapes[index].id = old;  // the next shape in this slot gets a new generation
  free_shapes.push_back(index);
}

ShapeId World::createShape(BodyId body, const ShapeDef& def) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("createShape");
  const Body& b = w.get(body);
  if (b.awake || w.created_asleep_before[body.index] != w.step_count + 1) w.wakeIsland(body.index);
  return w.shapes[w.attachShape(body.index, def, "density", def.density)].id;
}

void World::destroyShape(ShapeId id) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("destroyShape");
  const BodyShape& s = w.get(id);
  const uint32_t body = s.body.index;
  for (const Contact& c : w.contacts)  // what it held may now move
    if (c.shape_a == id.index || c.shape_b == id.index) {
      w.wakeIsland(c.a);
      w.wakeIsland(c.b);
    }
  const auto refersToShape = [&](const auto& c) { return c.shape_a == id.index || c.shape_b == id.index; };
  // Keys stay index for index with the contacts: erase both by the contacts' flags.
  std::vector<char> drop(w.contacts.size());
  for (size_t i = 0; i < w.contacts.size(); ++i) drop[i] = refersToShape(w.contacts[i]);
  size_t kept = 0;
  for (size_t i = 0; i < w.contacts.size(); ++i)
    if (!drop[i]) {
      w.contacts[kept] = w.contacts[i];
      w.contact_keys[kept++] = w.contact_keys[i];
    }
  w.contacts.resize(kept);
  w.contact_keys.resize(kept);
  w.contact_surfaces.clear();  // index for index with the contacts no more
  std::erase_if(w.previous_contacts, refersToShape);
  Body& b = w.bodies[body];
  std::erase(b.shapes, id);
  w.releaseShape(id.index);
  b.inertia_set = false;
  w.updateMass(b, "density", b.density);
  w.wakeIsland(body);
}

bool World::isValid(ShapeId id) const { return impl_->isLive(id); }
const BodyShape& World::shape(ShapeId id) const { return impl_->get(id); }

void World::setShapeMaterial(ShapeId id, const Material& m) {
  impl_->requireUnlocked("setShapeMaterial");
  impl_->get(id).material = WorldImpl::validatedMaterial(m.restitution, m.friction, m.static_friction);
  impl_->shapesEdited();
}

void World::setShapeFilter(ShapeId id, const Filter& filter) {
  impl_->requireUnlocked("setShapeFilter");
  BodyShape& s = impl_->get(id);
  s.filter = filter;
  s.default_filter = filter == Filter{};
  impl_->shapesEdited();
  ++impl_->layout_version;  // the queries' copy of the filter (WorldImpl::tree_shapes)
  impl_->wakeIsland(s.body.index);
}

void World::setShapeDensity(ShapeId id, double density) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setShapeDensity");
  BodyShape& s = w.get(id);
  requirePositive("density", density);
  const double old = s.density;
  s.density = density;
  Body& b = w.bodies[s.body.index];
  b.inertia_set = false;
  try {
    w.updateMass(b, "density", density);
  } catch (...) {
    s.density = old;
    throw;
  }
  w.wakeIsland(s.body.index);
}

void World::setShapeSensor(ShapeId id, bool sensor) {
  impl_->requireUnlocked("setShapeSensor");
  BodyShape& s = impl_->get(id);
  impl_->countShape(s, -1);
  s.sensor = sensor;
  impl_->shapesEdited();
  ++impl_->layout_version;  // the queries' copy of the flag (WorldImpl::tree_shapes)
  impl_->countShape(s, +1);
  impl_->updateMass(impl_->bodies[s.body.index], "density", s.density);  // the CCD bounds change
  impl_->wakeIsland(s.body.index);
}

void World::setBodySensor(BodyId id, bool sensor) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setBodySensor");
  Body& b = w.get(id);
  for (ShapeId s : b.shapes) {
    BodyShape& shape = w.shapes[s.index];
    w.countShape(shape, -1);
    shape.sensor = sensor;
    w.countShape(shape, +1);
  }
  w.shapesEdited();
  ++w.layout_version;  // the queries' copy of the flag (WorldImpl::tree_shapes)
  w.updateMass(b, "density", b.density);  // the CCD bounds change
  w.wakeIsland(id.index);
}

void World::setShapeEvents(ShapeId id, bool contact_events, bool hit_events, double hit_speed) {
  impl_->requireUnlocked("setShapeEvents");
  BodyShape& s = impl_->get(id);
  requireNonNegative("hit_speed", hit_speed);
  impl_->countShape(s, -1);
  s.contact_events = contact_events;
  s.hit_events = hit_events;
  s.hit_speed = hit_speed;
  impl_->countShape(s, +1);
}

void World::setShapeOneWay(ShapeId id, std::optional<Vec2> normal) {
  impl_->requireUnlocked("setShapeOneWay");
  BodyShape& s = impl_->get(id);
  if (normal) {
    requireFinite("one_way", *normal);
    if (!(normal->norm() > 0.0)) throw InputError("one_way", "one_way must be a direction, got " + formatVec(*normal));
    normal = normal->normalized();
  }
  impl_->countShape(s, -1);
  s.one_way = normal;
  impl_->countShape(s, +1);
  impl_->wakeIsland(s.body.index);
}

void World::setShapePreSolve(ShapeId id, bool on) {
  impl_->requireUnlocked("setShapePreSolve");
  BodyShape& s = impl_->get(id);
  impl_->countShape(s, -1);
  s.pre_solve = on;
  impl_->countShape(s, +1);
}

namespace {

// What touches the shape wakes (its contacts' bodies), and the shape's own body.
void wakeShapeContacts(WorldImpl& w, uint32_t shape) {
  for (const Contact& c : w.contacts)
    if (c.shape_a == shape || c.shape_b == shape) {
      w.wakeIsland(c.a);
      w.wakeIsland(c.b);
    }
  w.wakeIsland(w.shapes[shape].body.index);
}

}  // namespace

void World::setShapeSurface(ShapeId id, double tangent_speed, double rolling_resistance) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setShapeSurface");
  BodyShape& s = w.get(id);
  requireFinite("tangent_speed", tangent_speed);
  requireNonNegative("rolling_resistance", rolling_resistance);
  w.countShape(s, -1);
  s.tangent_speed = tangent_speed;
  s.rolling_resistance = rolling_resistance;
  w.countShape(s, +1);
  wakeShapeContacts(w, id.index);  // a belt switched on moves what rests on it
}

void World::setShapeGeometry(ShapeId id, const Shape& geometry) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setShapeGeometry");
  BodyShape& s = w.get(id);
  if (geometry.type != s.geometry.type)
    throw InputError("shape", std::string("a ") + shapeTypeName(s.geometry.type) + " stays a " +
                                  shapeTypeName(s.geometry.type) + ", got a " + shapeTypeName(geometry.type) +
                                  " (remove the shape and add another)");
  Shape checked = WorldImpl::validatedShape(geometry);
  Body& b = w.bodies[s.body.index];
  std::swap(s.geometry, checked);
  const bool inertia_set = b.inertia_set;
  b.inertia_set = false;
  try {
    w.updateMass(b, "density", s.density);
  } catch (...) {
    std::swap(s.geometry, checked);
    b.inertia_set = inertia_set;
    throw;
  }
  ++w.layout_version;
  ++w.static_version;
  w.shapesEdited();
  wakeShapeContacts(w, id.index);
}

std::optional<RayHit> World::shapeRayCast(ShapeId id, const Vec2& from, const Vec2& to) const {
  const WorldImpl& w = *impl_;
  const BodyShape& s = const_cast<WorldImpl&>(w).get(id);
  requireFinite("from", from);
  requireFinite("to", to);
  const std::optional<ShapeRayHit> h = rigidlab::rayCastShape(s.geometry, w.bodies[s.body.index].xf, from, to, 1.0);
  if (!h) return std::nullopt;
  return RayHit{id, s.body, h->point, h->normal, h->fraction};
}

double World::distanceBetween(ShapeId a, ShapeId b, Vec2* on_a, Vec2* on_b) const {
  WorldImpl& w = const_cast<WorldImpl&>(*impl_);
  const BodyShape &sa = w.get(a), &sb = w.get(b);
  return rigidlab::shapeDistance(sa.geometry, w.bodies[sa.body.index].xf, sb.geometry, w.bodies[sb.body.index].xf, on_a,
                                 on_b);
}

std::vector<ShapeId> World::createChain(BodyId body, const ChainDef& def) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("createChain");
  const Body& b = w.get(body);
  if (!b.isStatic()) throw InputError("body", std::string("chains are for static bodies; this body is ") + bodyTypeName(b.type));
  const size_t n = def.points.size();
  if (n < (def.loop ? 3u : 2u))
    throw InputError("points", std::string(def.loop ? "a loop" : "a chain") + " needs at least " + (def.loop ? "3" : "2") +
                                   " points, got " + std::to_string(n));
  const auto field = [](size_t i) { return "points[" + std::to_string(i + 1) + "]"; };
  for (size_t i = 0; i < n; ++i) {
    requireFinite(field(i), def.points[i]);
    requireNearOrigin(field(i), def.points[i]);
  }
  for (size_t i = 0; i + 1 < n || (def.loop && i < n); ++i) {
    const Vec2 &p = def.points[i], &q = def.points[(i + 1) % n];
    const size_t k = (i + 1) % n;
    if (!isFinite(q - p) || !std::isfinite((q - p).squaredNorm()))
      throw InputError(field(k), field(k) + " " + formatVec(q) + " is too far from the point before it, " + formatVec(p) +
                                     ": the segment's length overflows");
    const double size = std::max({p.norm(), q.norm(), 1e-300});
    if (!((q - p).norm() > 1e-9 * size))
      throw InputError(field(k), field(k) + " repeats the point before it, " + formatVec(q));
  }
  const Material material = WorldImpl::validatedMaterial(def.material.restitution, def.material.friction, def.material.static_friction);
  // Ghost vertices: the neighbours of each segment. An open chain's end segments have none at their
  // free ends (ghost = the end point itself): they collide like the end of a plain segment.
  const size_t segments = def.loop ? n : n - 1;
  const uint32_t chain = ++w.chains;
  std::vector<ShapeId> ids;
  ids.reserve(segments);
  Body& owner = w.bodies[body.index];
  // The mass once at the end (a static body's chain adds no area, so this cannot fail): each
  // segment's own update would cost the segments before it, n² for the chain.
  try {
    for (size_t i = 0; i < segments; ++i) {
      const Vec2& a = def.points[i];
      const Vec2& bb = def.points[(i + 1) % n];
      const Vec2 g1 = def.loop ? def.points[(i + n - 1) % n] : (i == 0 ? a : def.points[i - 1]);
      const Vec2 g2 = def.loop ? def.points[(i + 2) % n] : (i + 2 < n ? def.points[i + 2] : bb);
      ShapeDef sd;
      sd.shape = makeChainSegment(g1, a, bb, g2);
      sd.material = material;
      sd.filter = def.filter;
      sd.sensor = def.sensor;
      const uint32_t index = w.attachShape(body.index, sd, "density", 1.0, false);
      w.shapes[index].chain = chain;
      ids.push_back(w.shapes[index].id);
    }
  } catch (...) {
    w.updateMass(owner, "density", 1.0);
    throw;
  }
  w.updateMass(owner, "density", 1.0);
  return ids;
}

}  // namespace rigidlab

// Bodies: creation, removal and the setters that keep derived data (transform, inverse mass,
// sleep) consistent.
#include <algorithm>
#include <cmath>

#include "rigidlab/error.h"
#include "rigidlab/world.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

// The contacts' keys (contact.h: 12 bytes, index for index with the 320-byte contacts) name the
// same bodies, so the walks over what touches a body read them instead of the contacts.
void wakeTouching(WorldImpl& w, uint32_t slot) {  // what rested on it may now fall
  for (const ContactKey& k : w.contact_keys) {
    if (k.a == slot) w.wakeIsland(k.b);
    if (k.b == slot) w.wakeIsland(k.a);
  }
}

// Drops the contacts (and their keys) that refer to the slot, so contacts() never names a dead or
// disabled body. The step before last's contacts (previous_contacts) are left as they are: the
// next narrow phase clears them unread (narrow_phase.cpp, LastContacts).
void dropContacts(WorldImpl& w, uint32_t slot) {
  auto& keys = w.contact_keys;
  size_t kept = 0;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (keys[i].a == slot || keys[i].b == slot) continue;
    if (kept != i) {
      w.contacts[kept] = w.contacts[i];
      keys[kept] = keys[i];
    }
    ++kept;
  }
  w.contacts.resize(kept);
  keys.resize(kept);
  w.contact_surfaces.clear();  // index for index with the contacts no more
}

// Sets the body's transform and centre of mass from its origin and angle. A finite position near
// the largest double can still put the centre of mass (position + the rotated centre offset) out
// of range: refused naming position, so that no body starts with a non-finite state (fuzz_world).
void place(Body& b, const Vec2& position, double angle) {
  const Transform xf{position, Rot::fromAngle(angle)};
  const Vec2 center = xf.apply(b.local_center);
  if (!isFinite(center))
    throw InputError("position", "position " + formatVec(position) + " puts the centre of mass out of range, at " + formatVec(center));
  b.angle = angle;
  b.xf = xf;
  b.center = center;
}

bool hasShapeWithoutArea(const WorldImpl& w, const Body& b) {
  return std::any_of(b.shapes.begin(), b.shapes.end(),
                     [&](ShapeId s) { return !hasArea(w.shapes[s.index].geometry.type); });
}

}  // namespace

Body& WorldImpl::get(BodyId id) {
  if (!isLive(id)) throw InputError("body", "body handle is not valid (the body was removed or never existed)");
  return bodies[id.index];
}
const Body& WorldImpl::get(BodyId id) const { return const_cast<WorldImpl*>(this)->get(id); }

void WorldImpl::requireUnlocked(const char* what) const {
  if (locked)
    throw InputError(what, std::string(what) + " is not allowed while the world is stepping (e.g. from inside a force)");
}

BodyState WorldImpl::stateOf(const Body& b) {
  BodyState s;
  s.position = b.xf.p;
  s.center = b.center;
  s.angle = b.angle;
  s.q = b.xf.q;
  s.velocity = b.velocity;
  s.angular_velocity = b.angular_velocity;
  s.mass = b.mass;
  s.inertia = b.inertia;
  s.is_static = !b.isDynamic();
  s.id = b.id;
  s.uid = b.uid;
  return s;
}

const char* bodyTypeName(BodyType t) {
  switch (t) {
    case BodyType::Static: return "static";
    case BodyType::Kinematic: return "kinematic";
    case BodyType::Dynamic: return "dynamic";
  }
  return "?";
}

BodyId World::createBody(const BodyDef& def) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("createBody");
  // Everything is validated before anything is created, so a refused body leaves nothing behind.
  const Vec2 position = requireFinite("position", def.position);
  const double angle = requireFinite("angle", def.angle);
  const Vec2 velocity = requireFinite("velocity", def.velocity);
  const double angular_velocity = requireFinite("angular_velocity", def.angular_velocity);
  if (def.type == BodyType::Static && (velocity != Vec2::Zero() || angular_velocity != 0.0))
    throw InputError(velocity != Vec2::Zero() ? "velocity" : "angular_velocity",
                     "a static body cannot move: make it kinematic to give it a velocity");
  requireNonNegative("linear_damping", def.linear_damping);
  requireNonNegative("angular_damping", def.angular_damping);
  requireFinite("gravity_scale", def.gravity_scale);
  if (def.gravity) requireFinite("gravity", *def.gravity);
  ShapeDef shape_def;
  if (def.shape) {
    shape_def.shape = *def.shape;
    shape_def.material = WorldImpl::validatedMaterial(def.restitution, def.friction, def.static_friction.value_or(def.friction));
    shape_def.filter = def.filter;
    shape_def.sensor = def.sensor;
    if (def.mass) {
      requirePositive("mass", *def.mass);
      const Shape geometry = WorldImpl::validatedShape(*def.shape);
      if (!hasArea(geometry.type)) throw InputError("mass", std::string("a ") + shapeTypeName(geometry.type) + " has no area, so no mass");
      shape_def.density = *def.mass / computeMass(geometry, 1.0).area;
      if (!(std::isfinite(shape_def.density) && shape_def.density > 0.0)) {
        const MassData md = computeMass(geometry, shape_def.density);
        throw WorldImpl::massError("mass", md.mass, md.inertia, *def.mass);
      }
    } else {
      shape_def.density = requirePositive("density", def.density);
    }
  } else if (def.mass) {
    throw InputError("mass", "a body without shapes has no mass to set (add a shape, then set the mass)");
  }

  Body b;
  b.type = def.type;
  b.name = def.name;
  b.linear_damping = def.linear_damping;
  b.angular_damping = def.angular_damping;
  b.gravity_scale = def.gravity_scale;
  b.own_gravity = def.gravity.has_value();
  b.gravity = def.gravity.value_or(Vec2::Zero());
  b.sleeping_allowed = def.sleeping_allowed;
  b.fixed_rotation = def.fixed_rotation;
  b.bullet = def.bullet;
  b.enabled = def.enabled;
  // Only a dynamic body at rest may start asleep (a moving one would freeze in the air).
  const bool at_rest = def.velocity == Vec2::Zero() && def.angular_velocity == 0.0;
  b.awake = def.enabled && (def.awake || def.type != BodyType::Dynamic || !w.def.sleeping || !at_rest || !def.sleeping_allowed);
  w.updateMass(b, "density", 0.0);  // no shapes yet
  place(b, position, angle);

  uint32_t index;
  if (!w.free_bodies.empty()) {
    index = w.free_bodies.back();
    w.free_bodies.pop_back();
    b.id = {index, w.bodies[index].id.generation + 1};
    w.bodies[index] = std::move(b);
    w.alive[index] = 1;
  } else {
    index = static_cast<uint32_t>(w.bodies.size());
    b.id = {index, 0};
    w.bodies.push_back(std::move(b));
    w.alive.push_back(1);
  }
  const BodyId id = w.bodies[index].id;
  w.body_joints.resize(w.bodies.size());
  w.shapesEdited();  // the views point at the bodies, which may have moved
  w.created_asleep_before.resize(w.bodies.size());
  w.created_asleep_before[index] = w.bodies[index].awake ? 0 : w.step_count + 1;
  if (def.shape) {
    try {
      w.attachShape(index, shape_def, def.mass ? "mass" : "density", def.mass.value_or(def.density));
    } catch (...) {
      w.alive[index] = 0;  // nothing left behind: the slot goes back to the free list
      w.bodies[index].shapes.clear();
      w.free_bodies.push_back(index);
      throw;
    }
  }
  Body& body = w.bodies[index];
  body.uid = w.next_uid++;
  place(body, position, angle);  // the centre of mass moved with the shape
  if (body.isDynamic() || body.isKinematic()) {
    body.velocity = velocity;
    body.angular_velocity = body.fixed_rotation && body.isDynamic() ? 0.0 : angular_velocity;
  }
  if (body.isKinematic()) {
    ++w.kinematic_bodies;
    w.recordKinematicVelocity(index);
  }
  return id;
}

void World::destroyBody(BodyId id) {
  ++impl_->joint_edits;  // the energy watch lists the joints that put energy in anew
  WorldImpl& w = *impl_;
  w.requireUnlocked("destroyBody");
  w.get(id);
  for (uint32_t i = 0; i < w.forces.size(); ++i) {
    const ForceEntry& f = w.forces[i];
    if (f.alive && (f.a == id || f.b == id)) removeForce({i, f.generation});
  }
  wakeTouching(w, id.index);
  if (id.index < w.body_joints.size()) {
    const std::vector<uint32_t> joints = w.body_joints[id.index];  // releasing edits the list
    for (uint32_t k : joints)
      if (w.joints[k].alive) w.releaseJoint(k);
  }
  Body& b = w.bodies[id.index];
  if (b.isKinematic()) --w.kinematic_bodies;
  for (ShapeId s : b.shapes) w.releaseShape(s.index);
  w.shapesEdited();
  const BodyId old = b.id;
  b = Body{};
  b.id = old;  // keeps the generation, so the next body in this slot gets a new one
  b.uid = 0;
  w.alive[id.index] = 0;
  w.free_bodies.push_back(id.index);
  dropContacts(w, id.index);
}

bool World::isValid(BodyId id) const { return impl_->isLive(id); }
const Body& World::body(BodyId id) const { return impl_->get(id); }

std::vector<BodyId> World::bodyIds() const {
  std::vector<BodyId> ids;
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->alive[i]) ids.push_back(impl_->bodies[i].id);
  return ids;
}

int World::bodyCount() const { return static_cast<int>(std::count(impl_->alive.begin(), impl_->alive.end(), 1)); }

std::optional<BodyId> World::findBody(std::string_view name) const {
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->alive[i] && impl_->bodies[i].name == name) return impl_->bodies[i].id;
  return std::nullopt;
}

std::optional<BodyId> World::findBody(uint32_t uid) const {
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->alive[i] && impl_->bodies[i].uid == uid) return impl_->bodies[i].id;
  return std::nullopt;
}

void World::setTransform(BodyId id, const Vec2& position, double angle) {
  impl_->requireUnlocked("setTransform");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("position", position);
  requireFinite("angle", angle);
  place(b, position, angle);
  ++impl_->layout_version;
  ++impl_->static_version;
}

void World::setVelocity(BodyId id, const Vec2& velocity) {
  impl_->requireUnlocked("setVelocity");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("velocity", velocity);
  if (b.isStatic()) {
    if (velocity != Vec2::Zero())
      throw InputError("velocity", "a static body cannot move: make it kinematic to give it a velocity");
    return;
  }
  b.velocity = velocity;
}

void World::setAngularVelocity(BodyId id, double angular_velocity) {
  impl_->requireUnlocked("setAngularVelocity");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("angular_velocity", angular_velocity);
  if (b.isStatic()) {
    if (angular_velocity != 0.0)
      throw InputError("angular_velocity", "a static body cannot turn: make it kinematic to give it an angular velocity");
    return;
  }
  if (b.fixed_rotation && b.isDynamic()) return;  // never turns
  b.angular_velocity = angular_velocity;
}

void World::setType(BodyId id, BodyType type) {
  ++impl_->joint_edits;  // the energy watch lists the joints that put energy in anew
  WorldImpl& w = *impl_;
  w.requireUnlocked("setType");
  Body& b = w.get(id);
  if (type == BodyType::Dynamic && hasShapeWithoutArea(w, b))
    throw InputError("type", "a body with a segment or chain shape cannot be dynamic: segments have no area (use a capsule or a thin box)");
  w.wakeIsland(id.index);
  const bool became_kinematic = type == BodyType::Kinematic && !b.isKinematic();
  if (b.isKinematic() && type != BodyType::Kinematic) --w.kinematic_bodies;
  if (became_kinematic) ++w.kinematic_bodies;
  b.type = type;
  w.shapesEdited();
  if (became_kinematic) w.recordKinematicVelocity(id.index);
  ++w.static_version;
  if (type == BodyType::Dynamic) b.frozen = false;
  if (b.isStatic()) {
    b.velocity = Vec2::Zero();
    b.angular_velocity = 0.0;
  }
  w.updateMass(b, "density", b.density);  // valid when the shapes were made
}

void World::setInertia(BodyId id, double inertia) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setInertia");
  Body& b = w.get(id);
  requirePositive("inertia", inertia);
  if (!std::isfinite(1.0 / inertia)) throw WorldImpl::massError("inertia", b.mass, inertia, inertia);
  w.wakeIsland(id.index);
  b.inertia_set = true;
  b.inertia = inertia;
  b.inv_inertia = b.isDynamic() && !b.fixed_rotation ? 1.0 / b.inertia : 0.0;
}

void World::resetMass(BodyId id) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("resetMass");
  Body& b = w.get(id);
  w.wakeIsland(id.index);
  b.inertia_set = false;
  w.updateMass(b, "density", b.density);
}

void World::setMass(BodyId id, double mass) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setMass");
  Body& b = w.get(id);
  w.wakeIsland(id.index);
  requirePositive("mass", mass);
  if (!(b.area > 0.0)) throw InputError("mass", "the body has no shape with an area, so no mass to set");
  // Every shape's density scaled by the same factor, so their proportions stay. One shape: its
  // density is mass / area, as given.
  std::vector<double> old;
  for (ShapeId s : b.shapes) old.push_back(w.shapes[s.index].density);
  const double factor = mass / b.mass;
  for (ShapeId s : b.shapes) {
    BodyShape& shape = w.shapes[s.index];
    shape.density = b.shapes.size() == 1 ? mass / b.area : shape.density * factor;
  }
  try {
    w.updateMass(b, "mass", mass);
  } catch (...) {
    for (size_t i = 0; i < b.shapes.size(); ++i) w.shapes[b.shapes[i].index].density = old[i];
    throw;
  }
}

void World::setMaterial(BodyId id, const Material& m) {
  impl_->requireUnlocked("setMaterial");
  const Body& b = impl_->get(id);
  const Material checked = WorldImpl::validatedMaterial(m.restitution, m.friction, m.static_friction);
  for (ShapeId s : b.shapes) impl_->shapes[s.index].material = checked;
  impl_->shapesEdited();
}

void World::setName(BodyId id, std::string name) {
  impl_->requireUnlocked("setName");
  impl_->get(id).name = std::move(name);
}

void World::setLinearDamping(BodyId id, double damping) {
  impl_->requireUnlocked("setLinearDamping");
  Body& b = impl_->get(id);
  b.linear_damping = requireNonNegative("linear_damping", damping);
  impl_->wakeIsland(id.index);
}

void World::setAngularDamping(BodyId id, double damping) {
  impl_->requireUnlocked("setAngularDamping");
  Body& b = impl_->get(id);
  b.angular_damping = requireNonNegative("angular_damping", damping);
  impl_->wakeIsland(id.index);
}

void World::setGravityScale(BodyId id, double scale) {
  impl_->requireUnlocked("setGravityScale");
  Body& b = impl_->get(id);
  b.gravity_scale = requireFinite("gravity_scale", scale);
  impl_->wakeIsland(id.index);
}

void World::setFixedRotation(BodyId id, bool on) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setFixedRotation");
  Body& b = w.get(id);
  b.fixed_rotation = on;
  if (on && b.isDynamic()) b.angular_velocity = 0.0;
  w.updateMass(b, "density", b.density);
  w.wakeIsland(id.index);
}

void World::setBullet(BodyId id, bool on) {
  impl_->requireUnlocked("setBullet");
  impl_->get(id).bullet = on;
}

void World::setEnabled(BodyId id, bool on) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("setEnabled");
  Body& b = w.get(id);
  if (b.enabled == on) return;
  w.wakeIsland(id.index);
  ++w.layout_version;
  ++w.static_version;
  b.enabled = on;
  w.shapesEdited();
  b.awake = on;  // a disabled body is never awake (WorldImpl::isActive)
  b.sleep_time = 0.0;
  if (!on) {  // what rested on it may now fall; its contacts go
    wakeTouching(w, id.index);
    dropContacts(w, id.index);
  }
}

void World::setTarget(BodyId id, const Vec2& position, double angle, double time) {
  impl_->requireUnlocked("setTarget");
  Body& b = impl_->get(id);
  requireFinite("position", position);
  requireFinite("angle", angle);
  requirePositive("time", time);
  if (!b.isKinematic())
    throw InputError("body", std::string("set_target moves kinematic bodies; this body is ") + bodyTypeName(b.type));
  // The centre of mass where the origin will be at the target: c = p + q(θ) c_local.
  const Vec2 target_center = position + Rot::fromAngle(angle).apply(b.local_center);
  const Vec2 v = (target_center - b.center) / time;
  const double w = (angle - b.angle) / time;
  if (!isFinite(v) || !std::isfinite(w)) throw InputError("time", "time " + formatNumber(time) + " gives a velocity out of range");
  b.velocity = v;
  b.angular_velocity = w;
  impl_->wakeIsland(id.index);
}

void World::applyImpulse(BodyId id, const Vec2& impulse, const Vec2& world_point) {
  impl_->requireUnlocked("applyImpulse");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("impulse", impulse);
  requireFinite("point", world_point);
  // Δv = J / m, Δω = (p − c) × J / I.
  b.velocity += b.inv_mass * impulse;
  b.angular_velocity += b.inv_inertia * cross(world_point - b.center, impulse);
}

void World::applyAngularImpulse(BodyId id, double impulse) {
  impl_->requireUnlocked("applyAngularImpulse");
  Body& b = impl_->get(id);
  impl_->wakeIsland(id.index);
  requireFinite("impulse", impulse);
  b.angular_velocity += b.inv_inertia * impulse;  // Δω = j / I (0 for static, kinematic, fixed rotation)
}

void World::setBodyGravity(BodyId id, std::optional<Vec2> gravity) {
  impl_->requireUnlocked("setBodyGravity");
  Body& b = impl_->get(id);
  if (gravity) requireFinite("gravity", *gravity);
  b.own_gravity = gravity.has_value();
  b.gravity = gravity.value_or(Vec2::Zero());
  impl_->wakeIsland(id.index);
}

void World::setSleepingAllowed(BodyId id, bool on) {
  impl_->requireUnlocked("setSleepingAllowed");
  Body& b = impl_->get(id);
  b.sleeping_allowed = on;
  if (!on) impl_->wakeIsland(id.index);
}

void World::wake(BodyId id) {
  WorldImpl& w = *impl_;
  w.get(id);
  w.wakeIsland(id.index);
}

BodyState World::bodyState(BodyId id) const { return WorldImpl::stateOf(impl_->get(id)); }

}  // namespace rigidlab

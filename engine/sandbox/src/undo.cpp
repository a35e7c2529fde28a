// Undo history of whole-state edits (undo.h).
#include "undo.h"

#include <algorithm>

namespace rigidlab::sandbox {

bool operator==(const BodyProps& a, const BodyProps& b) {
  return a.type == b.type && a.position == b.position && a.angle == b.angle && a.velocity == b.velocity &&
         a.angular_velocity == b.angular_velocity && a.mass == b.mass &&
         a.material.restitution == b.material.restitution && a.material.friction == b.material.friction &&
         a.material.static_friction == b.material.static_friction && a.name == b.name;
}

BodyProps captureProps(const World& world, BodyId id) {
  const Body& b = world.body(id);
  const Material m = b.shapes.empty() ? Material{} : world.shape(b.shapes.front()).material;
  return {b.type, b.xf.p, b.angle, b.velocity, b.angular_velocity, b.mass, m, b.name};
}

void applyProps(World& world, BodyId id, const BodyProps& p) {
  // Type first: switching to static zeroes the velocity, switching back must not lose the new one.
  world.setType(id, p.type);
  world.setMass(id, p.mass);
  world.setMaterial(id, p.material);
  world.setTransform(id, p.position, p.angle);
  world.setVelocity(id, p.velocity);
  world.setAngularVelocity(id, p.angular_velocity);
  world.setName(id, p.name);
}

UndoHistory::Ref UndoHistory::refFor(BodyId id) {
  const auto it = std::find(refs_.begin(), refs_.end(), id);
  if (it != refs_.end()) return static_cast<Ref>(it - refs_.begin());
  refs_.push_back(id);
  return refs_.size() - 1;
}

bool UndoHistory::live(const World& world, Ref ref) const {
  return ref < refs_.size() && world.isValid(refs_[ref]);
}

UndoHistory::Snapshot UndoHistory::snapshotOf(const World& world, BodyId id) {
  const Body& b = world.body(id);
  Snapshot s;
  s.def.type = b.type;
  s.def.position = b.xf.p;
  s.def.angle = b.angle;
  s.def.name = b.name;
  s.def.linear_damping = b.linear_damping;
  s.def.angular_damping = b.angular_damping;
  s.def.gravity_scale = b.gravity_scale;
  s.def.fixed_rotation = b.fixed_rotation;
  s.def.bullet = b.bullet;
  s.def.enabled = b.enabled;
  s.velocity = b.velocity;
  s.angular_velocity = b.angular_velocity;
  for (const ShapeId sid : b.shapes) {
    const BodyShape& shape = world.shape(sid);
    ShapeDef d;
    d.shape = shape.geometry;
    d.density = shape.density;
    d.material = shape.material;
    d.filter = shape.filter;
    d.sensor = shape.sensor;
    s.shapes.push_back(d);
  }
  for (const ForceId fid : world.forceIds()) {
    const BodyId a = world.forceBodyA(fid), other_b = world.forceBodyB(fid);
    if (a != id && other_b != id) continue;
    AttachedForce f;
    f.time_left = world.forceTimeLeft(fid);
    const Force& force = world.force(fid);
    if (const auto* spring = dynamic_cast<const SpringForce*>(&force)) {
      f.is_spring = true;
      f.spring = spring->def();
      f.body_is_a = a == id;
      const BodyId other = f.body_is_a ? other_b : a;
      if (!other.isNull()) f.other = refFor(other);
    } else if (const auto* damper = dynamic_cast<const DamperForce*>(&force)) {
      f.is_spring = false;
      f.damper = damper->def();
    } else {
      ++s.lost_forces;
      continue;
    }
    s.forces.push_back(f);
  }
  return s;
}

BodyId UndoHistory::restore(World& world, Ref ref, const Snapshot& s) {
  // The shapes first, then the velocity: adding a shape moves the centre of mass, which would
  // otherwise change the velocity of a turning body.
  const BodyId id = world.createBody(s.def);
  for (const ShapeDef& d : s.shapes) world.createShape(id, d);
  world.setVelocity(id, s.velocity);
  world.setAngularVelocity(id, s.angular_velocity);
  refs_[ref] = id;
  for (const AttachedForce& f : s.forces) {
    if (!(f.time_left > 0.0)) continue;
    if (f.is_spring) {
      SpringDef def = f.spring;
      if (f.other && !live(world, *f.other)) continue;  // its other end is deleted too
      const BodyId other = f.other ? refs_[*f.other] : BodyId{};
      def.a = f.body_is_a ? id : other;
      def.b = f.body_is_a ? other : id;
      world.addSpring(def, f.time_left);
    } else {
      DamperDef def = f.damper;
      def.body = id;
      world.addDamper(def, f.time_left);
    }
  }
  return id;
}

void UndoHistory::push(Edit edit) {
  done_.push_back(std::move(edit));
  undone_.clear();
  if (done_.size() > kMaxEdits) done_.erase(done_.begin());
}

void UndoHistory::recordCreate(const World& world, BodyId id, std::string label) {
  Edit e{Kind::Create, refFor(id), std::move(label), snapshotOf(world, id), {}, {}};
  last_touched_ = id;
  push(std::move(e));
}

void UndoHistory::destroy(World& world, BodyId id, std::string label) {
  Edit e{Kind::Destroy, refFor(id), std::move(label), snapshotOf(world, id), {}, {}};
  if (e.snapshot.lost_forces > 0)
    e.label += " (" + std::to_string(e.snapshot.lost_forces) + " script force(s) cannot come back)";
  world.destroyBody(id);
  last_touched_ = {};
  push(std::move(e));
}

void UndoHistory::recordModify(BodyId id, const BodyProps& before, const BodyProps& after, std::string label) {
  if (before == after) return;
  Edit e{Kind::Modify, refFor(id), std::move(label), {}, before, after};
  last_touched_ = id;
  push(std::move(e));
}

bool UndoHistory::undo(World& world) {
  if (done_.empty()) return false;
  Edit& e = done_.back();
  const bool needs_live = e.kind != Kind::Destroy;
  if (needs_live != live(world, e.ref)) {  // the body was removed (or recreated) behind our back
    clear();
    return false;
  }
  switch (e.kind) {
    case Kind::Create:
      e.snapshot = snapshotOf(world, refs_[e.ref]);  // redo brings it back as it is now
      world.destroyBody(refs_[e.ref]);
      last_touched_ = {};
      break;
    case Kind::Destroy:
      last_touched_ = restore(world, e.ref, e.snapshot);
      break;
    case Kind::Modify:
      applyProps(world, refs_[e.ref], e.before);
      last_touched_ = refs_[e.ref];
      break;
  }
  undone_.push_back(std::move(e));
  done_.pop_back();
  return true;
}

bool UndoHistory::redo(World& world) {
  if (undone_.empty()) return false;
  Edit& e = undone_.back();
  const bool needs_live = e.kind != Kind::Create;
  if (needs_live != live(world, e.ref)) {
    clear();
    return false;
  }
  switch (e.kind) {
    case Kind::Create:
      last_touched_ = restore(world, e.ref, e.snapshot);
      break;
    case Kind::Destroy:
      e.snapshot = snapshotOf(world, refs_[e.ref]);
      world.destroyBody(refs_[e.ref]);
      last_touched_ = {};
      break;
    case Kind::Modify:
      applyProps(world, refs_[e.ref], e.after);
      last_touched_ = refs_[e.ref];
      break;
  }
  done_.push_back(std::move(e));
  undone_.pop_back();
  return true;
}

const std::string& UndoHistory::undoLabel() const {
  static const std::string kNone;
  return done_.empty() ? kNone : done_.back().label;
}

const std::string& UndoHistory::redoLabel() const {
  static const std::string kNone;
  return undone_.empty() ? kNone : undone_.back().label;
}

void UndoHistory::clear() {
  done_.clear();
  undone_.clear();
  refs_.clear();
  last_touched_ = {};
}

}  // namespace rigidlab::sandbox

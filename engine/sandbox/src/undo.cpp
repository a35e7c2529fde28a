// Undo history of whole-state edits (undo.h).
#include "undo.h"

#include <algorithm>

namespace rigidlab::sandbox {

bool operator==(const ShapeProps& a, const ShapeProps& b) {
  return a.density == b.density && a.material.restitution == b.material.restitution &&
         a.material.friction == b.material.friction && a.material.static_friction == b.material.static_friction &&
         a.filter == b.filter && a.sensor == b.sensor && a.tangent_speed == b.tangent_speed &&
         a.rolling_resistance == b.rolling_resistance;
}

bool operator==(const BodyProps& a, const BodyProps& b) {
  return a.type == b.type && a.position == b.position && a.angle == b.angle && a.velocity == b.velocity &&
         a.angular_velocity == b.angular_velocity && a.mass == b.mass && a.linear_damping == b.linear_damping &&
         a.angular_damping == b.angular_damping && a.gravity_scale == b.gravity_scale &&
         a.fixed_rotation == b.fixed_rotation && a.bullet == b.bullet && a.enabled == b.enabled &&
         a.shapes == b.shapes && a.name == b.name && a.gravity == b.gravity && a.sleeping_allowed == b.sleeping_allowed;
}

BodyProps captureProps(const World& world, BodyId id) {
  const Body& b = world.body(id);
  BodyProps p;
  p.type = b.type;
  p.position = b.xf.p;
  p.angle = b.angle;
  p.velocity = b.velocity;
  p.angular_velocity = b.angular_velocity;
  p.mass = b.mass;
  p.linear_damping = b.linear_damping;
  p.angular_damping = b.angular_damping;
  p.gravity_scale = b.gravity_scale;
  p.fixed_rotation = b.fixed_rotation;
  p.bullet = b.bullet;
  p.enabled = b.enabled;
  if (b.own_gravity) p.gravity = b.gravity;
  p.sleeping_allowed = b.sleeping_allowed;
  for (const ShapeId sid : b.shapes) {
    const BodyShape& s = world.shape(sid);
    p.shapes.push_back({s.density, s.material, s.filter, s.sensor, s.tangent_speed, s.rolling_resistance});
  }
  p.name = b.name;
  return p;
}

void applyProps(World& world, BodyId id, const BodyProps& p) {
  // Type first: switching to static zeroes the velocity, switching back must not lose the new one.
  // Shapes and mass before the velocity: they move the centre of mass, which changes the velocity
  // of a turning body. Fixed rotation before the angular velocity: turning it on stops the body.
  if (world.body(id).type != p.type) world.setType(id, p.type);
  const std::vector<ShapeId> shapes = world.body(id).shapes;
  bool densities_changed = false;
  for (size_t i = 0; i < shapes.size() && i < p.shapes.size(); ++i) {
    const ShapeProps& want = p.shapes[i];
    const BodyShape& s = world.shape(shapes[i]);
    if (s.density != want.density && hasArea(s.geometry.type)) {
      world.setShapeDensity(shapes[i], want.density);
      densities_changed = true;
    }
    const Material& m = s.material;
    if (m.restitution != want.material.restitution || m.friction != want.material.friction ||
        m.static_friction != want.material.static_friction)
      world.setShapeMaterial(shapes[i], want.material);
    if (!(s.filter == want.filter)) world.setShapeFilter(shapes[i], want.filter);
    if (s.sensor != want.sensor) world.setShapeSensor(shapes[i], want.sensor);
    if (s.tangent_speed != want.tangent_speed || s.rolling_resistance != want.rolling_resistance)
      world.setShapeSurface(shapes[i], want.tangent_speed, want.rolling_resistance);
  }
  if (!densities_changed && world.body(id).mass != p.mass) world.setMass(id, p.mass);
  world.setTransform(id, p.position, p.angle);
  if (world.body(id).fixed_rotation != p.fixed_rotation) world.setFixedRotation(id, p.fixed_rotation);
  world.setVelocity(id, p.velocity);
  world.setAngularVelocity(id, p.angular_velocity);
  world.setLinearDamping(id, p.linear_damping);
  world.setAngularDamping(id, p.angular_damping);
  world.setGravityScale(id, p.gravity_scale);
  world.setBodyGravity(id, p.gravity);
  if (world.body(id).sleeping_allowed != p.sleeping_allowed) world.setSleepingAllowed(id, p.sleeping_allowed);
  world.setBullet(id, p.bullet);
  if (world.body(id).enabled != p.enabled) world.setEnabled(id, p.enabled);
  world.setName(id, p.name);
}

bool sameTunables(const JointDef& a, const JointDef& b) {
  return a.collide_connected == b.collide_connected && a.break_force == b.break_force &&
         a.break_torque == b.break_torque && a.name == b.name && a.enable_limit == b.enable_limit &&
         a.lower == b.lower && a.upper == b.upper && a.enable_motor == b.enable_motor &&
         a.motor_speed == b.motor_speed && a.max_motor_torque == b.max_motor_torque &&
         a.max_motor_force == b.max_motor_force && a.enable_spring == b.enable_spring &&
         a.spring_hertz == b.spring_hertz && a.spring_damping == b.spring_damping && a.min_length == b.min_length &&
         a.max_length == b.max_length && a.max_spring_force == b.max_spring_force &&
         a.linear_hertz == b.linear_hertz && a.linear_damping == b.linear_damping &&
         a.angular_hertz == b.angular_hertz && a.angular_damping == b.angular_damping &&
         a.motor_hertz == b.motor_hertz && a.motor_damping == b.motor_damping &&
         a.linear_offset == b.linear_offset && a.angular_offset == b.angular_offset &&
         a.linear_velocity == b.linear_velocity && a.angular_velocity == b.angular_velocity &&
         a.max_force == b.max_force && a.max_torque == b.max_torque && a.length == b.length && a.ratio == b.ratio;
}

UndoHistory::Ref UndoHistory::refFor(BodyId id) {
  const auto it = std::find(refs_.begin(), refs_.end(), id);
  if (it != refs_.end()) return static_cast<Ref>(it - refs_.begin());
  refs_.push_back(id);
  return refs_.size() - 1;
}

UndoHistory::Ref UndoHistory::jointRefFor(JointId id) {
  const auto it = std::find(joint_refs_.begin(), joint_refs_.end(), id);
  if (it != joint_refs_.end()) return static_cast<Ref>(it - joint_refs_.begin());
  joint_refs_.push_back(id);
  return joint_refs_.size() - 1;
}

bool UndoHistory::live(const World& world, Ref ref) const {
  return ref < refs_.size() && world.isValid(refs_[ref]);
}

bool UndoHistory::liveJoint(const World& world, Ref ref) const {
  return ref < joint_refs_.size() && world.isValid(joint_refs_[ref]);
}

UndoHistory::JointSnapshot UndoHistory::jointSnapshotOf(const World& world, JointId id) {
  JointSnapshot j;
  j.ref = jointRefFor(id);
  j.def = world.joint(id);
  if (j.def.type == JointType::Gear && j.def.joint_a.isNull()) {  // a gear of two bodies' angles
    j.a = refFor(j.def.a);
    j.b = refFor(j.def.b);
  } else if (j.def.type == JointType::Gear) {
    j.joint_a = jointRefFor(j.def.joint_a);
    j.joint_b = jointRefFor(j.def.joint_b);
  } else {
    j.frames = lua::jointFrames(world, id);
    if (!j.def.a.isNull()) j.a = refFor(j.def.a);
    if (!j.def.b.isNull()) j.b = refFor(j.def.b);
  }
  return j;
}

std::vector<UndoHistory::JointSnapshot> UndoHistory::jointWithGears(const World& world, JointId id) {
  std::vector<JointSnapshot> out{jointSnapshotOf(world, id)};
  for (const JointId g : world.jointIds()) {
    const JointDef& d = world.joint(g);
    if (d.type == JointType::Gear && (d.joint_a == id || d.joint_b == id)) out.push_back(jointSnapshotOf(world, g));
  }
  return out;
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
  if (b.own_gravity) s.def.gravity = b.gravity;
  s.def.sleeping_allowed = b.sleeping_allowed;
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
    d.tangent_speed = shape.tangent_speed;
    d.rolling_resistance = shape.rolling_resistance;
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
  std::vector<JointId> joints = world.jointsOf(id);
  std::stable_partition(joints.begin(), joints.end(), [&](JointId j) { return world.joint(j).type != JointType::Gear; });
  for (const JointId j : joints) s.joints.push_back(jointSnapshotOf(world, j));
  return s;
}

void UndoHistory::restoreJoints(World& world, const std::vector<JointSnapshot>& joints, BodyId moved) {
  const auto body = [&](const std::optional<Ref>& r, bool& ok) {
    if (!r) return BodyId{};
    ok = ok && live(world, *r);
    return ok ? refs_[*r] : BodyId{};
  };
  for (const JointSnapshot& j : joints) {
    JointDef def = j.def;
    bool ok = true;
    if (def.type == JointType::Gear && !j.joint_a) {  // a gear of two bodies, from their angles now
      def.a = body(j.a, ok);
      def.b = body(j.b, ok);
      if (ok) joint_refs_[j.ref] = world.createJoint(def);
      continue;
    }
    if (def.type == JointType::Gear) {
      ok = liveJoint(world, *j.joint_a) && liveJoint(world, *j.joint_b);
      if (!ok) continue;
      def.joint_a = joint_refs_[*j.joint_a];
      def.joint_b = joint_refs_[*j.joint_b];
      def.a = def.b = {};
      joint_refs_[j.ref] = world.createJoint(def);
      continue;
    }
    def.a = body(j.a, ok);
    def.b = body(j.b, ok);
    if (!ok) continue;  // its other body is deleted too
    joint_refs_[j.ref] = lua::buildJoint(world, lua::jointBuild(world, def, j.frames, moved));
  }
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
  restoreJoints(world, s.joints, id);
  return id;
}

void UndoHistory::push(Edit edit) {
  done_.push_back(std::move(edit));
  undone_.clear();
  if (done_.size() > kMaxEdits) done_.erase(done_.begin());
}

void UndoHistory::recordCreate(const World& world, BodyId id, std::string label) {
  Edit e{Kind::Create, refFor(id), std::move(label), snapshotOf(world, id), {}, {}, {}, {}, {}};
  last_touched_ = id;
  last_joint_ = {};
  push(std::move(e));
}

void UndoHistory::destroy(World& world, BodyId id, std::string label) {
  Edit e{Kind::Destroy, refFor(id), std::move(label), snapshotOf(world, id), {}, {}, {}, {}, {}};
  if (e.snapshot.lost_forces > 0)
    e.label += " (" + std::to_string(e.snapshot.lost_forces) + " script force(s) cannot come back)";
  world.destroyBody(id);
  last_touched_ = {};
  last_joint_ = {};
  push(std::move(e));
}

void UndoHistory::recordModify(BodyId id, const BodyProps& before, const BodyProps& after, std::string label) {
  if (before == after) return;
  Edit e{Kind::Modify, refFor(id), std::move(label), {}, before, after, {}, {}, {}};
  last_touched_ = id;
  last_joint_ = {};
  push(std::move(e));
}

void UndoHistory::recordCreateJoint(const World& world, JointId id, std::string label) {
  Edit e{Kind::CreateJoint, jointRefFor(id), std::move(label), {}, {}, {}, jointWithGears(world, id), {}, {}};
  last_touched_ = {};
  last_joint_ = id;
  push(std::move(e));
}

void UndoHistory::destroyJoint(World& world, JointId id, std::string label) {
  Edit e{Kind::DestroyJoint, jointRefFor(id), std::move(label), {}, {}, {}, jointWithGears(world, id), {}, {}};
  world.destroyJoint(id);  // and the gears on it
  last_touched_ = {};
  last_joint_ = {};
  push(std::move(e));
}

void UndoHistory::recordModifyJoint(JointId id, const JointDef& before, const JointDef& after, std::string label) {
  if (sameTunables(before, after)) return;
  Edit e{Kind::ModifyJoint, jointRefFor(id), std::move(label), {}, {}, {}, {}, before, after};
  last_touched_ = {};
  last_joint_ = id;
  push(std::move(e));
}

// Undoes (or redoes) one edit. A create undone and a delete redone remove the thing again, taking
// a fresh snapshot so that the next step brings it back as it is now.
bool UndoHistory::applyEdit(World& world, Edit& e, bool undoing) {
  const bool joint = e.kind == Kind::CreateJoint || e.kind == Kind::DestroyJoint || e.kind == Kind::ModifyJoint;
  const bool removes = (e.kind == Kind::Create || e.kind == Kind::CreateJoint) == undoing &&
                       e.kind != Kind::Modify && e.kind != Kind::ModifyJoint;
  const bool modifies = e.kind == Kind::Modify || e.kind == Kind::ModifyJoint;
  const bool needs_live = removes || modifies;
  if (needs_live != (joint ? liveJoint(world, e.ref) : live(world, e.ref))) {
    clear();  // the body or joint was removed (or recreated) behind our back
    return false;
  }
  last_touched_ = {};
  last_joint_ = {};
  switch (e.kind) {
    case Kind::Create:
    case Kind::Destroy:
      if (removes) {
        e.snapshot = snapshotOf(world, refs_[e.ref]);
        world.destroyBody(refs_[e.ref]);
      } else {
        last_touched_ = restore(world, e.ref, e.snapshot);
      }
      break;
    case Kind::CreateJoint:
    case Kind::DestroyJoint:
      if (removes) {
        e.joints = jointWithGears(world, joint_refs_[e.ref]);
        world.destroyJoint(joint_refs_[e.ref]);
      } else {
        const JointSnapshot& j = e.joints.front();
        const bool bodies = (!j.a || live(world, *j.a)) && (!j.b || live(world, *j.b)) &&
                            (!j.joint_a || liveJoint(world, *j.joint_a)) && (!j.joint_b || liveJoint(world, *j.joint_b));
        if (!bodies) {
          clear();
          return false;
        }
        restoreJoints(world, e.joints, {});
        last_joint_ = joint_refs_[e.ref];
      }
      break;
    case Kind::Modify:
      applyProps(world, refs_[e.ref], undoing ? e.before : e.after);
      last_touched_ = refs_[e.ref];
      break;
    case Kind::ModifyJoint:
      world.updateJoint(joint_refs_[e.ref], undoing ? e.joint_before : e.joint_after);
      last_joint_ = joint_refs_[e.ref];
      break;
  }
  return true;
}

bool UndoHistory::undo(World& world) {
  if (done_.empty()) return false;
  Edit e = std::move(done_.back());
  done_.pop_back();
  if (!applyEdit(world, e, true)) return false;
  undone_.push_back(std::move(e));
  return true;
}

bool UndoHistory::redo(World& world) {
  if (undone_.empty()) return false;
  Edit e = std::move(undone_.back());
  undone_.pop_back();
  if (!applyEdit(world, e, false)) return false;
  done_.push_back(std::move(e));
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
  joint_refs_.clear();
  last_touched_ = {};
  last_joint_ = {};
}

}  // namespace rigidlab::sandbox

// Undo and redo for the sandbox's edits: property edits of bodies, their shapes and joints, moves
// and turns, type changes, adding and deleting bodies and joints.
//
// Each edit stores whole states (before and after), not deltas, so undo and redo are exact and need
// no inverse operations. Deleting a body or joint destroys its handle, and an undone delete creates
// a new one; edits therefore name bodies and joints by a `Ref` into tables that this history keeps
// up to date, never by handle. Springs, dampers and joints attached to a deleted body come back
// with it (those to another body only if that body exists at that moment; a gear only with both
// its joints); forces that are code (Lua forces) cannot be rebuilt from data and are reported as
// lost in the edit's label. A joint comes back holding its bodies as it held them when it went
// (the same angle, anchors and limits: lua::JointFrames), wherever they have moved since.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rigidlab/forces.h"
#include "rigidlab/lua/saved_joint.h"
#include "rigidlab/world.h"

namespace rigidlab::sandbox {

// What a property edit can change of one shape (the Body panel's shape fields).
struct ShapeProps {
  double density = 1.0;
  Material material;
  Filter filter;
  bool sensor = false;
  double tangent_speed = 0.0, rolling_resistance = 0.0;
  friend bool operator==(const ShapeProps&, const ShapeProps&);
};

// What a property edit can change of a body (the Body panel's fields and the paused move/rotate
// tools). `mass` follows from the shapes' densities; applyProps sets it only when the densities
// are unchanged (a mass edit), so an edit of either does not undo the other.
struct BodyProps {
  BodyType type = BodyType::Dynamic;
  Vec2 position = Vec2::Zero();  // body origin [m]
  double angle = 0.0;            // [rad]
  Vec2 velocity = Vec2::Zero();  // centre of mass [m/s]
  double angular_velocity = 0.0; // [rad/s]
  double mass = 1.0;             // [kg]
  double linear_damping = 0.0, angular_damping = 0.0, gravity_scale = 1.0;
  bool fixed_rotation = false, bullet = false, enabled = true;
  std::optional<Vec2> gravity;  // its own (BodyDef::gravity), or the world's
  bool sleeping_allowed = true;
  std::vector<ShapeProps> shapes;  // in the body's order
  std::string name;

  friend bool operator==(const BodyProps& a, const BodyProps& b);
};
BodyProps captureProps(const World& world, BodyId id);
// Throws what the world's setters throw (e.g. a dynamic type for a body with a segment).
void applyProps(World& world, BodyId id, const BodyProps& props);

// A joint's tunables (what World::updateJoint changes) compare equal.
bool sameTunables(const JointDef& a, const JointDef& b);

class UndoHistory {
 public:
  using Ref = size_t;
  static constexpr size_t kMaxEdits = 500;

  // Records that `id` was just created (e.g. by the add-circle tool), with its shapes.
  void recordCreate(const World& world, BodyId id, std::string label);
  // Deletes the body (and the forces and joints on it) and records it.
  void destroy(World& world, BodyId id, std::string label);
  // Records a change of a body's properties; nothing if before == after.
  void recordModify(BodyId id, const BodyProps& before, const BodyProps& after, std::string label);
  // The same for joints: made (e.g. by the joint tool), deleted (with the gears on it), tuned.
  void recordCreateJoint(const World& world, JointId id, std::string label);
  void destroyJoint(World& world, JointId id, std::string label);
  void recordModifyJoint(JointId id, const JointDef& before, const JointDef& after, std::string label);

  // Each returns false when there is nothing to undo/redo or the edit's body or joint is gone
  // (e.g. removed by a script, or a joint broke); the history is then cleared past that point
  // rather than applied to the wrong one.
  bool undo(World& world);
  bool redo(World& world);
  bool canUndo() const { return !done_.empty(); }
  bool canRedo() const { return !undone_.empty(); }
  const std::string& undoLabel() const;  // "" if none
  const std::string& redoLabel() const;
  size_t size() const { return done_.size(); }
  void clear();

  // The current handle of the body or joint an edit created, recreated or changed (for the
  // selection after undo); null if the last one removed it.
  BodyId lastTouched() const { return last_touched_; }
  JointId lastTouchedJoint() const { return last_joint_; }

 private:
  struct AttachedForce {
    bool is_spring = true;
    SpringDef spring;          // a and b are replaced by refs on restore
    DamperDef damper;
    bool body_is_a = true;     // spring: which end the deleted body was
    std::optional<Ref> other;  // spring between two bodies: the other one
    double time_left = World::kForever;
  };
  // A joint as data: its definition (bodies and geared joints replaced by refs on restore) and
  // frames.
  struct JointSnapshot {
    Ref ref = 0;  // into joint_refs_
    JointDef def;
    lua::JointFrames frames;
    std::optional<Ref> a, b;            // body refs; none: the world
    std::optional<Ref> joint_a, joint_b;  // gear: its joints' refs
  };
  struct Snapshot {
    BodyDef def;  // without its shapes and velocity (restore adds them in that order)
    std::vector<ShapeDef> shapes;
    Vec2 velocity = Vec2::Zero();
    double angular_velocity = 0.0;
    std::vector<AttachedForce> forces;
    std::vector<JointSnapshot> joints;  // gears last
    int lost_forces = 0;  // forces on the body that cannot be rebuilt (code, not data)
  };
  enum class Kind { Create, Destroy, Modify, CreateJoint, DestroyJoint, ModifyJoint };
  struct Edit {
    Kind kind;
    Ref ref;  // a body ref, or for the joint kinds a joint ref
    std::string label;
    Snapshot snapshot;                 // Create/Destroy
    BodyProps before, after;           // Modify
    std::vector<JointSnapshot> joints;  // CreateJoint/DestroyJoint: the joint, then gears on it
    JointDef joint_before, joint_after;  // ModifyJoint
  };

  Ref refFor(BodyId id);
  Ref jointRefFor(JointId id);
  Snapshot snapshotOf(const World& world, BodyId id);
  JointSnapshot jointSnapshotOf(const World& world, JointId id);
  // The joint and the gears on it, gears last.
  std::vector<JointSnapshot> jointWithGears(const World& world, JointId id);
  BodyId restore(World& world, Ref ref, const Snapshot& snapshot);
  // Makes the joints again whose bodies (and geared joints) exist; `moved`: the body to move if
  // one must be (saved_joint.h).
  void restoreJoints(World& world, const std::vector<JointSnapshot>& joints, BodyId moved);
  void push(Edit edit);
  bool live(const World& world, Ref ref) const;
  bool liveJoint(const World& world, Ref ref) const;
  bool applyEdit(World& world, Edit& e, bool undoing);

  std::vector<BodyId> refs_;         // Ref → current body handle
  std::vector<JointId> joint_refs_;  // Ref → current joint handle
  std::vector<Edit> done_, undone_;
  BodyId last_touched_;
  JointId last_joint_;
};

}  // namespace rigidlab::sandbox

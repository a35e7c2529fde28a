// Undo and redo for the sandbox's edits: property edits, moves and turns, static/dynamic toggles,
// adding and deleting bodies.
//
// Each edit stores whole states (before and after), not deltas, so undo and redo are exact and need
// no inverse operations. Deleting a body destroys its handle, and an undone delete creates a new
// body with a new handle; edits therefore name bodies by a `Ref` into a table that this history
// keeps up to date, never by BodyId. Springs and dampers attached to a deleted body come back with
// it (a spring only if its other body exists at that moment); forces that are code (Lua forces)
// cannot be rebuilt from data and are reported as lost in the edit's label.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rigidlab/forces.h"
#include "rigidlab/world.h"

namespace rigidlab::sandbox {

// What a property edit can change (the Body panel's fields and the paused move/rotate tools).
struct BodyProps {
  BodyType type = BodyType::Dynamic;
  Vec2 position = Vec2::Zero();  // body origin [m]
  double angle = 0.0;            // [rad]
  Vec2 velocity = Vec2::Zero();  // centre of mass [m/s]
  double angular_velocity = 0.0; // [rad/s]
  double mass = 1.0;             // [kg]
  Material material;
  std::string name;

  friend bool operator==(const BodyProps& a, const BodyProps& b);
};
BodyProps captureProps(const World& world, BodyId id);
void applyProps(World& world, BodyId id, const BodyProps& props);

class UndoHistory {
 public:
  using Ref = size_t;
  static constexpr size_t kMaxEdits = 500;

  // Records that `id` was just created (e.g. by the add-circle tool).
  void recordCreate(const World& world, BodyId id, std::string label);
  // Deletes the body (and the forces on it) and records it.
  void destroy(World& world, BodyId id, std::string label);
  // Records a change of a body's properties; nothing if before == after.
  void recordModify(BodyId id, const BodyProps& before, const BodyProps& after, std::string label);

  // Each returns false when there is nothing to undo/redo or the edit's body is gone (e.g. removed
  // by a script); the history is then cleared past that point rather than applied to the wrong body.
  bool undo(World& world);
  bool redo(World& world);
  bool canUndo() const { return !done_.empty(); }
  bool canRedo() const { return !undone_.empty(); }
  const std::string& undoLabel() const;  // "" if none
  const std::string& redoLabel() const;
  size_t size() const { return done_.size(); }
  void clear();

  // The current handle of a body that an edit created or recreated (for selection after undo).
  BodyId lastTouched() const { return last_touched_; }

 private:
  struct AttachedForce {
    bool is_spring = true;
    SpringDef spring;          // a and b are replaced by refs on restore
    DamperDef damper;
    bool body_is_a = true;     // spring: which end the deleted body was
    std::optional<Ref> other;  // spring between two bodies: the other one
    double time_left = World::kForever;
  };
  struct Snapshot {
    BodyDef def;  // without its shapes and velocity (restore adds them in that order)
    std::vector<ShapeDef> shapes;
    Vec2 velocity = Vec2::Zero();
    double angular_velocity = 0.0;
    std::vector<AttachedForce> forces;
    int lost_forces = 0;  // forces on the body that cannot be rebuilt (code, not data)
  };
  enum class Kind { Create, Destroy, Modify };
  struct Edit {
    Kind kind;
    Ref ref;
    std::string label;
    Snapshot snapshot;  // Create/Destroy
    BodyProps before, after;  // Modify
  };

  Ref refFor(BodyId id);
  Snapshot snapshotOf(const World& world, BodyId id);
  BodyId restore(World& world, Ref ref, const Snapshot& snapshot);
  void push(Edit edit);
  bool live(const World& world, Ref ref) const;

  std::vector<BodyId> refs_;  // Ref → current handle
  std::vector<Edit> done_, undone_;
  BodyId last_touched_;
};

}  // namespace rigidlab::sandbox

// World::snapshot and World::restore (world_snapshot.h). A snapshot is a copy of the world's whole
// internal state (WorldImpl is copyable: its vectors are values, the broad phase object holds only
// scratch, forces are cloned), so a restore is exact by construction; snapshot_format.cpp writes
// the part of it that a later step reads.
#include "snapshot_state.h"

#include <typeinfo>

#include "world_impl.h"

namespace rigidlab {

PlaceholderForce::~PlaceholderForce() = default;

void PlaceholderForce::evaluate(const ForceInput&, ForceOutput&) {
  // Never reached: restore() replaces every placeholder before the state goes live.
  throw SnapshotError("snapshot: a " + kind_ + " from a file was evaluated before it was restored");
}

WorldSnapshot::WorldSnapshot() = default;
WorldSnapshot::~WorldSnapshot() = default;
WorldSnapshot::WorldSnapshot(const WorldSnapshot&) = default;
WorldSnapshot& WorldSnapshot::operator=(const WorldSnapshot&) = default;
WorldSnapshot::WorldSnapshot(WorldSnapshot&&) noexcept = default;
WorldSnapshot& WorldSnapshot::operator=(WorldSnapshot&&) noexcept = default;

double WorldSnapshot::time() const { return state_ ? state_->clock.t : 0.0; }
long WorldSnapshot::stepCount() const { return state_ ? state_->step_count : 0; }
int WorldSnapshot::bodyCount() const {
  int n = 0;
  if (state_)
    for (char a : state_->alive) n += a ? 1 : 0;
  return n;
}

namespace {

template <typename T>
size_t bytesOf(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

// Clones the forces that can be cloned; the others (scripts' callbacks) stay shared.
void cloneForces(WorldImpl& w) {
  for (ForceEntry& f : w.forces)
    if (f.force)
      if (std::unique_ptr<Force> copy = f.force->clone()) f.force = std::move(copy);
}

}  // namespace

size_t WorldSnapshot::memoryBytes() const {
  if (!state_) return 0;
  const WorldImpl& w = *state_;
  const size_t own = label_.capacity() + app_data_.capacity();
  // The state's own vectors dominate; per-element heap of bodies' and shapes' lists is added.
  size_t n = own + sizeof(WorldImpl) + bytesOf(w.bodies) + bytesOf(w.alive) + bytesOf(w.shapes) + bytesOf(w.shape_alive) +
             bytesOf(w.forces) + bytesOf(w.joints) + bytesOf(w.contacts) + bytesOf(w.previous_contacts) +
             bytesOf(w.contact_keys) + bytesOf(w.proxies) + bytesOf(w.pair_cache.grown) + bytesOf(w.pair_cache.pairs) +
             bytesOf(w.pairs) + bytesOf(w.island) + bytesOf(w.created_asleep_before) + bytesOf(w.sensor_overlaps);
  for (const Body& b : w.bodies) n += bytesOf(b.shapes) + b.name.capacity();
  for (const BodyShape& s : w.shapes) n += bytesOf(s.geometry.vertices) + bytesOf(s.geometry.normals);
  for (const auto& j : w.body_joints) n += sizeof(j) + bytesOf(j);
  for (const auto& o : w.sensor_overlaps) n += bytesOf(o);
  for (const ForceEntry& f : w.forces)
    if (f.force) n += 64;  // a cloned built-in force (SpringForce, the largest, is under 100 bytes)
  n += bytesOf(w.solver_prepared) +
       bytesOf(w.shape_views) + bytesOf(w.world_vertices) + bytesOf(w.world_normals) +
       bytesOf(w.states) + bytesOf(w.wrenches) + bytesOf(w.const_wrenches) + bytesOf(w.solved) + bytesOf(w.soft_solved);
  return n;
}

WorldSnapshot World::snapshot() const {
  const WorldImpl& w = *impl_;
  w.requireUnlocked("snapshot");
  auto copy = std::make_shared<WorldImpl>(w);
  cloneForces(*copy);
  copy->pre_solve = nullptr;  // the restoring world keeps its own (world_snapshot.h)
  copy->should_collide = nullptr;
  WorldSnapshot s;
  s.state_ = std::move(copy);
  return s;
}

void World::restore(const WorldSnapshot& snapshot) {
  WorldImpl& w = *impl_;
  w.requireUnlocked("restore");
  if (!snapshot.state_) throw SnapshotError("restore: the snapshot is empty");
  auto next = std::make_unique<WorldImpl>(*snapshot.state_);
  // Forces read from a file: the scene made them again; take ours, by id and kind.
  for (uint32_t i = 0; i < next->forces.size(); ++i) {
    ForceEntry& f = next->forces[i];
    const auto* placeholder = dynamic_cast<const PlaceholderForce*>(f.force.get());
    if (!placeholder) continue;
    const bool have = i < w.forces.size() && w.forces[i].alive && w.forces[i].generation == f.generation &&
                      w.forces[i].force && w.forces[i].force->kind() == placeholder->kind() &&
                      !dynamic_cast<const PlaceholderForce*>(w.forces[i].force.get());
    if (!have)
      throw SnapshotError("restore: the snapshot has a " + placeholder->kindName() + " (force " + std::to_string(i) +
                          ", generation " + std::to_string(f.generation) +
                          ") that this world does not have: a force that cannot be copied is taken from the world "
                          "being restored, so it must have been made the same way (the same scene file, forces "
                          "added by a script before the snapshot in the same order)");
    f.force = w.forces[i].force;
  }
  cloneForces(*next);
  next->pre_solve = w.pre_solve;
  next->should_collide = w.should_collide;
  next->locked = false;
  next->def.threads = w.def.threads;  // not simulation state (WorldDef::threads): the world keeps its own
  next->pool = std::move(w.pool);
  impl_ = std::move(next);
}

}  // namespace rigidlab

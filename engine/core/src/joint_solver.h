// Joints inside the solvers' loops (joint_solver.cpp): building the joint's view of its bodies
// from a solver's arrays, and the position pass of sequential impulses.
#pragma once

#include <vector>

#include "joint.h"

namespace rigidlab {

struct WorldImpl;

// A body's pose and inverse masses as the solvers see them (asleep or static: immovable).
JointBodyPose jointPose(const WorldImpl& w, uint32_t slot);
// Prepares the joint at the bodies' current state.
void prepareJointAt(WorldImpl& w, Joint& j, const JointStep& step);

// Copies of a joint's bodies (up to four, aliases shared) made from an array of `Source` records
// and written back to it, for the solvers whose body records are not SoftBody.
template <typename Source>
struct JointViews {
  SoftBody views[4];
  uint32_t slots[4];
  int count = 0;
  JointBodies bodies{};

  SoftBody* viewOf(std::vector<Source>& source, uint32_t slot, SoftBody (*make)(const Source&)) {
    if (slot == kWorldSlot) slot = UINT32_MAX - 1;  // the world: one shared immovable view
    for (int i = 0; i < count; ++i)
      if (slots[i] == slot) return &views[i];
    slots[count] = slot;
    views[count] = slot == UINT32_MAX - 1 ? SoftBody{0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0} : make(source[slot]);
    return &views[count++];
  }
  JointViews(std::vector<Source>& source, const Joint& j, SoftBody (*make)(const Source&)) {
    bodies.a = viewOf(source, j.a, make);
    bodies.b = viewOf(source, j.b, make);
    bodies.c = viewOf(source, j.c, make);
    bodies.d = viewOf(source, j.d, make);
  }
  void writeBack(std::vector<Source>& source, void (*store)(Source&, const SoftBody&)) const {
    for (int i = 0; i < count; ++i)
      if (slots[i] != UINT32_MAX - 1) store(source[slots[i]], views[i]);
  }
};

// Sequential impulses' position pass over its joints (position_correction.cpp): the direct solve
// (Newton's method) of the joints' equality rows, then nonlinear Gauss–Seidel with the joints' own
// solve in position mode for their limits (joint.h). `displaced`: per body slot, Σ P of the contact
// points that displaced the body this step (position_correction.cpp applyContactDisplacement), empty
// when none did; those bodies have had their displacement.
void correctJointPositions(WorldImpl& w, double dt, const std::vector<double>& displaced);

// The joint's body i (0 to 3: a, b, c, d) as the position pass sees it: no velocity, its
// displacement and rotation since the joint was prepared, its inverse masses (0 if it is still:
// static or asleep); the world is an immovable body that has not moved.
SoftBody jointPositionView(WorldImpl& w, const Joint& j, int i);
// Moves a body during the position pass (by Δc, Δθ). Its transform is synced once, when the pass
// ends: until then only the views above read the body, and they read its centre and angle.
void moveJointBody(WorldImpl& w, uint32_t slot, const Vec2& dc, double d_angle);

// The direct solves of small islands of joints (joint_direct.cpp): exact for the joints' rigid
// equality rows, on the solver's velocities, and on the bodies' positions (Newton steps, inside
// correctJointPositions, which syncs the transforms of the bodies they move; returns how many
// were taken).
constexpr int kMaxDirectRows = 256;
// The islands they solve (WorldImpl::joint_island_*), found once a step after the solvers are
// chosen: until the step ends neither its SI joints nor which bodies are awake change.
void findJointIslands(WorldImpl& w);
struct SolverBody;
void directJointVelocities(WorldImpl& w, std::vector<SolverBody>& bodies);
int directJointPositions(WorldImpl& w);
// The velocity solve again on the bodies' own velocities, with the Jacobians at their positions
// after the position solve: the velocities end tangent to the constraints where the bodies are
// (RATTLE's second half; without it, integrating from the projected positions with velocities
// tangent elsewhere gains energy like explicit Euler, and a heavy load on a light chain blew up).
void directJointVelocitiesAtPositions(WorldImpl& w);

}  // namespace rigidlab

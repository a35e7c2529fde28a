// The stages of World::step, one file each, in pipeline order.
#pragma once

#include "rigidlab/world.h"
#include "step_context.h"

namespace rigidlab {

struct WorldImpl;
struct Contact;

// The step's time line (event_location.cpp): every body integrated over the step, split at force
// end times and, with located impacts, at impacts (docs/design/thesis.md §5, §6).
void integrate(WorldImpl& w, const StepContext& ctx);
// integrator.cpp: the start-of-step states (WorldImpl::start_*) and scratch; one interval of
// length h from time t0 with the world's integrator, for the awake dynamic bodies marked in `only`
// (per slot; nullptr: all of them) and the forces that act on them; kinematic bodies moved by dt.
void beginIntegration(WorldImpl& w);
void integrateInterval(WorldImpl& w, double t0, double h, const char* only);
void moveKinematicBodies(WorldImpl& w, double dt);
// The contacts of located impacts after the narrow phase (event_location.cpp): a located pair
// that is not touching waits for the next step, where its impact is located; the impacts located
// in this step become contact events (contact_events.cpp locatedImpactEvents).
void settleLocatedContacts(WorldImpl& w);
void locatedImpactEvents(WorldImpl& w);
void guardNonFinite(WorldImpl& w, const char* stage);  // nan_guard.cpp  after integrate and at the end
void sweepFastBodies(WorldImpl& w);        // continuous.cpp      fast bodies against static ones
// The linearly implicit Euler velocity change (implicit_solve.cpp) from the forces in w.wrenches:
// body slot i's Δv is (dv[3 r], dv[3 r + 1]), its Δω dv[3 r + 2], with r = row[i]; false (nothing
// computed) if no active force can be linearised. `only`: as integrateInterval's. The arrays are
// the solve's scratch, valid until its next call.
struct ImplicitVelocities {
  const int* row = nullptr;
  const double* dv = nullptr;
};
bool implicitVelocityChange(WorldImpl& w, double t0, double h, bool stiffness, const char* only, ImplicitVelocities& out);
void findPairs(WorldImpl& w);              // broad_phase.cpp     docs/design/thesis.md §7
// Keeps the broad phase's pair list between steps (PairCache, broad_phase.h) for this process; on
// by default. Off rebuilds every step: the same pairs, for tests.
void usePairCache(bool on);
void narrowPhase(WorldImpl& w);            // narrow_phase.cpp    docs/design/thesis.md §7
// Contact events (contact_events.cpp): a contact that begins or ends, from the narrow phase's merge
// of this step's contacts with the last step's; their impulses once the solve is done.
void contactBegins(WorldImpl& w, uint32_t contact);
void contactEnds(WorldImpl& w, const Contact& previous);
void finishContactEvents(WorldImpl& w);
void preSolve(WorldImpl& w);               // pre_solve.cpp       one-way platforms, the pre-solve callback
void updateSensors(WorldImpl& w);          // sensor.cpp          what is in each sensor
void solveContacts(WorldImpl& w, const StepContext& ctx);         // contact_solver.cpp  docs/design/thesis.md §8–10, calls softStep
void softStep(WorldImpl& w, const StepContext& ctx);         // soft_step.cpp       the contacts in w.soft_solved
// Chooses the soft step's AVX2 or baseline passes for this process (by default AVX2 where the
// processor has it); false if AVX2 was asked for and the processor lacks it. For tests.
bool softStepUseAvx2(bool on);
// Lets groups of one-point contacts take the one-point pass (on by default); off runs them through
// the two-point pass with a neutral second point: the same bits, for tests.
void softStepOnePointPass(bool on);
// κ: the weight an integrator's position update gives to the velocity gained during the step
// (contact_solver.cpp).
double restingWeight(Integrator integrator);
void correctPositions(WorldImpl& w, const StepContext& ctx);       // position_correction.cpp  docs/design/thesis.md §9, the contacts in w.solved
void updateSleep(WorldImpl& w, const StepContext& ctx);         // sleep.cpp           islands and sleeping
void breakJoints(WorldImpl& w);            // world_joint.cpp     joints over their break force or torque
void expireForces(WorldImpl& w);           // world.cpp           docs/design/thesis.md §6

}  // namespace rigidlab

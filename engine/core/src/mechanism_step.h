// Exact mechanisms inside the step (mechanism_step.cpp): which islands of jointed bodies are
// integrated with their joints (mechanism.h), and the calls the stages make into them.
//
//   integrate        chooseMechanisms at its start; at every stage of every integrator
//                    addMechanismForces (spring and constraint forces into the wrenches); after each
//                    interval projectMechanisms (positions and velocities back onto the joints)
//   solveContacts    settleMechanisms first: an island still touching nothing after the narrow
//                    phase keeps its joints out of the contact solvers (mechanismSettled); one that
//                    now touches something has its joints solved with its contacts this step
//   after the solve  finishMechanisms: the joints' reported impulses
#pragma once

#include <cstdint>

#include "rigidlab/world.h"
#include "step_context.h"

namespace rigidlab {

struct WorldImpl;

// Islands with more closed loops than this keep the contact solvers: a loop fills the factors of
// J M⁻¹ Jᵀ, and a joint grid of 100 × 100 discs (9 800 loops) took 0.5 s of CPU a step (measured),
// a hundred times the soft step's. Linkages (a four-bar: 1 loop, a Theo Jansen leg: 5), chains and
// trees (none) are far below it.
constexpr int kMaxMechanismLoops = 64;
void chooseMechanisms(WorldImpl& w, const StepContext& ctx);
// Per body slot: kStagedMechanism or kStiffMechanism for a moving body of an exact island this
// step, else 0; nullptr when there is none.
//   staged  the joints' forces at every stage of the integrator (addMechanismForces): the
//           integrator's order
//   stiff   an island whose fastest motion the integrator cannot follow in affordable steps (a long
//           chain under tension: its waves turn at h · ω far above 1): each step is semi-implicit
//           Euler with the joints' impulse at its start (the velocities projected onto the joints
//           where the bodies are), then the projection onto the joints after it (RATTLE's halves,
//           first order, stable at any step; stepStiffMechanisms)
constexpr char kStagedMechanism = 1, kStiffMechanism = 2;
const char* mechanismBodies(const WorldImpl& w);
void stepStiffMechanisms(WorldImpl& w, double t0, double h);
// At the start of every integrator step from t0 of length h: the motors that reach their speed in
// it are caught (mechanism.h Motor).
void beginMechanismStep(WorldImpl& w, double t0, double h);
// At time t of a stage with weight `weight` (its share of the interval h in the integrator's
// update: RK4's 1/6, 1/3, 1/3, 1/6; 1 for the Euler methods) on the stage states in w.states and
// the forces in w.wrenches, whose bodies' damping is in the stages when `staged_damping`.
// How many steps an interval of length h takes so that every staged mechanism turns at most
// kMechanismTurn per step (a body's angular speed, a joint spring's rate); 1 without mechanisms.
// An island whose joints' forces of the last step (their geometric stiffness, |F| |r| / I: a chain
// link pulled by its pins turns back at √(6 T / (m ℓ))) would need more than kStiffTurns per step is
// stiff from the start.
constexpr double kMechanismTurn = 1.0;  // [rad] per step: RK4's error is then 1 % of a step's turn
constexpr int kMaxMechanismSteps = 16;
constexpr double kStiffTurns = 8.0;
int mechanismSteps(const WorldImpl& w, double h);
// An interval is an attempt: when a step of it drifts off an exact mechanism's joints by more than
// kMaxMechanismDrift of the mechanism's size (its projection's error before projecting, an estimate
// of the step's local error: a chain's end whipping round faster than its turn at the start
// said), the bodies and the joints' impulses are put back and the interval is integrated again in
// twice as many steps.
// An attempt fails too when a projection leaves a joint open by more than kProjected of the size
// (Newton did not converge from the step's drift: a whipping end turned too far in it).
constexpr double kMaxMechanismDrift = 1e-3;
// A projection that Newton could not finish and the pins' closure did (mechanism.h TreeFactor::
// closePins: any drift is put back on the joints) fails too when it started from a drift above
// kMaxClosedDrift of the size: Newton would have failed there before the closure, and the step is
// taken again in more steps (a whipping 10 000-link chain's stiff step drifted 0.49 of its 0.05 m
// lever arms, measured; its usual steps 4e-4).
constexpr double kMaxClosedDrift = 0.1;
// Or, far from the origin, by more than kRoundOff times Newton's tolerance there (a few units in
// the last place of the island's coordinates, where Newton stops at round-off): a 10 000-link chain
// of 0.1 m links spans 1000 m, whose last place is 1.1e-13 m, above 1e-12 of its 0.05 m lever arms,
// and every step of it failed (16 steps of RK4, then the stiff step again: 31 steps' work a step).
constexpr double kProjected = 1e-12;
constexpr double kRoundOff = 16.0;
void beginMechanismAttempt(WorldImpl& w);
bool mechanismAttemptFailed(const WorldImpl& w);  // a staged island drifted too far
void restoreMechanismAttempt(WorldImpl& w);
bool stiffenDriftingMechanisms(WorldImpl& w);     // those islands become stiff; false: none was left to
void addMechanismForces(WorldImpl& w, double t, double weight, double h, bool staged_damping);
void projectMechanisms(WorldImpl& w, double t_end);
void settleMechanisms(WorldImpl& w, const StepContext& ctx);
bool mechanismSettled(const WorldImpl& w, uint32_t joint);
void finishMechanisms(WorldImpl& w, const StepContext& ctx);
int exactJointCount(const WorldImpl& w);  // joints settled this step

}  // namespace rigidlab

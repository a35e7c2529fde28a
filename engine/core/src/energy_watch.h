// Blow-up detection (docs/stability.md "Blow-ups caught"): the energy balance of every step.
//
// Mechanical energy E = kinetic + gravity's potential + what forces store (World::potentialEnergy).
// Over a step, E can grow only by the work of what puts energy in:
//   forces that store none (scripts, pushes, the mouse): W ≤ h (|F|max v_max + |τ|max ω_max) per body,
//     with |F|max, |τ|max the largest the integrator's stages saw and v_max, ω_max the larger of the
//     body's speeds at the two ends of the step (a force's positive work over the step is at most
//     |F| ∫|v| dt);
//   joints with a motor or a spring, or on a kinematic body: W ≤ h (|F| Δv_max + |τ| Δω_max) from
//     the joint's reaction and motor over the step and the anchors' relative speeds at both ends;
//   contacts with a kinematic body or a moving surface: W ≤ Σ (|P_n| + |P_t|) |v_k| + |P_t| |u|
//     per point (impulses P of the step, the kinematic body's point velocity v_k, surface speed u).
// Edits between steps (scripts setting velocities, impulses, new bodies) are outside the step: each
// step starts from the energy measured at its start, and what an edit added counts as put in.
//
// The run is marked blown up when the energy it gained from nowhere, summed over the steps,
//   X = Σ (E_end − E_start − W),
// exceeds 100 times all the energy the scene ever had to play with:
//   S = K₀ + U₀ + (V₀ − V_least) + Σ W + Σ edits + Σ_steps Σ_bodies ½ m (|g| h)² + Σ_bodies m (½ v_push² + |g| r),
// where K₀ is the first step's kinetic energy, U₀ what its forces store (springs), V₀ its potential
// energy, V_least the least potential energy seen (what falling released), ½ m (|g| h)² what a
// first-order integrator gains from gravity in a step (explicit Euler in free fall: v grows by g h
// before x moves, exactly this much a step, a bounded error), and the last term what
// contacts may give back when they push overlapping bodies apart (at most contact_push_speed,
// lifting a body by at most its extent r), summed over the bodies that have been in a contact or
// are jointed (the contact solvers push joint errors apart the same way); a body that touches
// nothing has nothing to give it back, so a lone spring's slow blow-up is measured against its
// own energy (explicit Euler at ωh = 0.1: E × 1.01 a step, reported within 8 s).
// An integrator that stays stable keeps X within a few S (semi-implicit Euler on a spring swings E
// up to 1/(1 − (ωh)²/4) times E₀, 10× at ωh = 1.9); one that blows up multiplies E by a factor each
// step (explicit Euler on a spring by 1 + (ωh)²) and passes 100 S within a few steps.
#pragma once

#include <cstdint>
#include <vector>

#include "rigidlab/force.h"

namespace rigidlab {

struct StepContext;  // step_context.h

struct WorldImpl;

struct EnergyWatch {
  bool started = false;
  bool reported = false;        // one incident per world: the watch then stops
  double energy_start = 0.0;    // E at the start of the step in progress [J]
  double energy_end = 0.0;      // E at the end of the last step [J]
  double excess = 0.0;          // X [J]
  double budget = 0.0;          // K₀ + U₀ + Σ W + Σ edits [J]
  double potential_first = 0.0, potential_least = 0.0;  // V₀, V_least [J]
  // Per body slot, when some force puts energy in (else empty): |v|, |ω| at the start of the step,
  // and the largest |F|, |τ| of such forces this step.
  std::vector<double> speed, spin, push, turn;
  std::vector<char> touched;  // per body slot: in a contact at the end of some step (the give-back term)
  bool forces_noted = false;  // push and turn hold something this step
  struct SourceJoint {        // a joint that may put energy in, and its anchors' motion at the start
    uint32_t slot;
    double slide, spin;
  };
  std::vector<SourceJoint> source_joints;
  uint64_t joints_listed = UINT64_MAX;  // WorldImpl::joint_edits when source_joints was listed
  size_t joints_listed_count = 0;       // and the number of joint slots then

  // A force that puts energy in (Force::putsEnergyIn) acted on body slot i with `wr`.
  void noteForce(uint32_t i, const Wrench& wr);
};

void beginEnergyWatch(WorldImpl& w);  // before the step's first stage
void endEnergyWatch(WorldImpl& w, const StepContext& ctx);    // after its last

}  // namespace rigidlab

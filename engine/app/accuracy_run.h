// Running one configuration (problem × integrator × dt) of the accuracy lab, after docs/design/accuracy.md §5
// and DiffEqDevTools' benchmark.jl:
//
//   error pass   one run with sampling on: every sample_dt the positions (and the metrics the
//                problem asks for) are compared with Exact(t); whole number of steps N = T/dt, never
//                `while t < T`. A run is stopped and marked `unstable` once E > 1e6·|E0|, or `nan`
//                once a state is not finite or the engine froze a body (NaN firewall).
//   timed runs   the scene is loaded untimed (setup excluded), one warm-up run, then R timed
//                repeats of the N steps with sampling off; runs shorter than 5 ms are batched
//                (K scenes loaded first, their runs timed together, divided by K). min and median.
#pragma once

#include <string>
#include <vector>

#include "accuracy_problem.h"
#include "rigidlab/world.h"

namespace rigidlab::app::accuracy {

// Step sizes of the sweep: dt_k = 1/30 · 2^−k, k = 0 … k_max (docs/design/accuracy.md §5).
double sweepDt(int k);

// Steps for `duration` at `dt`: N with |N dt − duration| ≤ 1e-9 duration, else std::runtime_error.
long wholeSteps(double duration, double dt, const std::string& what);

struct ErrorPass {
  std::string status = "ok";  // ok | unstable | nan
  long steps = 0;             // steps taken (fewer than planned if stopped)
  double stopped_at = 0.0;    // [s] simulated time when stopped (status ≠ ok)
  double err_linf = 0.0;      // max over samples and bodies of ‖p − p_exact‖ / reference_length
  double err_final = 0.0;     // the same at t_end
  double err_l2 = 0.0;        // RMS over the samples
  double vel_err_final = 0.0;     // max over bodies of ‖v − v_exact‖ / reference_speed at t_end
  double energy_drift_max = 0.0;  // max |E/E0 − 1|
  double energy_drift_trend = 0.0;  // least-squares slope of E(t)/E0 [1/s]
  double mom_err = 0.0;     // max |P − P0| [kg·m/s]
  double angmom_err = 0.0;  // max |L − L0| / |L0| (about the origin)
  double period_err = 0.0;  // |T_measured / T − 1| (Problem::period), ∞ if fewer than two crossings
  long force_evals = 0, lua_calls = 0;  // during the steps only
  int pairs_max = 0, contact_points_max = 0;
  long impacts = 0;  // impacts located inside steps (ImpactHandling::Located)
  // Summed stage times of the error pass [ms] (integrate, broad, narrow, solve, correct).
  double integrate_ms = 0, broad_ms = 0, narrow_ms = 0, solve_ms = 0, correct_ms = 0;
  std::vector<double> energy_t, energy_ratio;  // E(t)/E0 at the samples, if recorded
  std::string stages() const;  // which stages did work: "integrate, forces (Lua), contacts"
};

// The error pass. `record_energy`: keep E(t)/E0 at every sample (long runs).
ErrorPass errorPass(const Problem& problem, Integrator integrator, double dt, double duration, bool record_energy);

struct TimingOptions {
  int max_repeats = 20;           // R
  double budget_s = 0.5;          // stop repeating after this much wall time, loading included (≥ min_repeats)
  int min_repeats = 3;
  double batch_below_s = 0.005;   // runs shorter than this are batched
  double single_run_above_s = 2.0;  // one run longer than this: time it once (SciML's `seconds`)
};

struct Timing {
  double min_s = 0, median_s = 0, iqr_s = 0;  // per run [s]
  int repeats = 0;  // timed repeats
  int batch = 1;    // runs per timed repeat
};

// Times `steps` steps of the problem (stopping early if the error pass did: pass its step count).
Timing timeRuns(const Problem& problem, Integrator integrator, double dt, long steps, const TimingOptions& options);

}  // namespace rigidlab::app::accuracy

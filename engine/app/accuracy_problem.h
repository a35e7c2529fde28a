// A reference problem of the accuracy lab: a Lua scene under scripts/accuracy/ that defines
// Exact(t) and a global `accuracy` table (scripts/accuracy/README.md documents both).
//
// The Scene API runs the scene's own Lua state and exposes only its hooks, so the `accuracy` table
// is read by running the file a second time in a small, separate Lua state (base, math, string,
// table; `require` answers an empty stand-in). That state is kept: it also holds the optional
// `accuracy.energy(bodies, t)` function, for problems whose potential the world cannot know (a
// force written in Lua). It never sees the world and costs nothing during the timed runs.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rigidlab/world.h"

namespace rigidlab::app::accuracy {

// What the report does with a problem (scripts/accuracy/README.md, "group").
enum class Group {
  Smooth,   // no contacts: the order is fitted and gated
  Impact,   // isolated impacts, located inside the step (ImpactHandling::Located): fitted and gated
            //   like a smooth problem, the integrator's own order expected through the impacts
  Contact,  // persistent contact, solved once per step: order reported, not gated
  Sanity,   // round-off checks (free fall): not fitted
  Mechanism,  // jointed bodies touching nothing, integrated with their joints (WorldDef::exact_joints):
              //   fitted and gated like a smooth problem; a section of their own in the report
};
const char* groupName(Group g);

// The expected behaviour of one integrator on one problem.
struct Expected {
  bool known = false;  // false: no expectation (an integrator the problem does not mention)
  bool exact = false;  // round-off only: err ≤ 4 N ε
  double order = 0.0;
};

class ProblemScript;  // the separate Lua state (accuracy_problem.cpp)

struct Problem {
  std::string name;  // the file's stem, e.g. "sho"
  std::filesystem::path file;
  std::string title;  // from the scene table, else the name
  Group group = Group::Smooth;
  double t_end = 0.0;             // [s]
  double sample_dt = 0.1;         // [s]
  double reference_length = 1.0;  // [m]
  double reference_speed = 1.0;   // [m/s]
  bool energy = false, momentum = false, angmom = false, velocity = false;  // extra metrics
  std::map<std::string, Expected> expected;  // by integrator name; defaults filled in
  std::optional<double> long_run;            // [s] energy-over-time run at dt = 1/60
  // The exact period [s] of an oscillation about angle 0 of the body `period_body`: the run
  // measures its period from the times its angle crosses 0 (accuracy_run.cpp).
  std::optional<double> period;
  std::string period_body;
  std::string note;
  // What the error is: "position" (‖p − p_exact‖ / reference_length against Exact(t)), or
  // "energy" (max |E − E0| / energy_scale, for a chaotic problem whose trajectory has no closed
  // form but whose energy is conserved: the double pendulum).
  bool fit_energy = false;
  std::optional<double> energy_scale;     // [J]: energy errors are |E − E0| / energy_scale (else |E/E0 − 1|)
  std::optional<double> order_tolerance;  // around the expected orders (default ±0.2, ±0.3 for order 4)
  double asymptotic_below = 0.1;          // errors below this (and above round-off) are fitted
  std::shared_ptr<ProblemScript> script;  // holds accuracy.energy when the scene gives one

  Expected expectedFor(const std::string& integrator) const;
  bool hasCustomEnergy() const;
  // Total energy [J] of the world's bodies at time t: the scene's accuracy.energy if it gives one,
  // else World::kineticEnergy() + World::potentialEnergy().
  double energyOf(const World& world, double t) const;
};

// Reads the problem's `accuracy` table. Throws std::runtime_error("<file>: accuracy.<field>: ...").
Problem loadProblem(const std::filesystem::path& file);

// The .lua files directly in `dir`, sorted by name.
std::vector<std::filesystem::path> problemFiles(const std::filesystem::path& dir);

// The default reference problems: scripts/accuracy/.
std::filesystem::path problemDirectory();

// Default expectations (docs/design/accuracy.md §2): euler 1, semi_implicit_euler 1, rk4 4, implicit_euler 1.
std::optional<double> defaultOrder(const std::string& integrator);

}  // namespace rigidlab::app::accuracy

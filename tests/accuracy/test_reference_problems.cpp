// Gates of the accuracy lab on the reference problems of scripts/accuracy/ (docs/design/accuracy.md §5, "CI
// gates"): deterministic, never timings.
//   1. the observed order of every integrator on the smooth and sanity problems is its expected one
//      (euler 1, semi_implicit_euler 1, rk4 4, implicit_euler 1, within ±0.2, ±0.3 for 4; "exact"
//      problems within the round-off bound), fitted exactly as `rigidlab accuracy` fits it;
//   2. the error at dt = 1/60 is at most 1.05 × the value stored in stored_errors.csv (a
//      regression guard; the engine is deterministic for one binary), and not below a fifth of it
//      (a much smaller error means the problem or the metric changed: update the file on purpose);
//      stored values under 1e-9 are round-off: the error must only stay under 1e-9;
//   3. stages: a problem without contacts finds no pairs, one without Lua forces makes no Lua
//      calls, and a Lua force is called once per evaluation (4 per step with RK4).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "accuracy_problem.h"
#include "accuracy_report.h"
#include "accuracy_run.h"

namespace {

using namespace rigidlab::app::accuracy;

constexpr int kMaxK = 8;  // the report's sweep: dt = 1/30 … 1/7680

// stored_errors.csv: problem,integrator,err_linf at dt = 1/60.
const std::map<std::pair<std::string, std::string>, double>& storedErrors() {
  static const auto table = [] {
    std::map<std::pair<std::string, std::string>, double> t;
    std::ifstream in(RIGIDLAB_STORED_ERRORS);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || line.rfind("problem,", 0) == 0) continue;
      std::istringstream fields(line);
      std::string problem, integrator, value;
      std::getline(fields, problem, ',');
      std::getline(fields, integrator, ',');
      std::getline(fields, value, ',');
      t[{problem, integrator}] = std::stod(value);
    }
    return t;
  }();
  return table;
}

std::vector<std::string> integrators() {
  std::vector<std::string> out;
  std::istringstream in(rigidlab::integratorNames());
  std::string item;
  while (std::getline(in, item, ',')) {
    item.erase(0, item.find_first_not_of(' '));
    out.push_back(item);
  }
  return out;
}

// Problems whose scene has a force written in Lua.
const std::set<std::string> kLuaForces = {"kepler", "time_limited_force", "time_limited_naive"};

void checkProblem(const std::string& name) {
  const Problem problem = loadProblem(problemDirectory() / (name + ".lua"));
  for (const std::string& integrator_name : integrators()) {
    CAPTURE(integrator_name);
    const rigidlab::Integrator integrator = *rigidlab::parseIntegrator(integrator_name);
    std::vector<Row> rows(kMaxK + 1);
    for (int k = 0; k <= kMaxK; ++k) {
      Row& r = rows[k];
      r.problem = &problem;
      r.integrator = integrator_name;
      r.k = k;
      r.dt = sweepDt(k);
      r.steps_planned = wholeSteps(problem.t_end, r.dt, name);
      r.error = errorPass(problem, integrator, r.dt, problem.t_end, false);
    }
    std::vector<const Row*> pointers;
    for (const Row& r : rows) pointers.push_back(&r);

    // 1. Order.
    const Verdict v = judge(problem, integrator_name, pointers);
    if (v.gated) {
      INFO("observed order " << v.observed << ", expected " << v.expected << ": " << v.why);
      CHECK(v.pass);
    }

    // 2. Error at dt = 1/60 against the stored value.
    const Row& at60 = rows[1];
    const auto stored = storedErrors().find({name, integrator_name});
    if (stored == storedErrors().end()) {
      FAIL_CHECK("no stored error for " << name << " / " << integrator_name << " in stored_errors.csv (measured "
                                        << at60.error.err_linf << ")");
    } else {
      const double s = stored->second, e = at60.error.err_linf;
      INFO("err_linf at 1/60 = " << e << ", stored " << s);
      CHECK(std::isfinite(e));
      if (s < 1e-9) {
        CHECK(e <= 1e-9);  // round-off (or nearly): gated by its size, not its digits
      } else {
        CHECK(e <= 1.05 * s);
        CHECK(e >= 0.2 * s);
      }
    }

    // 3. Stages.
    for (const Row& r : rows) {
      CAPTURE(r.k);
      if (!kLuaForces.contains(name)) CHECK(r.error.lua_calls == 0);
      // An accurate run of a contact-free problem never brings two bodies together.
      const bool touches = problem.group == Group::Contact || problem.group == Group::Impact;
      // (A mechanism's links overlap their neighbours' bounds at every pin, so pairs form; no
      // contact point may.)
      if (!touches && r.error.err_linf < 0.1) {
        if (problem.group == Group::Mechanism) {
          CHECK(r.error.contact_points_max == 0);
        } else {
          CHECK(r.error.pairs_max == 0);
        }
      }
      if (problem.group == Group::Contact) CHECK((r.error.contact_points_max > 0 || r.error.impacts > 0));
      // Its order is gated because its impacts are located inside the step: they must be.
      if (problem.group == Group::Impact) CHECK(r.error.impacts > 0);
    }
  }
}

}  // namespace

TEST_CASE("reference problem: free_fall") { checkProblem("free_fall"); }
TEST_CASE("reference problem: drag_projectile") { checkProblem("drag_projectile"); }
TEST_CASE("reference problem: sho") { checkProblem("sho"); }
TEST_CASE("reference problem: damped_under") { checkProblem("damped_under"); }
TEST_CASE("reference problem: damped_critical") { checkProblem("damped_critical"); }
TEST_CASE("reference problem: damped_over") { checkProblem("damped_over"); }
TEST_CASE("reference problem: two_body_spring") { checkProblem("two_body_spring"); }
TEST_CASE("reference problem: kepler") { checkProblem("kepler"); }
TEST_CASE("reference problem: time_limited_force") { checkProblem("time_limited_force"); }
TEST_CASE("reference problem: time_limited_naive") { checkProblem("time_limited_naive"); }
TEST_CASE("reference problem: incline") { checkProblem("incline"); }
TEST_CASE("reference problem: disc_slide_roll") { checkProblem("disc_slide_roll"); }
TEST_CASE("reference problem: bouncing_ball") { checkProblem("bouncing_ball"); }
TEST_CASE("reference problem: bouncing_ball_drag") { checkProblem("bouncing_ball_drag"); }
TEST_CASE("reference problem: collision_1d") { checkProblem("collision_1d"); }
TEST_CASE("reference problem: collision_oblique") { checkProblem("collision_oblique"); }
TEST_CASE("reference problem: collision_friction") { checkProblem("collision_friction"); }
TEST_CASE("reference problem: collision_gravity") { checkProblem("collision_gravity"); }
TEST_CASE("reference problem: slope_bounce") { checkProblem("slope_bounce"); }
TEST_CASE("reference problem: kinematic_paddle") { checkProblem("kinematic_paddle"); }
TEST_CASE("reference problem: kinematic_spinner") { checkProblem("kinematic_spinner"); }
TEST_CASE("reference problem: pendulum_revolute") { checkProblem("pendulum_revolute"); }
TEST_CASE("reference problem: pendulum_small") { checkProblem("pendulum_small"); }
TEST_CASE("reference problem: pendulum_large") { checkProblem("pendulum_large"); }
TEST_CASE("reference problem: rod_pendulum") { checkProblem("rod_pendulum"); }
TEST_CASE("reference problem: double_pendulum") { checkProblem("double_pendulum"); }
TEST_CASE("reference problem: slider_incline") { checkProblem("slider_incline"); }
TEST_CASE("reference problem: atwood") { checkProblem("atwood"); }
TEST_CASE("reference problem: wheel_spring") { checkProblem("wheel_spring"); }
TEST_CASE("reference problem: four_bar") { checkProblem("four_bar"); }
TEST_CASE("reference problem: damped_body") { checkProblem("damped_body"); }

TEST_CASE("pendulum_revolute: the measured period converges to the exact 4 K(k) / ω0 at each integrator's order") {
  // A wrong T (the small-angle 2π/ω0 is 25 % short, a K off in its 4th digit) would leave a floor
  // under which the period error cannot fall. The pin is integrated with the pendulum (exact
  // joints): semi-implicit Euler's period error halves with the step (order 1), RK4's falls by
  // 2⁴ = 16 (order 4) until the crossing times' own round-off.
  const Problem problem = loadProblem(problemDirectory() / "pendulum_revolute.lua");
  REQUIRE(problem.period);
  CHECK(*problem.period == doctest::Approx(2.6725273101).epsilon(1e-9));
  for (const rigidlab::Integrator integrator : {rigidlab::Integrator::SemiImplicitEuler, rigidlab::Integrator::RungeKutta4}) {
    const bool rk4 = integrator == rigidlab::Integrator::RungeKutta4;
    double previous = 0.0;
    for (int k = 4; k <= kMaxK; ++k) {
      const double e = errorPass(problem, integrator, sweepDt(k), problem.t_end, false).period_err;
      CAPTURE(k);
      CAPTURE(e);
      CHECK(std::isfinite(e));
      if (k > 4 && !rk4) {
        CHECK(previous / e > 1.7);
        CHECK(previous / e < 2.6);
      }
      // Above 1e-13 (a few hundred ulps of T ≈ 2.67 s) the error is RK4's own: 16 per halving.
      if (k > 4 && rk4 && previous > 1e-13) CHECK(previous / e > 12.0);
      previous = e;
    }
    // At dt = 1/7680: 2 ⁄ 7680 of a period behind for the first-order method, round-off for RK4.
    CHECK(previous < (rk4 ? 1e-14 : 1.5e-3));
  }
}

TEST_CASE("reference problems: every file is gated above, with stored errors for every integrator") {
  std::set<std::string> gated = {"free_fall", "drag_projectile", "sho", "damped_under", "damped_critical", "damped_over",
                                 "two_body_spring", "kepler", "time_limited_force", "time_limited_naive", "incline",
                                 "disc_slide_roll", "bouncing_ball", "bouncing_ball_drag", "collision_1d", "collision_oblique",
                                 "collision_friction", "collision_gravity", "slope_bounce", "kinematic_paddle", "kinematic_spinner",
                                 "pendulum_revolute",
                                 "pendulum_small", "pendulum_large", "rod_pendulum", "double_pendulum", "slider_incline", "atwood", "wheel_spring", "four_bar", "damped_body"};
  for (const auto& file : problemFiles(problemDirectory())) {
    const std::string name = file.stem().string();
    CAPTURE(name);
    CHECK(gated.contains(name));
    CHECK_NOTHROW(loadProblem(file));
    for (const std::string& i : integrators()) {
      CAPTURE(i);
      CHECK(storedErrors().contains({name, i}));
    }
  }
}

TEST_CASE("invariants: momentum under pair forces and impacts, the orbit's angular momentum, impact algebra") {
  const double dt = sweepDt(1);
  const auto run = [&](const std::string& name, const std::string& integrator) {
    const Problem p = loadProblem(problemDirectory() / (name + ".lua"));
    return errorPass(p, *rigidlab::parseIntegrator(integrator), dt, p.t_end, false);
  };
  for (const std::string& integrator : integrators()) {
    CAPTURE(integrator);
    // Pair forces and contact impulses are equal and opposite: momentum to round-off (docs/design/accuracy.md §3.5, §3.10).
    for (const char* name : {"two_body_spring", "collision_1d", "collision_oblique", "collision_friction"}) {
      CAPTURE(name);
      CHECK(run(name, integrator).mom_err <= 1e-12);
    }
    // Head-on impacts: the velocities after the impact are Newton's law to round-off.
    CHECK(run("collision_1d", integrator).vel_err_final <= 1e-9);
  }
  // Semi-implicit Euler keeps a central force's angular momentum exactly (docs/design/accuracy.md §3.6):
  // L' = x' × v' = (x + h v') × v' = x × v + h x × a(x) = x × v.
  const ErrorPass semi = run("kepler", "semi_implicit_euler");
  CHECK(semi.angmom_err <= 1e-12);
  CHECK(run("kepler", "euler").angmom_err > 1e-3);  // control: explicit Euler does not
}

TEST_CASE("Lua forces: one call per evaluation, four per step with RK4, one with the Euler variants") {
  const Problem kepler = loadProblem(problemDirectory() / "kepler.lua");
  for (const auto& [name, per_step] : {std::pair{"rk4", 4}, {"semi_implicit_euler", 1}, {"euler", 1}}) {
    CAPTURE(name);
    const double dt = sweepDt(1);
    const ErrorPass e = errorPass(kepler, *rigidlab::parseIntegrator(name), dt, kepler.t_end, false);
    CHECK(e.steps == wholeSteps(kepler.t_end, dt, "kepler"));
    CHECK(e.force_evals == per_step * e.steps);
    CHECK(e.lua_calls == e.force_evals);
    CHECK(e.stages() == "integrate, forces (Lua)");
  }
}

TEST_CASE("order fit: the slope over the asymptotic window, round-off and unstable runs left out") {
  Problem p;
  p.name = "synthetic";
  p.group = Group::Smooth;
  std::vector<Row> rows(9);
  std::vector<const Row*> pointers;
  for (int k = 0; k <= 8; ++k) {
    Row& r = rows[k];
    r.problem = &p;
    r.integrator = "rk4";
    r.k = k;
    r.dt = sweepDt(k);
    r.steps_planned = 30L << k;
    // err = 100 dt^4 down to a round-off floor of 1e-13; the coarsest run unstable.
    r.error.err_linf = std::max(100 * std::pow(r.dt, 4), 1e-13);
    if (k == 0) r.error.status = "unstable";
    pointers.push_back(&r);
  }
  const Fit f = fitOrder(pointers);
  CHECK(f.points >= 3);
  CHECK(f.order == doctest::Approx(4.0).epsilon(1e-9));
  CHECK(f.dt_max == sweepDt(1));  // the unstable k = 0 run is not in the fit
  CHECK(judge(p, "rk4", pointers).pass);
  CHECK_FALSE(judge(p, "euler", pointers).pass);  // order 4 observed, 1 expected

  // "exact": every error within 16 N ε.
  p.expected["rk4"] = Expected{true, true, 0.0};
  for (Row& r : rows) r.error.status = "ok", r.error.err_linf = 1e-15;
  CHECK(judge(p, "rk4", pointers).pass);
  rows[3].error.err_linf = 1e-6;
  CHECK_FALSE(judge(p, "rk4", pointers).pass);
}

TEST_CASE("problem files: a scene without the accuracy table or with a bad field is refused with its name") {
  const auto dir = std::filesystem::temp_directory_path() / "rigidlab_accuracy_test";
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  const std::string body = "function PopulateWorld(world) end\nfunction Exact(t) return {} end\n";
  const auto message = [](const std::filesystem::path& f) {
    try {
      loadProblem(f);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK(message(write("none.lua", body)).find("no `accuracy` table") != std::string::npos);
  CHECK(message(write("grid.lua", body + "accuracy = { t_end = 1.05 }\n")).find("accuracy.t_end must be a multiple of sample_dt") !=
        std::string::npos);
  CHECK(message(write("metric.lua", body + "accuracy = { t_end = 1, metrics = {'speed'} }\n")).find("unknown metric \"speed\"") !=
        std::string::npos);
  CHECK(message(write("noexact.lua", "function PopulateWorld(world) end\naccuracy = { t_end = 1 }\n")).find("no Exact(t)") !=
        std::string::npos);
  const Problem ok = loadProblem(write("ok.lua", body + "accuracy = { t_end = 2, expected_order = { rk4 = 'exact', euler = 2 } }\n"));
  CHECK(ok.t_end == 2.0);
  CHECK(ok.expectedFor("rk4").exact);
  CHECK(ok.expectedFor("euler").order == 2.0);
  CHECK(ok.expectedFor("semi_implicit_euler").order == 1.0);
  // An energy function that never returns is stopped by an instruction budget.
  const Problem spin = loadProblem(write("spin.lua", body + "accuracy = { t_end = 1, energy = function() while true do end end }\n"));
  rigidlab::World world;
  CHECK_THROWS_WITH_AS(spin.energyOf(world, 0.0), doctest::Contains("million instructions"), std::runtime_error);
  std::filesystem::remove_all(dir);
}

// Stability cases on springs, dampers and long runs, and frame-rate independence
// (docs/design/accuracy.md §4: S1–S6, S9, S11). Parameters and expected figures are the document's.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>

#include "accuracy_problem.h"
#include "gnuplot_script.h"
#include "rigidlab/lua/scene.h"
#include "rigidlab/world.h"
#include "stability_cases.h"

namespace rigidlab::app::stability {
namespace {

constexpr double kDt = 1.0 / 60.0;  // [s] every case runs at 60 Hz (docs/design/accuracy.md §4)
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::optional<Integrator> find(const std::string& name) { return parseIntegrator(name); }

// Energy went up from one step to the next by more than 1e-9 relative. Energies under 1e-200·E0
// do not count: there x² underflows to subnormal numbers and the energy is round-off (an implicit
// step at k = 1e6 takes 50 J to 1e-316 J in about 130 steps).
bool increased(double e, double previous, double e0) { return e > previous * (1.0 + 1e-9) && e > 1e-200 * e0; }

// A body of mass 1 kg on a spring to a fixed anchor at the origin (rest length 0, so F = −k x − c v
// along the line), released at rest from (x0, 0), no gravity.
struct Oscillator {
  World world;
  BodyId body;
  Oscillator(Integrator integrator, double k, double c, double x0, double mass = 1.0) {
    WorldDef def;
    def.gravity = Vec2::Zero();
    def.integrator = integrator;
    world = World(def);
    BodyDef b;
    b.shape = makeCircle(0.01);
    b.mass = mass;
    b.position = Vec2(x0, 0.0);
    body = world.createBody(b);
    SpringDef s;
    s.a = body;
    s.anchor = Vec2::Zero();
    s.stiffness = k;
    s.rest_length = 0.0;
    s.damping = c;
    world.addSpring(s);
  }
  double energy() const { return world.kineticEnergy() + world.potentialEnergy(); }
  // False once the state is not finite or the NaN firewall froze the body (made it static).
  bool healthy() const {
    const Body& b = world.body(body);
    return !b.isStatic() && isFinite(b.center) && isFinite(b.velocity);
  }
};

// What a run of an oscillator did.
struct SpringRun {
  bool finite = true;           // never non-finite (nor frozen)
  long blowup_step = -1;        // first step with E > 1e6·E0 or a non-finite state (−1: never)
  long watch_step = -1;         // step of the world's blow-up incident (energy_watch.h; −1: none)
  double max_ratio = 0;         // max E/E0
  double min_ratio = 1e300;     // min E/E0
  bool monotone = true;         // E_n ≤ E_{n−1}·(1 + 1e-9) at every step
  double max_abs_x = 0;         // [m]
  double worst_growth_err = 0;  // max over steps of |E_n/E_{n−1} − expected_growth| / expected_growth
};

SpringRun runOscillator(Integrator integrator, double k, double c, double x0, long steps, double expected_growth = kNaN) {
  Oscillator o(integrator, k, c, x0);
  SpringRun r;
  const double e0 = o.energy();
  double previous = e0;
  for (long n = 1; n <= steps; ++n) {
    o.world.step(kDt);
    if (r.watch_step < 0)
      for (const Incident& incident : o.world.incidents())
        if (!incident.frozen) r.watch_step = n;
    if (!o.healthy()) {
      r.finite = false;
      if (r.blowup_step < 0) r.blowup_step = n;
      break;
    }
    const double e = o.energy();
    const double ratio = e / e0;
    r.max_ratio = std::max(r.max_ratio, ratio);
    r.min_ratio = std::min(r.min_ratio, ratio);
    r.max_abs_x = std::max(r.max_abs_x, std::abs(o.world.body(o.body).center.x()));
    if (increased(e, previous, e0)) r.monotone = false;
    if (std::isfinite(expected_growth) && previous > 0 && std::isfinite(e))
      r.worst_growth_err = std::max(r.worst_growth_err, std::abs(e / previous - expected_growth) / expected_growth);
    if (!(ratio <= 1e6) && r.blowup_step < 0) r.blowup_step = n;
    if (!std::isfinite(e)) {
      r.finite = false;
      break;
    }
    previous = e;
  }
  return r;
}


std::string yesNo(bool b) { return b ? "yes" : "no"; }

// Least-squares slope of y against x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double den = n * sxx - sx * sx;
  return den != 0 ? (n * sxy - sx * sy) / den : 0.0;
}

}  // namespace

std::vector<std::string> integrators() {
  std::vector<std::string> out;
  std::istringstream in(integratorNames());
  std::string item;
  while (std::getline(in, item, ',')) {
    item.erase(0, item.find_first_not_of(' '));
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::string fmt(double x, int digits) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// S2, S3, S4: where each integrator stops being stable on an undamped spring at 60 Hz.
CaseResult stiffSpringThresholds(const Options&) {
  CaseResult r;
  r.name = "stiff_spring_thresholds";
  r.title = "Stiff springs: largest stable k per integrator (S2–S4)";
  r.rule = "m = 1 kg, x0 = 0.01 m, 10 s at dt = 1/60; a run is stable if it stays finite and the world reports no "
           "blow-up (the energy watch, \"Blow-ups caught\"). "
           "PASS if semi-implicit Euler is stable at k = 12 996 (ωh = 1.9) and unstable at 15 876 (ωh = 2.1), RK4 "
           "stable at 25 000 (ωh = 2.64) and unstable at 32 400 (ωh = 3.0), and explicit Euler multiplies the "
           "energy by exactly 1 + (ωh)² per step on k = 4π² (1e-12 relative): the integrators are the textbook ones";
  const std::vector<double> ks = {1e2, 1e3, 1e4, 12996, 15876, 25000, 32400, 1e5, 1e6, 1e7};
  constexpr long kSteps = 600;
  Table t;
  t.title = "stable (S) or not (–) at each k [N/m]";
  t.header = {"integrator"};
  for (double k : ks) t.header.push_back(fmt(k, 6));
  t.header.push_back("largest stable k");
  bool pass = true;
  for (const std::string& name : integrators()) {
    const Integrator integrator = *find(name);
    std::vector<std::string> row = {name};
    double largest = kNaN;
    bool still = true;
    for (double k : ks) {
      const SpringRun s = runOscillator(integrator, k, 0.0, 0.01, kSteps);
      const bool stable = s.finite && s.watch_step < 0;
      row.push_back(stable ? "S" : "–");
      if (stable && still) largest = k;
      still &= stable;
      const auto expect = [&](const char* who, double at, bool want) {
        if (name != who || (k != at)) return;
        if (stable != want) {
          pass = false;
          r.notes.push_back(name + " at k = " + fmt(k, 6) + ": " + (stable ? "stable" : "unstable") + ", expected " +
                            (want ? "stable" : "unstable"));
        }
      };
      expect("semi_implicit_euler", 12996, true);
      expect("semi_implicit_euler", 15876, false);
      expect("rk4", 25000, true);
      expect("rk4", 32400, false);
    }
    row.push_back(std::isnan(largest) ? "none (unstable at 100 N/m)" : fmt(largest, 6));
    r.figures.push_back({"largest_stable_k_" + name, largest, "N/m", std::isnan(largest) ? "none" : ""});
    t.rows.push_back(row);
  }
  // S4: explicit Euler's energy grows by exactly 1 + a² per step on an undamped spring.
  if (const auto euler = find("euler")) {
    const double k = 4 * M_PI * M_PI, a = std::sqrt(k) * kDt;
    const SpringRun s = runOscillator(*euler, k, 0.0, 0.1, 600, 1.0 + a * a);
    r.figures.push_back({"euler_growth_factor_error", s.worst_growth_err, "", ""});
    if (!(s.worst_growth_err <= 1e-12)) {
      pass = false;
      r.notes.push_back("explicit Euler's energy factor per step is off 1 + (ωh)² by " + fmt(s.worst_growth_err) + " (relative)");
    }
  }
  r.tables.push_back(t);
  r.pass = pass;

  // The picture's sweep: the table's k and 25 more, ωh = 0.1 … 100 (8 a decade), every integrator;
  // max E/E0 over the run (until it stops being finite) and whether it is stable by the same rule.
  std::vector<double> sweep = ks;
  for (int i = 0; i <= 24; ++i) {
    const double omega_h = 0.1 * std::pow(10.0, i / 8.0);
    sweep.push_back(std::pow(omega_h / kDt, 2));
  }
  std::sort(sweep.begin(), sweep.end());
  DataFile data{"stiff_springs", {"integrator", "k", "omega_h", "stable", "max_energy_ratio", "blowup_reported_step", "gated_k"}, {}};
  for (const std::string& name : integrators())
    for (double k : sweep) {
      const SpringRun s = runOscillator(*find(name), k, 0.0, 0.01, kSteps);
      const bool gated = std::find(ks.begin(), ks.end(), k) != ks.end();
      data.rows.push_back({name, fmt(k, 10), fmt(std::sqrt(k) * kDt, 10), yesNo(s.finite && s.watch_step < 0),
                           fmt(s.max_ratio, 10), s.watch_step < 0 ? "" : std::to_string(s.watch_step), yesNo(gated)});
    }
  r.data.push_back(std::move(data));
  Picture p{.name = "stiff_springs", .data = "stiff_springs",
              .title = "Undamped spring, m = 1 kg, 10 s at dt = 1/60: largest energy against ωh",
              .xlabel = "ωh = √(k/m)·dt", .ylabel = "max E/E_0 over the run (above 10^{12}: top edge)"};
  const double ceiling = 1e12;
  for (size_t i = 0; i < integrators().size(); ++i) {
    const std::string name = integrators()[i];
    const gnuplot::Style style = gnuplot::integratorStyle(name, i);
    p.series.push_back({name + ": stable", "omega_h", "max_energy_ratio", {{"integrator", name}, {"stable", "yes"}},
                        style.color, style.filled, true, style.dash, ceiling});
    p.series.push_back({name + ": blown up", "omega_h", "max_energy_ratio", {{"integrator", name}, {"stable", "no"}},
                        style.color, style.open, false, 1, ceiling});
  }
  p.marks.push_back({"ωh = 2: semi-implicit Euler's limit", 2.0, true});
  p.marks.push_back({"ωh = 2√2: RK4's limit", 2.0 * std::sqrt(2.0), true, 0, 0, "#60a060"});
  r.pictures.push_back(std::move(p));
  return r;
}

// S1: k = 1e6 N/m at 60 Hz must stay finite, with energy never increasing, for the stiff-stable integrator.
CaseResult stiffSpringImplicit(const Options&) {
  CaseResult r;
  r.name = "stiff_spring_implicit";
  r.title = "Very stiff spring, k = 1e6 N/m at dt = 1/60 (S1)";
  r.rule = "m = 1 kg, x0 = 0.01 m (ωh = 16.7), 10 s. PASS if implicit_euler stays finite, its energy never "
           "increases (E_n ≤ E_{n−1}·(1 + 1e-9)), |x| ≤ x0 and the world reports no blow-up; and the world reports "
           "a blow-up (the energy watch, \"Blow-ups caught\") within 8 steps for each explicit integrator";
  Table t;
  t.title = "per integrator";
  t.header = {"integrator", "finite for 10 s", "step where E > 1e6·E0", "blow-up reported at step", "max E/E0",
              "energy never increases (1e-9 per step)", "max |x| [m]"};
  bool pass = true, found = false;
  const auto step = [](long n) { return n < 0 ? std::string("never") : std::to_string(n); };
  for (const std::string& name : integrators()) {
    const SpringRun s = runOscillator(*find(name), 1e6, 0.0, 0.01, 600);
    t.rows.push_back({name, yesNo(s.finite && s.blowup_step < 0), step(s.blowup_step), step(s.watch_step), fmt(s.max_ratio),
                      yesNo(s.monotone), fmt(s.max_abs_x)});
    r.figures.push_back({"blowup_step_" + name, s.blowup_step < 0 ? kNaN : static_cast<double>(s.blowup_step), "step",
                         s.blowup_step < 0 ? "never" : ""});
    r.figures.push_back({"blowup_reported_step_" + name, s.watch_step < 0 ? kNaN : static_cast<double>(s.watch_step), "step",
                         s.watch_step < 0 ? "never" : ""});
    if (name == "implicit_euler") {
      found = true;
      const bool held = s.finite && s.blowup_step < 0 && s.monotone && s.max_abs_x <= 0.01 * (1 + 1e-12) && s.watch_step < 0;
      pass &= held;
      r.figures.push_back({"implicit_euler_max_energy_ratio", s.max_ratio, "", ""});
      if (!held)
        r.notes.push_back("implicit_euler: finite " + yesNo(s.finite) + ", energy never increases " + yesNo(s.monotone) +
                          ", max |x| " + fmt(s.max_abs_x) + ", blow-up reported at step " + step(s.watch_step));
    } else if (!(s.watch_step >= 1 && s.watch_step <= 8)) {
      pass = false;
      r.notes.push_back(name + ": blow-up reported at step " + step(s.watch_step) + ", expected within 8 steps");
    }
  }
  if (!found) r.notes.push_back("the engine has no implicit_euler integrator (integrators: " + integratorNames() + ")");
  r.tables.push_back(t);
  r.pass = pass && found;
  return r;
}

// S5: a pure damper must never flip the sign of a velocity, whatever b·dt/m is (damper_sign), and
// must never make it grow (damper_monotone).
namespace {
CaseResult damperCase(bool monotone_rule) {
  CaseResult r;
  r.name = monotone_rule ? "damper_monotone" : "damper_sign";
  r.title = monotone_rule ? "Dampers never make a speed grow (S5)" : "Dampers never flip a velocity's sign (S5)";
  r.rule = std::string("m = 1 kg, v0 = 1 m/s, a damper F = −b v with b·dt/m = 1.5, 2.5, 10, 100, 1 s at dt = 1/60, no "
                       "gravity. PASS if for every integrator and every b ") +
           (monotone_rule ? "the speed never grows (|v_{n+1}| ≤ |v_n|)" : "the velocity keeps its sign (v_n·v0 ≥ 0)");
  const std::vector<double> ratios = {1.5, 2.5, 10, 100};
  Table t;
  t.title = std::string("velocity factor of the first step, v1/v0 (implicit/Padé: 1/(1 + b·dt/m)); ! marks ") +
            (monotone_rule ? "a speed that grew" : "a sign flip");
  t.header = {"integrator"};
  for (double q : ratios) t.header.push_back("b·dt/m = " + fmt(q));
  bool pass = true;
  for (const std::string& name : integrators()) {
    std::vector<std::string> row = {name};
    for (double q : ratios) {
      WorldDef def;
      def.gravity = Vec2::Zero();
      def.integrator = *find(name);
      World w(def);
      BodyDef b;
      b.shape = makeCircle(0.1);
      b.mass = 1.0;
      b.velocity = Vec2(1.0, 0.0);
      const BodyId id = w.createBody(b);
      DamperDef d;
      d.body = id;
      d.coefficient = q / kDt;
      w.addDamper(d);
      double v_prev = 1.0, factor = kNaN;
      bool ok = true, blew_up = false;
      for (int n = 1; n <= 60; ++n) {
        w.step(kDt);
        const Body& body = w.body(id);
        const double v = body.isStatic() ? kNaN : body.velocity.x();
        if (n == 1) factor = v;
        // A velocity that is no longer finite (or a body the NaN firewall froze) fails both rules.
        blew_up = !std::isfinite(v);
        const bool flipped = v < 0.0, grew = !(std::abs(v) <= std::abs(v_prev) * (1 + 1e-12));
        if (blew_up || (monotone_rule ? grew : flipped)) {
          ok = false;
          break;
        }
        v_prev = v;
      }
      row.push_back(fmt(factor) + (ok ? "" : " !"));
      if (!monotone_rule) r.figures.push_back({name + "_first_step_factor_at_" + fmt(q), factor, "", ""});
      if (!ok) {
        pass = false;
        r.notes.push_back(name + " at b·dt/m = " + fmt(q) + ": first-step factor " + fmt(factor) +
                          (blew_up ? " (the velocity blew up: not finite)"
                                   : monotone_rule ? " (the speed grows)" : " (the sign flips)"));
      }
    }
    t.rows.push_back(row);
  }
  r.tables.push_back(t);
  r.pass = pass;
  return r;
}
}  // namespace

CaseResult damperSign(const Options&) { return damperCase(false); }
CaseResult damperMonotone(const Options&) { return damperCase(true); }

// S6: a critically damped, moderately stiff spring: explicit dampers make symplectic Euler blow up.
CaseResult criticalDamper(const Options&) {
  CaseResult r;
  r.name = "critical_damper";
  r.title = "Critically damped spring at ωh = 0.9 (S6)";
  r.rule = "m = 1 kg, k = 2916 N/m, c = 108 N·s/m (ζ = 1, ωh = 0.9), x0 = 0.01 m, 10 s at dt = 1/60. PASS if "
           "semi_implicit_euler and implicit_euler stay finite with energy never increasing (1e-9 per step); "
           "explicit Euler and RK4 are reported (a naive semi-implicit Euler has ρ = 1.25 and blows up)";
  Table t;
  t.title = "per integrator";
  t.header = {"integrator", "finite", "energy never increases", "max E/E0", "E/E0 at 10 s"};
  bool pass = true;
  for (const std::string& name : integrators()) {
    Oscillator o(*find(name), 2916.0, 108.0, 0.01);
    const double e0 = o.energy();
    double prev = e0, max_ratio = 1.0;
    bool finite = true, monotone = true;
    for (int n = 1; n <= 600; ++n) {
      o.world.step(kDt);
      if (!o.healthy()) {
        finite = false;
        break;
      }
      const double e = o.energy();
      if (increased(e, prev, e0)) monotone = false;
      max_ratio = std::max(max_ratio, e / e0);
      prev = e;
    }
    t.rows.push_back({name, yesNo(finite), yesNo(monotone), fmt(max_ratio), finite ? fmt(prev / e0) : "–"});
    if (name == "semi_implicit_euler" || name == "implicit_euler") {
      if (!finite || !monotone) {
        pass = false;
        r.notes.push_back(name + ": finite " + yesNo(finite) + ", energy never increases " + yesNo(monotone) + " (max E/E0 " + fmt(max_ratio) + ")");
      }
    }
  }
  r.tables.push_back(t);
  r.pass = pass;
  return r;
}

// S9: long runs: energy drift and its trend on an undamped oscillator and a Kepler orbit.
CaseResult longRuns(const Options&) {
  CaseResult r;
  // Not shortened for --quick: the runs are cheap (about a second), and a shorter run cannot tell a
  // bounded oscillation of the orbit's energy (period 10 s) from a trend of 1e-6 per s.
  const long steps = 100000;
  r.name = "long_runs";
  r.title = "Long runs: energy drift over " + std::to_string(steps) + " steps (S9)";
  r.rule = "dt = 1/60. Spring–mass k = 4π², m = 1, x0 = 0.1 m, and the Kepler orbit of scripts/accuracy/kepler.lua "
           "(e = 0.6, P = 10 s, force in Lua). PASS if semi-implicit Euler keeps the spring's energy inside its band "
           "[1/(1 + ωh/2), 1/(1 − ωh/2)]·E0 with a trend below 1e-6·E0 per s, keeps the orbit's angular momentum to "
           "1e-12 and its energy trend below 1e-6 per s, and implicit_euler never gains energy on the spring. "
           "Explicit Euler and RK4 are reported";
  Table t;
  t.title = "per integrator (trend: least-squares slope of E/E0 against t)";
  t.header = {"problem", "integrator", "max |E/E0 − 1|", "trend [1/s]", "E/E0 at the end", "max |ΔL/L|", "status"};
  bool pass = true;
  const double a = 2 * M_PI * kDt;
  const double band_lo = 1 / (1 + a / 2), band_hi = 1 / (1 - a / 2);

  // The spring–mass, in C++.
  for (const std::string& name : integrators()) {
    Oscillator o(*find(name), 4 * M_PI * M_PI, 0.0, 0.1);
    const double e0 = o.energy();
    double max_dev = 0, lo = 1, hi = 1, prev = e0;
    bool monotone = true;
    std::string status = "ok";
    std::vector<double> ts, es;
    ts.reserve(steps / 10 + 1), es.reserve(steps / 10 + 1);
    long n = 1;
    for (; n <= steps; ++n) {
      o.world.step(kDt);
      const double e = o.energy();
      if (!o.healthy() || !std::isfinite(e)) {
        status = "nan at step " + std::to_string(n);
        break;
      }
      const double ratio = e / e0;
      if (increased(e, prev, e0)) monotone = false;
      prev = e;
      max_dev = std::max(max_dev, std::abs(ratio - 1));
      lo = std::min(lo, ratio), hi = std::max(hi, ratio);
      if (n % 10 == 0) ts.push_back(n * kDt), es.push_back(ratio);
      if (ratio > 1e6) {
        status = "stopped at t = " + fmt(n * kDt) + " s (E > 1e6·E0)";
        break;
      }
    }
    const double trend = ts.size() > 2 ? slope(ts, es) : kNaN;
    t.rows.push_back({"spring", name, fmt(max_dev), fmt(trend), fmt(prev / e0, 8), "–", status});
    r.figures.push_back({"spring_" + name + "_max_energy_drift", max_dev, "", ""});
    r.figures.push_back({"spring_" + name + "_energy_trend", trend, "1/s", ""});
    if (name == "semi_implicit_euler") {
      const bool ok = status == "ok" && lo >= band_lo * (1 - 1e-9) && hi <= band_hi * (1 + 1e-9) && std::abs(trend) < 1e-6;
      if (!ok) {
        pass = false;
        r.notes.push_back("semi-implicit Euler on the spring: E/E0 in [" + fmt(lo, 6) + ", " + fmt(hi, 6) + "] (band [" +
                          fmt(band_lo, 6) + ", " + fmt(band_hi, 6) + "]), trend " + fmt(trend));
      }
    }
    if (name == "implicit_euler" && (status != "ok" || !monotone)) {
      pass = false;
      r.notes.push_back("implicit_euler gained energy on the spring");
    }
  }

  // The Kepler orbit, from its Lua scene (the force is a Lua function).
  const auto file = accuracy::problemDirectory() / "kepler.lua";
  const accuracy::Problem problem = accuracy::loadProblem(file);
  for (const std::string& name : integrators()) {
    auto scene = lua::Scene::loadFile(file);
    World& w = scene->world();
    w.setIntegrator(*find(name));
    const BodyId planet = *w.findBody("planet");
    const auto angmom = [&] {
      const Body& b = w.body(planet);
      return b.mass * cross(b.center, b.velocity) + b.inertia * b.angular_velocity;
    };
    const double e0 = problem.energyOf(w, 0), l0 = angmom();
    double max_dev = 0, max_dl = 0, last = 1;
    std::string status = "ok";
    std::vector<double> ts, es;
    for (long n = 1; n <= steps; ++n) {
      scene->step(kDt);
      const Body& b = w.body(planet);
      if (b.isStatic() || !isFinite(b.center) || !isFinite(b.velocity)) {
        status = "nan at step " + std::to_string(n);
        break;
      }
      if (n % 10 != 0 && n != steps) continue;
      const double ratio = problem.energyOf(w, n * kDt) / e0;
      last = ratio;
      max_dev = std::max(max_dev, std::abs(ratio - 1));
      max_dl = std::max(max_dl, std::abs(angmom() - l0) / std::abs(l0));
      ts.push_back(n * kDt), es.push_back(ratio);
    }
    const double trend = ts.size() > 2 ? slope(ts, es) : kNaN;
    t.rows.push_back({"kepler", name, fmt(max_dev), fmt(trend), fmt(last, 8), fmt(max_dl), status});
    r.figures.push_back({"kepler_" + name + "_max_energy_drift", max_dev, "", ""});
    r.figures.push_back({"kepler_" + name + "_energy_trend", trend, "1/s", ""});
    r.figures.push_back({"kepler_" + name + "_angular_momentum_drift", max_dl, "", ""});
    if (name == "semi_implicit_euler" && !(status == "ok" && max_dl <= 1e-12 && std::abs(trend) < 1e-6)) {
      pass = false;
      r.notes.push_back("semi-implicit Euler on the orbit: ΔL/L " + fmt(max_dl) + ", trend " + fmt(trend));
    }
  }
  r.tables.push_back(t);
  r.pass = pass;
  return r;
}

// S11: the same scene driven by frame times of 1/30, 1/60 and 1/144 s through the fixed-step
// accumulator gives bit-identical states at the same simulated time.
//
// The accumulator is the sandbox's (engine/sandbox/src/frame_clock.cpp, FrameClock::plan, fixed
// mode), restated here because the program does not link the sandbox's internals when it is built
// without the sandbox: a frame counts as at most 0.25 s, steps = floor((acc + 1e-9·dt)/dt) capped
// at 8, acc −= steps·dt. tests/accuracy/test_frame_rate.cpp drives the real FrameClock.
namespace {

struct Accumulator {
  double acc = 0;
  int plan(double frame, double dt) {
    acc += std::min(frame, 0.25);
    const int wanted = static_cast<int>(std::floor((acc + 1e-9 * dt) / dt));
    const int steps = std::min(wanted, 8);
    acc = std::max(acc - steps * dt, 0.0);
    if (wanted > 8) acc = std::fmod(acc, dt);
    return steps;
  }
};

// A small scene with contacts, friction, a spring and rotation: a pyramid of 10 boxes, a box sliding
// into it, a disc swinging on a spring.
World frameRateScene() {
  World w;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = makeBox(40, 1);
  ground.position = Vec2(0, -0.5);
  w.createBody(ground);
  for (int row = 0; row < 4; ++row)
    for (int i = 0; i < 4 - row; ++i) {
      BodyDef b;
      b.shape = makeBox(1, 1);
      b.position = Vec2((i - (3 - row) / 2.0) * 1.0, 0.5 + row);
      w.createBody(b);
    }
  BodyDef slider;
  slider.shape = makeBox(0.5, 0.5);
  slider.position = Vec2(-8, 0.25);
  slider.velocity = Vec2(6, 0);
  w.createBody(slider);
  BodyDef disc;
  disc.shape = makeCircle(0.3);
  disc.position = Vec2(6, 4);
  disc.velocity = Vec2(0, 3);
  const BodyId d = w.createBody(disc);
  SpringDef s;
  s.a = d;
  s.anchor = Vec2(5, 6);
  s.stiffness = 40;
  s.damping = 0.2;
  w.addSpring(s);
  return w;
}

// FNV-1a over the bits of every body's position, angle and velocities.
uint64_t stateHash(const World& w) {
  uint64_t h = 1469598103934665603ull;
  const auto add = [&](double x) {
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    for (int i = 0; i < 8; ++i) h = (h ^ ((bits >> (8 * i)) & 0xFF)) * 1099511628211ull;
  };
  for (const BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    add(b.center.x()), add(b.center.y()), add(b.angle), add(b.velocity.x()), add(b.velocity.y()), add(b.angular_velocity);
  }
  return h;
}

}  // namespace

CaseResult frameRate(const Options& options) {
  const bool quick = options.quick;
  CaseResult r;
  const long steps = quick ? 300 : 600;
  r.name = "frame_rate";
  r.title = "Frame-rate independence through the fixed-step loop (S11)";
  r.rule = "a scene with contacts, friction and a spring, dt = 1/60, driven by frame times of 1/30, 1/60 and 1/144 s "
           "through the sandbox's fixed-step accumulator until " + std::to_string(steps) +
           " steps: PASS if the three final states are bit-identical. A naive loop that steps by the frame time is "
           "reported for contrast";
  Table t;
  t.title = "final state";
  t.header = {"loop", "frame time", "frames", "steps", "state hash", "max |Δposition| vs 1/60 fixed [m]"};
  std::vector<uint64_t> hashes;
  std::vector<Vec2> reference;
  const auto positions = [](const World& w) {
    std::vector<Vec2> p;
    for (const BodyId id : w.bodyIds()) p.push_back(w.body(id).center);
    return p;
  };
  const auto deviation = [&](const World& w) {
    double d = 0;
    const auto p = positions(w);
    for (size_t i = 0; i < p.size() && i < reference.size(); ++i) d = std::max(d, (p[i] - reference[i]).norm());
    return d;
  };
  for (const auto& [frame, label] : {std::pair{1.0 / 60, "1/60"}, {1.0 / 30, "1/30"}, {1.0 / 144, "1/144"}}) {
    World w = frameRateScene();
    Accumulator clock;
    long taken = 0, frames = 0;
    while (taken < steps) {
      const int n = clock.plan(frame, kDt);
      ++frames;
      for (int i = 0; i < n && taken < steps; ++i, ++taken) w.step(kDt);
    }
    if (reference.empty()) reference = positions(w);
    hashes.push_back(stateHash(w));
    char hex[20];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hashes.back()));
    t.rows.push_back({"fixed step", label, std::to_string(frames), std::to_string(taken), hex, fmt(deviation(w))});
  }
  // Contrast: one step of the frame's length per frame, to the same simulated time.
  for (const auto& [frame, label] : {std::pair{1.0 / 30, "1/30"}, {1.0 / 144, "1/144"}}) {
    World w = frameRateScene();
    const long frames = std::lround(steps * kDt / frame);
    for (long i = 0; i < frames; ++i) w.step(frame);
    char hex[20];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(stateHash(w)));
    const double d = deviation(w);
    t.rows.push_back({"variable step", label, std::to_string(frames), std::to_string(frames), hex, fmt(d)});
    r.figures.push_back({std::string("variable_step_deviation_") + (frame < 0.01 ? "144" : "30"), d, "m", ""});
  }
  r.pass = hashes.size() == 3 && hashes[0] == hashes[1] && hashes[1] == hashes[2];
  if (!r.pass) r.notes.push_back("the fixed-step states differ between frame rates");
  r.figures.push_back({"identical_states", r.pass ? 1.0 : 0.0, "", r.pass ? "yes" : "no"});
  r.tables.push_back(t);
  return r;
}

}  // namespace rigidlab::app::stability

// Files of the accuracy report (accuracy_report.h).
#include "accuracy_report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "gnuplot_script.h"
#include "rigidlab/lua/scene.h"

namespace rigidlab::app::accuracy {
namespace {

constexpr double kEps = 2.220446049250313e-16;  // double machine epsilon
// The round-off floor of a run of N steps: errors at or below max(1e3 ε, 100 N ε) are rounding,
// not truncation, so the order fit leaves them out (and the pictures draw the floor).
constexpr double kFloorAbsolute = 1e3 * kEps, kFloorPerStep = 100.0 * kEps;

std::string num(double x, int digits = 10) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// Scientific with 3 significant digits, for tables.
std::string sci(double x) {
  if (std::isnan(x)) return "–";
  if (std::isinf(x)) return "∞";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", x);
  return buf;
}

std::string fixed(double x, int decimals) {
  if (!std::isfinite(x)) return num(x);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

std::string run(const std::string& command) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return out;
  std::array<char, 256> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string noCommas(std::string s) {
  std::replace(s.begin(), s.end(), ',', ';');
  return s;
}

std::vector<const Row*> rowsOf(const ReportInput& in, const Problem* p, const std::string& integrator) {
  std::vector<const Row*> out;
  for (const Row& r : in.rows)
    if (r.problem == p && r.integrator == integrator) out.push_back(&r);
  return out;
}

}  // namespace

std::string dtLabel(int k) { return "1/" + std::to_string(30L << k); }

BuildInfo buildInfo() {
  BuildInfo b;
  const std::filesystem::path source = lua::scriptsDirectory().parent_path();
  b.engine_version = "unknown";
  if (std::ifstream cmake(source / "CMakeLists.txt"); cmake) {
    std::string line;
    while (std::getline(cmake, line)) {
      const size_t at = line.find("project(rigidlab VERSION ");
      if (at == std::string::npos) continue;
      std::istringstream words(line.substr(at + 25));
      words >> b.engine_version;
      break;
    }
  }
  const std::string git = "git -C '" + source.string() + "' ";
  b.git_hash = run(git + "rev-parse --short=12 HEAD 2>/dev/null");
  if (b.git_hash.empty()) {
    b.git_hash = "unknown";
  } else if (!run(git + "status --porcelain --untracked-files=no 2>/dev/null").empty()) {
    b.git_hash += "+dirty";
  }
#ifdef NDEBUG
  b.build = "release";
#else
  b.build = "debug";
#endif
#ifdef __OPTIMIZE__
  b.build += " optimized";
#endif
#if defined(__clang__)
  b.build += " clang " __clang_version__;
#elif defined(__GNUC__)
  b.build += " gcc " __VERSION__;
#endif
#ifdef __SANITIZE_ADDRESS__
  b.build += " +asan";
#endif
  b.cpu = "unknown";
  if (std::ifstream info("/proc/cpuinfo"); info) {
    std::string line, model;
    int count = 0;
    while (std::getline(info, line)) {
      if (line.rfind("processor", 0) == 0) ++count;
      if (model.empty() && line.rfind("model name", 0) == 0) model = line.substr(line.find(':') + 2);
    }
    if (!model.empty()) b.cpu = model + " x" + std::to_string(count);
  }
  b.build = noCommas(b.build);
  b.cpu = noCommas(b.cpu);
  return b;
}

namespace {

// Least squares of log err against log x(row) over the asymptotic window.
template <typename X>
Fit fitLog(const std::vector<const Row*>& rows, X x_of) {
  Fit f;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Row* r : rows) {
    const double e = r->error.err_linf;
    const double floor = std::max(kFloorAbsolute, kFloorPerStep * static_cast<double>(r->steps_planned));
    const std::optional<double> at = x_of(*r);
    if (r->error.status != "ok" || !(e > floor) || !(e < r->problem->asymptotic_below) || !at || !(*at > 0.0)) continue;
    const double x = std::log(*at), y = std::log(e);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
    if (f.points == 0 || r->dt < f.dt_min) f.dt_min = r->dt;
    if (f.points == 0 || r->dt > f.dt_max) f.dt_max = r->dt;
    ++f.points;
  }
  if (f.points < 2) return f;
  const double n = f.points, den = n * sxx - sx * sx;
  if (den == 0.0) {
    f.points = 0;
    return f;
  }
  f.order = (n * sxy - sx * sy) / den;
  f.log_c = (sy - f.order * sx) / n;
  return f;
}

}  // namespace

Fit fitOrder(const std::vector<const Row*>& rows) {
  return fitLog(rows, [](const Row& r) { return std::optional<double>(r.dt); });
}

Fit fitWork(const std::vector<const Row*>& rows) {
  return fitLog(rows, [](const Row& r) { return r.timing ? std::optional<double>(r.timing->min_s) : std::nullopt; });
}

double orderTolerance(double expected) { return expected >= 3.0 ? 0.3 : 0.2; }

Verdict judge(const Problem& problem, const std::string& integrator, const std::vector<const Row*>& rows) {
  Verdict v;
  const Expected e = problem.expectedFor(integrator);
  v.gated = e.known && problem.group != Group::Contact;
  if (e.known && e.exact) {
    v.expected = "exact";
    double worst = 0.0, worst_ratio = 0.0;
    bool all_ok = true;
    for (const Row* r : rows) {
      all_ok &= r->error.status == "ok";
      // Round-off grows with the number of steps: |err| ≤ 16 N ε (docs/design/accuracy.md §3.1 uses 4 N ε |y|).
      const double bound = 16.0 * static_cast<double>(r->steps_planned) * kEps;
      worst = std::max(worst, r->error.err_linf);
      worst_ratio = std::max(worst_ratio, r->error.err_linf / bound);
    }
    v.pass = all_ok && worst_ratio <= 1.0 && !rows.empty();
    v.observed = v.pass ? "exact (≤ " + sci(worst) + ")" : "not exact (" + sci(worst) + ")";
    if (!v.pass) v.why = "error above the round-off bound 16 N ε";
    return v;
  }
  const Fit f = fitOrder(rows);
  if (f.points >= 2) {
    v.observed = fixed(f.order, 2);
  } else {
    // Why there is no fit: every error under the round-off floor, or every one above 0.1.
    bool all_small = !rows.empty();
    for (const Row* r : rows) all_small &= r->error.status == "ok" && r->error.err_linf <= 0.1;
    v.observed = all_small ? "round-off" : "pre-asymptotic";
  }
  if (!e.known) {
    v.expected = "–";
    return v;
  }
  v.expected = fixed(e.order, e.order == std::floor(e.order) ? 0 : 1);
  if (f.points < 2) {
    v.pass = false;
    v.inconclusive = true;
    v.why = "fewer than 2 runs with 1e3 ε < err < 0.1";
  } else if (std::abs(f.order - e.order) > problem.order_tolerance.value_or(orderTolerance(e.order))) {
    v.pass = false;
    v.why = "outside ±" + fixed(problem.order_tolerance.value_or(orderTolerance(e.order)), 1);
  }
  return v;
}

// ---------------------------------------------------------------------------------------------
// CSV

void writeCsv(const ReportInput& in, const std::filesystem::path& dir) {
  std::ofstream csv(dir / "accuracy.csv");
  if (!csv) throw std::runtime_error((dir / "accuracy.csv").string() + ": cannot write");
  csv << "scene,integrator,dt,substeps,steps,force_evals,lua_calls,t_end,wall_s_min,wall_s_median,repeats,"
         "err_linf,err_final,err_l2,energy_drift_max,energy_drift_trend,mom_err,angmom_err,order_pairwise,status,"
         "engine_version,git_hash,build,cpu,"
         "k,group,reference_length,wall_s_iqr,batch,vel_err_final,pairs_max,contact_points_max,stages,stopped_at,period_err\n";
  for (const Row& r : in.rows) {
    const Problem& p = *r.problem;
    const ErrorPass& e = r.error;
    const auto opt = [](bool on, double x) { return on ? num(x) : std::string(); };
    csv << p.name << ',' << r.integrator << ',' << num(r.dt, 17) << ',' << num((1.0 / 60.0) / r.dt, 6) << ','
        << e.steps << ',' << e.force_evals << ',' << e.lua_calls << ',' << num(p.t_end) << ','
        << (r.timing ? num(r.timing->min_s) : "") << ',' << (r.timing ? num(r.timing->median_s) : "") << ','
        << (r.timing ? std::to_string(r.timing->repeats) : "") << ',' << num(e.err_linf) << ','
        << num(e.err_final) << ',' << num(e.err_l2) << ',' << opt(p.energy, e.energy_drift_max) << ','
        << opt(p.energy, e.energy_drift_trend) << ',' << opt(p.momentum, e.mom_err) << ','
        << opt(p.angmom, e.angmom_err) << ',' << (std::isnan(r.order_pairwise) ? "" : num(r.order_pairwise, 4))
        << ',' << e.status << ',' << in.build.engine_version << ',' << in.build.git_hash << ',' << in.build.build
        << ',' << in.build.cpu << ',' << r.k << ',' << groupName(p.group) << ',' << num(p.reference_length) << ','
        << (r.timing ? num(r.timing->iqr_s) : "") << ',' << (r.timing ? std::to_string(r.timing->batch) : "")
        << ',' << opt(p.velocity, e.vel_err_final) << ',' << e.pairs_max << ',' << e.contact_points_max << ','
        << noCommas(e.stages()) << ',' << (e.status == "ok" ? "" : num(e.stopped_at)) << ','
        << opt(p.period.has_value(), e.period_err) << '\n';
  }

  // Energy over time of the long runs: t, then E(t)/E0 per integrator (empty after a stop).
  std::map<const Problem*, std::vector<const LongRun*>> by_problem;
  for (const LongRun& l : in.long_runs) by_problem[l.problem].push_back(&l);
  for (const auto& [p, runs] : by_problem) {
    std::ofstream out(dir / ("energy_" + p->name + ".csv"));
    out << "t";
    size_t longest = 0;
    const LongRun* ref = runs.front();
    for (const LongRun* l : runs) {
      out << ',' << l->integrator;
      if (l->error.energy_t.size() > longest) longest = l->error.energy_t.size(), ref = l;
    }
    out << '\n';
    for (size_t i = 0; i < longest; ++i) {
      out << num(ref->error.energy_t[i]);
      for (const LongRun* l : runs) out << ',' << (i < l->error.energy_ratio.size() ? num(l->error.energy_ratio[i], 15) : "");
      out << '\n';
    }
  }
}

// ---------------------------------------------------------------------------------------------
// summary.md

int writeSummary(const ReportInput& in, const std::filesystem::path& dir, bool strict) {
  std::ofstream md(dir / "summary.md");
  if (!md) throw std::runtime_error((dir / "summary.md").string() + ": cannot write");
  int failed = 0;
  md << "# rigidlab accuracy report\n\n";
  md << "`" << in.command_line << "`  \n";
  md << "engine " << in.build.engine_version << ", git " << in.build.git_hash << ", " << in.build.build << ", "
     << in.build.cpu << "; report made in " << fixed(in.runtime_s, 1) << " s.\n\n";
  md << "Errors are the maximum over a 0.1 s sample grid of ‖p − p_exact‖ divided by the problem's reference "
        "length (`err_linf`); every run takes a whole number of steps to `t_end`. Step sizes dt = 1/30 · 2^−k. "
     << (in.timed ? "Times are the minimum over repeated runs with sampling off, setup excluded (`wall_s_min`). "
                  : "Timing was off for this report. ")
     << "`accuracy.csv` holds every number; the pictures are made from it by `plots.gp`.\n\n";

  // Observed orders.
  md << "## Observed order against expected\n\n";
  md << "Least-squares slope of log err against log dt over the runs with 1e3 ε < err < 0.1 (and err above "
        "100 N ε, the round-off of N steps); at least 2 runs, else \"pre-asymptotic\" (errors above 0.1) or "
        "\"round-off\" (errors at the floor). Gated: smooth, impact (impacts located inside the step) and sanity "
        "problems, tolerance ±0.2 (±0.3 for order 4); contact problems are reported only.\n\n";
  md << "| problem | group |";
  for (const std::string& i : in.integrators) md << ' ' << i << " |";
  md << "\n|---|---|";
  for (size_t i = 0; i < in.integrators.size(); ++i) md << "---|";
  md << '\n';
  std::vector<std::string> failures;
  for (const Problem* p : in.problems) {
    md << "| " << p->name << " | " << groupName(p->group) << " |";
    for (const std::string& i : in.integrators) {
      const Verdict v = judge(*p, i, rowsOf(in, p, i));
      md << ' ' << v.observed << " (" << v.expected << ")";
      if (v.gated) md << (v.pass ? " PASS" : (strict || !v.inconclusive) ? " **FAIL**" : " (no fit in this sweep)");
      md << " |";
      if (v.gated && !v.pass && (strict || !v.inconclusive)) {
        ++failed;
        failures.push_back(p->name + " / " + i + ": observed " + v.observed + ", expected " + v.expected + " (" + v.why + ")");
      }
    }
    md << '\n';
  }
  md << "\nEach cell: observed (expected).\n";
  if (!failures.empty()) {
    md << "\nFailed expectations:\n\n";
    for (const std::string& f : failures) md << "- " << f << '\n';
  }

  // Mechanisms: both fits, against dt and against run time.
  bool any_mechanism = false;
  for (const Problem* p : in.problems) any_mechanism |= p->group == Group::Mechanism;
  if (any_mechanism) {
    md << "\n## Mechanisms\n\n";
    md << "Jointed bodies that touch nothing, integrated with their joints (`exact_joints`, docs/integrators.md \"Joints "
          "inside the integrator\"). Per integrator: the order fitted against dt, the slope fitted against the run "
          "time (wall_s_min; −order when the cost is proportional to the steps), and the error at 1/60 and at 1/480. "
          "The error is the position error, or for problems fitted on energy max |E − E0| / energy_scale.\n\n";
    md << "| problem | error | integrator | order vs dt | slope vs run time | err @ 1/60 | err @ 1/480 |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const Problem* p : in.problems) {
      if (p->group != Group::Mechanism) continue;
      for (const std::string& i : in.integrators) {
        const std::vector<const Row*> rows = rowsOf(in, p, i);
        const Fit order = fitOrder(rows), work = fitWork(rows);
        const auto at = [&](int k) {
          for (const Row* r : rows)
            if (r->k == k) return sci(r->error.err_linf);
          return std::string("–");
        };
        md << "| " << p->name << " | " << (p->fit_energy ? "energy" : "position") << " | " << i << " | "
           << (order.points >= 2 ? fixed(order.order, 2) : "–") << " | "
           << (work.points >= 2 ? fixed(work.order, 2) : "–") << " | " << at(1) << " | " << at(4) << " |\n";
      }
    }
  }

  // Error and work at 1/60.
  md << "\n## At dt = 1/60 s\n\n";
  md << "| problem | integrator | err_linf | err_final | energy drift | force evals / step | Lua calls / step |"
     << (in.timed ? " wall (min) |" : "") << " status |\n";
  md << "|---|---|---|---|---|---|---|" << (in.timed ? "---|" : "") << "---|\n";
  for (const Problem* p : in.problems)
    for (const std::string& i : in.integrators)
      for (const Row* r : rowsOf(in, p, i)) {
        if (r->k != 1) continue;
        const double steps = std::max<double>(1, static_cast<double>(r->error.steps));
        md << "| " << p->name << " | " << i << " | " << sci(r->error.err_linf) << " | " << sci(r->error.err_final)
           << " | " << (p->energy ? sci(r->error.energy_drift_max) : "–") << " | "
           << fixed(static_cast<double>(r->error.force_evals) / steps, 1) << " | "
           << fixed(static_cast<double>(r->error.lua_calls) / steps, 1) << " |";
        if (in.timed) md << ' ' << (r->timing ? fixed(r->timing->min_s * 1e3, 3) + " ms" : "–") << " |";
        md << ' ' << r->error.status << " |\n";
      }

  // Periods: the measured period against the exact one, for every step.
  bool any_period = false;
  for (const Problem* p : in.problems) any_period |= p->period.has_value();
  if (any_period) {
    md << "\n## Period\n\n";
    md << "|T/T_exact − 1| of the problems with an exact period, the period measured from the times the body's angle "
          "crosses 0.\n\n";
    for (const Problem* p : in.problems) {
      if (!p->period) continue;
      md << "**" << p->name << "** (T = " << num(*p->period, 10) << " s)\n\n| integrator |";
      int k_max = 0;
      for (const Row& r : in.rows)
        if (r.problem == p) k_max = std::max(k_max, r.k);
      for (int k = 0; k <= k_max; ++k) md << ' ' << dtLabel(k) << " |";
      md << "\n|---|";
      for (int k = 0; k <= k_max; ++k) md << "---|";
      md << '\n';
      for (const std::string& i : in.integrators) {
        md << "| " << i << " |";
        for (int k = 0; k <= k_max; ++k) {
          const Row* found = nullptr;
          for (const Row* r : rowsOf(in, p, i))
            if (r->k == k) found = r;
          md << ' ' << (found ? sci(found->error.period_err) : "–") << " |";
        }
        md << '\n';
      }
      md << '\n';
    }
  }

  // What each accuracy costs: the fastest configuration that reaches an error.
  if (in.timed) {
    md << "\n## Cheapest configuration for a target error\n\n";
    md << "The fastest run (wall_s_min) whose err_linf is at or below the target.\n\n";
    const double targets[] = {1e-2, 1e-4, 1e-6, 1e-8};
    md << "| problem |";
    for (double t : targets) md << " err ≤ " << sci(t) << " |";
    md << "\n|---|";
    for (size_t i = 0; i < std::size(targets); ++i) md << "---|";
    md << '\n';
    for (const Problem* p : in.problems) {
      md << "| " << p->name << " |";
      for (double target : targets) {
        const Row* best = nullptr;
        for (const Row& r : in.rows)
          if (r.problem == p && r.timing && r.error.status == "ok" && r.error.err_linf <= target &&
              (!best || r.timing->min_s < best->timing->min_s))
            best = &r;
        if (best) md << ' ' << best->integrator << " @ " << dtLabel(best->k) << " (" << fixed(best->timing->min_s * 1e3, 3) << " ms) |";
        else md << " none in the sweep |";
      }
      md << '\n';
    }
  }

  // Which stages ran.
  md << "\n## Which stages ran\n\n";
  md << "From the engine's per-step statistics in the error pass at dt = 1/60 (the integrator with the smallest error there): a stage "
        "counts as running when it found work (candidate pairs, contact points, force evaluations, Lua calls).\n\n";
  md << "| problem | stages | pairs (max) | contact points (max) | force evals / step | Lua calls / step | "
        "broad + narrow + solve + correct ms / step |\n|---|---|---|---|---|---|---|\n";
  for (const Problem* p : in.problems) {
    const Row* r = nullptr;  // the most accurate run at 1/60 (an inaccurate one may collide where it should not)
    for (const Row& row : in.rows)
      if (row.problem == p && row.k == 1 && (!r || row.error.err_linf < r->error.err_linf)) r = &row;
    if (!r) continue;
    const double steps = std::max<double>(1, static_cast<double>(r->error.steps));
    md << "| " << p->name << " | " << r->error.stages() << " | " << r->error.pairs_max << " | "
       << r->error.contact_points_max << " | " << fixed(static_cast<double>(r->error.force_evals) / steps, 1) << " | "
       << fixed(static_cast<double>(r->error.lua_calls) / steps, 1) << " | "
       << fixed((r->error.broad_ms + r->error.narrow_ms + r->error.solve_ms + r->error.correct_ms) / steps, 4)
       << " |\n";
  }

  // Long runs.
  if (!in.long_runs.empty()) {
    md << "\n## Long runs at dt = 1/60 s: energy\n\n";
    md << "| problem | integrator | duration | max \\|E/E0 − 1\\| | trend of E/E0 [1/s] | final E/E0 | ΔL/L max | "
          "status |\n|---|---|---|---|---|---|---|---|\n";
    for (const LongRun& l : in.long_runs) {
      const ErrorPass& e = l.error;
      const double final_ratio = e.energy_ratio.empty() ? std::nan("") : e.energy_ratio.back();
      md << "| " << l.problem->name << " | " << l.integrator << " | " << num(*l.problem->long_run) << " s | "
         << sci(e.energy_drift_max) << " | " << sci(e.energy_drift_trend) << " | " << num(final_ratio, 8) << " | "
         << (l.problem->angmom ? sci(e.angmom_err) : "–") << " | " << e.status
         << (e.status == "ok" ? "" : " at t = " + num(e.stopped_at, 6) + " s") << " |\n";
    }
  }

  // Unstable runs.
  std::vector<const Row*> unstable;
  for (const Row& r : in.rows)
    if (r.error.status != "ok") unstable.push_back(&r);
  md << "\n## Unstable runs\n\n";
  if (unstable.empty()) md << "None.\n";
  for (const Row* r : unstable)
    md << "- " << r->problem->name << " / " << r->integrator << " @ " << dtLabel(r->k) << ": " << r->error.status
       << " at t = " << num(r->error.stopped_at, 6) << " s (drawn as open markers at the edge of the plots)\n";

  // Pictures.
  md << "\n## Pictures\n\n";
  for (const Problem* p : in.problems) {
    md << "### " << p->name << ": " << p->title << "\n\n";
    if (!p->note.empty()) md << p->note << ". ";
    md << "Reference length " << num(p->reference_length) << " m, t_end " << num(p->t_end) << " s.\n\n";
    md << "![convergence](conv_" << p->name << ".svg)";
    if (in.timed) md << " ![work-precision](wp_" << p->name << ".svg)";
    if (p->long_run) md << " ![energy](energy_" << p->name << ".svg)";
    md << "\n\n";
  }
  return failed;
}

// ---------------------------------------------------------------------------------------------
// Pictures: one gnuplot script that reads accuracy.csv and energy_*.csv.

std::optional<std::string> writePlots(const ReportInput& in, const std::filesystem::path& dir) {
  std::ofstream gp(dir / "plots.gp");
  if (!gp) return (dir / "plots.gp").string() + ": cannot write";
  // Columns of accuracy.csv (1-based).
  constexpr int kScene = 1, kIntegrator = 2, kDt = 3, kWall = 9, kErr = 12, kStatus = 20;
  gp << "# Pictures of the accuracy report, made from accuracy.csv (and energy_<problem>.csv).\n"
        "# Re-run by hand with: gnuplot plots.gp (in this directory). Written by rigidlab accuracy.\n"
     << gnuplot::kPreamble;
  const auto sel = [&](const Problem* p, const std::string& i, bool ok) {
    return "(strcol(" + std::to_string(kScene) + ") eq " + gnuplot::quoted(p->name) + " && strcol(" +
           std::to_string(kIntegrator) + ") eq " + gnuplot::quoted(i) + " && strcol(" + std::to_string(kStatus) + ") " +
           (ok ? "eq" : "ne") + " \"ok\")";
  };
  const auto terminals = [&](const std::string& stem, const std::string& body) { gnuplot::writeTerminals(gp, stem, body); };

  for (size_t pi = 0; pi < in.problems.size(); ++pi) {
    const Problem* p = in.problems[pi];
    // Ranges from the finite errors and times, so unstable runs can sit on the edge.
    double emin = 1e300, emax = 0, dmin = 1e300, dmax = 0, wmin = 1e300, wmax = 0;
    bool any_unstable = false;
    for (const Row& r : in.rows) {
      if (r.problem != p) continue;
      dmin = std::min(dmin, r.dt), dmax = std::max(dmax, r.dt);
      if (r.error.status != "ok") any_unstable = true;
      const double e = r.error.err_linf;
      if (std::isfinite(e) && e > 0 && r.error.status == "ok") emin = std::min(emin, e), emax = std::max(emax, e);
      if (r.timing && r.timing->min_s > 0) wmin = std::min(wmin, r.timing->min_s), wmax = std::max(wmax, r.timing->min_s);
    }
    if (emax == 0) emin = 1e-16, emax = 1;
    emin = std::max(emin, 1e-17);
    const double ylo = emin / 4, yhi = emax * 8, edge = yhi / 1.6;

    // Convergence: err against dt, fitted order in the legend, reference slopes 1, 2, 4.
    std::ostringstream conv;
    conv << "set title " << gnuplot::quoted(p->title + ": error against step size") << "\n"
         << "set xlabel 'dt [s]'\nset ylabel " << gnuplot::quoted("max ‖p − p_{exact}‖ / " + num(p->reference_length) + " m") << "\n"
         << "set logscale xy\nset xrange [" << num(dmin / 1.5) << ':' << num(dmax * 1.5) << "]\n"
         << "set yrange [" << num(ylo) << ':' << num(yhi) << "]\nset key outside right top Left reverse width -9 samplen 2.5\nset samples 400\n";
    std::string plot = "plot ";
    const double xmid = std::sqrt(dmin * dmax), ymid = std::sqrt(ylo * yhi);
    for (size_t ii = 0; ii < in.integrators.size(); ++ii) {
      const std::string& i = in.integrators[ii];
      const auto rows = rowsOf(in, p, i);
      if (rows.empty()) continue;
      const gnuplot::Style s = gnuplot::integratorStyle(i, ii);
      const Verdict v = judge(*p, i, rows);
      const Fit f = fitOrder(rows);
      std::string title = i + ": p = " + v.observed + " (expected " + v.expected + ")";
      plot += "'accuracy.csv' skip 1 using (" + sel(p, i, true) + " ? $" + std::to_string(kDt) + " : NaN):($" +
              std::to_string(kErr) + " > 1e-17 ? $" + std::to_string(kErr) + " : 1e-17) with linespoints lw 2 dt " + std::to_string(s.dash) + " lc rgb '" +
              s.color + "' pt " + std::to_string(s.filled) + " ps 1.1 title " + gnuplot::quoted(title) + " noenhanced, \\\n  ";
      if (any_unstable)
        plot += "'accuracy.csv' skip 1 using (" + sel(p, i, false) + " ? $" + std::to_string(kDt) + " : NaN):(" +
                num(edge) + ") with points lc rgb '" + s.color + "' pt " + std::to_string(s.open) +
                " ps 1.6 notitle, \\\n  ";
      if (f.points >= 2 && !(v.expected == "exact"))
        plot += "(x >= " + num(f.dt_min / 1.0001) + " && x <= " + num(f.dt_max * 1.0001) + " ? exp(" + num(f.log_c, 17) +
                ")*x**" + num(f.order, 17) + " : NaN) dt 3 lw 1.5 lc rgb '" + s.color + "' notitle, \\\n  ";
    }
    const char* dashes[] = {"3", "4", "5"};
    int di = 0;
    for (int slope : {1, 2, 4})
      plot += num(ymid) + "*(x/" + num(xmid) + ")**" +
              std::to_string(slope) + " dt " + dashes[di++] + " lw 1 lc rgb '#999999' title 'slope " +
              std::to_string(slope) + "', \\\n  ";
    // N = t_end / dt steps at step size x.
    plot += "(" + num(kFloorAbsolute, 17) + " > " + num(kFloorPerStep * p->t_end, 17) + "/x ? " + num(kFloorAbsolute, 17) +
            " : " + num(kFloorPerStep * p->t_end, 17) + "/x) lw 3 lc rgb '#e0c080' title 'round-off floor: not fitted below', \\\n  ";
    if (any_unstable)
      plot += "NaN with points pt 6 lc rgb '#555555' title 'unstable (stopped): top edge', \\\n  ";
    plot.resize(plot.size() - 6);
    conv << plot << "\n";
    terminals("conv_" + p->name, conv.str());

    // Work–precision: wall time against err, one line per integrator.
    if (in.timed && wmax > 0) {
      const double xlo = emin / 4, xhi = emax * 8, xedge = xhi / 1.6;
      std::ostringstream wp;
      wp << "set title " << gnuplot::quoted(p->title + ": work against precision") << "\n"
         << "set xlabel " << gnuplot::quoted("error: max ‖p − p_{exact}‖ / " + num(p->reference_length) + " m") << "\n"
         << "set ylabel 'wall time per run, min of repeats [s]'\nset logscale xy\n"
         << "set xrange [" << num(xlo) << ':' << num(xhi) << "]\nset yrange [" << num(wmin / 3) << ':'
         << num(wmax * 3) << "]\nset key outside right top Left reverse width 0 samplen 2.5\n";
      std::string wplot = "plot ";
      for (size_t ii = 0; ii < in.integrators.size(); ++ii) {
        const std::string& i = in.integrators[ii];
        if (rowsOf(in, p, i).empty()) continue;
        const gnuplot::Style s = gnuplot::integratorStyle(i, ii);
        wplot += "'accuracy.csv' skip 1 using (" + sel(p, i, true) + " ? ($" + std::to_string(kErr) + " > 1e-17 ? $" +
                 std::to_string(kErr) + " : 1e-17) : NaN):" + std::to_string(kWall) + " with linespoints lw 2 dt " +
                 std::to_string(s.dash) + " lc rgb '" + s.color + "' pt " + std::to_string(s.filled) + " ps 1.1 title " + gnuplot::quoted(i) + " noenhanced, \\\n  ";
        // Each marker labelled with its step, 1/30 … 1/7680 (1/dt rounded: the sweep's dt are 1/30 · 2^-k).
        wplot += "'accuracy.csv' skip 1 using (" + sel(p, i, true) + " ? ($" + std::to_string(kErr) + " > 1e-17 ? $" +
                 std::to_string(kErr) + " : 1e-17) : NaN):" + std::to_string(kWall) + ":(sprintf('1/%.0f', 1/$" +
                 std::to_string(kDt) + ")) with labels offset char 0.6,0.6 left font ',7' tc rgb '" + s.color + "' notitle, \\\n  ";
        if (any_unstable)
          wplot += "'accuracy.csv' skip 1 using (" + sel(p, i, false) + " ? " + num(xedge) + " : NaN):" +
                   std::to_string(kWall) + " with points lc rgb '" + s.color + "' pt " + std::to_string(s.open) +
                   " ps 1.6 notitle, \\\n  ";
      }
      if (any_unstable)
        wplot += "NaN with points pt 6 lc rgb '#555555' title 'unstable (time until stopped): right edge', \\\n  ";
      wplot += "NaN with lines lc rgb '#ffffff' title 'one marker per dt, labelled with it [s]', \\\n  ";
      wplot.resize(wplot.size() - 6);
      wp << wplot << "\n";
      terminals("wp_" + p->name, wp.str());
    }

    // Energy over time of the long runs.
    if (p->long_run) {
      std::vector<const LongRun*> runs;
      for (const LongRun& l : in.long_runs)
        if (l.problem == p) runs.push_back(&l);
      if (!runs.empty()) {
        std::ostringstream en;
        en << "set title " << gnuplot::quoted(p->title + ": energy error over " + num(*p->long_run) + " s at dt = 1/60 s") << "\n"
           << "set xlabel 't [s]'\nset ylabel '|E/E_0 − 1| (gain solid, loss dotted)'\nunset logscale\nset logscale y\nset format x '%g'\n"
           << "set autoscale xy\nset xrange [0:" << num(*p->long_run) << "]\nset yrange [1e-16<*:*]\nset key inside bottom right Left reverse width 0\n";
        std::string eplot = "plot ";
        for (size_t ii = 0; ii < runs.size(); ++ii) {
          const std::string& i = runs[ii]->integrator;
          size_t index = 0;
          while (index < in.integrators.size() && in.integrators[index] != i) ++index;
          const gnuplot::Style s = gnuplot::integratorStyle(i, index);
          std::string title = i;
          if (runs[ii]->error.status != "ok") title += " (" + runs[ii]->error.status + " at t = " + num(runs[ii]->error.stopped_at, 5) + " s)";
          // Signed: a gain (E > E0) solid, a loss dotted, both as |E/E0 − 1| on the log axis.
          const std::string column = "$" + std::to_string(ii + 2);
          eplot += "'energy_" + p->name + ".csv' skip 1 using 1:(" + column + " > 1 ? " + column +
                   " - 1 : NaN) with lines lw 1.4 lc rgb '" + s.color + "' title " + gnuplot::quoted(title + ": gain") + " noenhanced, \\\n  ";
          eplot += "'energy_" + p->name + ".csv' skip 1 using 1:(" + column + " < 1 ? 1 - " + column +
                   " : NaN) with lines lw 1.4 dt 3 lc rgb '" + s.color + "' title " + gnuplot::quoted(title + ": loss") + " noenhanced, \\\n  ";
        }
        eplot.resize(eplot.size() - 6);
        en << eplot << "\nset format x '10^{%L}'\n";
        terminals("energy_" + p->name, en.str());
      }
    }
    gp << "reset\n" << gnuplot::kPreamble;
  }
  gp.close();

  return gnuplot::run(dir);
}

}  // namespace rigidlab::app::accuracy

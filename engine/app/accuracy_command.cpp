// rigidlab accuracy: error against run time for every reference problem × integrator × step size
// (the accuracy lab, issue 5; design: docs/design/accuracy.md §5). The problems are Lua scenes with Exact(t)
// (scripts/accuracy/); the runs are in accuracy_run.cpp, the files in accuracy_report.cpp.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "accuracy_problem.h"
#include "accuracy_report.h"
#include "accuracy_run.h"
#include "cli.h"
#include "commands.h"
#include "rigidlab/lua/scene.h"

namespace rigidlab::app {
namespace {

using namespace accuracy;

constexpr const char* kHelp = R"(usage: rigidlab accuracy [--out DIR] [--scenes A,B,...] [--integrators X,Y,...] [options]

Runs every reference problem (Lua scenes with Exact(t), default: scripts/accuracy/*.lua) with
every integrator and step sizes dt = 1/30 * 2^-k, k = 0..8, and measures the error against the
closed form (max position error on a 0.1 s grid, final error, energy drift where energy is
conserved) and the run time (min and median of repeated runs, sampling off, setup excluded).
Writes to DIR (default accuracy-report):
  accuracy.csv          one row per problem x integrator x dt (the contract)
  summary.md            observed against expected orders, errors at 1/60, cheapest settings,
                        which stages ran, long-run energy, unstable runs
  energy_<problem>.csv  E(t)/E0 of the long runs at dt = 1/60
  plots.gp              gnuplot script that makes the pictures from the CSV files:
  conv_<problem>.svg/png  error against dt, fitted order per integrator
  wp_<problem>.svg/png    work-precision: run time against error
  energy_<problem>.svg/png  energy error over time (long runs)

  --scenes LIST       problem names (sho, kepler, ...) or .lua files, comma-separated
  --integrators LIST  comma-separated, default all the engine offers
  --kmax K            finest step 1/30 * 2^-K (default 8, at most 12)
  --repeats R         timed repeats per run (default 20; fewer once 0.5 s has been spent on the
                      configuration, at least 3; one run if a run takes over 2 s)
  --budget S          seconds of timing per run before repeats stop (default 0.5); raise it
                      for steadier minimums on a busy machine
  --quick             k = 0..5, 3 repeats, no long runs: a fast look
  --no-timing         error passes only (no wall times, no work-precision pictures)
  --no-long           skip the long energy runs
  --no-plots          do not run gnuplot

Prints the observed order per problem and integrator beside the expected one ("?": no fit, the
sweep stops before the asymptotic range). Exit status: 0 if every gated expectation holds
(orders on smooth, impact and sanity problems; with --kmax below 8 or --quick, a missing fit
does not count), 1 if one fails or a scene has an error, 2 for a usage error.
)";

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, ',')) {
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::vector<std::string> allIntegrators() { return splitList(integratorNames()); }

// A progress line on standard error: rewritten in place on a terminal, one line per problem and
// integrator otherwise.
class Progress {
 public:
  explicit Progress(long total) : total_(total), tty_(isatty(STDERR_FILENO)) {}
  void show(const std::string& what, bool milestone) {
    ++done_;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (tty_) {
      std::fprintf(stderr, "\raccuracy [%4ld/%ld] %6.0f s  %-60.60s", done_, total_, elapsed, what.c_str());
    } else if (milestone) {
      std::fprintf(stderr, "accuracy [%4ld/%ld] %6.0f s  %s\n", done_, total_, elapsed, what.c_str());
    }
    std::fflush(stderr);
  }
  ~Progress() {
    if (tty_) std::fprintf(stderr, "\r%90s\r", "");
  }

 private:
  long total_, done_ = 0;
  bool tty_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

int accuracyCommand(const std::vector<std::string>& argv) {
  const Args args("accuracy", argv, {"out", "scenes", "integrators", "kmax", "repeats", "budget"},
                  {"quick", "no-timing", "no-long", "no-plots"});
  if (args.help()) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (!args.positional().empty()) throw UsageError("accuracy: unexpected argument '" + args.positional()[0] + "'");
  const bool quick = args.flag("quick");
  const int kmax = static_cast<int>(args.integer("kmax", 0).value_or(quick ? 5 : 8));
  if (kmax > 12) throw UsageError("accuracy: --kmax must be at most 12");
  TimingOptions timing;
  timing.max_repeats = static_cast<int>(args.integer("repeats", 1).value_or(quick ? 3 : 20));
  timing.min_repeats = std::min(timing.min_repeats, timing.max_repeats);
  if (quick) timing.budget_s = 0.1;
  if (const auto budget = args.number("budget")) {
    if (!(*budget > 0)) throw UsageError("accuracy: --budget must be > 0");
    timing.budget_s = *budget;
  }
  const bool timed = !args.flag("no-timing");
  const bool long_runs = !quick && !args.flag("no-long");
  const std::filesystem::path out = args.value("out").value_or("accuracy-report");

  std::vector<std::string> integrators = allIntegrators();
  if (const auto list = args.value("integrators")) {
    integrators = splitList(*list);
    for (const std::string& i : integrators)
      if (!parseIntegrator(i)) throw UsageError("accuracy: --integrators: unknown integrator '" + i + "' (one of " + integratorNames() + ")");
  }
  std::vector<std::filesystem::path> files;
  if (const auto list = args.value("scenes")) {
    for (const std::string& s : splitList(*list)) {
      std::filesystem::path f = s;
      if (f.extension() != ".lua") f = problemDirectory() / (s + ".lua");
      if (!std::filesystem::is_regular_file(f)) throw UsageError("accuracy: --scenes: no problem '" + s + "' (" + f.string() + ")");
      files.push_back(f);
    }
  } else {
    files = problemFiles(problemDirectory());
  }

  std::vector<Problem> problems;
  problems.reserve(files.size());
  try {
    for (const auto& f : files) problems.push_back(loadProblem(f));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitSceneError;
  }

  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) {
    std::fprintf(stderr, "accuracy: cannot create %s: %s\n", out.string().c_str(), ec.message().c_str());
    return kExitSceneError;
  }

  ReportInput report;
  report.timed = timed;
  report.integrators = integrators;
  report.build = buildInfo();
  report.command_line = "rigidlab accuracy";
  for (const std::string& a : argv) report.command_line += " " + a;
  for (const Problem& p : problems) report.problems.push_back(&p);

  const auto start = std::chrono::steady_clock::now();
  long total = static_cast<long>(problems.size() * integrators.size()) * (kmax + 1);
  if (long_runs)
    for (const Problem& p : problems) total += p.long_run ? static_cast<long>(integrators.size()) : 0;
  try {
    Progress progress(total);
    for (const Problem& p : problems) {
      for (const std::string& name : integrators) {
        const Integrator integrator = *parseIntegrator(name);
        const size_t first = report.rows.size();
        for (int k = 0; k <= kmax; ++k) {
          Row row;
          row.problem = &p;
          row.integrator = name;
          row.k = k;
          row.dt = sweepDt(k);
          row.steps_planned = wholeSteps(p.t_end, row.dt, p.name + ": t_end");
          progress.show(p.name + " " + name + " dt=" + dtLabel(k), k == kmax);
          row.error = errorPass(p, integrator, row.dt, p.t_end, false);
          if (timed) row.timing = timeRuns(p, integrator, row.dt, row.error.steps, timing);
          report.rows.push_back(std::move(row));
        }
        for (size_t i = first; i + 1 < report.rows.size(); ++i) {
          const double a = report.rows[i].error.err_linf, b = report.rows[i + 1].error.err_linf;
          if (a > 0 && b > 0 && std::isfinite(a) && std::isfinite(b)) report.rows[i].order_pairwise = std::log2(a / b);
        }
      }
      if (long_runs && p.long_run) {
        for (const std::string& name : integrators) {
          progress.show(p.name + " " + name + " long run " + std::to_string(static_cast<long>(*p.long_run)) + " s", true);
          LongRun l;
          l.problem = &p;
          l.integrator = name;
          l.error = errorPass(p, *parseIntegrator(name), 1.0 / 60.0, *p.long_run, true);
          report.long_runs.push_back(std::move(l));
        }
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitSceneError;
  }
  report.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  int failed = 0;
  try {
    writeCsv(report, out);
    // A sweep that stops before k = 8 may not reach the asymptotic range of every integrator (explicit
    // Euler on the spring needs dt ≤ 1/3840): there "no fit" is reported, not failed.
    failed = writeSummary(report, out, kmax >= 8);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "accuracy: %s\n", e.what());
    return kExitSceneError;
  }
  if (!args.flag("no-plots"))
    if (const auto problem = writePlots(report, out)) std::fprintf(stderr, "accuracy: %s\n", problem->c_str());

  // The observed orders beside the expected ones.
  std::printf("%-22s", "observed order");
  for (const std::string& i : integrators) std::printf(" %-26s", i.c_str());
  std::printf("\n");
  for (const Problem& p : problems) {
    std::printf("%-22s", p.name.c_str());
    for (const std::string& i : integrators) {
      std::vector<const Row*> rows;
      for (const Row& r : report.rows)
        if (r.problem == &p && r.integrator == i) rows.push_back(&r);
      const Verdict v = judge(p, i, rows);
      const bool counts = v.gated && !v.pass && (kmax >= 8 || !v.inconclusive);
      const std::string cell = v.observed + " (" + v.expected + ")" + (v.gated ? (v.pass ? " ok" : counts ? " FAIL" : " ?") : "");
      std::printf(" %-26s", cell.c_str());
    }
    std::printf("\n");
  }
  std::printf("report in %s (summary.md, accuracy.csv, pictures) after %.1f s%s\n", out.string().c_str(),
              report.runtime_s, failed ? "" : "; every gated expectation holds");
  if (failed) std::printf("%d gated expectation(s) failed: see %s\n", failed, (out / "summary.md").string().c_str());
  return failed ? kExitSceneError : kExitOk;
}

}  // namespace rigidlab::app

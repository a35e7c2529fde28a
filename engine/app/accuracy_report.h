// The accuracy report: rows of the sweep, the order fit, and the files written from them —
// accuracy.csv (the contract, columns of docs/design/accuracy.md §5 plus a few at the end), energy_<problem>.csv,
// summary.md, and gnuplot pictures generated from the CSV (plots.gp, re-runnable by hand).
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "accuracy_problem.h"
#include "accuracy_run.h"

namespace rigidlab::app::accuracy {

// Where and how the numbers were made (CSV columns engine_version, git_hash, build, cpu).
struct BuildInfo {
  std::string engine_version;  // from the source tree's CMakeLists.txt project(VERSION)
  std::string git_hash;        // `git rev-parse --short HEAD` of the source tree, "+dirty" if modified
  std::string build;           // "release gcc 12.2.0" / "debug ..." / "+asan"
  std::string cpu;             // /proc/cpuinfo model name × count
};
BuildInfo buildInfo();

struct Row {
  const Problem* problem = nullptr;
  std::string integrator;
  int k = 0;                // dt = 1/30 · 2^−k
  double dt = 0.0;
  long steps_planned = 0;
  ErrorPass error;
  std::optional<Timing> timing;
  double order_pairwise = std::numeric_limits<double>::quiet_NaN();  // log2(err_k / err_{k+1})
};

// The observed order on one problem for one integrator: a least-squares fit of log err against
// log dt over the asymptotic window (docs/design/accuracy.md §5): points of status ok with
// max(1e3 ε, 100 N ε) < err_linf < 0.1, where N is the run's step count (round-off grows with N).
struct Fit {
  int points = 0;  // in the window; the fit needs 2
  double order = std::numeric_limits<double>::quiet_NaN();
  double log_c = 0.0;  // log err ≈ log_c + order · log dt
  double dt_min = 0, dt_max = 0;
};
Fit fitOrder(const std::vector<const Row*>& rows);
// The same window fitted against the run time instead of dt: log err ≈ c + slope · log wall_s_min
// (timed runs only). A method of order p whose cost is proportional to its steps has slope −p.
Fit fitWork(const std::vector<const Row*>& rows);

// The verdict on one problem × integrator against its expectation.
struct Verdict {
  std::string observed;  // "1.00", "exact", "n/a"
  std::string expected;  // "1", "exact", "-"
  bool pass = true;
  bool gated = false;  // counts for the exit status (smooth and sanity problems)
  // No fit: fewer than 2 runs in the asymptotic window (a failure; with a sweep shorter than the
  // default one, e.g. --quick, the command reports it without failing).
  bool inconclusive = false;
  std::string why;     // when it fails
};
Verdict judge(const Problem& problem, const std::string& integrator, const std::vector<const Row*>& rows);

// Order tolerance around an expected order (docs/design/accuracy.md §5: ±0.2, RK4 ±0.3).
double orderTolerance(double expected);

struct LongRun {
  const Problem* problem = nullptr;
  std::string integrator;
  ErrorPass error;  // with energy_t / energy_ratio
};

struct ReportInput {
  std::vector<const Problem*> problems;
  std::vector<std::string> integrators;
  std::vector<Row> rows;
  std::vector<LongRun> long_runs;
  BuildInfo build;
  std::string command_line;
  double runtime_s = 0.0;
  bool timed = true;
};

// accuracy.csv; energy_<problem>.csv for the long runs.
void writeCsv(const ReportInput& in, const std::filesystem::path& dir);
// summary.md. Returns the number of gated expectations that failed (inconclusive ones only if
// `strict`).
int writeSummary(const ReportInput& in, const std::filesystem::path& dir, bool strict = true);
// plots.gp, then runs gnuplot on it if it is installed: wp_<p>.svg/png, conv_<p>.svg/png,
// energy_<p>.svg/png. Returns a message if the pictures could not be made.
std::optional<std::string> writePlots(const ReportInput& in, const std::filesystem::path& dir);

std::string dtLabel(int k);  // "1/30", "1/60", ...

}  // namespace rigidlab::app::accuracy

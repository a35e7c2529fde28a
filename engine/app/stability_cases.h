// The stiff and extreme cases of `rigidlab stability` (docs/design/accuracy.md §4, S1–S11). Each case builds its
// worlds in C++ (or loads a reference problem from scripts/accuracy/), runs them, and returns its
// figures and a PASS/FAIL against a rule stated in the case, and the CSV files and pictures of its
// sweeps. Options::quick selects the short versions that ctest runs (fewer steps, same rules);
// Options::long_sweeps adds the sweeps that take minutes (a case without it lists them as skipped).
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace rigidlab::app::stability {

struct Figure {
  std::string key;    // snake_case, for JSON
  double value = 0;   // the number (NaN when it does not apply)
  std::string unit;   // "m", "m/s", "1/s", "" ...
  std::string text;   // when the figure is not a number ("none", "semi_implicit_euler", ...)
};

struct Table {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// A CSV file the command writes beside the report, <name>.csv: one row per run of a sweep.
struct DataFile {
  std::string name;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// One curve of a picture: column `y` against column `x` of the picture's CSV, over the rows whose
// columns hold the values in `where`.
struct Series {
  std::string title;  // in the key ("" = none)
  std::string x, y;
  std::vector<std::pair<std::string, std::string>> where;
  std::string color = "#1f77b4";
  int point = 7;        // gnuplot point type (7 filled circle, 6 open circle, 5/4 squares, 9/8 triangles)
  bool lines = true;    // points joined by lines, else points only
  int dash = 1;         // gnuplot dash type
  double ceiling = 0;   // > 0: values above it, and values that are not finite, drawn at it
};

// A line drawn across a picture: a gate (y = at over x_from … x_to, the whole width if both are 0)
// or, vertical, a threshold x = at.
struct Mark {
  std::string title;
  double at = 0;
  bool vertical = false;
  double x_from = 0, x_to = 0;
  std::string color = "#e0a030";
};

// A picture of one CSV file, <name>.svg and <name>.png, made by plots.gp.
struct Picture {
  std::string name;  // file stem
  std::string data;  // DataFile::name
  std::string title, xlabel, ylabel;
  bool log_x = true, log_y = true;
  std::string key = "outside right top";  // gnuplot `set key` placement
  std::vector<Series> series{};
  std::vector<Mark> marks{};
};

struct CaseResult {
  std::string name, title;
  std::string rule;  // the pass/fail rule, one sentence
  bool pass = false;
  std::vector<Figure> figures;
  std::vector<Table> tables;
  std::vector<std::string> notes;    // what failed and why, what is reported only
  std::vector<std::string> skipped;  // sweeps not run (without --long), each saying what it is
  std::vector<DataFile> data;        // written as <name>.csv
  std::vector<Picture> pictures;     // drawn from `data` by plots.gp
  double seconds = 0;                // wall time of the case
};

struct Options {
  bool quick = false;        // --quick: the short versions, as ctest runs them
  bool long_sweeps = false;  // --long: also the sweeps that take minutes
};

struct Case {
  std::string name;
  std::string summary;      // for --help
  std::string long_sweeps;  // for --help: what only --long runs ("" = nothing)
  std::function<CaseResult(const Options&)> run;
};

const std::vector<Case>& cases();

// Helpers shared by the case files.
std::vector<std::string> integrators();  // every integrator the engine offers, by name
std::string fmt(double x, int digits = 4);  // %.{digits}g, "inf", "nan"

// stability_cases.cpp: springs, dampers, long runs, frame-rate independence.
CaseResult stiffSpringThresholds(const Options& options);
CaseResult stiffSpringImplicit(const Options& options);
CaseResult damperSign(const Options& options);
CaseResult damperMonotone(const Options& options);
CaseResult criticalDamper(const Options& options);
CaseResult longRuns(const Options& options);
CaseResult frameRate(const Options& options);
// stability_contact_cases.cpp: stacks, mass ratios, fast bodies, overlaps, scale.
CaseResult massRatio(const Options& options);
CaseResult tallStack(const Options& options);
CaseResult pyramid(const Options& options);
CaseResult fastBodies(const Options& options);
CaseResult deepOverlap(const Options& options);
CaseResult scale(const Options& options);
// stability_joint_cases.cpp: a chain released horizontally, a 100:1 load, a chain whirled fast.
CaseResult jointChain(const Options& options);
CaseResult jointHeavyLoad(const Options& options);
CaseResult jointWhirl(const Options& options);
CaseResult jointLongChains(const Options& options);

}  // namespace rigidlab::app::stability

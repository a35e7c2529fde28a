// The stiff and extreme cases of `rigidlab stability` (docs/design/accuracy.md §4, S1–S11). Each case builds its
// worlds in C++ (or loads a reference problem from scripts/accuracy/), runs them, and returns its
// figures and a PASS/FAIL against a rule stated in the case. `quick` selects the short versions
// that ctest runs (fewer steps, same rules).
#pragma once

#include <functional>
#include <string>
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

struct CaseResult {
  std::string name, title;
  std::string rule;  // the pass/fail rule, one sentence
  bool pass = false;
  std::vector<Figure> figures;
  std::vector<Table> tables;
  std::vector<std::string> notes;  // what failed and why, what is reported only
  double seconds = 0;              // wall time of the case
};

struct Case {
  std::string name;
  std::string summary;  // for --help
  std::function<CaseResult(bool quick)> run;
};

const std::vector<Case>& cases();

// Helpers shared by the case files.
std::vector<std::string> integrators();  // every integrator the engine offers, by name
std::string fmt(double x, int digits = 4);  // %.{digits}g, "inf", "nan"

// stability_cases.cpp: springs, dampers, long runs, frame-rate independence.
CaseResult stiffSpringThresholds(bool quick);
CaseResult stiffSpringImplicit(bool quick);
CaseResult damperSign(bool quick);
CaseResult damperMonotone(bool quick);
CaseResult criticalDamper(bool quick);
CaseResult longRuns(bool quick);
CaseResult frameRate(bool quick);
// stability_contact_cases.cpp: stacks, mass ratios, fast bodies, overlaps, scale.
CaseResult massRatio(bool quick);
CaseResult tallStack(bool quick);
CaseResult pyramid(bool quick);
CaseResult fastBodies(bool quick);
CaseResult deepOverlap(bool quick);
CaseResult scale(bool quick);
// stability_joint_cases.cpp: a chain released horizontally, a 100:1 load, a chain whirled fast.
CaseResult jointChain(bool quick);
CaseResult jointHeavyLoad(bool quick);
CaseResult jointWhirl(bool quick);
CaseResult jointLongChains(bool quick);

}  // namespace rigidlab::app::stability

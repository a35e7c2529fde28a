// The stability report's data and pictures: each case's sweeps as <name>.csv, and plots.gp, a
// gnuplot script that draws the cases' pictures from those files (re-runnable by hand).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stability_cases.h"

namespace rigidlab::app::stability {

// <data>.csv for every DataFile of the results. Throws if a file cannot be written.
void writeData(const std::vector<CaseResult>& results, const std::filesystem::path& dir);

// plots.gp for every Picture of the results, then gnuplot on it if `draw` and gnuplot is installed.
// Returns a message if the pictures could not be made.
std::optional<std::string> writePlots(const std::vector<CaseResult>& results, const std::filesystem::path& dir, bool draw);

}  // namespace rigidlab::app::stability

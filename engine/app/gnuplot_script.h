// Pieces of the gnuplot scripts the lab writes beside its CSV files (plots.gp of `rigidlab accuracy`
// and `rigidlab stability`): one look for every picture, and running gnuplot when it is installed.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

namespace rigidlab::app::gnuplot {

// The lines every picture starts from (after `reset`): comma-separated data, UTF-8, a light grid,
// a small key, powers of ten on both axes.
extern const char* const kPreamble;

// Colour, filled and open point types, dash of an integrator's curve: the same integrator looks the
// same in every picture (index: its place in the run's list, for integrators without a fixed style).
struct Style {
  const char* color;
  int filled, open;
  int dash = 1;  // implicit_euler is dashed: it often coincides with semi-implicit Euler
};
Style integratorStyle(const std::string& integrator, size_t index);

// A gnuplot string literal.
std::string quoted(const std::string& s);

// Writes `body` (set ... and plot ...) twice, into <stem>.svg and <stem>.png.
void writeTerminals(std::ostream& gp, const std::string& stem, const std::string& body);

// Runs `gnuplot <script>` in `dir` if gnuplot is installed (errors to gnuplot.log there). Returns a
// message when the pictures could not be made.
std::optional<std::string> run(const std::filesystem::path& dir, const std::string& script = "plots.gp");

}  // namespace rigidlab::app::gnuplot

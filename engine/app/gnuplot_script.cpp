// Pieces of the lab's gnuplot scripts (gnuplot_script.h).
#include "gnuplot_script.h"

#include <cstdlib>

namespace rigidlab::app::gnuplot {

const char* const kPreamble =
    "set datafile separator comma\n"
    "set encoding utf8\n"
    "set grid lw 0.5 lc rgb '#dddddd'\n"
    "set key font ',9' spacing 1.1\n"
    "set format x '10^{%L}'\nset format y '10^{%L}'\n";

Style integratorStyle(const std::string& integrator, size_t index) {
  if (integrator == "euler") return {"#d62728", 7, 6};
  if (integrator == "semi_implicit_euler") return {"#1f77b4", 5, 4};
  if (integrator == "rk4") return {"#2ca02c", 9, 8};
  if (integrator == "implicit_euler") return {"#9467bd", 13, 12, 2};
  static const Style extra[] = {{"#ff7f0e", 11, 10}, {"#8c564b", 15, 14}, {"#e377c2", 7, 6}};
  return extra[index % 3];
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

void writeTerminals(std::ostream& gp, const std::string& stem, const std::string& body) {
  for (const std::string format : {"svg", "png"}) {
    if (format == "svg")
      gp << "set terminal svg size 900,520 dynamic enhanced font 'sans,12' background '#ffffff'\n";
    else
      gp << "set terminal pngcairo size 1000,600 enhanced font 'sans,11' background '#ffffff'\n";
    gp << "set output '" << stem << '.' << format << "'\n" << body << "unset output\n";
  }
}

std::optional<std::string> run(const std::filesystem::path& dir, const std::string& script) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    return "gnuplot is not installed (Debian: gnuplot-nox): " + script + " written, pictures not made";
  const std::string command = "cd '" + dir.string() + "' && gnuplot " + script + " 2> gnuplot.log";
  if (std::system(command.c_str()) != 0)
    return "gnuplot failed on " + (dir / script).string() + " (see " + (dir / "gnuplot.log").string() + ")";
  return std::nullopt;
}

}  // namespace rigidlab::app::gnuplot

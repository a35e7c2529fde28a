// The stability report's CSV files and plots.gp (stability_plots.h).
#include "stability_plots.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "gnuplot_script.h"

namespace rigidlab::app::stability {
namespace {

std::string noCommas(std::string s) {
  for (char& c : s)
    if (c == ',') c = ';';
  return s;
}

const DataFile* findData(const CaseResult& r, const std::string& name) {
  for (const DataFile& d : r.data)
    if (d.name == name) return &d;
  return nullptr;
}

// 1-based column of `name` in the file (gnuplot's numbering).
int column(const DataFile& d, const std::string& name) {
  for (size_t i = 0; i < d.header.size(); ++i)
    if (d.header[i] == name) return static_cast<int>(i) + 1;
  throw std::logic_error("picture of " + d.name + ".csv: no column '" + name + "'");
}

// The plot clause of one series: x where the row matches, else NaN (gnuplot leaves the point out).
std::string seriesClause(const DataFile& d, const Series& s) {
  std::string where;
  for (const auto& [col, value] : s.where)
    where += std::string(where.empty() ? "" : " && ") + "strcol(" + std::to_string(column(d, col)) + ") eq " +
             gnuplot::quoted(noCommas(value));
  const std::string x = "$" + std::to_string(column(d, s.x));
  const int yc = column(d, s.y);
  std::string y = "($" + std::to_string(yc) + ")";
  if (s.ceiling > 0) {
    const std::string c = std::to_string(yc), cap = fmt(s.ceiling, 17);
    y = "(strcol(" + c + ") eq 'nan' || strcol(" + c + ") eq 'inf' || $" + c + " > " + cap + " ? " + cap + " : $" + c + ")";
  }
  return "'" + d.name + ".csv' skip 1 using (" + (where.empty() ? x : "(" + where + ") ? " + x + " : NaN") + "):" + y +
         " with " + (s.lines ? "linespoints lw 2" : "points") + " dt " + std::to_string(s.dash) + " lc rgb '" + s.color +
         "' pt " + std::to_string(s.point) + " ps 1.2 " + (s.title.empty() ? "notitle" : "title " + gnuplot::quoted(s.title) + " noenhanced");
}

std::string picture(const DataFile& d, const Picture& p) {
  std::ostringstream body;
  body << "set title " << gnuplot::quoted(p.title) << " noenhanced\nset xlabel " << gnuplot::quoted(p.xlabel)
       << "\nset ylabel " << gnuplot::quoted(p.ylabel) << "\nunset logscale\n";
  if (p.log_x) body << "set logscale x\n";
  else body << "set format x '%g'\n";
  if (p.log_y) body << "set logscale y\n";
  else body << "set format y '%g'\n";
  body << "set offsets graph 0.04, graph 0.04, graph 0.06, graph 0.06\nset key " << p.key << " Left reverse samplen 2.5\n"
       << "set samples 1000\nunset arrow\n";
  std::string plot = "plot ";
  for (const Series& s : p.series) plot += seriesClause(d, s) + ", \\\n  ";
  for (const Mark& m : p.marks) {
    if (m.vertical) {
      body << "set arrow from " << fmt(m.at, 17) << ", graph 0 to " << fmt(m.at, 17) << ", graph 1 nohead lw 2 dt 2 lc rgb '"
           << m.color << "'\n";
      plot += "NaN with lines lw 2 dt 2 lc rgb '" + m.color + "' title " + gnuplot::quoted(m.title) + ", \\\n  ";
    } else if (m.x_from > 0 || m.x_to > 0) {
      plot += "(x >= " + fmt(m.x_from / 1.0001, 17) + " && x <= " + fmt(m.x_to * 1.0001, 17) + " ? " + fmt(m.at, 17) +
              " : NaN) with lines lw 3 lc rgb '" + m.color + "' title " + gnuplot::quoted(m.title) + ", \\\n  ";
    } else {
      plot += fmt(m.at, 17) + " with lines lw 3 lc rgb '" + m.color + "' title " + gnuplot::quoted(m.title) + ", \\\n  ";
    }
  }
  plot.resize(plot.size() - 6);
  body << plot << "\n";
  return body.str();
}

}  // namespace

void writeData(const std::vector<CaseResult>& results, const std::filesystem::path& dir) {
  for (const CaseResult& r : results)
    for (const DataFile& d : r.data) {
      const std::filesystem::path file = dir / (d.name + ".csv");
      std::ofstream csv(file);
      if (!csv) throw std::runtime_error(file.string() + ": cannot write");
      for (size_t i = 0; i < d.header.size(); ++i) csv << (i ? "," : "") << d.header[i];
      csv << '\n';
      for (const auto& row : d.rows) {
        for (size_t i = 0; i < row.size(); ++i) csv << (i ? "," : "") << noCommas(row[i]);
        csv << '\n';
      }
    }
}

std::optional<std::string> writePlots(const std::vector<CaseResult>& results, const std::filesystem::path& dir, bool draw) {
  std::ofstream gp(dir / "plots.gp");
  if (!gp) return (dir / "plots.gp").string() + ": cannot write";
  gp << "# Pictures of the stability report, made from its CSV files (one per sweep).\n"
        "# Re-run by hand with: gnuplot plots.gp (in this directory). Written by rigidlab stability.\n";
  int count = 0;
  for (const CaseResult& r : results)
    for (const Picture& p : r.pictures) {
      const DataFile* d = findData(r, p.data);
      if (!d || d->rows.empty()) continue;  // nothing ran (the sweep was skipped)
      gp << "\n# " << r.name << ": " << p.name << ".svg/png from " << p.data << ".csv\nreset\n" << gnuplot::kPreamble;
      gnuplot::writeTerminals(gp, p.name, picture(*d, p));
      ++count;
    }
  gp.close();
  if (!draw || count == 0) return std::nullopt;
  return gnuplot::run(dir);
}

}  // namespace rigidlab::app::stability

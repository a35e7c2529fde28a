// rigidlab stability: the stiff and extreme cases (docs/design/accuracy.md §4, issue 5), each with a pass/fail
// rule and its figures, written as stability.json and stability.md. The cases are in
// stability_cases.cpp, stability_contact_cases.cpp and stability_joint_cases.cpp.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "accuracy_report.h"
#include "cli.h"
#include "commands.h"
#include "report.h"
#include "stability_cases.h"
#include "stability_plots.h"

namespace rigidlab::app {
namespace {

using namespace stability;

std::string help() {
  std::string h = R"(usage: rigidlab stability [--out DIR] [--cases A,B,...] [--quick] [--long] [--no-plots]

Runs the stiff and extreme cases (docs/design/accuracy.md section 4), each with a pass/fail rule, and
writes to DIR (default stability-report):
  stability.md, stability.json  every case's rule, figures and PASS/FAIL, the sweeps skipped
  <sweep>.csv                   one row per run of a case's sweep (mass_ratio.csv, long_chains.csv,
                                stiff_springs.csv, joint_chain.csv, ...)
  plots.gp                      gnuplot script that makes the pictures from the CSV files
                                (<picture>.svg/png, linked from stability.md)
A line per case on standard output.

  --cases LIST  run only these cases (comma-separated)
  --quick       the short versions (fewer steps; the same rules), as ctest runs them
  --long        also the long sweeps (minutes; listed below): without it they are skipped,
                and the report and the case's line say which
  --no-plots    do not run gnuplot (plots.gp is still written)

Exit status: 0 if every case run passes, 1 if one fails, 2 for a usage error. A case passes on
what it ran: a skipped sweep is never counted as passed.

cases:
)";
  for (const Case& c : cases()) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-24s %s\n", c.name.c_str(), c.summary.c_str());
    h += line;
  }
  h += "\nlong sweeps (--long):\n";
  for (const Case& c : cases()) {
    if (c.long_sweeps.empty()) continue;
    char line[200];
    std::snprintf(line, sizeof line, "  %-24s %s\n", c.name.c_str(), c.long_sweeps.c_str());
    h += line;
  }
  return h;
}

std::string mdCell(std::string s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

void writeJson(const std::filesystem::path& file, const std::vector<CaseResult>& results, const accuracy::BuildInfo& b,
               const Options& options) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
  out << "{\n  \"engine_version\": " << jsonString(b.engine_version) << ",\n  \"git_hash\": " << jsonString(b.git_hash)
      << ",\n  \"build\": " << jsonString(b.build) << ",\n  \"cpu\": " << jsonString(b.cpu)
      << ",\n  \"quick\": " << (options.quick ? "true" : "false") << ",\n  \"long\": " << (options.long_sweeps ? "true" : "false")
      << ",\n  \"cases\": [\n";
  for (size_t i = 0; i < results.size(); ++i) {
    const CaseResult& r = results[i];
    out << "    {\"name\": " << jsonString(r.name) << ", \"title\": " << jsonString(r.title)
        << ", \"pass\": " << (r.pass ? "true" : "false") << ", \"seconds\": " << jsonNumber(r.seconds)
        << ",\n     \"rule\": " << jsonString(r.rule) << ",\n     \"figures\": {";
    for (size_t j = 0; j < r.figures.size(); ++j) {
      const Figure& f = r.figures[j];
      out << (j ? ", " : "") << jsonString(f.key) << ": ";
      if (!f.text.empty() && !std::isfinite(f.value)) out << jsonString(f.text);
      else out << jsonNumber(f.value);
    }
    out << "},\n     \"notes\": [";
    for (size_t j = 0; j < r.notes.size(); ++j) out << (j ? ", " : "") << jsonString(r.notes[j]);
    out << "],\n     \"skipped\": [";
    for (size_t j = 0; j < r.skipped.size(); ++j) out << (j ? ", " : "") << jsonString(r.skipped[j]);
    out << "],\n     \"data\": [";
    for (size_t j = 0; j < r.data.size(); ++j) out << (j ? ", " : "") << jsonString(r.data[j].name + ".csv");
    out << "],\n     \"tables\": [";
    for (size_t j = 0; j < r.tables.size(); ++j) {
      const Table& t = r.tables[j];
      out << (j ? ", " : "") << "{\"title\": " << jsonString(t.title) << ", \"rows\": [";
      for (size_t k = 0; k < t.rows.size(); ++k) {
        out << (k ? ", " : "") << "{";
        for (size_t c = 0; c < t.rows[k].size() && c < t.header.size(); ++c)
          out << (c ? ", " : "") << jsonString(t.header[c]) << ": " << jsonString(t.rows[k][c]);
        out << "}";
      }
      out << "]}";
    }
    out << "]}" << (i + 1 < results.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

// "PASS", "**FAIL**", and what was not run.
std::string verdict(const CaseResult& r) {
  std::string v = r.pass ? "PASS" : "**FAIL**";
  if (!r.skipped.empty()) v += " on what ran (" + std::to_string(r.skipped.size()) + " skipped)";
  return v;
}

void writeMarkdown(const std::filesystem::path& file, const std::vector<CaseResult>& results,
                   const accuracy::BuildInfo& b, const Options& options, double seconds) {
  std::ofstream md(file);
  if (!md) throw std::runtime_error(file.string() + ": cannot write");
  int passed = 0;
  std::string partial;
  for (const CaseResult& r : results) {
    passed += r.pass ? 1 : 0;
    if (!r.skipped.empty()) partial += (partial.empty() ? "" : ",") + r.name;
  }
  md << "# rigidlab stability report" << (options.quick ? " (quick versions)" : "") << "\n\n";
  md << "engine " << b.engine_version << ", git " << b.git_hash << ", " << b.build << ", " << b.cpu << "; "
     << passed << " of " << results.size() << " cases pass; " << std::lround(seconds) << " s"
     << (options.long_sweeps ? "; with the long sweeps (--long)" : "") << ".\n\n";
  if (!partial.empty()) {
    md << "**Skipped:** the long sweeps of " << partial << " did not run (they take minutes), and their case passes or fails "
       << "on what ran only. Run them with `rigidlab stability --long --cases " << partial << (options.quick ? " --quick" : "")
       << "`:\n\n";
    for (const CaseResult& r : results)
      for (const std::string& s : r.skipped) md << "- " << r.name << ": " << s << "\n";
    md << "\n";
  }
  md << "| case | result | key figures |\n|---|---|---|\n";
  for (const CaseResult& r : results) {
    std::string figures;
    for (size_t i = 0; i < r.figures.size() && i < 4; ++i)
      figures += (i ? "; " : "") + r.figures[i].key + " = " +
                 (r.figures[i].text.empty() || std::isfinite(r.figures[i].value) ? fmt(r.figures[i].value) : r.figures[i].text) +
                 (r.figures[i].unit.empty() ? "" : " " + r.figures[i].unit);
    md << "| [" << r.name << "](#" << r.name << ") | " << verdict(r) << " | " << mdCell(figures) << " |\n";
  }
  for (const CaseResult& r : results) {
    md << "\n## " << r.name << "\n\n**" << r.title << "** — " << verdict(r) << " ("
       << fmt(r.seconds, 3) << " s)\n\nRule: " << r.rule << ".\n\n";
    for (const std::string& s : r.skipped)
      md << "- skipped: " << s << "; run it with `rigidlab stability --long --cases " << r.name << (options.quick ? " --quick" : "")
         << "`\n";
    for (const std::string& n : r.notes) md << "- " << n << "\n";
    if (!r.notes.empty() || !r.skipped.empty()) md << "\n";
    if (!r.figures.empty()) {
      md << "| figure | value |\n|---|---|\n";
      for (const Figure& f : r.figures)
        md << "| " << f.key << " | "
           << (f.text.empty() || std::isfinite(f.value) ? fmt(f.value) : f.text) << (f.unit.empty() ? "" : " " + f.unit)
           << " |\n";
      md << "\n";
    }
    for (const Table& t : r.tables) {
      md << t.title << ":\n\n|";
      for (const std::string& h : t.header) md << ' ' << mdCell(h) << " |";
      md << "\n|";
      for (size_t i = 0; i < t.header.size(); ++i) md << "---|";
      md << "\n";
      for (const auto& row : t.rows) {
        md << "|";
        for (const std::string& c : row) md << ' ' << mdCell(c) << " |";
        md << "\n";
      }
      md << "\n";
    }
    for (const Picture& p : r.pictures)
      for (const DataFile& d : r.data)
        if (d.name == p.data && !d.rows.empty()) md << "![" << p.title << "](" << p.name << ".svg)\n\n";
    for (const DataFile& d : r.data) md << "Data: [" << d.name << ".csv](" << d.name << ".csv)\n\n";
  }
}

}  // namespace

int stabilityCommand(const std::vector<std::string>& argv) {
  const Args args("stability", argv, {"out", "cases"}, {"quick", "long", "no-plots"});
  if (args.help()) {
    std::fputs(help().c_str(), stdout);
    return kExitOk;
  }
  if (!args.positional().empty()) throw UsageError("stability: unexpected argument '" + args.positional()[0] + "'");
  Options options;
  options.quick = args.flag("quick");
  options.long_sweeps = args.flag("long");
  const std::filesystem::path out = args.value("out").value_or("stability-report");
  std::vector<const Case*> selected;
  if (const auto list = args.value("cases")) {
    std::istringstream in(*list);
    std::string name;
    while (std::getline(in, name, ',')) {
      if (name.empty()) continue;
      const Case* found = nullptr;
      for (const Case& c : cases())
        if (c.name == name) found = &c;
      if (!found) throw UsageError("stability: unknown case '" + name + "' (see rigidlab stability --help)");
      selected.push_back(found);
    }
  } else {
    for (const Case& c : cases()) selected.push_back(&c);
  }

  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) {
    std::fprintf(stderr, "stability: cannot create %s: %s\n", out.string().c_str(), ec.message().c_str());
    return kExitSceneError;
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<CaseResult> results;
  const bool tty = isatty(STDERR_FILENO);
  for (size_t i = 0; i < selected.size(); ++i) {
    const Case& c = *selected[i];
    std::fprintf(stderr, tty ? "\rstability [%zu/%zu] %-40s" : "stability [%zu/%zu] %s\n", i + 1, selected.size(), c.name.c_str());
    std::fflush(stderr);
    const auto t0 = std::chrono::steady_clock::now();
    CaseResult r;
    try {
      r = c.run(options);
    } catch (const std::exception& e) {
      r.name = c.name;
      r.title = c.summary;
      r.rule = "the case must run";
      r.pass = false;
      r.notes.push_back(std::string("error: ") + e.what());
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (tty) std::fprintf(stderr, "\r%70s\r", "");
    std::printf("%-24s %s  %6.2f s", r.name.c_str(), r.pass ? "PASS" : "FAIL", r.seconds);
    if (!r.pass && !r.notes.empty()) std::printf("  %s", r.notes.front().c_str());
    for (size_t k = 0; k < r.skipped.size(); ++k) std::printf("%s%s", k ? "; " : "  skipped: ", r.skipped[k].c_str());
    std::printf("\n");
    std::fflush(stdout);
    results.push_back(std::move(r));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const accuracy::BuildInfo build = accuracy::buildInfo();
  try {
    writeData(results, out);
    writeJson(out / "stability.json", results, build, options);
    writeMarkdown(out / "stability.md", results, build, options, seconds);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stability: %s\n", e.what());
    return kExitSceneError;
  }
  if (const auto problem = writePlots(results, out, !args.flag("no-plots")))
    std::fprintf(stderr, "stability: %s\n", problem->c_str());
  int failed = 0;
  for (const CaseResult& r : results) failed += r.pass ? 0 : 1;
  size_t skipped = 0;
  for (const CaseResult& r : results) skipped += r.skipped.size();
  std::printf("%zu of %zu cases pass; report in %s (stability.md, stability.json, CSV files, pictures)\n",
              results.size() - failed, results.size(), out.string().c_str());
  if (skipped) std::printf("long sweeps skipped (not counted as passed): %zu; run them with --long\n", skipped);
  return failed ? kExitSceneError : kExitOk;
}

}  // namespace rigidlab::app

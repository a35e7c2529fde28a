#include "golden_trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "rigidlab/error.h"
#include "rigidlab/lua/bounded_file.h"
#include "rigidlab/lua/scene_text.h"
#include "text_file.h"

namespace rigidlab::app {
namespace {

// %.17g reads back as the same double; nan and inf stay readable.
std::string exact(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// A name is the rest of its line: only what would break the line (control bytes) and the escape
// character itself are escaped.
std::string escapeName(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    if (c == '\\') {
      out += "\\\\";
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string unescapeName(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 1 < text.size() && text[i + 1] == '\\') {
      out += '\\';
      ++i;
    } else if (text[i] == '\\' && i + 3 < text.size() && text[i + 1] == 'x') {
      out += static_cast<char>(std::strtol(text.substr(i + 2, 2).c_str(), nullptr, 16));
      i += 3;
    } else {
      out += text[i];
    }
  }
  return out;
}

// Reads a trajectory file line by line; every error names the file and line.
class Reader {
 public:
  Reader(const std::string& text, std::string path) : text_(text), path_(std::move(path)) {}

  // The next line that is not a comment or blank; false at the end.
  bool next() {
    while (pos_ < text_.size()) {
      const size_t end = std::min(text_.find('\n', pos_), text_.size());
      line_ = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++number_;
      if (!line_.empty() && line_.back() == '\r') line_.pop_back();
      if (!line_.empty() && line_[0] != '#') {
        field_ = 0;
        return true;
      }
    }
    return false;
  }
  // The next space-separated field of the line.
  std::string word(const char* what) {
    while (field_ < line_.size() && line_[field_] == ' ') ++field_;
    const size_t end = std::min(line_.find(' ', field_), line_.size());
    if (end == field_) fail(std::string("expected ") + what);
    std::string w = line_.substr(field_, end - field_);
    field_ = end;
    return w;
  }
  std::string rest() {
    if (field_ < line_.size() && line_[field_] == ' ') ++field_;
    return field_ < line_.size() ? line_.substr(field_) : std::string();
  }
  void keyword(const char* key) {
    if (word(key) != key) fail(std::string("expected '") + key + "'");
  }
  double number(const char* what) {
    const std::string w = word(what);
    char* end = nullptr;
    const double x = std::strtod(w.c_str(), &end);
    if (*end != '\0') fail(std::string(what) + " must be a number, got '" + w + "'");
    return x;
  }
  long integer(const char* what) {
    const std::string w = word(what);
    char* end = nullptr;
    const long x = std::strtol(w.c_str(), &end, 10);
    if (*end != '\0' || x < 0) fail(std::string(what) + " must be a whole number >= 0, got '" + w + "'");
    return x;
  }
  const std::string& line() const { return line_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_ + ":" + std::to_string(number_) + ": " + what);
  }

 private:
  const std::string& text_;
  std::string path_;
  std::string line_;
  size_t pos_ = 0, field_ = 0;
  int number_ = 0;
};

// Bit for bit (tolerance 0: -0 and 0 differ, a NaN matches a NaN), else within the tolerance.
bool same(double expected, double actual, double tolerance) {
  if (std::isnan(expected) || std::isnan(actual)) return std::isnan(expected) && std::isnan(actual);
  if (tolerance == 0.0) return std::memcmp(&expected, &actual, sizeof(double)) == 0;
  return std::fabs(actual - expected) <= tolerance;
}

std::string bodyName(const BodySample& b) {
  return "body " + std::to_string(b.uid) + (b.name.empty() ? "" : " \"" + lua::displayText(b.name, 64) + "\"");
}

std::string at(const TrajectorySample& s) {
  return "step " + std::to_string(s.step) + " (t = " + formatNumber(s.time) + " s)";
}

// The field of `a` that differs most from `e`, as "y is 3.8000000000000003, expected 3.8 (off by
// 4.4e-16)"; empty if none differs.
std::string differingField(const BodySample& e, const BodySample& a, double tolerance) {
  const std::pair<const char*, double BodySample::*> fields[] = {
      {"x", &BodySample::x},   {"y", &BodySample::y},   {"angle", &BodySample::angle},
      {"vx", &BodySample::vx}, {"vy", &BodySample::vy}, {"angular velocity", &BodySample::omega}};
  const char* worst = nullptr;
  double worst_by = -1.0, worst_e = 0.0, worst_a = 0.0;
  for (const auto& [name, member] : fields) {
    const double ev = e.*member, av = a.*member;
    if (same(ev, av, tolerance)) continue;
    const double by = std::isnan(av - ev) ? INFINITY : std::fabs(av - ev);
    if (by > worst_by) {
      worst = name;
      worst_by = by;
      worst_e = ev;
      worst_a = av;
    }
  }
  if (!worst) return "";
  char by[32];
  std::snprintf(by, sizeof by, "%.3g", worst_by);
  return std::string(worst) + " is " + formatNumber(worst_a) + ", expected " + formatNumber(worst_e) + " (off by " +
         by + ")";
}

}  // namespace

TrajectorySample sampleWorld(const World& world, long step) {
  TrajectorySample sample;
  sample.step = step;
  sample.time = world.time();
  for (BodyId id : world.bodyIds()) {
    const Body& b = world.body(id);
    sample.bodies.push_back({b.uid, b.name, b.position().x(), b.position().y(), b.angle, b.velocity.x(),
                             b.velocity.y(), b.angular_velocity});
  }
  std::sort(sample.bodies.begin(), sample.bodies.end(),
            [](const BodySample& a, const BodySample& b) { return a.uid < b.uid; });
  return sample;
}

std::string formatTrajectory(const Trajectory& t) {
  std::string out =
      "# rigidlab golden trajectory: `rigidlab test --update` rewrites it; review a change like code.\n"
      "# Per sample: 'sample <step> <time>', then per body: <step> <uid> <x> <y> <angle> <vx> <vy> "
      "<angular velocity> <name>\n";
  out += "scene " + escapeName(t.scene) + "\n";
  out += "dt " + exact(t.dt) + "\n";
  out += "steps " + std::to_string(t.steps) + "\n";
  out += "every " + std::to_string(t.every) + "\n";
  for (const TrajectorySample& s : t.samples) {
    out += "sample " + std::to_string(s.step) + " " + exact(s.time) + "\n";
    const std::string step = std::to_string(s.step) + " ";
    for (const BodySample& b : s.bodies) {
      out += step + std::to_string(b.uid) + " " + exact(b.x) + " " + exact(b.y) + " " + exact(b.angle) + " " +
             exact(b.vx) + " " + exact(b.vy) + " " + exact(b.omega);
      out += b.name.empty() ? "\n" : " " + escapeName(b.name) + "\n";
    }
  }
  return out;
}

size_t sampleBytesBound(const TrajectorySample& s) {
  // "sample <step> <time>\n", then per body: step, uid, six numbers of at most 24 characters
  // (-1.2345678901234567e-308), a space each, an escaped name (at most 4 bytes per byte: \xHH).
  constexpr size_t kLine = 20 + 1 + 10 + 6 * (1 + 24) + 2;
  size_t bytes = 8 + 20 + 1 + 24 + 1;
  for (const BodySample& b : s.bodies) bytes += kLine + 4 * b.name.size();
  return bytes;
}

Trajectory parseTrajectory(const std::string& text, const std::string& path) {
  Trajectory t;
  Reader r(text, path);
  const auto header = [&](const char* key) {
    if (!r.next()) r.fail(std::string("ends before its '") + key + "' line");
    r.keyword(key);
  };
  header("scene");
  t.scene = unescapeName(r.rest());
  header("dt");
  t.dt = r.number("dt");
  header("steps");
  t.steps = r.integer("steps");
  header("every");
  t.every = r.integer("every");
  while (r.next()) {
    if (r.line().starts_with("sample ")) {
      r.keyword("sample");
      TrajectorySample s;
      s.step = r.integer("the sample's step");
      s.time = r.number("the sample's time");
      t.samples.push_back(std::move(s));
      continue;
    }
    if (t.samples.empty()) r.fail("a body line before the first 'sample' line");
    TrajectorySample& s = t.samples.back();
    if (r.integer("step") != s.step) r.fail("the step differs from its sample's, " + std::to_string(s.step));
    BodySample b;
    const long uid = r.integer("uid");
    if (uid > static_cast<long>(UINT32_MAX)) r.fail("uid out of range");
    b.uid = static_cast<uint32_t>(uid);
    b.x = r.number("x");
    b.y = r.number("y");
    b.angle = r.number("angle");
    b.vx = r.number("vx");
    b.vy = r.number("vy");
    b.omega = r.number("angular velocity");
    b.name = unescapeName(r.rest());
    s.bodies.push_back(std::move(b));
  }
  return t;
}

std::filesystem::path goldenPath(const std::filesystem::path& scene, const std::string& name) {
  return scene.parent_path() / "golden" / (name + ".txt");
}

std::optional<std::string> compareTrajectories(const Trajectory& expected, const Trajectory& actual, double tolerance) {
  const auto recorded = [](const Trajectory& t) {
    return "dt " + formatNumber(t.dt) + ", " + std::to_string(t.steps) + " steps, a sample every " +
           std::to_string(t.every);
  };
  if (!same(expected.dt, actual.dt, 0.0) || expected.steps != actual.steps || expected.every != actual.every)
    return "the golden trajectory was recorded with " + recorded(expected) + "; this run has " + recorded(actual);
  const size_t samples = std::min(expected.samples.size(), actual.samples.size());
  for (size_t i = 0; i < samples; ++i) {
    const TrajectorySample& e = expected.samples[i];
    const TrajectorySample& a = actual.samples[i];
    if (e.step != a.step) return "sample " + std::to_string(i + 1) + " is at step " + std::to_string(a.step) +
                                 ", expected at step " + std::to_string(e.step);
    // Bodies by uid: the first one that is missing, extra or off, and how many more are.
    std::string first;
    long more = 0;
    const auto report = [&](const std::string& what) {
      if (first.empty()) first = what;
      else ++more;
    };
    size_t ei = 0, ai = 0;
    while (ei < e.bodies.size() || ai < a.bodies.size()) {
      if (ai == a.bodies.size() || (ei < e.bodies.size() && e.bodies[ei].uid < a.bodies[ai].uid)) {
        report(bodyName(e.bodies[ei++]) + " is in the golden trajectory but not in this run at " + at(a));
      } else if (ei == e.bodies.size() || a.bodies[ai].uid < e.bodies[ei].uid) {
        report(bodyName(a.bodies[ai++]) + " is in this run but not in the golden trajectory at " + at(a));
      } else {
        const std::string field = differingField(e.bodies[ei], a.bodies[ai], tolerance);
        if (!field.empty()) report(bodyName(a.bodies[ai]) + " diverged first at " + at(a) + ": " + field);
        ++ei;
        ++ai;
      }
    }
    if (!first.empty()) {
      char tol[32];
      std::snprintf(tol, sizeof tol, "%g", tolerance);
      return first + (tolerance == 0.0 ? " (tolerance 0: bit for bit)" : std::string(" (tolerance ") + tol + ")") +
             (more ? "; " + std::to_string(more) + " more bodies differ at that step" : "");
    }
  }
  if (expected.samples.size() != actual.samples.size())
    return "this run has " + std::to_string(actual.samples.size()) + " samples, the golden trajectory " +
           std::to_string(expected.samples.size());
  return std::nullopt;
}

std::filesystem::path writeGolden(const std::filesystem::path& scene, const std::string& name,
                                  const Trajectory& trajectory) {
  const std::filesystem::path file = goldenPath(scene, name);
  const std::string text = formatTrajectory(trajectory);
  if (text.size() > kMaxGoldenBytes)  // not reached after a run that kept to sampleBytesBound
    throw std::runtime_error(file.string() + ": the trajectory is " + std::to_string(text.size()) +
                             " bytes, more than the limit of " +
                             lua::formatBytes(kMaxGoldenBytes) + " for a golden trajectory");
  writeFile(file, text, Folders::Make);
  return file;
}

std::optional<std::string> checkGolden(const std::filesystem::path& scene, const std::string& name,
                                       const Trajectory& actual, double tolerance,
                                       const std::filesystem::path& diff_dir) {
  const std::filesystem::path file = goldenPath(scene, name);
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    return "golden trajectory " + file.string() + " does not exist; record it with `rigidlab test --update " +
           scene.string() + "`";
  std::string text;
  try {
    text = readFile(file, kMaxGoldenBytes, "a golden trajectory");
  } catch (const std::runtime_error& e) {
    return std::string("cannot read the golden trajectory: ") + e.what();  // too large: no diff written
  }
  std::optional<std::string> mismatch;
  try {
    mismatch = compareTrajectories(parseTrajectory(text, file.string()), actual, tolerance);
  } catch (const std::runtime_error& e) {
    mismatch = std::string("cannot read the golden trajectory: ") + e.what();
  }
  if (!mismatch) return std::nullopt;
  writeFile(diff_dir / "expected.txt", text, Folders::Make);
  writeFile(diff_dir / "actual.txt", formatTrajectory(actual), Folders::Make);
  const std::string dir = diff_dir.string();
  return "golden trajectory " + file.string() + ": " + *mismatch + "\nboth trajectories are in " + dir +
         "/: diff -u " + dir + "/expected.txt " + dir + "/actual.txt";
}

}  // namespace rigidlab::app

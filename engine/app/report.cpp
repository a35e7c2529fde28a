#include "report.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "rigidlab/error.h"

namespace rigidlab::app {

std::string jsonNumber(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

namespace {

std::string fixed(double x, int decimals = 4) {
  if (!std::isfinite(x)) return formatNumber(x);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

std::string vec(const Vec2& v) { return "(" + fixed(v.x()) + ", " + fixed(v.y()) + ")"; }

}  // namespace

void printSummary(std::FILE* out, const lua::Scene& scene, const RunInfo& info) {
  const World& w = scene.world();
  const WorldDef& def = w.settings();
  const std::string name = scene.file().empty() ? scene.settings().title : scene.file().string();
  std::fprintf(out, "scene   %s (\"%s\")\n", name.c_str(), scene.settings().title.c_str());
  std::fprintf(out, "run     %ld steps of %.6g s to t = %.6g s; %s, %d iterations; %.1f ms wall\n", info.steps,
               scene.settings().dt, w.time(),
               std::string(integratorName(def.integrator)).c_str(), def.iterations, info.wall_ms);
  const double k = w.kineticEnergy(), p = w.potentialEnergy();
  std::fprintf(out, "energy  kinetic %s J, potential %s J, total %s J\n", fixed(k, 6).c_str(), fixed(p, 6).c_str(),
               fixed(k + p, 6).c_str());
  const auto ids = w.bodyIds();
  std::fprintf(out, "bodies  %zu\n", ids.size());
  std::fprintf(out, "  %4s  %-12s %-6s %-24s %-9s %-24s %s\n", "id", "name", "type", "position", "angle", "velocity",
               "omega");
  constexpr size_t kShown = 20;
  for (size_t i = 0; i < ids.size() && i < kShown; ++i) {
    const Body& b = w.body(ids[i]);
    std::fprintf(out, "  %4u  %-12s %-6s %-24s %-9s %-24s %s\n", b.uid, b.name.substr(0, 12).c_str(),
                 b.isStatic() ? "static" : "", vec(b.position()).c_str(), fixed(b.angle).c_str(), vec(b.velocity).c_str(),
                 fixed(b.angular_velocity).c_str());
  }
  if (ids.size() > kShown) std::fprintf(out, "  ... and %zu more (use --json for all)\n", ids.size() - kShown);
  std::fprintf(out, "check   %s\n", info.check.c_str());
}

void printJson(std::FILE* out, const lua::Scene& scene, const RunInfo& info) {
  const World& w = scene.world();
  std::string s = "{\"time\":" + jsonNumber(w.time()) + ",\"steps\":" + std::to_string(info.steps) + ",\"bodies\":[";
  bool first = true;
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    s += first ? "" : ",";
    first = false;
    s += "{\"id\":" + std::to_string(b.uid) + ",\"name\":" + jsonString(b.name) +
         ",\"static\":" + (b.isStatic() ? "true" : "false") + ",\"position\":[" + jsonNumber(b.position().x()) + "," +
         jsonNumber(b.position().y()) + "],\"angle\":" + jsonNumber(b.angle) + ",\"velocity\":[" +
         jsonNumber(b.velocity.x()) + "," + jsonNumber(b.velocity.y()) + "],\"angular_velocity\":" +
         jsonNumber(b.angular_velocity) + "}";
  }
  s += "],\"energy\":{\"kinetic\":" + jsonNumber(w.kineticEnergy()) + ",\"potential\":" + jsonNumber(w.potentialEnergy()) +
       "},\"incidents\":[";
  first = true;
  for (const Incident& incident : w.incidents()) {
    s += first ? "" : ",";
    first = false;
    s += jsonString(incident.message());
  }
  s += "],\"check\":" + jsonString(info.check) + "}\n";
  std::fputs(s.c_str(), out);
}

Trace::Trace(const std::string& path) : file_(std::fopen(path.c_str(), "w")), path_(path) {
  if (!file_) throw std::runtime_error(path + ": " + std::strerror(errno));
  std::fputs("time,id,name,x,y,angle,vx,vy,omega\n", file_);
}

Trace::~Trace() {
  if (file_) std::fclose(file_);
}

void Trace::write(const World& world) {
  const auto num = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);  // nan and inf stay readable in CSV
    return std::string(buf);
  };
  const std::string t = num(world.time());
  for (BodyId id : world.bodyIds()) {
    const Body& b = world.body(id);
    // Names are quoted CSV fields (a name may hold commas or quotes).
    std::string name = "\"";
    for (char c : b.name) name += c == '"' ? std::string("\"\"") : std::string(1, c);
    name += "\"";
    std::fprintf(file_, "%s,%u,%s,%s,%s,%s,%s,%s,%s\n", t.c_str(), b.uid, name.c_str(), num(b.position().x()).c_str(),
                 num(b.position().y()).c_str(), num(b.angle).c_str(), num(b.velocity.x()).c_str(),
                 num(b.velocity.y()).c_str(), num(b.angular_velocity).c_str());
  }
  if (std::ferror(file_)) throw std::runtime_error(path_ + ": write failed");
}

}  // namespace rigidlab::app

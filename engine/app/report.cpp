#include "report.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "rigidlab/error.h"
#include "rigidlab/lua/scene_text.h"

namespace rigidlab::app {

std::string jsonNumber(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string jsonString(const std::string& text) {
  // JSON text is UTF-8: bytes that are not (a body name is any bytes) become U+FFFD.
  const std::string s = lua::validUtf8(text);
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

// A scene's string in a column of about `width` bytes: escaped, cut between characters.
std::string column(const std::string& text, size_t width) {
  std::string shown = lua::displayText(text, width);
  if (const size_t cut = shown.find("... ("); cut != std::string::npos) shown = shown.substr(0, cut) + "...";
  return shown;
}

}  // namespace

std::vector<std::string> incidents(const World& world, const RunInfo& info) {
  std::vector<std::string> list;
  for (const Incident& incident : world.incidents()) list.push_back(incident.message());
  if (info.energy_blowup_step > 0)
    list.push_back("the energy became non-finite at step " + std::to_string(info.energy_blowup_step) + " (t = " +
                   formatNumber(info.energy_blowup_time) + " s): kinetic " + formatNumber(info.blowup_kinetic) +
                   " J, potential " + formatNumber(info.blowup_potential) + " J");
  return list;
}

void printSummary(std::FILE* out, const lua::Scene& scene, const RunInfo& info) {
  const World& w = scene.world();
  const WorldDef& def = w.settings();
  // Names and the title come from the scene: shown escaped and shortened (scene_text.h).
  const std::string title = lua::displayText(scene.settings().title, lua::kTitleBytes);
  const std::string name = scene.file().empty() ? title : lua::displayText(scene.file().string(), 4096);
  std::fprintf(out, "scene   %s (\"%s\")\n", name.c_str(), title.c_str());
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
    std::fprintf(out, "  %4u  %-12s %-6s %-24s %-9s %-24s %s\n", b.uid, column(b.name, 12).c_str(),
                 b.isStatic() ? "static" : "", vec(b.position()).c_str(), fixed(b.angle).c_str(), vec(b.velocity).c_str(),
                 fixed(b.angular_velocity).c_str());
  }
  if (ids.size() > kShown) std::fprintf(out, "  ... and %zu more (use --json for all)\n", ids.size() - kShown);
  std::fprintf(out, "check   %s\n", info.check.c_str());
  const std::vector<std::string> list = incidents(w, info);
  if (!list.empty()) {
    std::fprintf(out, "incidents %zu%s: the run blew up%s\n", list.size(),
                 info.expect_incidents ? " (expected: scene.expect_incidents)" : "",
                 info.expect_incidents ? "" : " (exit status 3)");
    constexpr size_t kListed = 5;
    for (size_t i = 0; i < list.size() && i < kListed; ++i)
      std::fprintf(out, "  %s\n", lua::displayText(list[i], lua::kMessageBytes).c_str());
    if (list.size() > kListed) std::fprintf(out, "  ... and %zu more (use --json for all)\n", list.size() - kListed);
  }
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
  for (const std::string& incident : incidents(w, info)) {
    s += first ? "" : ",";
    first = false;
    s += jsonString(incident);
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

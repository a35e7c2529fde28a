// Saving a world as a Lua scene file (scene_writer.h).
//
// Format. The file is data plus one fixed PopulateWorld that hands the data to
// scripts/saved_world.lua, so a saved scene loads through the same sandboxed path (and the same
// validation) as any hand-written scene, and nothing a user typed (a body name) can become code:
// strings are written with every byte outside printable ASCII, and the quote and backslash,
// escaped as \ddd or \" \\ (reliability.md §4, "Write data only").
//
// Numbers. Each double is written as its shortest decimal form that reads back to the same bits
// (std::to_chars without a precision, then strtod in Lua's parser: both are correctly rounded), with
// ".0" added to integral values so Lua reads a float, never an integer (keeps -0.0 and values past
// 2^63). Non-finite numbers are refused with the field path: a NaN in a scene file would load as a
// global variable named `nan`, i.e. nil.
//
// Atomic write (reliability.md §4, Redis rdbSave; measured there: 0/200 torn files under kill -9):
// create `.<name>.rigidlab-tmp-<pid>-<n>` in the target's directory with O_EXCL, write, fsync, close,
// rename over the target, fsync the directory. Every error before the rename removes the temporary
// file; a SIGKILL cannot, so removeStaleTemporaries() sweeps them at the next start and the sandbox's
// file watcher ignores them (isTemporaryName).
#include "rigidlab/lua/scene_writer.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <system_error>

#include "rigidlab/error.h"
#include "rigidlab/forces.h"

namespace rigidlab::lua {

namespace {

constexpr std::string_view kTemporaryMarker = ".rigidlab-tmp-";
// Version 2 writes a body as one row of values instead of named fields (version 1, still read by
// saved_world.lua): a third smaller, so a 16 000-body world fits the 4 MiB a scene file may be.
constexpr int kFormatVersion = 2;

class Writer {
 public:
  std::string text;

  void raw(std::string_view s) { text += s; }
  // A line break inside a record: no trailing blank, continuation indented.
  void wrap() {
    while (!text.empty() && text.back() == ' ') text.pop_back();
    text += "\n     ";
  }

  void number(const std::string& field, double x) {
    if (!std::isfinite(x)) throw SceneError(field + ": cannot save a non-finite number (" + formatNumber(x) + ")");
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
    std::string_view s(buffer, static_cast<size_t>(result.ptr - buffer));
    text += s;
    if (s.find_first_of(".e") == std::string_view::npos) text += ".0";
  }

  void vec(const std::string& field, const Vec2& v) {
    text += '{';
    number(field + ".x", v.x());
    text += ", ";
    number(field + ".y", v.y());
    text += '}';
  }

  void string(std::string_view s) {
    text += '"';
    for (const unsigned char c : s) {
      if (c == '"' || c == '\\') {
        text += '\\';
        text += static_cast<char>(c);
      } else if (c >= 0x20 && c < 0x7f) {
        text += static_cast<char>(c);
      } else {
        // Three digits always, so a following digit cannot join the escape.
        char escape[8];
        std::snprintf(escape, sizeof escape, "\\%03u", static_cast<unsigned>(c));
        text += escape;
      }
    }
    text += '"';
  }

  // `key = <number>, `
  void field(std::string_view key, const std::string& path, double x) {
    text += key;
    text += " = ";
    number(path + "." + std::string(key), x);
    text += ", ";
  }
  void field(std::string_view key, const std::string& path, const Vec2& v) {
    text += key;
    text += " = ";
    vec(path + "." + std::string(key), v);
    text += ", ";
  }
};

void writeSettings(Writer& w, const World& world, const SceneSettings& settings) {
  const WorldDef& def = world.settings();
  w.raw("scene = {\n  title = ");
  w.string(settings.title);
  w.raw(",\n  gravity = ");
  w.vec("scene.gravity", def.gravity);
  w.raw(",\n  dt = ");
  w.number("scene.dt", settings.dt);
  w.raw(",\n  integrator = ");
  w.string(integratorName(def.integrator));
  w.raw(",\n  solver = ");
  w.string(contactSolverName(def.contact_solver));
  w.raw(",\n  iterations = ");
  w.raw(std::to_string(def.iterations));
  w.raw(",\n  substeps = ");
  w.raw(std::to_string(def.substeps));
  w.raw(",\n  sleeping = ");
  w.raw(def.sleeping ? "true" : "false");
  w.raw(",\n  duration = ");
  w.number("scene.duration", settings.duration);
  w.raw(",\n");
  if (settings.camera_center || settings.camera_height) {
    w.raw("  camera = {");
    if (settings.camera_center) {
      w.raw("center = ");
      w.vec("scene.camera.center", *settings.camera_center);
      if (settings.camera_height) w.raw(", ");
    }
    if (settings.camera_height) {
      w.raw("height = ");
      w.number("scene.camera.height", *settings.camera_height);
    }
    w.raw("},\n");
  }
  w.raw("}\n\n");
}

// One row: shape, size, position x, y, angle, velocity x, y, angular velocity, mass, restitution,
// friction, static friction, static [, name] (the order saved_world.lua reads).
void writeBody(Writer& w, const World& world, const Body& b, int index) {
  const std::string path = "bodies[" + std::to_string(index) + "]";
  const BodyShape& first = world.shape(b.shapes.front());
  const Shape& shape = first.geometry;
  w.raw("    {");
  Vec2 position = b.xf.p;
  if (shape.type == ShapeType::Circle) {
    // The Lua API places a circle's centre at the body origin; a C++ body may offset it. Moving the
    // origin onto the centre describes the same physical body (same centre of mass and motion).
    position = b.xf.apply(shape.center);
    w.raw("\"circle\", ");
    w.number(path + ".radius", shape.radius);
  } else {
    w.raw("\"polygon\", {");
    for (size_t i = 0; i < shape.vertices.size(); ++i) {
      if (i > 0) w.raw(", ");
      w.vec(path + ".vertices[" + std::to_string(i + 1) + "]", shape.vertices[i]);
    }
    w.raw("}");
  }
  const std::pair<const char*, double> values[] = {
      {"position.x", position.x()},      {"position.y", position.y()},  {"angle", b.angle},
      {"velocity.x", b.velocity.x()},    {"velocity.y", b.velocity.y()}, {"angular_velocity", b.angular_velocity},
      {"mass", b.mass},                  {"restitution", first.material.restitution},
      {"friction", first.material.friction}, {"static_friction", first.material.static_friction}};
  for (const auto& [field, x] : values) {
    w.raw(", ");
    w.number(path + "." + field, x);
  }
  w.raw(b.isStatic() ? ", true" : ", false");
  if (!b.name.empty()) {
    w.raw(", ");
    w.string(b.name);
  }
  w.raw("},\n");
}

}  // namespace

std::string sceneSource(const World& world, const SceneSettings& settings) {
  Writer w;
  w.raw("-- A world saved by the rigidlab sandbox at t = ");
  w.number("time", world.time());
  w.raw(" s. Data only: bodies, materials, springs, dampers, settings, camera.\n");
  w.raw("-- Load it like any scene (rigidlab FILE.lua); scripts/saved_world.lua builds the world.\n\n");
  writeSettings(w, world, settings);

  std::map<uint32_t, int> index_of_slot;  // BodyId::index → 1-based index in data.bodies
  w.raw("local data = {\n  version = ");
  w.raw(std::to_string(kFormatVersion));
  w.raw(",\n  -- One row per body: shape (\"circle\", radius or \"polygon\", {{x, y}, ...}), position x, y,\n"
        "  -- angle, velocity x, y, angular velocity, mass, restitution, friction, static friction,\n"
        "  -- static [, name]\n  bodies = {\n");
  int count = 0;
  for (const BodyId id : world.bodyIds()) {
    index_of_slot[id.index] = ++count;
    writeBody(w, world, world.body(id), count);
  }
  w.raw("  },\n");

  std::string springs, dampers;
  std::map<std::string, int> skipped;  // force kinds that are code, not data
  int spring_count = 0, damper_count = 0;
  for (const ForceId fid : world.forceIds()) {
    const Force& force = world.force(fid);
    if (const auto* spring = dynamic_cast<const SpringForce*>(&force)) {
      const SpringDef& def = spring->def();
      const std::string path = "springs[" + std::to_string(++spring_count) + "]";
      Writer s;
      s.raw("    {a = ");
      s.raw(std::to_string(index_of_slot.at(world.forceBodyA(fid).index)));
      s.raw(", ");
      const BodyId b = world.forceBodyB(fid);
      if (b.isNull()) {
        s.field("anchor", path, def.anchor);
      } else {
        s.raw("b = ");
        s.raw(std::to_string(index_of_slot.at(b.index)));
        s.raw(", ");
        s.field("local_b", path, def.local_b);
      }
      s.field("local_a", path, def.local_a);
      s.field("stiffness", path, def.stiffness);
      s.field("rest_length", path, def.rest_length.value_or(0.0));
      s.field("damping", path, def.damping);
      s.text.resize(s.text.size() - 2);  // the last ", "
      s.raw("},\n");
      springs += s.text;
    } else if (const auto* damper = dynamic_cast<const DamperForce*>(&force)) {
      const DamperDef& def = damper->def();
      const std::string path = "dampers[" + std::to_string(++damper_count) + "]";
      Writer s;
      s.raw("    {body = ");
      s.raw(std::to_string(index_of_slot.at(world.forceBodyA(fid).index)));
      s.raw(", ");
      s.field("coefficient", path, def.coefficient);
      s.field("angular_coefficient", path, def.angular_coefficient);
      s.text.resize(s.text.size() - 2);
      s.raw("},\n");
      dampers += s.text;
    } else {
      ++skipped[std::string(force.kind())];
    }
  }
  w.raw("  springs = {\n");
  w.raw(springs);
  w.raw("  },\n  dampers = {\n");
  w.raw(dampers);
  w.raw("  },\n}\n\n");
  if (!skipped.empty()) {
    w.raw("-- Not saved (code or interaction, not data):");
    const char* separator = " ";
    for (const auto& [kind, n] : skipped) {
      w.raw(separator + kind + " x" + std::to_string(n));
      separator = ", ";
    }
    w.raw(".\n\n");
  }
  w.raw("function PopulateWorld(world)\n  require(\"saved_world\").populate(world, data)\nend\n");
  return std::move(w.text);
}

bool isTemporaryName(const std::filesystem::path& file) {
  return file.filename().string().find(kTemporaryMarker) != std::string::npos;
}

namespace {

std::string errorText(const std::filesystem::path& path, int error) {
  return path.string() + ": " + std::strerror(error);
}

bool writeAll(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

}  // namespace

void saveScene(const World& world, const SceneSettings& settings, const std::filesystem::path& path, size_t max_bytes) {
  namespace fs = std::filesystem;
  const std::string source = sceneSource(world, settings);  // throws before any file is touched
  if (source.size() > max_bytes) {
    char size[32];
    std::snprintf(size, sizeof size, "%.1f MiB", static_cast<double>(source.size()) / double(1 << 20));
    throw SceneError(path.string() + ": not saved: the world (" + std::to_string(world.bodyCount()) +
                     " bodies) would make a file of " + size + " (" + std::to_string(source.size()) +
                     " bytes), more than the " + std::to_string(max_bytes) +
                     " bytes a scene file may be, so it could not be opened again; remove some bodies");
  }

  // Replace what a symlink points to, not the link itself (renameio's caveat).
  std::error_code ec;
  fs::path target = path;
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    target = fs::canonical(path, ec);
    if (ec) throw SceneError(path.string() + ": " + ec.message());
  }
  if (fs::is_directory(target, ec)) throw SceneError(target.string() + ": " + std::strerror(EISDIR));
  if (target.filename().empty()) throw SceneError(path.string() + ": not a file name");
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");

  static std::atomic<unsigned> counter{0};
  const fs::path temporary =
      directory / ("." + target.filename().string() + std::string(kTemporaryMarker) +
                   std::to_string(::getpid()) + "-" + std::to_string(counter++));

  // Keep the permission bits of the file being replaced; a new file gets 0666 & ~umask.
  mode_t mode = 0666;
  struct stat existing {};
  const bool exists = ::stat(target.c_str(), &existing) == 0;
  if (exists) mode = existing.st_mode & 07777;

  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) throw SceneError(errorText(target, errno));
  const auto fail = [&](int error) {
    ::close(fd);
    ::unlink(temporary.c_str());
    throw SceneError(errorText(target, error));
  };
  if (exists && ::fchmod(fd, mode) != 0) fail(errno);
  if (!writeAll(fd, source)) fail(errno);
  if (::fsync(fd) != 0) fail(errno);
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw SceneError(errorText(target, error));
  }
  if (::rename(temporary.c_str(), target.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw SceneError(errorText(target, error));
  }
  // Durability of the directory entry (Redis fsyncFileDir). The new content is already in place,
  // so a failure here is not reported as a failed save.
  const int dir_fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

void removeStaleTemporaries(const std::filesystem::path& directory) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& file = it->path();
    if (!isTemporaryName(file) || !it->is_regular_file(ec)) continue;
    // Leave the file of a save that is still running in another live process.
    const std::string name = file.filename().string();
    const size_t at = name.find(kTemporaryMarker) + kTemporaryMarker.size();
    const pid_t pid = static_cast<pid_t>(std::atol(name.c_str() + at));
    if (pid > 0 && pid != ::getpid() && ::kill(pid, 0) == 0) continue;
    fs::remove(file, ec);
  }
}

}  // namespace rigidlab::lua

// Saving a world as a Lua scene file (scene_writer.h).
//
// Format. The file is data plus one fixed PopulateWorld that hands the data to
// scripts/saved_world.lua, so a saved scene loads through the same sandboxed path (and the same
// validation) as any hand-written scene, and nothing a user typed (a body name) can become code:
// strings are written with every byte outside printable ASCII, and the quote and backslash,
// escaped as \ddd or \" \\ (docs/design/reliability.md §4, "Write data only").
//
// Numbers. Each double is written as its shortest decimal form that reads back to the same bits
// (std::to_chars without a precision, then strtod in Lua's parser: both are correctly rounded), with
// ".0" added to integral values so Lua reads a float, never an integer (keeps -0.0 and values past
// 2^63). Non-finite numbers are refused with the field path: a NaN in a scene file would load as a
// global variable named `nan`, i.e. nil.
//
// Atomic write (docs/design/reliability.md §4, Redis rdbSave; measured there: 0/200 torn files under kill -9):
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
#include <optional>
#include <system_error>

#include "rigidlab/error.h"
#include "rigidlab/forces.h"
#include "rigidlab/lua/saved_joint.h"

namespace rigidlab::lua {

namespace {

constexpr std::string_view kTemporaryMarker = ".rigidlab-tmp-";
// Version 2 writes a body as one row of values instead of named fields (version 1): a third
// smaller, so a 16 000-body world fits the 4 MiB a scene file may be. Version 3 keeps the row for
// the first shape and adds what is not at its default (more shapes, body type and options,
// filters) in a table at its end, and joints; saved_world.lua reads all three.
constexpr int kFormatVersion = 3;

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

// What the file leaves out, by reason (listed in a comment at its end).
using Skipped = std::map<std::string, int>;

// A body's shapes as the file writes them: the first one in the row (by the world's shorthand
// for it), the others as body:add_shape options. Chain segments are written as their chain.
struct ChainRun {
  std::vector<Vec2> points;
  bool loop = false;
  const BodyShape* first = nullptr;
};

// The body's first chain, from its consecutive segments (World::createChain made them in order).
// Segments of further chains, or of a chain that lost a segment, end the run.
std::optional<ChainRun> firstChain(const World& world, const Body& b, std::vector<bool>& in_run) {
  in_run.assign(b.shapes.size(), false);
  ChainRun run;
  uint32_t chain = 0;
  size_t last = 0;
  for (size_t i = 0; i < b.shapes.size(); ++i) {
    const BodyShape& s = world.shape(b.shapes[i]);
    if (s.chain == 0) continue;
    if (!run.first) {
      run.first = &s;
      chain = s.chain;
      run.points = {s.geometry.vertices[0], s.geometry.vertices[1]};
    } else if (s.chain == chain && i == last + 1 && s.geometry.vertices[0] == run.points.back() &&
               s.material.friction == run.first->material.friction &&
               s.material.static_friction == run.first->material.static_friction &&
               s.material.restitution == run.first->material.restitution && s.filter == run.first->filter &&
               s.sensor == run.first->sensor) {
      run.points.push_back(s.geometry.vertices[1]);
    } else {
      continue;
    }
    in_run[i] = true;
    last = i;
  }
  if (!run.first) return std::nullopt;
  // A loop: it closes on its first point, and its first segment's ghost is the point before.
  if (run.points.size() >= 4 && run.points.back() == run.points.front() && run.first->geometry.ghost1 != run.points.front()) {
    run.points.pop_back();
    run.loop = true;
  }
  return run;
}

void hex(Writer& w, uint64_t x) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "0x%llx", static_cast<unsigned long long>(x));
  w.raw(buffer);  // a hexadecimal literal is a Lua integer of these 64 bits
}

// `tangent_speed = ..., rolling_resistance = ..., ` where not 0.
void surfaceFields(Writer& w, const BodyShape& s, const std::string& path) {
  if (s.tangent_speed != 0.0) w.field("tangent_speed", path, s.tangent_speed);
  if (s.rolling_resistance != 0.0) w.field("rolling_resistance", path, s.rolling_resistance);
}

// `category = ..., mask = ..., group = ..., sensor = true, ` where not at their defaults.
void filterFields(Writer& w, const Filter& f, bool sensor) {
  const Filter d;
  if (f.category != d.category) {
    w.raw("category = ");
    hex(w, f.category);
    w.raw(", ");
  }
  if (f.mask != d.mask) {
    w.raw("mask = ");
    hex(w, f.mask);
    w.raw(", ");
  }
  if (f.group != d.group) w.raw("group = " + std::to_string(f.group) + ", ");
  if (sensor) w.raw("sensor = true, ");
}

void points(Writer& w, const std::string& path, const std::vector<Vec2>& list, const Vec2& shift) {
  w.raw("{");
  for (size_t i = 0; i < list.size(); ++i) {
    if (i > 0) w.raw(", ");
    w.vec(path + "[" + std::to_string(i + 1) + "]", list[i] - shift);
  }
  w.raw("}");
}

// One shape of a compound body as body:add_shape options, in the body's coordinates less `shift`.
void writeShape(Writer& w, const BodyShape& s, const std::string& path, const Vec2& shift) {
  const Shape& g = s.geometry;
  w.raw("{shape = \"");
  w.raw(g.type == ShapeType::Polygon ? "polygon" : shapeTypeName(g.type));
  w.raw("\", ");
  switch (g.type) {
    case ShapeType::Circle:
      w.field("radius", path, g.radius);
      w.field("offset", path, Vec2(g.center - shift));
      break;
    case ShapeType::Polygon:
      w.raw("vertices = ");
      points(w, path + ".vertices", g.vertices, shift);
      w.raw(", ");
      break;
    case ShapeType::Capsule:
    case ShapeType::Segment:
      w.field("a", path, Vec2(g.vertices[0] - shift));
      w.field("b", path, Vec2(g.vertices[1] - shift));
      if (g.type == ShapeType::Capsule) w.field("radius", path, g.radius);
      break;
    case ShapeType::ChainSegment:
      break;  // not reached: chains are written as chains
  }
  if (hasArea(g.type)) w.field("density", path, s.density);
  w.field("restitution", path, s.material.restitution);
  w.field("friction", path, s.material.friction);
  w.field("static_friction", path, s.material.static_friction);
  surfaceFields(w, s, path);
  filterFields(w, s.filter, s.sensor);
  w.text.resize(w.text.size() - 2);
  w.raw("}");
}

// One row: first shape kind and geometry, position x, y, angle, velocity x, y, angular velocity,
// density, restitution, friction, static friction, type [, name [, more]] (saved_world.lua reads
// them in this order). False if the body cannot be written (it has no shape).
bool writeBody(Writer& w, const World& world, const Body& b, int index, Skipped& skipped) {
  if (b.shapes.empty()) {
    ++skipped["body without shapes (the scene API makes bodies with a shape)"];
    return false;
  }
  const std::string path = "bodies[" + std::to_string(index) + "]";
  std::vector<bool> in_chain;
  const std::optional<ChainRun> chain = firstChain(world, b, in_chain);
  const BodyShape& first = chain ? *chain->first : world.shape(b.shapes.front());
  const Shape& shape = first.geometry;
  // The world's shorthands put a circle's centre at the body origin. For a circle elsewhere the
  // origin moves onto its centre and every shape is written relative to it: the same physical
  // body (same centre of mass, inertia and motion).
  const Vec2 shift = shape.type == ShapeType::Circle ? shape.center : Vec2(Vec2::Zero());
  const Vec2 position = shift == Vec2::Zero() ? b.xf.p : Vec2(b.xf.apply(shift));
  w.raw("    {\"");
  w.raw(chain ? "chain" : shape.type == ShapeType::Polygon ? "polygon" : shapeTypeName(shape.type));
  w.raw("\", ");
  if (chain) {
    points(w, path + ".points", chain->points, shift);
  } else if (shape.type == ShapeType::Circle) {
    w.number(path + ".radius", shape.radius);
  } else if (shape.type == ShapeType::Polygon) {
    points(w, path + ".vertices", shape.vertices, shift);
  } else {
    w.raw("{");
    w.vec(path + ".a", shape.vertices[0]);
    w.raw(", ");
    w.vec(path + ".b", shape.vertices[1]);
    if (shape.type == ShapeType::Capsule) {
      w.raw(", ");
      w.number(path + ".radius", shape.radius);
    }
    w.raw("}");
  }
  const std::pair<const char*, double> values[] = {
      {"position.x", position.x()},      {"position.y", position.y()},  {"angle", b.angle},
      {"velocity.x", b.velocity.x()},    {"velocity.y", b.velocity.y()}, {"angular_velocity", b.angular_velocity},
      {"density", first.density},        {"restitution", first.material.restitution},
      {"friction", first.material.friction}, {"static_friction", first.material.static_friction}};
  for (const auto& [field, x] : values) {
    w.raw(", ");
    w.number(path + "." + field, x);
  }
  w.raw(", \"");
  w.raw(bodyTypeName(b.type));
  w.raw("\"");

  // The rest, where not at the defaults.
  Writer more;
  const BodyDef defaults;
  if (b.linear_damping != defaults.linear_damping) more.field("linear_damping", path, b.linear_damping);
  if (b.angular_damping != defaults.angular_damping) more.field("angular_damping", path, b.angular_damping);
  if (b.gravity_scale != defaults.gravity_scale) more.field("gravity_scale", path, b.gravity_scale);
  if (b.own_gravity) more.field("gravity", path, b.gravity);
  if (!b.sleeping_allowed) more.raw("sleeping_allowed = false, ");
  surfaceFields(more, first, path);
  if (b.fixed_rotation) more.raw("fixed_rotation = true, ");
  if (b.bullet) more.raw("bullet = true, ");
  if (!b.enabled) more.raw("enabled = false, ");
  filterFields(more, first.filter, first.sensor);
  if (chain && chain->loop) more.raw("loop = true, ");
  Writer shapes;
  int count = 0;
  for (size_t i = 0; i < b.shapes.size(); ++i) {
    const BodyShape& s = world.shape(b.shapes[i]);
    if (&s == &first || (chain && in_chain[i])) continue;
    if (s.chain != 0) {
      ++skipped["chain segment of a body's second chain (the scene API makes one chain per body)"];
      continue;
    }
    shapes.wrap();
    writeShape(shapes, s, path + ".shapes[" + std::to_string(++count) + "]", shift);
    shapes.raw(",");
  }
  if (count > 0) {
    more.raw("shapes = {");
    more.raw(shapes.text);
    more.raw("}, ");
  }
  if (!b.name.empty() || !more.text.empty()) {
    w.raw(", ");
    w.string(b.name);
  }
  if (!more.text.empty()) {
    more.text.resize(more.text.size() - 2);
    w.raw(", {");
    w.raw(more.text);
    w.raw("}");
  }
  w.raw("},\n");
  return true;
}

// The options of world:add_<kind> for the joint (the defaults left out), its bodies by index.
void writeJoint(Writer& w, const World& world, JointId id, int index, const std::map<uint32_t, int>& body_index,
                const std::map<uint32_t, int>& joint_index) {
  const JointBuild build = jointBuild(world, id);
  const JointDef& d = build.def;
  const bool pinned = d.a.isNull() && d.type != JointType::Gear;
  const std::string path = "joints[" + std::to_string(index) + "]";
  Writer j;
  j.raw("    {kind = ");
  j.string(jointTypeName(d.type));
  j.raw(", ");
  if (d.type == JointType::Gear && d.joint_a.isNull()) {  // a gear of two bodies' angles
    j.raw("a = " + std::to_string(body_index.at(d.a.index)) + ", ");
    j.raw("b = " + std::to_string(body_index.at(d.b.index)) + ", ");
    j.field("ratio", path, d.ratio);
  } else if (d.type == JointType::Gear) {
    j.raw("joint_a = " + std::to_string(joint_index.at(d.joint_a.index)) + ", ");
    j.raw("joint_b = " + std::to_string(joint_index.at(d.joint_b.index)) + ", ");
    j.field("ratio", path, d.ratio);
  } else {
    // Pinned to the world, the core's body a is the world and the scene's `a` is the core's b.
    j.raw("a = " + std::to_string(body_index.at((pinned ? d.b : d.a).index)) + ", ");
    if (!pinned) j.raw("b = " + std::to_string(body_index.at(d.b.index)) + ", ");
  }
  const bool limit = d.enable_limit, motor = d.enable_motor, spring = d.enable_spring;
  const auto springFields = [&] {
    if (!spring) return;
    j.field("spring_hertz", path, d.spring_hertz);
    j.field("spring_damping", path, d.spring_damping);
  };
  switch (d.type) {
    case JointType::Revolute:
    case JointType::Weld:
    case JointType::Friction:
      j.field("anchor", path, d.anchor_a);
      break;
    case JointType::Prismatic:
    case JointType::Wheel:
      j.field("anchor", path, d.anchor_a);
      j.field("axis", path, d.axis);
      break;
    case JointType::Distance:
    case JointType::Pulley:
      j.field("anchor_a", path, pinned ? d.anchor_b : d.anchor_a);
      j.field("anchor_b", path, pinned ? d.anchor_a : d.anchor_b);
      break;
    case JointType::Motor:
      j.field("anchor", path, d.anchor_a);
      break;
    case JointType::Gear:
      break;
  }
  switch (d.type) {
    case JointType::Revolute:
      if (limit) {
        j.field("lower_angle", path, d.lower);
        j.field("upper_angle", path, d.upper);
      }
      if (motor) {
        j.field("motor_speed", path, d.motor_speed);
        j.field("max_motor_torque", path, d.max_motor_torque);
      }
      springFields();
      break;
    case JointType::Prismatic:
    case JointType::Wheel:
      if (limit) {
        j.field("lower", path, d.lower);
        j.field("upper", path, d.upper);
      }
      if (motor) {
        j.field("motor_speed", path, d.motor_speed);
        if (d.type == JointType::Prismatic) j.field("max_motor_force", path, d.max_motor_force);
        else j.field("max_motor_torque", path, d.max_motor_torque);
      }
      springFields();
      break;
    case JointType::Distance:
      j.field("length", path, d.length);
      if (limit) {
        j.field("min_length", path, d.min_length);
        if (std::isfinite(d.max_length)) j.field("max_length", path, d.max_length);
      }
      springFields();
      if (spring && std::isfinite(d.max_spring_force)) j.field("max_spring_force", path, d.max_spring_force);
      break;
    case JointType::Weld:
      if (d.linear_hertz != 0.0 || d.linear_damping != 0.0) {
        j.field("linear_hertz", path, d.linear_hertz);
        j.field("linear_damping", path, d.linear_damping);
      }
      if (d.angular_hertz != 0.0 || d.angular_damping != 0.0) {
        j.field("angular_hertz", path, d.angular_hertz);
        j.field("angular_damping", path, d.angular_damping);
      }
      break;
    case JointType::Motor:
      j.field("linear_offset", path, d.linear_offset);
      j.field("angular_offset", path, d.angular_offset);
      j.field("max_force", path, d.max_force);
      j.field("max_torque", path, d.max_torque);
      j.field("motor_hertz", path, d.motor_hertz);
      j.field("motor_damping", path, d.motor_damping);
      if (d.linear_velocity != Vec2::Zero()) j.field("linear_velocity", path, d.linear_velocity);
      if (d.angular_velocity != 0.0) j.field("angular_velocity", path, d.angular_velocity);
      break;
    case JointType::Friction:
      j.field("max_force", path, d.max_force);
      j.field("max_torque", path, d.max_torque);
      break;
    case JointType::Pulley:
      j.field("ground_a", path, d.ground_a);
      j.field("ground_b", path, d.ground_b);
      j.field("ratio", path, d.ratio);
      break;
    case JointType::Gear:
      break;
  }
  if (d.collide_connected) j.raw("collide_connected = true, ");
  if (std::isfinite(d.break_force)) j.field("break_force", path, d.break_force);
  if (std::isfinite(d.break_torque)) j.field("break_torque", path, d.break_torque);
  if (!d.name.empty()) {
    j.raw("name = ");
    j.string(d.name);
    j.raw(", ");
  }
  if (build.move) {
    j.raw("made_at = {");
    j.number(path + ".made_at.x", build.position.x());
    j.raw(", ");
    j.number(path + ".made_at.y", build.position.y());
    j.raw(", ");
    j.number(path + ".made_at.angle", build.angle);
    j.raw("}, ");
  }
  j.text.resize(j.text.size() - 2);
  j.raw("},\n");
  w.raw(j.text);
}

// Why a joint cannot be written, or nothing. Gears are written after the other joints.
std::optional<std::string> unsaved(const World& world, JointId id, const std::map<uint32_t, int>& body_index,
                                   const std::map<uint32_t, int>& joint_index) {
  const JointDef& d = world.joint(id);
  const auto saved = [&](BodyId b) { return b.isNull() || body_index.count(b.index) > 0; };
  const auto dynamic = [&](BodyId b) { return !b.isNull() && world.body(b).isDynamic(); };
  if (d.type == JointType::Gear && d.joint_a.isNull()) {
    if (!saved(d.a) || !saved(d.b)) return "gear of a body not saved";
    return std::nullopt;
  }
  if (d.type == JointType::Gear) {
    if (!joint_index.count(d.joint_a.index) || !joint_index.count(d.joint_b.index)) return "gear of a joint not saved";
    return std::nullopt;
  }
  if (d.b.isNull()) return "joint with the world as body b (the scene API pins to the world as body a)";
  if (d.type == JointType::Pulley && d.a.isNull()) return "pulley with the world as a body (the scene API's pulley joins two bodies)";
  if (!saved(d.a) || !saved(d.b)) return "joint of a body not saved";
  if (!dynamic(d.a) && !dynamic(d.b)) return "joint between bodies that are not dynamic (it does nothing)";
  return std::nullopt;
}

}  // namespace

std::string sceneSource(const World& world, const SceneSettings& settings) {
  Writer w;
  w.raw("-- A world saved by the rigidlab sandbox at t = ");
  w.number("time", world.time());
  w.raw(" s. Data only: bodies and their shapes, joints, springs, dampers, settings, camera.\n");
  w.raw("-- Load it like any scene (rigidlab FILE.lua); scripts/saved_world.lua builds the world.\n\n");
  writeSettings(w, world, settings);

  std::map<uint32_t, int> index_of_slot;  // BodyId::index → 1-based index in data.bodies
  Skipped skipped;                          // what is left out, and why
  w.raw("local data = {\n  version = ");
  w.raw(std::to_string(kFormatVersion));
  w.raw(",\n  -- One row per body: first shape (\"circle\", radius | \"polygon\", {{x, y}, ...} |\n"
        "  -- \"capsule\", {a, b, radius} | \"segment\", {a, b} | \"chain\", {{x, y}, ...}), position x, y,\n"
        "  -- angle, velocity x, y, angular velocity, density, restitution, friction, static friction,\n"
        "  -- type [, name [, {other options, shapes = {more shapes}}]] (scripts/saved_world.lua)\n  bodies = {\n");
  int count = 0;
  for (const BodyId id : world.bodyIds()) {
    if (writeBody(w, world, world.body(id), count + 1, skipped)) index_of_slot[id.index] = ++count;
  }
  w.raw("  },\n");

  // Joints: every kind but gears, then gears (they name the joints they couple).
  std::map<uint32_t, int> joint_index;
  std::string joints;
  int joint_count = 0;
  for (const bool gears : {false, true}) {
    for (const JointId id : world.jointIds()) {
      if ((world.joint(id).type == JointType::Gear) != gears) continue;
      if (const auto why = unsaved(world, id, index_of_slot, joint_index)) {
        ++skipped[*why];
        continue;
      }
      Writer j;
      writeJoint(j, world, id, joint_count + 1, index_of_slot, joint_index);
      joints += j.text;
      joint_index[id.index] = ++joint_count;
    }
  }
  w.raw("  joints = {\n");
  w.raw(joints);
  w.raw("  },\n");

  std::string springs, dampers;
  int spring_count = 0, damper_count = 0;
  for (const ForceId fid : world.forceIds()) {
    const Force& force = world.force(fid);
    const BodyId a = world.forceBodyA(fid), b = world.forceBodyB(fid);
    if (!index_of_slot.count(a.index) || (!b.isNull() && !index_of_slot.count(b.index))) {
      ++skipped[std::string(force.kind()) + " of a body not saved"];
      continue;
    }
    if (const auto* spring = dynamic_cast<const SpringForce*>(&force)) {
      const SpringDef& def = spring->def();
      const std::string path = "springs[" + std::to_string(++spring_count) + "]";
      Writer s;
      s.raw("    {a = ");
      s.raw(std::to_string(index_of_slot.at(a.index)));
      s.raw(", ");
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
      s.raw(std::to_string(index_of_slot.at(a.index)));
      s.raw(", ");
      s.field("coefficient", path, def.coefficient);
      s.field("angular_coefficient", path, def.angular_coefficient);
      s.text.resize(s.text.size() - 2);
      s.raw("},\n");
      dampers += s.text;
    } else {
      ++skipped[std::string(force.kind()) + " (code, not data)"];
    }
  }
  w.raw("  springs = {\n");
  w.raw(springs);
  w.raw("  },\n  dampers = {\n");
  w.raw(dampers);
  w.raw("  },\n}\n\n");
  if (!skipped.empty()) {
    w.raw("-- Not saved:");
    const char* separator = " ";
    for (const auto& [what, n] : skipped) {
      w.raw(separator + what + " x" + std::to_string(n));
      separator = "; ";
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

// scripts/benchmarks/*.lua build the same worlds as the C++ scenes of Box2D v3's suite that
// `rigidlab bench` runs (engine/app/bench_suite.cpp): for each scene, the Lua world and the C++
// world must be the same bits right after they are built and again after a few steps (the Lua
// scene stepped as `rigidlab run` steps it, its OnStep included; the C++ one as `rigidlab bench`
// steps it, its edits before each step included). Same bits means the same serialized snapshot
// (serializeSnapshot: every body, shape and joint with all their parameters, contacts, warm
// starts, sleep timers, the settings and the clock; all but the last step's wall-clock timings);
// when they differ, the message names the first body, shape or joint field that does. Then the
// Lua scene's Check must pass.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "rigidlab/lua/scene.h"
#include "rigidlab/world_snapshot.h"

using namespace rigidlab;
using namespace rigidlab::app;

namespace {

const std::filesystem::path kScenes = std::filesystem::path(RIGIDLAB_SOURCE_DIR) / "scripts" / "benchmarks";

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string vec(const Vec2& v) { return "(" + num(v.x()) + ", " + num(v.y()) + ")"; }

std::string uidOf(const World& w, BodyId id) { return id.isNull() ? "world" : std::to_string(w.body(id).uid); }

// One line per body, shape and joint with what the scene sets and what a step changes, every
// number to 17 digits, so the first line that differs says what differs. `definitions` false:
// the bodies' states only.
std::vector<std::string> describe(const World& w, bool definitions = true) {
  std::vector<std::string> lines;
  const WorldDef& d = w.settings();
  lines.push_back("world: gravity " + vec(d.gravity) + ", sleeping " + std::to_string(d.sleeping) + ", integrator " +
                  std::to_string(static_cast<int>(d.integrator)) + ", step " + std::to_string(w.stepCount()) +
                  ", time " + num(w.time()));
  for (const BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    std::string line = "body uid " + std::to_string(b.uid) + " (slot " + std::to_string(id.index) + "): type " +
                       std::to_string(static_cast<int>(b.type)) + ", position " + vec(b.position()) + ", angle " +
                       num(b.angle) + ", velocity " + vec(b.velocity) + ", angular velocity " +
                       num(b.angular_velocity) + ", awake " + std::to_string(b.awake) + ", sleep time " +
                       num(b.sleep_time);
    if (definitions) {
      line += ", mass " + num(b.mass) + ", inertia " + num(b.inertia) + ", damping " + num(b.linear_damping) + " " +
              num(b.angular_damping) + ", gravity scale " + num(b.gravity_scale) + ", fixed rotation " +
              std::to_string(b.fixed_rotation) + ", bullet " + std::to_string(b.bullet) + ", enabled " +
              std::to_string(b.enabled) + ", name '" + b.name + "', " + std::to_string(b.shapes.size()) + " shapes";
    }
    lines.push_back(line);
    if (!definitions) continue;
    for (size_t k = 0; k < b.shapes.size(); ++k) {
      const BodyShape& s = w.shape(b.shapes[k]);
      std::string shape = "  shape " + std::to_string(k) + " of body uid " + std::to_string(b.uid) + ": kind " +
                          std::to_string(static_cast<int>(s.geometry.type)) + ", radius " + num(s.geometry.radius) +
                          ", center " + vec(s.geometry.center) + ", points";
      for (const Vec2& p : s.geometry.vertices) shape += " " + vec(p);
      shape += ", ghosts " + vec(s.geometry.ghost1) + " " + vec(s.geometry.ghost2) + ", density " + num(s.density) +
               ", restitution " + num(s.material.restitution) + ", friction " + num(s.material.friction) + " static " +
               num(s.material.static_friction) + ", category " + std::to_string(s.filter.category) + ", mask " +
               std::to_string(s.filter.mask) + ", group " + std::to_string(s.filter.group) + ", sensor " +
               std::to_string(s.sensor);
      lines.push_back(shape);
    }
  }
  if (!definitions) return lines;
  for (const JointId id : w.jointIds()) {
    const JointDef& j = w.joint(id);
    const JointState s = w.jointState(id);
    lines.push_back(
        "joint slot " + std::to_string(id.index) + ": type " + std::to_string(static_cast<int>(j.type)) + ", bodies " +
        uidOf(w, j.a) + " " + uidOf(w, j.b) + ", anchor " + vec(j.anchor_a) + ", reference angle " +
        (j.reference_angle ? num(*j.reference_angle) : "at creation") + ", limit " + std::to_string(j.enable_limit) +
        " " + num(j.lower) + " " + num(j.upper) + ", motor " + std::to_string(j.enable_motor) + " " +
        num(j.motor_speed) + " " + num(j.max_motor_torque) + ", spring " + std::to_string(j.enable_spring) + " " +
        num(j.spring_hertz) + " " + num(j.spring_damping) + ", collide connected " +
        std::to_string(j.collide_connected) + ", breaks at " + num(j.break_force) + " " + num(j.break_torque) +
        "; anchors now " + vec(s.world_anchor_a) + " " + vec(s.world_anchor_b) + ", angle " + num(s.angle) +
        ", speed " + num(s.speed));
  }
  return lines;
}

// The world's snapshot as bytes, without what differs between two runs of the same world: the
// checksum at the end and the last step's wall-clock timings (StepStats' *_ms, the 7 doubles
// serialized one after the other), set to zero.
std::string snapshotBytes(const World& w) {
  std::string bytes = serializeSnapshot(w.snapshot());
  bytes.resize(bytes.size() - sizeof(uint64_t));
  const StepStats& s = w.stats();
  const double timings[] = {s.integrate_ms, s.broad_phase_ms, s.narrow_phase_ms, s.solve_ms,
                            s.correct_ms,   s.finish_ms,      s.forces_ms};
  const std::string pattern(reinterpret_cast<const char*>(timings), sizeof timings);
  if (pattern == std::string(sizeof timings, '\0')) return bytes;
  const size_t at = bytes.find(pattern);
  REQUIRE_MESSAGE(at != std::string::npos, "the step's timings are not in the snapshot");
  REQUIRE_MESSAGE(bytes.find(pattern, at + 1) == std::string::npos, "the step's timings are twice in the snapshot");
  std::fill(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.begin() + static_cast<std::ptrdiff_t>(at + sizeof timings), '\0');
  return bytes;
}

// "" when the worlds are the same bits, else the first difference. `definitions` false: the
// bodies' states only.
std::string difference(const World& cpp, const World& lua, bool definitions = true) {
  if (definitions && snapshotBytes(cpp) == snapshotBytes(lua)) return "";
  const std::vector<std::string> a = describe(cpp, definitions), b = describe(lua, definitions);
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    if (a[i] != b[i]) return "first difference:\n  C++: " + a[i] + "\n  Lua: " + b[i];
  if (a.size() != b.size())
    return "C++ has " + std::to_string(a.size()) + " bodies, shapes and joints, Lua " + std::to_string(b.size()) +
           "; the first extra: " + (a.size() > b.size() ? "C++: " + a[b.size()] : "Lua: " + b[a.size()]);
  if (!definitions) return "";
  const std::string x = snapshotBytes(cpp), y = snapshotBytes(lua);
  const size_t at = static_cast<size_t>(std::mismatch(x.begin(), x.end(), y.begin(), y.end()).first - x.begin());
  return "the snapshots differ at byte " + std::to_string(at) + " of " + std::to_string(x.size()) + " and " +
         std::to_string(y.size()) + " (state the lines compared do not show: contacts, warm starts, islands, ...)";
}

const BenchScene& suiteScene(const std::string& name) {
  const auto& scenes = benchScenes();
  const auto it = std::find_if(scenes.begin(), scenes.end(), [&](const BenchScene& s) { return s.name == name; });
  REQUIRE(it != scenes.end());
  return *it;
}

std::unique_ptr<lua::Scene> loadLua(const std::string& name, std::map<std::string, double> controls = {}) {
  lua::SceneOptions options;
  options.log = [](const std::string&) {};  // what Check prints
  options.limits.hook_seconds = 120;        // 22 000 add_box calls in PopulateWorld; the sanitizers are slow
  options.control_values = std::move(controls);
  return lua::Scene::loadFile(kScenes / (name + ".lua"), options);
}

// The C++ world as `rigidlab bench` steps it: the scene's edits before step i, then step i.
struct CppRun {
  BenchWorld bench;
  int steps = 0;
  explicit CppRun(BenchWorld b) : bench(std::move(b)) { edit(); }
  World& world() { return bench.get(); }
  void edit() {
    if (bench.before_step) bench.before_step(world(), steps);
  }
  // The scene's edits before the next step are made at once, as the Lua scene's OnStep makes them
  // after the step before: both worlds then stand between the same two steps.
  void step(double dt) {
    world().step(dt);
    ++steps;
    edit();
  }
};

// The Lua scene and the C++ scene, built and after `steps` steps: the same bits. `patch` edits the
// C++ world right after it is built, for what the Lua API cannot say.
void compare(const std::string& name, CppRun cpp, int steps, std::map<std::string, double> controls = {},
             const std::function<void(World&)>& patch = nullptr) {
  const std::unique_ptr<lua::Scene> lua = loadLua(name, std::move(controls));
  const double dt = suiteScene(name).dt;
  CHECK(lua->settings().dt == dt);
  CHECK(lua->settings().duration == suiteScene(name).steps * dt);
  if (patch) patch(cpp.world());
  INFO("scripts/benchmarks/" << name << ".lua against bench_suite.cpp's " << name);
  const std::string built = difference(cpp.world(), lua->world());
  REQUIRE_MESSAGE(built.empty(), "as built: " << built);
  for (int i = 0; i < steps; ++i) {
    cpp.step(dt);
    lua->step();
  }
  CHECK(lua->world().stepCount() == steps);
  const std::string stepped = difference(cpp.world(), lua->world());
  CHECK_MESSAGE(stepped.empty(), "after " << steps << " steps: " << stepped);
  // And the scene's Check passes there (ctest also runs it through `rigidlab run`, but not in the
  // sanitizer build: tests/CMakeLists.txt says why).
  try {
    lua->runCheck();
  } catch (const lua::SceneError& e) {
    FAIL_CHECK("Check after " << steps << " steps: " << std::string(e.what()));
  }
}

void compare(const std::string& name, int steps) { compare(name, CppRun(suiteScene(name).build()), steps); }

}  // namespace

TEST_CASE("large_pyramid.lua is the suite's large_pyramid, built and after 3 steps") { compare("large_pyramid", 3); }
TEST_CASE("many_pyramids.lua is the suite's many_pyramids, built and after 2 steps") { compare("many_pyramids", 2); }
TEST_CASE("joint_grid.lua is the suite's joint_grid, built and after 2 steps") { compare("joint_grid", 2); }
TEST_CASE("smash.lua is the suite's smash, built and after 3 steps") { compare("smash", 3); }
TEST_CASE("tumbler.lua is the suite's tumbler, built and after 3 steps") { compare("tumbler", 3); }

// The first two columns of ragdolls (steps 0 and 8).
TEST_CASE("ragdolls.lua is the suite's ragdolls, built and after 9 steps") { compare("ragdolls", 9); }

// Removal: with 2 columns (the scene's slider, bench_suite.cpp's suiteRagdolls), the oldest
// column is removed and a new one made at steps 16, 24 and 32, each body in the slot of one removed.
TEST_CASE("ragdolls.lua with 2 columns is the suite's rain of 2 columns: removal and respawn, 33 steps") {
  compare("ragdolls", CppRun(suiteRagdolls(2)), 33, {{"columns", 2.0}});
}

// The Lua API refuses an infinite max_motor_torque (the C++ scene's paddle motor has one): the Lua
// scene gives it DBL_MAX. That is the one difference, patched into the C++ world before comparing;
// and the paddle and the bodies move exactly as with the infinite torque.
TEST_CASE("spinner.lua is the suite's spinner but for the motor's finite max_motor_torque, built and after 3 steps") {
  const auto patch = [](World& w) {
    const std::vector<JointId> joints = w.jointIds();
    REQUIRE(joints.size() == 1);
    JointDef j = w.joint(joints[0]);
    CHECK(j.max_motor_torque == INFINITY);
    j.max_motor_torque = DBL_MAX;
    w.updateJoint(joints[0], j);
  };
  compare("spinner", CppRun(suiteScene("spinner").build()), 3, {}, patch);

  CppRun infinite(suiteScene("spinner").build());
  const std::unique_ptr<lua::Scene> lua = loadLua("spinner");
  for (int i = 0; i < 3; ++i) {
    infinite.step(1.0 / 60.0);
    lua->step();
  }
  const std::string bodies = difference(infinite.world(), lua->world(), false);
  CHECK_MESSAGE(bodies.empty(), "bodies after 3 steps: " << bodies);
}

TEST_CASE("compounds.lua is the suite's compounds, built and after 3 steps") { compare("compounds", 3); }
TEST_CASE("junkyard.lua is the suite's junkyard (its pusher set before each step), built and after 3 steps") {
  compare("junkyard", 3);
}
TEST_CASE("washer.lua is the suite's washer, built and after 3 steps") { compare("washer", 3); }

// Box2D v3's benchmark program prints its counts of bodies and shapes: compounds 3001 and 6282
// (a ground of 81 + 2 × 100 boxes and a segment; 3000 bodies of 2 triangles), junkyard 8002 and
// 8262 (161 + 2 × 50 ground boxes, 8000 pentagons, the pusher), washer 8102 and 8140 (a ground
// without shapes, the drum's 36 + 4 pieces, 8100 boxes). The same here, with the same body types.
TEST_CASE("compounds, junkyard and washer make Box2D v3's bodies and shapes") {
  struct Expected {
    const char* name;
    int bodies, shapes, statics, kinematics, polygon_vertices;  // polygon_vertices: of every dynamic body's shapes
  };
  for (const Expected& e : {Expected{"compounds", 3001, 6282, 1, 0, 3}, Expected{"junkyard", 8002, 8262, 1, 1, 5},
                            Expected{"washer", 8102, 8140, 1, 1, 4}}) {
    CAPTURE(e.name);
    BenchWorld bench = suiteScene(e.name).build();
    World& w = bench.get();
    int shapes = 0, statics = 0, kinematics = 0, dynamic_shapes = 0, wrong_vertices = 0;
    for (BodyId id : w.bodyIds()) {
      const Body& b = w.body(id);
      shapes += static_cast<int>(b.shapes.size());
      statics += b.type == BodyType::Static;
      kinematics += b.type == BodyType::Kinematic;
      if (!b.isDynamic()) continue;
      for (ShapeId s : b.shapes) {
        ++dynamic_shapes;
        wrong_vertices += static_cast<int>(w.shape(s).geometry.vertices.size()) != e.polygon_vertices;
      }
    }
    CHECK(w.bodyCount() == e.bodies);
    CHECK(shapes == e.shapes);
    CHECK(statics == e.statics);
    CHECK(kinematics == e.kinematics);
    CHECK(wrong_vertices == 0);
    CHECK(dynamic_shapes == (e.polygon_vertices == 3 ? 6000 : e.bodies - 2));
  }
}

// The washer's drum: kinematic, turning at 25°/s about its centre (0, 10) (the 4 fins every 90°
// keep the centre of mass on the axis); its ring closed all round between 16 and 18 m (each piece
// overlaps its neighbours by 1°), so that no box passes through; the grid of boxes centred in it,
// its corners' centres 9.9√2 = 14.0 m from the axis, as v3 places them.
TEST_CASE("washer: the drum turns about its axis, its ring is closed, the boxes start where v3 puts them") {
  BenchWorld bench = suiteScene("washer").build();
  World& w = bench.get();
  const Body* drum = nullptr;
  double farthest = 0.0;
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    if (b.type == BodyType::Kinematic) drum = &b;
    if (b.isDynamic()) farthest = std::max(farthest, (b.position() - Vec2(0.0, 10.0)).norm());
  }
  REQUIRE(drum != nullptr);
  CHECK((drum->center - Vec2(0.0, 10.0)).norm() < 1e-12);
  CHECK(drum->angular_velocity == doctest::Approx(std::numbers::pi / 180.0 * 25.0).epsilon(1e-15));
  CHECK(farthest == doctest::Approx(9.9 * std::sqrt(2.0)).epsilon(1e-12));
  // Points 16.05 and 17.85 m from the axis every 0.1°: each inside a piece of the ring.
  int covered = 0, points = 0;
  for (double r : {16.05, 17.85}) {  // the pieces are chords: their outer edge 18 cos 6° = 17.9 m from the axis at the least
    for (int k = 0; k < 3600; ++k, ++points) {
      const double t = k * std::numbers::pi / 1800.0;
      const Vec2 p = drum->xf.apply(r * Vec2(std::cos(t), std::sin(t)));
      for (ShapeId s : drum->shapes)
        if (containsPoint(w.shape(s).geometry, drum->xf, p)) {
          ++covered;
          break;
        }
    }
  }
  CHECK(covered == points);
}

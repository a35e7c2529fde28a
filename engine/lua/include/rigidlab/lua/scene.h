// A Lua scene: a Lua 5.4 file that defines PopulateWorld(world) and optional hooks, run in its own
// sandboxed Lua state. The public Lua API (names, fields, errors) is documented in
// docs/scenes.md (writing scenes), docs/lua-api.md (bodies, shapes, joints, events, the world) and in
// scripts/meta/rigidlab.lua for editors.
//
//   auto scene = rigidlab::lua::Scene::loadFile("scripts/scenes/pyramid.lua");
//   for (int i = 0; i < 600; ++i) scene->step();   // world step + OnStep hook
//   scene->runCheck();                              // Check(world), throws SceneError if it fails
//
// Every script problem — syntax error, runtime error, bad value, unknown option, a force that
// returns NaN — surfaces as one SceneError whose message starts with the script's file:line, then
// the function, then what is wrong and the bad value:
//   scenes/box.lua:12: add_circle: radius must be > 0, got -1
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rigidlab/world.h"

namespace rigidlab::lua {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Limits on what one scene's scripts may consume (docs/security.md). A scene can lower its own
// memory cap (`scene = { memory_limit = 64 }`, MiB), never raise it.
struct ScriptLimits {
  size_t memory_bytes = size_t{256} << 20;  // cap of the scene's Lua allocator
  size_t source_bytes = size_t{4} << 20;    // largest scene or module file (and load() chunk)
  // Budgets of the scene thread's CPU time, C++ calls the script makes included, with a wall-clock
  // backstop of 10 times the budget (engine/lua/src/budget.h). A script still running when its budget is
  // spent stops with "<file>:<line>: <hook>: script ran longer than its budget of 1 s (infinite
  // loop?)"; pcall cannot catch it.
  double hook_seconds = 1.0;   // each call of the main chunk, PopulateWorld, OnStep, Check, OnKey, OnDraw, Exact,
                               // OnMouse, OnControl [s]
  double force_seconds = 1.0;  // all Lua force evaluations of one Scene::step together [s]
};

// Scene-level settings from the script's `scene` table, with their defaults. Gravity, integrator
// and iterations are applied to the World (read them there).
struct SceneSettings {
  std::string title;         // default: the file name
  double dt = 1.0 / 60.0;    // step size [s]
  double duration = 10.0;    // length of a headless run when none is given [s]
  // Initial sandbox camera from `scene.camera = {center = {x, y}, height = h}`: the world point at
  // the middle of the window and the height of the view in metres. Unset: fit to the scene.
  std::optional<Vec2> camera_center;
  std::optional<double> camera_height;
  // `scene.camera = {follow = body}` (a body or a body's name, read after PopulateWorld): the
  // camera keeps this body in the middle of the view.
  std::optional<BodyId> camera_follow;
  // `scene.expect_incidents = true`: bodies frozen by the NaN firewall or a non-finite energy are
  // what the scene is about (a test of the firewall), so a headless run still exits with 0.
  bool expect_incidents = false;

  // --- sandbox mod hooks (OnMouse, scene.keys, scene.controls)
  // `scene.keys = {"space", "a"}`: keys the scene takes from the sandbox's own bindings while it
  // runs; OnKey(world, key) gets them instead (key names as OnKey receives them).
  std::vector<std::string> keys;
  // `scene.controls = {{name = "wind", min = 0, max = 20, value = 5}, {name = "reset", kind = "button"}}`:
  // sliders and buttons in the sandbox's Controls panel, in the order given.
  struct Control {
    enum class Kind { Slider, Button };
    std::string name;
    Kind kind = Kind::Slider;
    double min = 0.0, max = 1.0, value = 0.0;  // a slider's range and default value
  };
  std::vector<Control> controls;

  // rigidlab test (docs/testing.md): `golden` names the recorded trajectory
  // (<scene dir>/golden/<golden>.txt) the run must reproduce, sampled every `golden_every` steps,
  // each value within `golden_tolerance` (0: bit for bit); `skip` is why the scene is not run.
  std::string golden;  // empty: none
  int golden_every = 10;
  double golden_tolerance = 0.0;
  std::optional<std::string> skip;
};

// A mouse event of the sandbox as OnMouse(world, event) receives it (Scene::onMouse).
struct MouseEvent {
  enum class Kind { Press, Release, Move, Wheel };
  enum class Button { None, Left, Right, Middle };  // None: a move or a wheel turn
  Kind kind = Kind::Move;
  Button button = Button::None;
  Vec2 position = Vec2::Zero();  // the cursor in world coordinates [m]
  Vec2 screen = Vec2::Zero();    // the cursor in pixels from the window's top-left corner, y down
  bool shift = false, ctrl = false, alt = false;
  double wheel = 0.0;  // Wheel: notches turned, > 0 away from the user (the sandbox zooms in)
};

struct SceneOptions {
  // Slider values to start with instead of the scene's defaults, by control name (the sandbox
  // passes the running scene's on a hot reload, so they are kept); a value outside the new range
  // is clamped into it, a name the scene no longer has is ignored.
  std::map<std::string, double> control_values;
  // Where require() looks for modules after the scene's own directory; default: the scripts/
  // directory of this installation (see scriptsDirectory()).
  std::vector<std::filesystem::path> module_dirs;
  // Receives everything the scripts print(); default: standard error.
  std::function<void(const std::string&)> log;
  ScriptLimits limits;
};

// Drawing calls a scene makes from OnDraw(draw, world), in world coordinates (draw.screen's are
// converted with screenToWorld and metresPerPixel before they get here).
class OverlayDraw {
 public:
  virtual ~OverlayDraw() = default;
  virtual void line(const Vec2& a, const Vec2& b, const Color& color) = 0;
  virtual void circle(const Vec2& center, double radius, const Color& color) = 0;
  virtual void text(const Vec2& position, const std::string& text, const Color& color) = 0;

  // --- filled shapes and screen space (draw:polygon, draw:capsule, a circle's fill, draw.screen).
  // The defaults draw outlines with line() and circle() and take screen coordinates as world ones,
  // for drawers that only count or record calls.
  // A polygon of 3 or more points in order (concave allowed), filled with `fill` if given.
  virtual void polygon(std::span<const Vec2> points, const Color& color, const std::optional<Color>& fill);
  virtual void capsule(const Vec2& a, const Vec2& b, double radius, const Color& color, const std::optional<Color>& fill);
  // A circle filled with `fill` (circle() is the outline only).
  virtual void disc(const Vec2& center, double radius, const Color& color, const Color& fill);
  // draw.screen's coordinates: the world point under pixel `px` (from the window's top-left, y
  // down) and the length of one pixel [m], this frame.
  virtual Vec2 screenToWorld(const Vec2& px) const { return px; }
  virtual double metresPerPixel() const { return 1.0; }
};

class Scene {
 public:
  // Loads and runs the file, reads its `scene` table and calls PopulateWorld(world).
  static std::unique_ptr<Scene> loadFile(const std::filesystem::path& file, const SceneOptions& options = {});
  // Same from source text; `name` is what messages show as the file name.
  static std::unique_ptr<Scene> loadString(std::string_view source, const std::string& name,
                                           const SceneOptions& options = {});
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  World& world();
  const World& world() const;
  const SceneSettings& settings() const;
  void setDt(double dt);  // validated, > 0
  // The file as given to loadFile (empty for loadString) and every module it require()d, for
  // hot reload.
  const std::filesystem::path& file() const;
  std::vector<std::filesystem::path> sourceFiles() const;

  // One world step of settings().dt (or `dt`), then OnStep(world, dt) if the scene defines it.
  // A script error (in a Lua force or in OnStep) throws SceneError; a force error leaves the world
  // as it was before the step.
  void step();
  void step(double dt);

  bool hasCheck() const;
  void runCheck();  // Check(world); throws SceneError if it raises
  bool hasOnStep() const;
  bool hasOnKey() const;
  void onKey(const std::string& key);  // OnKey(world, key); key names as SDL's, lower case ("space", "a")
  bool hasOnDraw() const;
  // What one OnDraw call drew. A frame draws at most kMaxDrawLines lines, kMaxDrawCircles circles,
  // kMaxDrawShapes polygons and capsules together, and kMaxDrawTexts texts (of at most kDrawTextBytes each, kMaxDrawTextBytes in all): calls
  // past that are dropped and `truncated` says so (the sandbox shows it).
  struct DrawReport {
    int lines = 0, circles = 0, texts = 0;
    int shapes = 0;  // polygons and capsules
    bool truncated = false;
  };
  static constexpr int kMaxDrawLines = 20000, kMaxDrawCircles = 2000, kMaxDrawTexts = 500;
  static constexpr int kMaxDrawShapes = 2000;          // polygons and capsules per frame
  static constexpr size_t kMaxDrawPolygonPoints = 256;  // points of one draw:polygon
  static constexpr size_t kMaxDrawTextBytes = 64 << 10;
  DrawReport onDraw(OverlayDraw& draw);  // OnDraw(draw, world)

  // --- sandbox mod hooks
  bool hasOnMouse() const;
  // OnMouse(world, event); true if it returned true (the event is consumed: the sandbox's tool
  // does not act on it). It must return true, false or nothing.
  bool onMouse(const MouseEvent& event);
  // The current value of settings().controls[i] (a slider; 0 for a button).
  double controlValue(size_t i) const;
  // Sets slider i, clamped into its range (the sandbox's panel; world.controls.<name> = v).
  void setControlValue(size_t i, double value);
  // The sliders' current values by name (kept across a hot reload: SceneOptions::control_values).
  std::map<std::string, double> controlValues() const;
  // OnControl(world, name) if the scene defines it: after a button was pressed or a slider moved.
  void onControl(const std::string& name);

  // Exact(t): a scene that knows its closed-form solution returns, for time t, a table keyed by
  // body name (or body handle) of states {position = {x, y} [, velocity = {x, y}] [, angle = a]
  // [, angular_velocity = w]}. Used by `rigidlab accuracy` and the sandbox's live error.
  struct ExactState {
    uint32_t uid = 0;  // Body::uid
    Vec2 position = Vec2::Zero();
    std::optional<Vec2> velocity;
    std::optional<double> angle, angular_velocity;
  };
  bool hasExact() const;
  std::vector<ExactState> exact(double t);  // sorted by uid; SceneError on a malformed answer

  // Calls made from C++ into Lua so far (hooks and force evaluations): a scene without Lua forces
  // makes none during a step.
  long luaCalls() const;
  // Wall time the last step() spent delivering its events to the event hooks (OnContactBegin ...:
  // building their arguments and calling them) [s]; 0 when the scene defines none.
  double eventSeconds() const;
  // The same as CPU time of the calling thread [s]: what the delivery cost without the time the
  // thread waited for the processor (a loaded machine).
  double eventCpuSeconds() const;

  // The world's snapshot labelled "scene: <file>\ndt: <dt as %a>\n" (world_snapshot.h), and a restore that also
  // mends the scene's Lua side (forgets handles of bodies that are gone; docs/lua-api.md
  // "Snapshots"). The scene's own Lua state is in a snapshot if the scene defines SaveState(world):
  // its value is the snapshot's appData, given back to LoadState(world, value) after a restore.
  // Both throw SceneError (an error in the hooks, a value SaveState cannot save).
  WorldSnapshot snapshot() const;
  void restore(const WorldSnapshot& snapshot);

  struct Impl;

 private:
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// The scripts/ directory (Lua modules, scenes): $RIGIDLAB_SCRIPTS if set, else this installation's
// (data_directory.h).
std::filesystem::path scriptsDirectory();

}  // namespace rigidlab::lua

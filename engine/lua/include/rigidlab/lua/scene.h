// A Lua scene: a Lua 5.4 file that defines PopulateWorld(world) and optional hooks, run in its own
// sandboxed Lua state. The public Lua API (names, fields, errors) is documented in README.md
// ("Writing scenes"), docs/lua-api.md (bodies, shapes, joints, the world) and in
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
#include <memory>
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

// Limits on what one scene's scripts may consume (README "Security"). A scene can lower its own
// memory cap (`scene = { memory_limit = 64 }`, MiB), never raise it.
struct ScriptLimits {
  size_t memory_bytes = size_t{256} << 20;  // cap of the scene's Lua allocator
  size_t source_bytes = size_t{4} << 20;    // largest scene or module file (and load() chunk)
  // Wall-clock budgets (engine/lua/src/budget.h). A script still running when its budget is
  // spent stops with "<file>:<line>: <hook>: script ran longer than its budget of 1 s (infinite
  // loop?)"; pcall cannot catch it.
  double hook_seconds = 1.0;   // each call of the main chunk, PopulateWorld, OnStep, Check, OnKey, OnDraw, Exact [s]
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
  // `scene.expect_incidents = true`: bodies frozen by the NaN firewall or a non-finite energy are
  // what the scene is about (a test of the firewall), so a headless run still exits with 0.
  bool expect_incidents = false;
};

struct SceneOptions {
  // Where require() looks for modules after the scene's own directory; default: the scripts/
  // directory of this installation (see scriptsDirectory()).
  std::vector<std::filesystem::path> module_dirs;
  // Receives everything the scripts print(); default: standard error.
  std::function<void(const std::string&)> log;
  ScriptLimits limits;
};

// Drawing calls a scene makes from OnDraw(draw), in world coordinates.
class OverlayDraw {
 public:
  virtual ~OverlayDraw() = default;
  virtual void line(const Vec2& a, const Vec2& b, const Color& color) = 0;
  virtual void circle(const Vec2& center, double radius, const Color& color) = 0;
  virtual void text(const Vec2& position, const std::string& text, const Color& color) = 0;
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
  // What one OnDraw call drew. A frame draws at most kMaxDrawLines lines, kMaxDrawCircles circles
  // and kMaxDrawTexts texts (of at most kDrawTextBytes each, kMaxDrawTextBytes in all): calls
  // past that are dropped and `truncated` says so (the sandbox shows it).
  struct DrawReport {
    int lines = 0, circles = 0, texts = 0;
    bool truncated = false;
  };
  static constexpr int kMaxDrawLines = 20000, kMaxDrawCircles = 2000, kMaxDrawTexts = 500;
  static constexpr size_t kMaxDrawTextBytes = 64 << 10;
  DrawReport onDraw(OverlayDraw& draw);  // OnDraw(draw)

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

  struct Impl;

 private:
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// The scripts/ directory (Lua modules, scenes): $RIGIDLAB_SCRIPTS if set, else the source tree's
// scripts/ that this binary was built from.
std::filesystem::path scriptsDirectory();

}  // namespace rigidlab::lua

// Benchmark scenes for `rigidlab bench`. The peer scenes (pyramid, stack, rain, massratio, bullet)
// are built exactly as the peer programs build them for Box2D 2.4 and Chipmunk 7 (docs/performance.md; same
// sizes, positions, density 1, friction 0.6, gravity (0, −10), dt 1/60, same step counts), and
// report the same stability metrics, so one script compares the engines. rigidlab's own scenes
// measure forces (1000 bodies on springs, no contacts, built in and written in Lua) and located
// impacts (100 balls bouncing apart, each its own island).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "rigidlab/lua/scene.h"
#include "rigidlab/world.h"

namespace rigidlab::app {

// How a body was built, for the stability metrics.
struct BenchBody {
  BodyId id;
  bool is_static = false;
  bool circle = false;
  Vec2 start = Vec2::Zero();
  double hx = 0.5, hy = 0.5, r = 0.5;
  bool projectile = false;
};

// A world to step: either owned directly or inside a Lua scene.
struct BenchWorld {
  std::unique_ptr<World> world;
  std::unique_ptr<lua::Scene> scene;
  std::vector<BenchBody> bodies;
  int top = -1, bottom = -1;  // index into bodies (pyramid/stack top box; massratio boxes; bullet)
  double wall_x = 0, wall_hx = 0;                     // bullet
  double cont_min_x = 0, cont_max_x = 0, cont_floor = 0;  // rain container interior
  // Edits the scene makes before a step (Box2D v3's rain adds and removes ragdolls); timed with it.
  std::function<void(World&, int step)> before_step;
  // Step through lua::Scene::step (the event hooks and OnStep run after the world's step) instead
  // of World::step alone.
  bool scene_steps = false;
  World& get() { return scene ? scene->world() : *world; }
  long luaCalls() const { return scene ? scene->luaCalls() : 0; }
};

// Observations made after each step (outside the timed region), as the peers make them.
struct BenchTracker {
  double collapse_time = -1, max_box_pen = -1e30, max_ground_pen = -1e30;
  double vx_after_first_step = NAN;
  double lean_time = -1;
  long impacts_located = 0;  // over every step (balls)
  void observe(const std::string& kind, BenchWorld& w, int step, double dt);
};

// What a scene's probe measured after its steps (outside the timed step): times in µs by series
// name, reported as each series' median and interquartile range, and figures reported as given.
struct BenchSamples {
  std::map<std::string, std::vector<double>> us;
  std::map<std::string, double> figures;
};

struct BenchScene {
  std::string name;         // what the command line names: "pyramid40"
  std::string kind;         // the peers' scene name: "pyramid"
  int n = 0;
  std::string description;
  int steps = 600;
  double dt = 1.0 / 60.0;
  std::function<BenchWorld()> build;
  // Called after every step (its time is not the step's): a scene that measures something other
  // than the step (queries, event delivery) records it here.
  using Probe = std::function<void(BenchWorld&, int step, BenchSamples&)>;
  Probe probe = nullptr;
};

const std::vector<BenchScene>& benchScenes();

// Box2D v3's benchmark suite (bench_suite.cpp): large_pyramid, many_pyramids, joint_grid,
// ragdolls, smash, spinner, tumbler, compounds, junkyard, washer.
void addSuiteScenes(std::vector<BenchScene>& scenes);
bool isSuiteScene(const std::string& kind);
// The suite's ragdolls (Box2D v3's rain) keeping `columns` columns of ragdolls before the oldest is
// replaced; the suite's scene keeps 40. A small one lets a test compare the spawning and removal of
// scripts/benchmarks/ragdolls.lua (its `columns` slider) with this scene's in a few dozen steps.
BenchWorld suiteRagdolls(int columns);
// Where each dynamic body was after the first step (by uid), for suiteMetrics.
struct SuiteTracker {
  std::unordered_map<uint32_t, Vec2> start;
  void observe(World& w, int step);
};
std::string suiteMetrics(World& w, const SuiteTracker& tracker);

// The query benchmarks (bench_queries.cpp): ray casts and box queries against 10 000 bodies.
void addQueryScenes(std::vector<BenchScene>& scenes);
// The event delivery benchmark (bench_events.cpp): 1000 contact begin events to a Lua hook.
void addEventScenes(std::vector<BenchScene>& scenes);

// Solver settings every bench world starts from (rigidlab's defaults unless `rigidlab bench`
// is told otherwise), so one run can show what sub-steps or iterations cost and buy.
WorldDef& benchSettings();

// The peers' "metrics" object for this scene's final state, as JSON.
std::string benchMetrics(const BenchScene& scene, BenchWorld& w, const BenchTracker& tracker);

}  // namespace rigidlab::app

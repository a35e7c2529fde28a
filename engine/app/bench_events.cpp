// The event delivery benchmarks of `rigidlab bench` (docs/performance.md "Events"): 1000 balls
// flagged for contact events are put onto a static floor every other step, so that step reports
// 1000 contact begin events, which the scene's trivial OnContactBegin receives. Only the delivery
// is timed (lua::Scene::eventSeconds: the contact tables built and the hook called), per step, as
// wall time and as the thread's CPU time (which a loaded machine inflates less).
#include <string>

#include "bench_scenes.h"

namespace rigidlab::app {
namespace {

constexpr int kBalls = 1000;

// OnStep moves the balls off the floor after a step where they began touching it and back onto it
// (1 mm deep) after the next, when their contacts ended: begin events on even steps, and each ball's
// box begins to overlap the floor's anew. `ball_options` go into each ball's table, `hooks` is more
// of the scene's Lua.
std::string teleportingBalls(const std::string& ball_options, const std::string& hooks) {
  return R"lua(
    scene = { gravity = {0, 0}, sleeping = false }
    local balls, down, begins = {}, true, 0
    function PopulateWorld(world)
      world:add_box{ static = true, position = {0, -0.5}, width = )lua" + std::to_string(kBalls + 2) + R"lua(, height = 1 }
      for i = 1, )lua" + std::to_string(kBalls) + R"lua( do
        balls[i] = world:add_circle{ radius = 0.2, position = {i - 0.5 * )lua" + std::to_string(kBalls) +
         R"lua(, 0.199})lua" + ball_options + R"lua( }
      end
    end
    function OnStep(world, dt)
      down = not down
      local y = down and 0.199 or 2
      for i, b in ipairs(balls) do
        b.position = {b.position.x, y}
        b.velocity = {0, 0}
      end
    end
  )lua" + hooks;
}

BenchWorld eventWorld() {
  BenchWorld b;
  b.scene = lua::Scene::loadString(teleportingBalls(", contact_events = true", R"lua(
    function OnContactBegin(world, contact)
      begins = begins + 1
    end
    function Check(world)
      assert(begins > 0)
    end
  )lua"),
                                   "bench:events");
  b.scene_steps = true;
  return b;
}

// The same balls with a ShouldCollide hook that lets every pair collide or, for the baseline,
// none: the difference of the two scenes' step times is what the 1000 calls of every other step
// cost (bench_command.cpp prints it per call).
BenchWorld shouldCollideWorld(bool with_hook) {
  BenchWorld b;
  b.scene = lua::Scene::loadString(
      teleportingBalls("", with_hook ? "function ShouldCollide(a, b) return true end" : ""),
      with_hook ? "bench:should_collide" : "bench:should_collide_off");
  b.scene_steps = true;
  return b;
}

void probeEvents(BenchWorld& bw, int step, BenchSamples& out) {
  if (step % 2 != 0) return;
  long begins = 0;
  for (const World::ContactEvent& e : bw.get().contactEvents()) begins += e.kind == World::ContactEvent::Kind::Begin;
  out.us["deliver_begin"].push_back(1e6 * bw.scene->eventSeconds());
  out.us["deliver_begin_cpu"].push_back(1e6 * bw.scene->eventCpuSeconds());
  out.figures["begin_events_per_step"] = static_cast<double>(begins);
}

// 1000 balls resting on a floor whose shape has a pre_solve function (writing the contact's
// friction, as a porter's setFriction would) or, for the baseline, none: the difference of the two
// scenes' step times is what 1000 pre_solve calls cost a step (bench_command.cpp prints it per call).
BenchWorld preSolveWorld(bool with_function) {
  const std::string source = R"lua(
    scene = { gravity = {0, -10}, sleeping = false }
    calls = 0
    function PopulateWorld(world)
      local floor = world:add_box{ static = true, position = {0, -0.5}, width = )lua" + std::to_string(kBalls + 2) + R"lua(, height = 1 }
      )lua" + (with_function ? "floor.shapes[1].pre_solve = function(c) calls = calls + 1; c.friction = 0.5 end" : "") + R"lua(
      for i = 1, )lua" + std::to_string(kBalls) + R"lua( do
        world:add_circle{ radius = 0.2, position = {i - 0.5 * )lua" + std::to_string(kBalls) + R"lua(, 0.2} }
      end
    end
  )lua";
  BenchWorld b;
  b.scene = lua::Scene::loadString(source, with_function ? "bench:pre_solve" : "bench:pre_solve_off");
  b.scene_steps = true;
  return b;
}

}  // namespace

void addEventScenes(std::vector<BenchScene>& scenes) {
  scenes.push_back({"pre_solve", "pre_solve", kBalls,
                    "1000 balls resting on a floor whose pre_solve function writes each contact's friction, 100 steps",
                    100, 1.0 / 60.0, [] { return preSolveWorld(true); }});
  scenes.push_back({"pre_solve_off", "pre_solve", kBalls, "the same without the pre_solve function, 100 steps", 100,
                    1.0 / 60.0, [] { return preSolveWorld(false); }});
  scenes.push_back({"should_collide", "should_collide", kBalls,
                    "1000 balls put onto a floor every other step, with a ShouldCollide hook (true), 100 steps", 100,
                    1.0 / 60.0, [] { return shouldCollideWorld(true); }});
  scenes.push_back({"should_collide_off", "should_collide", kBalls, "the same without the hook, 100 steps", 100,
                    1.0 / 60.0, [] { return shouldCollideWorld(false); }});
  BenchScene s{"events", "events", kBalls,
               "1000 contact begin events delivered to a Lua OnContactBegin every other step, 100 steps", 100,
               1.0 / 60.0, eventWorld};
  s.probe = probeEvents;
  scenes.push_back(std::move(s));
}

}  // namespace rigidlab::app

// The event delivery benchmark of `rigidlab bench` (docs/performance.md "Events"): 1000 balls
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
// (1 mm deep) after the next, when their contacts ended: begin events on even steps.
BenchWorld eventWorld() {
  const std::string source = R"lua(
    scene = { gravity = {0, 0}, sleeping = false }
    local balls, down, begins = {}, true, 0
    function PopulateWorld(world)
      world:add_box{ static = true, position = {0, -0.5}, width = )lua" + std::to_string(kBalls + 2) + R"lua(, height = 1 }
      for i = 1, )lua" + std::to_string(kBalls) + R"lua( do
        balls[i] = world:add_circle{ radius = 0.2, position = {i - 0.5 * )lua" + std::to_string(kBalls) +
                             R"lua(, 0.199}, contact_events = true }
      end
    end
    function OnContactBegin(world, contact)
      begins = begins + 1
    end
    function OnStep(world, dt)
      down = not down
      local y = down and 0.199 or 2
      for i, b in ipairs(balls) do
        b.position = {b.position.x, y}
        b.velocity = {0, 0}
      end
    end
    function Check(world)
      assert(begins > 0)
    end
  )lua";
  BenchWorld b;
  b.scene = lua::Scene::loadString(source, "bench:events");
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

}  // namespace

void addEventScenes(std::vector<BenchScene>& scenes) {
  BenchScene s{"events", "events", kBalls,
               "1000 contact begin events delivered to a Lua OnContactBegin every other step, 100 steps", 100,
               1.0 / 60.0, eventWorld};
  s.probe = probeEvents;
  scenes.push_back(std::move(s));
}

}  // namespace rigidlab::app

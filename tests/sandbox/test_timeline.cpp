// The sandbox's timeline (timeline.h) without a window: bounded by time and memory, scrubbing back
// and forth, and a resume or an edit at a past state dropping its future; and the session's rewind
// (rewind.cpp): stepping back shows the exact earlier state, and resuming from it repeats the run.
#include <doctest/doctest.h>

#include "session_helpers.h"
#include "timeline.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;
using namespace rigidlab::sandbox::testing;

namespace {

std::string state(long step) { return std::string(100, static_cast<char>('a' + step % 26)); }

// 60 steps per second for `seconds`, one state of 100 bytes each.
void fill(Timeline& t, long from, long to) {
  for (long i = from; i < to; ++i) t.record(i / 60.0, i, state(i));
}

}  // namespace

TEST_CASE("timeline: keeps the last 10 s of states, at most max_bytes, one every `every` steps") {
  Timeline t;
  fill(t, 0, 60 * 30);  // 30 s
  CHECK(t.span() == doctest::Approx(10.0).epsilon(0.002));
  CHECK(t.size() == 601);  // 10 s at 60 Hz, both ends
  CHECK(t.at(0).step == 60 * 20 - 1);
  CHECK(t.stateBytes(0) == state(60 * 20 - 1));
  Timeline small({10.0, 5000, 1});
  fill(small, 0, 600);
  CHECK(small.bytes() <= 5000);
  CHECK(small.size() > 30);
  CHECK(small.at(small.size() - 1).step == 599);
  for (size_t i = 0; i < small.size(); ++i) CHECK(small.stateBytes(i) == state(small.at(i).step));
  Timeline sparse({10.0, size_t{1} << 20, 4});
  for (long i = 0; i < 100; ++i)
    if (sparse.due(i)) sparse.record(i / 60.0, i, state(i));
  CHECK(sparse.size() == 25);
  CHECK(sparse.at(1).step == 4);
}

TEST_CASE("timeline: scrub back N and forward, clamped; a new state at a past one drops the future") {
  Timeline t;
  fill(t, 0, 100);
  CHECK(!t.rewound());
  CHECK(t.cursor() == 99);
  const Timeline::Entry* e = t.move(-10);
  REQUIRE(e);
  CHECK(e->step == 89);
  CHECK(t.rewound());
  CHECK(t.move(+3)->step == 92);
  CHECK(t.move(-1000)->step == 0);   // clamped at the oldest
  CHECK(t.move(-1) == nullptr);      // nothing older
  CHECK(t.seek(50)->step == 50);
  CHECK(t.size() == 100);            // scrubbing keeps every state
  t.record(50 / 60.0 + 1e-3, 51, "resumed");  // the simulation went on from step 50
  CHECK(!t.rewound());
  CHECK(t.size() == 52);
  CHECK(t.stateBytes(51) == "resumed");
  CHECK(t.stateBytes(50) == state(50));
  // An edit at a past state (truncate) drops its future and leaves it the newest.
  t.move(-20);
  t.truncate();
  CHECK(t.size() == 32);
  CHECK(!t.rewound());
  CHECK(t.seek(31) == nullptr);      // already there
}

TEST_CASE("timeline: states kept as differences rebuild exactly, through evictions of key states") {
  // 10 kB states of which a few bytes change per step (as static bodies do not), some growing.
  std::string base(10000, 'x');
  const auto make = [&](long i) {
    std::string s = base;
    s[static_cast<size_t>(i * 37) % s.size()] = static_cast<char>('a' + i % 26);
    s += std::string(static_cast<size_t>(i % 5) * 70, static_cast<char>('0' + i % 10));  // sizes change
    return s;
  };
  Timeline t({2.0, size_t{64} << 20, 1});
  for (long i = 0; i < 600; ++i) t.record(i / 60.0, i, make(i));
  CHECK((t.size() == 121 || t.size() == 122));   // 2 s at 60 Hz, and one at or before its start
  CHECK(t.bytes() < t.size() * 10000 / 4);        // whole states would take 1.2 MB
  CHECK(t.at(0).key);                             // the oldest is always whole
  for (size_t i = 0; i < t.size(); ++i) CHECK(t.stateBytes(i) == make(t.at(i).step));
  t.seek(40);
  t.record(1.0, 1000, "new");                     // drops the states after 40
  CHECK(t.size() == 42);
  CHECK(t.stateBytes(40) == make(t.at(40).step));
  CHECK(t.stateBytes(41) == "new");
}

TEST_CASE("rewind: Shift+N shows the exact earlier state; resuming from it repeats the run bit for bit") {
  TempDir dir;
  const fs::path file = dir.path / "stack.lua";
  write(file, R"(
scene = {title = "stack"}
function PopulateWorld(world)
  world:add_box{width = 20, height = 1, position = {0, -0.5}, static = true}
  for i = 0, 4 do world:add_box{width = 1, height = 1, position = {0.1 * i, 0.5 + i}, name = "box" .. i} end
  world:add_circle{radius = 0.3, position = {3, 5}, name = "ball"}
end
)");
  Session s;
  startSession(s, file);
  for (int i = 0; i < 60; ++i) stepOnce(s);
  const World& w = s.world();
  const Vec2 at60 = w.body(*w.findBody("box4")).center;
  for (int i = 0; i < 60; ++i) stepOnce(s);
  const Vec2 at120 = w.body(*w.findBody("box4")).center;
  CHECK(s.timeline.size() == 121);  // the loaded state and 120 steps
  CHECK(s.timeline.bytes() > 0);
  for (int i = 0; i < 60; ++i) CHECK(stepBack(s));
  CHECK(s.world().stepCount() == 60);
  CHECK(s.world().body(*s.world().findBody("box4")).center == at60);
  CHECK(s.timeline.rewound());
  // N while rewound moves forward through the kept states.
  stepOnce(s);
  CHECK(s.world().stepCount() == 61);
  CHECK(s.timeline.size() == 121);
  seekState(s, 60);
  // Resuming steps anew from here: the future is dropped, and the run repeats bit for bit.
  setPaused(s, false);
  for (int i = 0; i < 60; ++i) advance(s, 1.0 / 60.0);
  setPaused(s, true);
  while (s.world().stepCount() < 120) stepOnce(s);
  CHECK(s.world().stepCount() == 120);
  CHECK(s.world().body(*s.world().findBody("box4")).center == at120);
  CHECK(!s.timeline.rewound());
  // Save state writes a file that names the scene.
  std::string message;
  const fs::path state = suggestStatePath(s);
  CHECK(state.filename() == "stack_state.snap");
  REQUIRE(saveState(s, state, message));
  std::ifstream in(state, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const WorldSnapshot snap = deserializeSnapshot(bytes);
  CHECK(snap.stepCount() == 120);
  CHECK(snap.label().find("stack.lua") != std::string::npos);
}

TEST_CASE("rewind: an edit at a past state drops the later states") {
  TempDir dir;
  const fs::path file = dir.path / "ball.lua";
  write(file, "function PopulateWorld(world) world:add_circle{radius = 0.5, name = 'ball'} end\n");
  Session s;
  startSession(s, file);
  for (int i = 0; i < 30; ++i) stepOnce(s);
  for (int i = 0; i < 10; ++i) stepBack(s);
  CHECK(s.timeline.size() == 31);
  BodyDef d;
  d.shape = makeBox(1, 1);
  d.position = {3, 0};
  addBody(s, d, "add box");
  syncTimeline(s);
  CHECK(s.timeline.size() == 21);
  CHECK(!s.timeline.rewound());
  CHECK(s.world().bodyCount() == 2);
}

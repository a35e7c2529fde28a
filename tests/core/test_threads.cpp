// Worker threads (WorldDef::threads, task_pool.h): the narrow phase's manifolds and the soft step's
// passes split across threads give the same bits as one thread, whatever the count; the setting is
// validated and is not simulation state.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "task_pool.h"
#include "test_util.h"

using namespace rigidlab;
using namespace rigidlab::test;

namespace {

// Every bit of every body's state, and of the contacts' impulses (the warm start of the next step).
std::vector<double> stateBits(const World& w) {
  std::vector<double> s;
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    s.insert(s.end(), {b.center.x(), b.center.y(), b.angle, b.velocity.x(), b.velocity.y(), b.angular_velocity});
  }
  for (const ContactInfo& c : w.contacts())
    for (int i = 0; i < c.count; ++i) s.insert(s.end(), {c.normal_impulses[i], c.tangent_impulses[i], c.separations[i]});
  return s;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

WorldDef defOf(int threads) {
  WorldDef def;
  def.threads = threads;
  def.sleeping = false;  // keep every body awake, so every step does the whole work
  return def;
}

// A pyramid of `base` rows of 1 m boxes (the bench's pyramid): the soft step, two-point contacts,
// one colour per row and the serial groups' overflow at the ground.
void pyramid(World& w, int base) {
  addBox(w, 2.0 * std::max(50.0, 0.5 * base + 10.0), 2.0, {0.0, -1.0}, true);
  for (int i = 0; i < base; ++i)
    for (int j = i; j < base; ++j) {
      BodyDef d;
      d.shape = makeBox(1.0, 1.0);
      d.position = Vec2((i + 1.0) * 0.5 + (j - i) - 0.5 * base, i + 0.5);
      d.friction = 0.6;
      w.createBody(d);
    }
}

// Circles of several sizes rained into a container: one-point contacts, many new and ending pairs
// per step (the narrow phase), a few bouncing (restitution).
void rain(World& w, int n) {
  addBox(w, 42.0, 1.0, {0.0, -0.5}, true);
  addBox(w, 1.0, 100.0, {-20.5, 50.0}, true);
  addBox(w, 1.0, 100.0, {20.5, 50.0}, true);
  const int cols = 36;
  for (int k = 0; k < n; ++k) {
    BodyDef d;
    d.shape = makeCircle(0.25 + 0.05 * (k % 6));
    d.position = Vec2(-0.5 * (cols - 1) * 1.05 + (k % cols) * 1.05 + 0.01 * (k % 3), 1.0 + (k / cols) * 1.05);
    d.restitution = k % 5 == 0 ? 0.5 : 0.0;
    w.createBody(d);
  }
}

// Chains of boxes hanging from the top and swinging onto a heap of boxes: joints and contacts in
// one soft step.
void joints(World& w) {
  addBox(w, 80.0, 1.0, {0.0, -0.5}, true);
  const BodyId top = addBox(w, 80.0, 1.0, {0.0, 30.5}, true);
  for (int c = 0; c < 20; ++c) {
    BodyId previous = top;
    for (int k = 0; k < 20; ++k) {
      const Vec2 at(-38.0 + 4.0 * c + 0.5 + k, 30.0);
      const BodyId link = addBox(w, 1.0, 0.25, at);
      JointDef j;
      j.type = JointType::Revolute;
      j.a = previous;
      j.b = link;
      j.anchor_a = at - Vec2(0.5, 0.0);
      w.createJoint(j);
      previous = link;
    }
  }
  for (int k = 0; k < 600; ++k) addBox(w, 0.8, 0.8, {-30.0 + 0.9 * (k % 66) + 0.05 * (k % 4), 0.4 + 0.85 * (k / 66)});
}

// Steps a world on one thread and one on `threads` side by side, comparing every step, and returns
// the first step whose state differs (0 if none did), with the index of the first value that
// differed, so a failure says where the bits parted.
template <typename Build>
int firstDifference(int threads, int steps, Build build, size_t& value) {
  World one(defOf(1)), many(defOf(threads));
  build(one);
  build(many);
  for (int i = 1; i <= steps; ++i) {
    one.step(1.0 / 60.0);
    many.step(1.0 / 60.0);
    const std::vector<double> a = stateBits(one), b = stateBits(many);
    if (!sameBits(a, b)) {
      value = 0;
      while (value < a.size() && value < b.size() && std::memcmp(&a[value], &b[value], sizeof(double)) == 0) ++value;
      return i;
    }
  }
  return 0;
}

}  // namespace

TEST_CASE("threads: a pyramid, a rain and a jointed heap give the same bits on 1, 2, 3 and 4 threads") {
  // Each large enough that both the narrow phase and the soft step split their loops (more pairs,
  // contacts and bodies than two threads' minimum work).
  struct Scene {
    const char* name;
    int steps;
    void (*build)(World&);
  };
  const Scene scenes[] = {
      {"pyramid 40", 60, [](World& w) { pyramid(w, 40); }},
      {"rain 1500", 120, [](World& w) { rain(w, 1500); }},
      {"jointed heap", 90, joints},
  };
  for (const Scene& s : scenes) {
    const std::string scene = s.name;  // captured as text (a char* would be printed as an address)
    CAPTURE(scene);
    for (int threads : {2, 3, 4}) {
      CAPTURE(threads);
      size_t value = 0;
      const int step = firstDifference(threads, s.steps, s.build, value);
      CAPTURE(value);  // the index in stateBits: 6 per body, then 3 per contact point
      CHECK(step == 0);
    }
  }
}

TEST_CASE("threads: the scenes are big enough to take the threaded paths") {
  // The thresholds (narrow_phase.cpp kPairGrain, soft_step.cpp kContactGrain: 256 per thread):
  // the pyramid of the test above has more pairs and soft contacts than two threads' minimum.
  World big(defOf(2));
  pyramid(big, 40);
  big.step(1.0 / 60.0);
  CHECK(big.stats().pairs >= 2 * 256);
  CHECK(big.stats().contacts >= 2 * 256);
}

TEST_CASE("threads: the setting is validated, 1 by default, 0 takes the machine's cores") {
  for (int bad : {-1, 65, 1000}) {
    CAPTURE(bad);
    WorldDef def;
    def.threads = bad;
    CHECK(errorOf([&] { World w(def); }) ==
          "threads must be between 0 (the machine's cores) and 64, got " + std::to_string(bad));
    World w;
    CHECK(errorOf([&] { w.setThreads(bad); }) ==
          "threads must be between 0 (the machine's cores) and 64, got " + std::to_string(bad));
  }
  World w;
  CHECK(w.settings().threads == 1);  // the default: serial
  w.setThreads(64);
  CHECK(w.settings().threads == 64);
  CHECK(resolvedThreads(3) == 3);
  CHECK(resolvedThreads(0) >= 1);
  CHECK(resolvedThreads(0) <= 64);
}

TEST_CASE("threads: a snapshot neither carries nor restores the setting, and stepping on is the same bits") {
  World a(defOf(2));
  pyramid(a, 30);
  for (int i = 0; i < 20; ++i) a.step(1.0 / 60.0);
  const WorldSnapshot s = a.snapshot();
  for (int i = 0; i < 20; ++i) a.step(1.0 / 60.0);
  const std::vector<double> after = stateBits(a);
  a.setThreads(3);
  a.restore(s);
  CHECK(a.settings().threads == 3);  // the restoring world keeps its own
  for (int i = 0; i < 20; ++i) a.step(1.0 / 60.0);
  CHECK(sameBits(stateBits(a), after));
}

TEST_CASE("threads: the pool runs every index once, whatever the thread count") {
  for (int threads : {1, 2, 3, 5}) {
    CAPTURE(threads);
    TaskPool pool(threads);
    for (size_t count : {size_t{0}, size_t{1}, size_t{7}, size_t{1000}, size_t{12345}}) {
      CAPTURE(count);
      std::vector<int> hits(count, 0);
      std::atomic<int> calls{0};
      pool.parallelFor(count, 1, [&](size_t begin, size_t end) {
        ++calls;
        for (size_t i = begin; i < end; ++i) ++hits[i];
      });
      bool once = true;
      for (int h : hits) once &= h == 1;
      CHECK(once);
      CHECK(calls.load() <= 4 * threads);  // a few chunks per thread
      // Below the grain the caller does it all in one call.
      calls = 0;
      pool.parallelFor(count, count + 1, [&](size_t, size_t) { ++calls; });
      CHECK(calls.load() == (count > 0 ? 1 : 0));
    }
    size_t b0, e0, b1, e1;
    TaskPool::rangeOf(10, 0, 3, b0, e0);
    TaskPool::rangeOf(10, 1, 3, b1, e1);
    CHECK(b0 == 0);
    CHECK(e0 == b1);
  }
}

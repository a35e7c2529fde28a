// Broad phase: the grid must report exactly the pairs all-pairs reports, in the same order.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "broad_phase.h"
#include "rigidlab/world.h"
#include "stages.h"
#include "test_util.h"

using namespace rigidlab;

namespace {

std::vector<Proxy> randomProxies(unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-20.0, 20.0), size(0.1, 1.5), coin(0.0, 1.0);
  std::vector<Proxy> proxies(n);
  for (Proxy& p : proxies) {
    const Vec2 c(pos(rng), pos(rng));
    Vec2 half(size(rng), size(rng));
    if (coin(rng) < 0.03) half *= 30.0;  // a few boxes far larger than a cell
    p.aabb = {c - half, c + half};
    p.is_static = coin(rng) < 0.2;
    p.active = coin(rng) < 0.95;
  }
  return proxies;
}

}  // namespace

TEST_CASE("the grid broad phase finds exactly the all-pairs pairs, in the same order") {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    CAPTURE(seed);
    const auto proxies = randomProxies(seed, 400);
    std::vector<BodyPair> expected, got;
    AllPairsBroadPhase().findPairs(proxies, expected);
    GridBroadPhase grid;
    grid.findPairs(proxies, got);
    REQUIRE(got.size() == expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
      REQUIRE(got[i].a == expected[i].a);
      REQUIRE(got[i].b == expected[i].b);
    }
    CHECK(expected.size() > 100);  // the scenes do overlap
    grid.findPairs(proxies, got);  // reusing the scratch gives the same answer
    CHECK(got.size() == expected.size());
  }
}

TEST_CASE("the grid copes with far-away and huge coordinates") {
  std::vector<Proxy> proxies(3);
  proxies[0] = {{Vec2(1e5, 1e5), Vec2(1e5 + 1, 1e5 + 1)}, false, true};
  proxies[1] = {{Vec2(1e5 + 0.5, 1e5 + 0.5), Vec2(1e5 + 1.5, 1e5 + 1.5)}, false, true};
  proxies[2] = {{Vec2(-1e6, -1e6), Vec2(1e6, 1e6)}, true, true};  // a 2 km static box around both
  std::vector<BodyPair> pairs;
  GridBroadPhase().findPairs(proxies, pairs);
  REQUIRE(pairs.size() == 3);
  CHECK((pairs[0].a == 0 && pairs[0].b == 1));
  CHECK((pairs[1].a == 0 && pairs[1].b == 2));
  CHECK((pairs[2].a == 1 && pairs[2].b == 2));
}

namespace {

// A pile of circles and boxes settling in a container, with edits between steps that the kept
// pair list must notice: a teleport onto another body, a switch to static and back, a removal, a
// new body in a freed slot. Returns every body's state after each step, bit for bit.
std::vector<double> pileTrace(int& reused_steps) {
  World w;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = makeBox(30.0, 1.0);
  ground.position = Vec2(0.0, -0.5);
  w.createBody(ground);
  for (double x : {-10.0, 10.0}) {
    ground.shape = makeBox(1.0, 20.0);
    ground.position = Vec2(x, 10.0);
    w.createBody(ground);
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<BodyId> ids;
  for (int i = 0; i < 150; ++i) {
    BodyDef d;
    d.shape = u(rng) < 0.5 ? makeCircle(0.2 + 0.3 * u(rng)) : makeBox(0.3 + 0.6 * u(rng), 0.3 + 0.6 * u(rng));
    d.position = Vec2(-8.0 + 16.0 * u(rng), 0.5 + 12.0 * u(rng));
    d.angle = 3.0 * u(rng);
    ids.push_back(w.createBody(d));
  }
  std::vector<double> trace;
  reused_steps = 0;
  for (int step = 0; step < 400; ++step) {
    if (step == 200) w.setTransform(ids[3], w.body(ids[4]).position(), 0.0);  // onto another body
    if (step == 230) w.setType(ids[10], BodyType::Static);
    if (step == 260) w.setType(ids[10], BodyType::Dynamic);
    if (step == 290) w.destroyBody(ids[20]);
    if (step == 291) {
      BodyDef d;
      d.shape = makeCircle(0.4);
      d.position = w.body(ids[21]).position() + Vec2(0.0, 0.5);
      w.createBody(d);
    }
    w.step(1.0 / 60.0);
    reused_steps += w.stats().pairs_reused ? 1 : 0;
    for (BodyId id : w.bodyIds()) {
      const Body& b = w.body(id);
      trace.insert(trace.end(), {b.center.x(), b.center.y(), b.angle, b.velocity.x(), b.velocity.y(), b.angular_velocity});
    }
  }
  return trace;
}

}  // namespace

TEST_CASE("the kept pair list gives the same simulation, bit for bit, as rebuilding every step") {
  int reused_off = 0, reused_on = 0;
  usePairCache(false);
  const std::vector<double> rebuilt = pileTrace(reused_off);
  usePairCache(true);
  const std::vector<double> kept = pileTrace(reused_on);
  CHECK(reused_off == 0);
  CHECK(reused_on > 100);  // once the pile settles the list serves most steps (171 of 400 measured)
  MESSAGE("steps served by the kept list: " << reused_on << " of 400");
  REQUIRE(rebuilt.size() == kept.size());
  CHECK(std::memcmp(rebuilt.data(), kept.data(), kept.size() * sizeof(double)) == 0);
}

TEST_CASE("both broad phases stop at their pair limit and say where the boxes crowd") {
  // 400 coincident boxes would make 79 800 pairs; the limit stops the pass at 1000.
  std::vector<Proxy> proxies(400);
  for (Proxy& p : proxies) p = {{Vec2(1.0, 2.0), Vec2(2.0, 3.0)}, false, true};
  PairLimit limit;
  limit.pairs = 1000;
  for (int grid = 0; grid < 2; ++grid) {
    CAPTURE(grid);
    std::vector<BodyPair> pairs;
    PairOverflow overflow;
    const bool done = grid ? GridBroadPhase().findPairs(proxies, pairs, limit, &overflow)
                           : AllPairsBroadPhase().findPairs(proxies, pairs, limit, &overflow);
    CHECK_FALSE(done);
    CHECK(pairs.size() == 1000);
    CHECK_FALSE(overflow.tests);
    CHECK(overflow.crowd == 400);
    CHECK(overflow.where == Vec2(1.5, 2.5));
  }
  // Under the limit nothing changes: the same pairs as without one.
  limit.pairs = 79800;
  std::vector<BodyPair> pairs;
  CHECK(GridBroadPhase().findPairs(proxies, pairs, limit));
  CHECK(pairs.size() == 79800);
}

TEST_CASE("the grid stops at its test limit in a cell crowded with boxes that do not overlap") {
  // One large dynamic box sets a large cell; 2000 small static boxes side by side fill one cell
  // without overlapping (and static-static pairs are never pairs): about 2 million tests, no pair.
  std::vector<Proxy> proxies;
  proxies.push_back({{Vec2(0.0, 0.0), Vec2(400.0, 400.0)}, false, true});
  for (int i = 0; i < 2000; ++i) {
    const Vec2 lower(1000.0 + 0.02 * (i % 40), 1000.0 + 0.02 * (i / 40));
    proxies.push_back({{lower, lower + Vec2(0.01, 0.01)}, true, true});
  }
  PairLimit limit;
  limit.tests = 100000;
  std::vector<BodyPair> pairs;
  PairOverflow overflow;
  CHECK_FALSE(GridBroadPhase().findPairs(proxies, pairs, limit, &overflow));
  CHECK(overflow.tests);
  CHECK(overflow.crowd == 2000);
  CHECK(GridBroadPhase().findPairs(proxies, pairs));  // without a limit: no pairs at all
  CHECK(pairs.empty());
}

TEST_CASE("a step over the pair cap fails, naming the crowd, and leaves the world as it was") {
  WorldDef def;
  def.pair_cap = 1000;
  def.pair_cap_per_body = 2;
  World w(def);
  struct NanForce final : Force {
    void evaluate(const ForceInput&, ForceOutput& out) override { out.a.force = {NAN, 0.0}; }
    std::string_view kind() const override { return "nan"; }
  };
  const BodyId frozen = test::addCircle(w, 0.5, {40, 0});  // frozen by the NaN firewall in the failed step
  w.addForce(std::make_unique<NanForce>(), frozen);
  std::vector<BodyId> heap;
  for (int i = 0; i < 100; ++i) heap.push_back(test::addCircle(w, 0.5, {0.001 * i, 0}));  // 4950 pairs
  w.setVelocity(heap[5], {1, 2});
  const std::string message = test::errorOf([&] { w.step(1.0 / 60.0); });
  CHECK(message == "too many bodies on top of each other at step 1 (t = 0 s): 100 bodies overlap around (0, "
                   "-0.001362), more than the 1000 candidate contact pairs a step may have (min(1000000, max(1000, 2 per "
                   "body)) for 101 bodies); spread them out");
  CHECK(w.time() == 0.0);
  CHECK(w.stepCount() == 0);
  CHECK_FALSE(w.isStepping());
  CHECK(w.incidents().empty());
  CHECK_FALSE(w.body(frozen).isStatic());
  CHECK(w.body(frozen).position() == Vec2(40, 0));
  CHECK(w.body(heap[5]).position() == Vec2(0.005, 0));
  CHECK(w.body(heap[5]).velocity == Vec2(1, 2));
  // Spread out, the same bodies step (and the frozen one is frozen for real).
  for (int i = 0; i < 100; ++i) w.setTransform(heap[i], {2.0 * i, 10}, 0.0);
  w.step(1.0 / 60.0);
  CHECK(w.incidents().size() == 1);
}

TEST_CASE("a kept pair list over the cap falls back to a plain pass: the step succeeds") {
  // Boxes in a row with 0.1 m gaps: no box overlaps another, but their boxes grown by a quarter
  // (the kept list, PairCache) do: 2 per box, over a cap of 1 per box.
  WorldDef def;
  def.pair_cap = 1;
  def.pair_cap_per_body = 1;
  def.pair_cap_max = 1000;
  def.gravity = Vec2::Zero();
  World w(def);
  for (int i = 0; i < 50; ++i) test::addBox(w, 1.0, 1.0, {1.1 * i, 0});
  CHECK(test::errorOf([&] { w.step(1.0 / 60.0); }) == "(no error)");
  CHECK(w.stats().pairs == 0);
}

TEST_CASE("the pair cap stops growing with the number of bodies at pair_cap_max") {
  WorldDef def;
  def.pair_cap = 10;
  def.pair_cap_per_body = 32;
  def.pair_cap_max = 500;
  World w(def);
  // 40 clusters of 5 coincident circles: 400 pairs, under 32 per body but over the ceiling of 500
  // once a cluster more is added.
  for (int c = 0; c < 40; ++c)
    for (int i = 0; i < 5; ++i) test::addCircle(w, 0.5, {3.0 * c, 0.001 * i});
  CHECK(test::errorOf([&] { w.step(1.0 / 60.0); }) == "(no error)");
  CHECK(w.stats().pairs == 400);
  for (int c = 40; c < 70; ++c)
    for (int i = 0; i < 5; ++i) test::addCircle(w, 0.5, {3.0 * c, 0.001 * i});
  CHECK(test::errorOf([&] { w.step(1.0 / 60.0); }).find("more than the 500 candidate contact pairs") != std::string::npos);
  def.pair_cap_max = 5;
  CHECK(test::errorOf([&] { World bad(def); }) == "pair_cap_max must be at least pair_cap (10), got 5");
}

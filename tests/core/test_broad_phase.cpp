// Broad phase: the grid must report exactly the pairs all-pairs reports, in the same order.
#include <doctest/doctest.h>

#include <random>

#include "broad_phase.h"

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

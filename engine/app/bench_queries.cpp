// The query benchmarks of `rigidlab bench` (docs/performance.md "Queries"): World::rayCast and
// World::queryBox against 10 000 moving bodies, timed call by call after every step so that the
// figures are the medians and interquartile ranges of single queries. The first query after a
// step is timed apart ("first_ray"): it brings the query tree up to date with what the step moved
// (world_query.cpp), which every later query of that step is spared.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "bench_scenes.h"

namespace rigidlab::app {
namespace {

constexpr int kSide = 100;               // kSide × kSide bodies, 1 m apart
constexpr int kRaysPerStep = 1000;
constexpr int kBoxesPerStep = 200;
constexpr double kRayLength = 20.0;      // [m]
constexpr double kBoxSide = 9.5;         // [m]: about 100 shapes overlap a box this size

// A fixed xorshift sequence, so that every run casts the same rays.
struct Rng {
  uint32_t s = 0x2545F491u;
  double uniform() {
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    return (s >> 8) * (1.0 / 16777216.0);
  }
  double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

// Circles, boxes and capsules of 0.3-0.7 m, one per square metre, drifting (no gravity) at up to
// 0.5 m/s and turning, so that the step moves every shape and some leave their tree leaves.
BenchWorld queryWorld() {
  BenchWorld b;
  WorldDef def = benchSettings();
  def.gravity = Vec2::Zero();
  def.sleeping = false;
  b.world = std::make_unique<World>(def);
  Rng rng;
  for (int i = 0; i < kSide * kSide; ++i) {
    BodyDef d;
    d.position = Vec2(i % kSide + rng.range(-0.1, 0.1), i / kSide + rng.range(-0.1, 0.1));
    d.angle = rng.range(0.0, 2.0 * std::numbers::pi);
    d.velocity = Vec2(rng.range(-0.35, 0.35), rng.range(-0.35, 0.35));
    d.angular_velocity = rng.range(-1.0, 1.0);
    switch (i % 3) {
      case 0:
        d.shape = makeCircle(rng.range(0.15, 0.35));
        break;
      case 1:
        d.shape = makeBox(rng.range(0.3, 0.7), rng.range(0.3, 0.7));
        break;
      default:
        d.shape = makeCapsule(Vec2(-0.2, 0.0), Vec2(0.2, 0.0), rng.range(0.1, 0.15));
        break;
    }
    b.world->createBody(d);
  }
  return b;
}

double microseconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

void probeQueries(BenchWorld& bw, int /*step*/, BenchSamples& out) {
  using Clock = std::chrono::steady_clock;
  static Rng rng;  // one sequence over the whole run: every step and repetition casts new rays
  const World& w = bw.get();
  const auto ray = [&] {
    const Vec2 from(rng.range(0.0, kSide), rng.range(0.0, kSide));
    const double a = rng.range(0.0, 2.0 * std::numbers::pi);
    return std::pair{from, Vec2(from + kRayLength * Vec2(std::cos(a), std::sin(a)))};
  };
  std::vector<double>& rays = out.us["ray"];
  std::vector<double>& boxes = out.us["box"];
  double& hits = out.figures["ray_hit_fraction"];
  double& found = out.figures["box_shapes_mean"];
  {
    const auto [from, to] = ray();
    const auto t0 = Clock::now();
    const auto hit = w.rayCast(from, to);
    out.us["first_ray"].push_back(microseconds(t0, Clock::now()));
    if (hit && hit->fraction > 1.0) out.figures["bad_hit"] = 1;  // keeps the call from being elided
  }
  long ray_hits = 0;
  for (int i = 0; i < kRaysPerStep; ++i) {
    const auto [from, to] = ray();
    const auto t0 = Clock::now();
    const auto hit = w.rayCast(from, to);
    rays.push_back(microseconds(t0, Clock::now()));
    ray_hits += hit ? 1 : 0;
  }
  long shapes = 0;
  for (int i = 0; i < kBoxesPerStep; ++i) {
    const Vec2 lower(rng.range(0.0, kSide - kBoxSide), rng.range(0.0, kSide - kBoxSide));
    const Aabb box{lower, lower + Vec2::Constant(kBoxSide)};
    const auto t0 = Clock::now();
    const auto ids = w.queryBox(box);
    boxes.push_back(microseconds(t0, Clock::now()));
    shapes += static_cast<long>(ids.size());
  }
  // Running means over every step probed so far.
  const double steps = static_cast<double>(boxes.size()) / kBoxesPerStep;
  hits += (static_cast<double>(ray_hits) / kRaysPerStep - hits) / steps;
  found += (static_cast<double>(shapes) / kBoxesPerStep - found) / steps;
}

}  // namespace

void addQueryScenes(std::vector<BenchScene>& scenes) {
  BenchScene s{"queries", "queries", kSide * kSide,
               "ray casts (20 m) and 9.5 m box queries against 10 000 drifting bodies, after each of 20 steps",
               20, 1.0 / 60.0, queryWorld};
  s.probe = probeQueries;
  scenes.push_back(std::move(s));
}

}  // namespace rigidlab::app

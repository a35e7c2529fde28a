#include "bench_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "report.h"

namespace rigidlab::app {
WorldDef& benchSettings() {
  static WorldDef def;
  return def;
}

namespace {

// The peers' deterministic xorshift generator (same sequence for every engine).
struct Rng {
  uint32_t s;
  explicit Rng(uint32_t seed) : s(seed ? seed : 0x9E3779B9u) {}
  uint32_t next() {
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    return s;
  }
  double uniform() { return (next() >> 8) * (1.0 / 16777216.0); }
  double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

WorldDef peerWorld() {
  WorldDef def = benchSettings();
  def.gravity = Vec2(0.0, -10.0);
  def.sleeping = false;  // the peers time their scenes with sleeping off
  return def;  // otherwise rigidlab's defaults: what a user gets
}

void addBox(BenchWorld& b, double x, double y, double hx, double hy, bool is_static, double density = 1.0) {
  BodyDef d;
  d.type = is_static ? BodyType::Static : BodyType::Dynamic;
  d.shape = makeBox(2 * hx, 2 * hy);
  d.position = Vec2(x, y);
  d.density = density;
  d.friction = 0.6;  // pair friction sqrt(0.6 · 0.6) = 0.6, as the peers set it
  b.bodies.push_back({b.world->createBody(d), is_static, false, Vec2(x, y), hx, hy, 0.0, false});
}

void addCircle(BenchWorld& b, double x, double y, double r, Vec2 velocity = Vec2::Zero(), bool projectile = false) {
  BodyDef d;
  d.shape = makeCircle(r);
  d.position = Vec2(x, y);
  d.velocity = velocity;
  d.friction = 0.6;
  b.bodies.push_back({b.world->createBody(d), false, true, Vec2(x, y), 0.0, 0.0, r, projectile});
}

BenchWorld pyramid(int n) {
  BenchWorld b;
  b.world = std::make_unique<World>(peerWorld());
  addBox(b, 0.0, -1.0, std::max(50.0, 0.5 * n + 10.0), 1.0, true);
  const double a = 0.5;
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) addBox(b, (i + 1.0) * a + 2.0 * (j - i) * a - a * n, (2.0 * i + 1.0) * a, a, a, false);
  b.top = static_cast<int>(b.bodies.size()) - 1;
  return b;
}

BenchWorld stack(int n) {
  BenchWorld b;
  b.world = std::make_unique<World>(peerWorld());
  addBox(b, 0.0, -1.0, 20.0, 1.0, true);
  for (int i = 0; i < n; ++i) addBox(b, 0.0, 0.5 + i, 0.5, 0.5, false);
  b.top = static_cast<int>(b.bodies.size()) - 1;
  return b;
}

BenchWorld rain(int n) {
  BenchWorld b;
  b.world = std::make_unique<World>(peerWorld());
  const double width = 40.0, wall_height = 150.0, t = 0.5;
  addBox(b, 0.0, -t, 0.5 * width + 2 * t, t, true);
  addBox(b, -0.5 * width - t, 0.5 * wall_height, t, 0.5 * wall_height, true);
  addBox(b, 0.5 * width + t, 0.5 * wall_height, t, 0.5 * wall_height, true);
  b.cont_min_x = -0.5 * width;
  b.cont_max_x = 0.5 * width;
  b.cont_floor = 0.0;
  Rng rng(12345u);
  const int cols = 36;
  const double pitch = 1.05;
  for (int k = 0; k < n; ++k) {
    const int row = k / cols, col = k % cols;
    const double r = rng.range(0.25, 0.5);
    const double jx = rng.range(-0.02, 0.02);
    addCircle(b, -0.5 * (cols - 1) * pitch + col * pitch + jx, 1.0 + row * pitch, r);
  }
  return b;
}

// A 100 kg box (1 m) on a 1 kg box (1 m) on the ground: the peers' run.sh settings.
BenchWorld massRatio() {
  BenchWorld b;
  b.world = std::make_unique<World>(peerWorld());
  addBox(b, 0.0, -1.0, 20.0, 1.0, true);
  addBox(b, 0.0, 0.5, 0.5, 0.5, false, 1.0);
  b.bottom = 1;
  addBox(b, 0.0, 1.5, 0.5, 0.5, false, 100.0);
  b.top = 2;
  return b;
}

// 100 balls (r = 0.1 m, e = 0.8) 0.5 m apart, dropped from 1 m to 1.99 m, so that every impact
// falls at its own phase of the step: 100 islands of one body, each in free flight between its
// bounces, which is what located impacts are for (100 first impacts in the first 60 steps, the
// second ones after 1.17 s).
BenchWorld balls() {
  BenchWorld b;
  b.world = std::make_unique<World>(peerWorld());
  addBox(b, 0.0, -1.0, 30.0, 1.0, true);
  for (int i = 0; i < 100; ++i) {
    BodyDef d;
    d.shape = makeCircle(0.1);
    d.position = Vec2(-24.75 + 0.5 * i, 1.1 + 0.01 * i);
    d.restitution = 0.8;
    b.bodies.push_back({b.world->createBody(d), false, true, d.position, 0.0, 0.0, 0.1, false});
  }
  return b;
}

BenchWorld bullet() {
  BenchWorld b;
  b.world = std::make_unique<World>(peerWorld());
  b.wall_hx = 0.05;
  b.wall_x = 10.0 + b.wall_hx;
  addBox(b, b.wall_x, 0.0, b.wall_hx, 0.5 + 5.0, true);
  addCircle(b, 0.0, 0.0, 0.1, Vec2(500.0, 0.0), true);
  b.top = 1;
  return b;
}

// 1000 discs in a 40 × 25 grid, 1 m apart (no contacts), each hanging from its own anchor on a
// spring (k = 100 N/m, c = 0.1 N·s/m, stretched 0.2 m), RK4 under gravity.
constexpr int kSpringBodies = 1000;

BenchWorld builtinSprings() {
  BenchWorld b;
  WorldDef def;
  def.integrator = Integrator::RungeKutta4;
  b.world = std::make_unique<World>(def);
  for (int i = 0; i < kSpringBodies; ++i) {
    BodyDef d;
    d.shape = makeCircle(0.1);
    d.position = Vec2(i % 40, -(i / 40) * 1.0);
    const BodyId id = b.world->createBody(d);
    SpringDef s;
    s.a = id;
    s.anchor = d.position + Vec2(0.0, 0.5);
    s.stiffness = 100.0;
    s.rest_length = 0.3;
    s.damping = 0.1;
    b.world->addSpring(s);
  }
  return b;
}

// A chain of n links (0.1 × 0.01 m boxes of 1 kg) pinned end to end, the first to the world,
// released horizontally, no contacts (the links do not collide): one island of the exact joints
// (docs/performance.md "Exact joints"), whose cost per step should grow linearly in n. The probe
// reports the largest pin gap over the run.
BenchWorld linkChain(int n) {
  BenchWorld b;
  WorldDef def;
  def.integrator = Integrator::RungeKutta4;
  b.world = std::make_unique<World>(def);
  World& w = *b.world;
  BodyId previous{};
  for (int i = 0; i < n; ++i) {
    BodyDef d;
    d.shape = makeBox(0.1, 0.01);
    d.position = Vec2((i + 0.5) * 0.1, 0.0);
    d.mass = 1.0;
    d.filter.group = -1;  // links never collide: the island stays exact
    const BodyId link = w.createBody(d);
    JointDef j;
    j.type = JointType::Revolute;
    j.a = link;
    j.b = previous;
    j.anchor_a = Vec2(i * 0.1, 0.0);
    w.createJoint(j);
    previous = link;
  }
  return b;
}

void probeChainGap(BenchWorld& bw, int /*step*/, BenchSamples& out) {
  double& gap = out.figures["max_pin_gap_m"];
  World& w = bw.get();
  // Over the run: the projections' Newton iterations and the intervals integrated again (what a
  // step's cost is made of besides the factorisations).
  out.figures["newton_iterations"] += w.stats().mechanism_newton;
  out.figures["retries"] += w.stats().mechanism_retries;
  for (JointId id : w.jointIds()) {
    const JointState s = w.jointState(id);
    gap = std::max(gap, (s.world_anchor_a - s.world_anchor_b).norm());
  }
}

// The same scene with the springs written in Lua (scripts/forces/spring.lua).
BenchWorld luaSprings() {
  const std::string source = R"lua(
    scene = { integrator = "rk4" }
    local spring = require "forces.spring"
    function PopulateWorld(world)
      for i = 0, )lua" + std::to_string(kSpringBodies - 1) + R"lua( do
        local x, y = i % 40, -(i // 40) * 1.0
        local body = world:add_circle{ radius = 0.1, position = {x, y} }
        spring.add(world, { a = body, anchor = {x, y + 0.5}, stiffness = 100, rest_length = 0.3, damping = 0.1 })
      end
    end
  )lua";
  BenchWorld b;
  b.scene = lua::Scene::loadString(source, "bench:lua_springs");
  return b;
}

struct State {
  Vec2 p = Vec2::Zero();
  double angle = 0.0;
  Vec2 v = Vec2::Zero();
};

State stateOf(BenchWorld& w, int index) {
  const Body& b = w.get().body(w.bodies[index].id);
  return {b.position(), b.angle, b.velocity};
}

double boxBottom(const BenchBody& d, const State& s) {
  const double c = std::abs(std::cos(s.angle)), sn = std::abs(std::sin(s.angle));
  return s.p.y() - (d.hx * sn + d.hy * c);
}

// The peers' collapse rule: the top box sank more than half the smaller height into the bottom
// one, slid off it, or ended below it.
bool massRatioCollapsed(const BenchBody& bd, const BenchBody& td, const State& bs, const State& ts, double& box_pen) {
  box_pen = (bd.hy + td.hy) - (ts.p.y() - bs.p.y());
  const bool slid_off = std::abs(ts.p.x() - bs.p.x()) > bd.hx + td.hx;
  return slid_off || box_pen > 0.5 * std::min(bd.hy, td.hy) || ts.p.y() < bs.p.y();
}

// JSON object builder in the peers' format (%.6g numbers).
struct Json {
  std::string s;
  void key(const char* k) { s += (s.empty() ? "" : ", ") + std::string("\"") + k + "\": "; }
  void num(const char* k, double v) {
    key(k);
    char buf[64];
    std::snprintf(buf, sizeof buf, std::isfinite(v) ? "%.6g" : "null", v);
    s += buf;
  }
  void integer(const char* k, long long v) {
    key(k);
    s += std::to_string(v);
  }
  void boolean(const char* k, bool v) {
    key(k);
    s += v ? "true" : "false";
  }
  std::string done() const { return "{" + s + "}"; }
};

}  // namespace

void BenchTracker::observe(const std::string& kind, BenchWorld& w, int step, double dt) {
  if (kind == "massratio") {
    const State bs = stateOf(w, w.bottom), ts = stateOf(w, w.top);
    double box_pen;
    if (massRatioCollapsed(w.bodies[w.bottom], w.bodies[w.top], bs, ts, box_pen) && collapse_time < 0)
      collapse_time = (step + 1) * dt;
    max_box_pen = std::max(max_box_pen, box_pen);
    max_ground_pen = std::max(max_ground_pen, 0.0 - boxBottom(w.bodies[w.bottom], bs));
  } else if (kind == "bullet" && step == 0) {
    vx_after_first_step = stateOf(w, w.top).v.x();
  } else if (kind == "balls") {
    impacts_located += w.get().stats().impacts_located;
  } else if (kind == "stack") {
    if (lean_time < 0 && std::abs(stateOf(w, w.top).p.x() - w.bodies[w.top].start.x()) > 0.1) lean_time = (step + 1) * dt;
  }
}

std::string benchMetrics(const BenchScene& scene, BenchWorld& w, const BenchTracker& t) {
  Json j;
  int dynamic = 0;
  for (const BenchBody& b : w.bodies) dynamic += b.is_static ? 0 : 1;
  j.integer("awake_at_end", w.get().stats().awake_bodies);
  const std::string& kind = scene.kind;
  if (kind == "pyramid" || kind == "stack") {
    double max_disp = 0, sum_disp = 0, max_y = -1e30, max_abs_dx = 0, max_abs_angle = 0;
    int moved = 0;
    for (size_t i = 0; i < w.bodies.size(); ++i) {
      if (w.bodies[i].is_static) continue;
      const State s = stateOf(w, static_cast<int>(i));
      const double d = (s.p - w.bodies[i].start).norm();
      max_disp = std::max(max_disp, d);
      sum_disp += d;
      moved += d > 0.25 ? 1 : 0;
      if (static_cast<int>(i) != w.top) max_y = std::max(max_y, s.p.y());
      max_abs_dx = std::max(max_abs_dx, std::abs(s.p.x() - w.bodies[i].start.x()));
      max_abs_angle = std::max(max_abs_angle, std::abs(s.angle));
    }
    const State top = stateOf(w, w.top);
    const Vec2 top0 = w.bodies[w.top].start;
    j.num("max_disp_m", max_disp);
    j.num("mean_disp_m", sum_disp / std::max(1, dynamic));
    j.integer("moved_gt_0.25m", moved);
    j.boolean("top_on_top", top.p.y() > max_y + 0.5 && std::abs(top.p.x() - top0.x()) < 0.5);
    j.num("top_dx_m", top.p.x() - top0.x());
    j.num("top_height_loss_m", top0.y() - top.p.y());
    j.num("top_angle_rad", top.angle);
    j.num("max_abs_dx_m", max_abs_dx);
    j.num("max_abs_angle_rad", max_abs_angle);
    if (kind == "stack") {
      j.num("lean_0.1m_time_s", t.lean_time);
      j.boolean("toppled", top0.y() - top.p.y() > 0.5);
    }
  } else if (kind == "rain") {
    int escaped = 0, overlapping = 0;
    double max_top = -1e30, max_speed = 0, sum_speed = 0, max_boundary = 0, max_pen = 0, sum_pen = 0;
    std::vector<std::pair<State, double>> circles;
    for (size_t i = 0; i < w.bodies.size(); ++i) {
      if (w.bodies[i].is_static) continue;
      const State s = stateOf(w, static_cast<int>(i));
      const double r = w.bodies[i].r;
      if (!(s.p.x() > w.cont_min_x && s.p.x() < w.cont_max_x && s.p.y() > w.cont_floor)) ++escaped;
      max_boundary = std::max({max_boundary, w.cont_min_x - (s.p.x() - r), (s.p.x() + r) - w.cont_max_x,
                               w.cont_floor - (s.p.y() - r)});
      max_top = std::max(max_top, s.p.y() + r);
      max_speed = std::max(max_speed, s.v.norm());
      sum_speed += s.v.norm();
      circles.push_back({s, r});
    }
    // Pairwise overlap, sorted by x so only neighbours within 1 m (the largest diameter) are tested.
    std::sort(circles.begin(), circles.end(), [](const auto& a, const auto& b) { return a.first.p.x() < b.first.p.x(); });
    for (size_t i = 0; i < circles.size(); ++i) {
      for (size_t k = i + 1; k < circles.size() && circles[k].first.p.x() - circles[i].first.p.x() < 1.0; ++k) {
        const double pen = circles[i].second + circles[k].second - (circles[k].first.p - circles[i].first.p).norm();
        if (pen > 0) {
          max_pen = std::max(max_pen, pen);
          sum_pen += pen;
          ++overlapping;
        }
      }
    }
    j.integer("escaped", escaped);
    j.num("pile_top_m", max_top);
    j.num("mean_speed_mps", sum_speed / std::max(1, dynamic));
    j.num("max_speed_mps", max_speed);
    j.num("max_boundary_overlap_m", max_boundary);
    j.integer("overlapping_pairs", overlapping);
    j.num("max_overlap_m", max_pen);
    j.num("mean_overlap_m", overlapping ? sum_pen / overlapping : 0.0);
  } else if (kind == "massratio") {
    const BenchBody &bd = w.bodies[w.bottom], &td = w.bodies[w.top];
    const State bs = stateOf(w, w.bottom), ts = stateOf(w, w.top);
    double box_pen;
    const bool collapsed = massRatioCollapsed(bd, td, bs, ts, box_pen);
    j.num("top_mass_kg", w.get().body(td.id).mass);
    j.num("bottom_mass_kg", w.get().body(bd.id).mass);
    j.num("ground_penetration_m", 0.0 - boxBottom(bd, bs));
    j.num("box_box_penetration_m", box_pen);
    j.num("max_box_box_penetration_m", t.max_box_pen);
    j.num("max_ground_penetration_m", t.max_ground_pen);
    j.num("collapse_time_s", t.collapse_time);
    j.num("top_dx_m", ts.p.x() - td.start.x());
    j.num("top_height_loss_m", td.start.y() - ts.p.y());
    j.num("bottom_angle_rad", bs.angle);
    j.boolean("collapsed", collapsed);
  } else if (kind == "balls") {
    j.integer("impacts_located", t.impacts_located);
  } else if (kind == "bullet") {
    const State s = stateOf(w, w.top);
    const double r = w.bodies[w.top].r;
    const bool passed = s.p.x() - r > w.wall_x + w.wall_hx;
    j.boolean("passed_through", passed);
    j.num("final_x_m", s.p.x());
    j.num("final_vx_mps", s.v.x());
    j.num("vx_after_step1_mps", t.vx_after_first_step);
    j.num("wall_near_face_x_m", w.wall_x - w.wall_hx);
    j.integer("projectiles", 1);
    j.integer("passed_count", passed ? 1 : 0);
  }
  return j.done();
}

const std::vector<BenchScene>& benchScenes() {
  static const std::vector<BenchScene> scenes = [] {
    std::vector<BenchScene> v = {
      {"pyramid20", "pyramid", 20, "pyramid of 1 m boxes, base 20 (210 boxes), 500 steps", 500, 1.0 / 60.0, [] { return pyramid(20); }},
      {"pyramid40", "pyramid", 40, "pyramid, base 40 (820 boxes), 500 steps", 500, 1.0 / 60.0, [] { return pyramid(40); }},
      {"pyramid100", "pyramid", 100, "pyramid, base 100 (5050 boxes), 300 steps", 300, 1.0 / 60.0, [] { return pyramid(100); }},
      {"stack10", "stack", 10, "column of 10 boxes, 10 s", 600, 1.0 / 60.0, [] { return stack(10); }},
      {"stack20", "stack", 20, "column of 20 boxes, 10 s", 600, 1.0 / 60.0, [] { return stack(20); }},
      {"rain1000", "rain", 1000, "1000 circles dropped into a 40 m container, 600 steps", 600, 1.0 / 60.0, [] { return rain(1000); }},
      {"rain4000", "rain", 4000, "4000 circles dropped into a 40 m container, 600 steps", 600, 1.0 / 60.0, [] { return rain(4000); }},
      {"massratio", "massratio", 2, "a 100 kg box on a 1 kg box, 5 s", 300, 1.0 / 60.0, massRatio},
      {"bullet", "bullet", 1, "a 0.1 m disc at 500 m/s toward a 0.1 m wall, 1 s", 60, 1.0 / 60.0, bullet},
      {"balls100", "balls", 100, "100 balls bouncing apart (e = 0.8, dropped 1-2 m), 10 s", 600, 1.0 / 60.0, balls},
      {"springs", "springs", 1000, "1000 bodies on built-in springs, RK4, no contacts", 600, 1.0 / 60.0, builtinSprings},
      {"lua_springs", "lua_springs", 1000, "1000 bodies on Lua springs (forces.spring), RK4, no contacts", 600, 1.0 / 60.0,
       luaSprings},
    };
    for (int links : {1000, 10000}) {
      BenchScene chain{"chain" + std::to_string(links), "chain", links,
                       "chain of " + std::to_string(links) + " links (0.1 m, 1 kg) released horizontally, RK4, exact joints, 60 steps",
                       60, 1.0 / 60.0, [links] { return linkChain(links); }};
      chain.probe = probeChainGap;
      v.push_back(chain);
    }
    addSuiteScenes(v);
    addQueryScenes(v);
    addEventScenes(v);
    return v;
  }();
  return scenes;
}

}  // namespace rigidlab::app

// Stability cases with contacts (docs/design/accuracy.md §4: S7, S8, S10 and the stress cases of issue 5):
// mass ratios, a tall stack, a pyramid, fast bodies against a thin wall, deep overlaps, and scale.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "rigidlab/world.h"
#include "stability_cases.h"

namespace rigidlab::app::stability {
namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

BodyId box(World& w, double width, double height, Vec2 position, bool is_static = false,
           std::optional<double> mass = std::nullopt, double density = 1.0) {
  BodyDef d;
  d.type = is_static ? BodyType::Static : BodyType::Dynamic;
  d.shape = makeBox(width, height);
  d.position = position;
  d.mass = mass;
  d.density = density;
  return w.createBody(d);
}

// Deepest overlap among the current contact points [m] (0 if none overlaps).
double penetration(const World& w) {
  double p = 0;
  for (const ContactInfo& c : w.contacts())
    for (int i = 0; i < c.count; ++i) p = std::max(p, -c.separations[i]);
  return p;
}

double maxSpeed(const World& w) {
  double s = 0;
  for (const BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    if (!b.isStatic()) s = std::max(s, b.velocity.norm());
  }
  return s;
}

bool healthy(const World& w, const std::vector<BodyId>& dynamic) {
  for (const BodyId id : dynamic) {
    const Body& b = w.body(id);
    if (b.isStatic() || !isFinite(b.center) || !isFinite(b.velocity)) return false;
  }
  return true;
}

std::string yesNo(bool b) { return b ? "yes" : "no"; }

// Settings that the mass-ratio case compares: the defaults, each position correction the engine
// offers on top of the other defaults, and the thesis's original solver.
struct Setting {
  std::string name;
  WorldDef def;
};
std::vector<Setting> solverSettings() {
  std::vector<Setting> out;
  out.push_back({"default", WorldDef{}});
  WorldDef awake;
  awake.sleeping = false;
  out.push_back({"default, sleeping off", awake});
  for (int i = 0; i < 16; ++i) {
    const auto pc = static_cast<PositionCorrection>(i);
    const std::string_view name = positionCorrectionName(pc);
    if (name.empty()) break;
    if (pc == WorldDef{}.position_correction) continue;
    WorldDef d;
    d.position_correction = pc;
    out.push_back({"default + " + std::string(name), d});
  }
  WorldDef original;
  original.warm_starting = false;
  original.contact_displacement = false;
  original.position_correction = PositionCorrection::LinearProjection;
  out.push_back({"original (no warm start, no contact displacement, linear projection)", original});
  return out;
}

// Figures of a resting structure over a run: how far boxes moved, how fast, how deep.
struct RestFigures {
  double max_pen = 0, final_pen = 0;     // [m]
  double max_horizontal = 0;             // max |x − x0| of any box at any time [m]
  double top_drop_settled = 0;           // y of the top body at settle_time minus at the end [m]
  double top_drop_total = 0;             // y0 − y_end of the top body [m]
  double top_sink = 0;                   // y0 − the lowest y of the top body [m]
  double speed_after_settle = 0;         // max speed of any body after settle_time [m/s]
  double jitter_last_second = 0;         // max speed of any body in the last second [m/s]
  double max_angle = 0;                  // max |angle| of any body [rad]
  double first_drift_time = -1;          // [s] when a box first moved more than 1 cm sideways (−1: never)
  bool finite = true;
};

RestFigures runRest(World& w, const std::vector<BodyId>& bodies, BodyId top, double seconds, double settle_time = 2.0) {
  RestFigures f;
  std::vector<Vec2> start;
  for (const BodyId id : bodies) start.push_back(w.body(id).center);
  const double y0 = w.body(top).center.y();
  double y_settled = y0;
  const long steps = std::lround(seconds / kDt), settle = std::lround(settle_time / kDt), last = std::lround(1.0 / kDt);
  for (long n = 1; n <= steps; ++n) {
    w.step(kDt);
    if (!healthy(w, bodies)) {
      f.finite = false;
      break;
    }
    f.max_pen = std::max(f.max_pen, penetration(w));
    for (size_t i = 0; i < bodies.size(); ++i) {
      const Body& b = w.body(bodies[i]);
      f.max_horizontal = std::max(f.max_horizontal, std::abs(b.center.x() - start[i].x()));
      if (f.first_drift_time < 0 && f.max_horizontal > 0.01) f.first_drift_time = n * kDt;
      f.max_angle = std::max(f.max_angle, std::abs(b.angle));
    }
    f.top_sink = std::max(f.top_sink, y0 - w.body(top).center.y());
    if (n == settle) y_settled = w.body(top).center.y();
    if (n > settle) f.speed_after_settle = std::max(f.speed_after_settle, maxSpeed(w));
    if (n > steps - last) f.jitter_last_second = std::max(f.jitter_last_second, maxSpeed(w));
  }
  f.final_pen = penetration(w);
  f.top_drop_settled = y_settled - w.body(top).center.y();
  f.top_drop_total = y0 - w.body(top).center.y();
  return f;
}

}  // namespace

// S7: a light box under a heavy one on static ground.
CaseResult massRatio(const Options&) {
  CaseResult r;
  r.name = "mass_ratio";
  r.title = "Mass ratios: a 1 kg box under 1 kg to 1e6 kg (S7)";
  r.rule = "two 1×1 m boxes on static ground, the lower 1 kg, the upper 1 to 1e6 kg, 5 s at dt = 1/60. PASS if "
           "with default settings the 100:1 stack holds: penetration always under 1 cm, the top box does not sink "
           "(moves less than 1 mm after t = 2 s), bodies at rest (|v| < 1e-3 m/s after 2 s) and upright (|angle| < "
           "1e-3 rad); and if from 1000:1 to 1e6:1 the top box sinks at most 1 cm over the 5 s (its height at the "
           "start less its lowest height) with penetration always under 1 cm. The other settings are reported";
  Table t;
  t.title = "per setting and ratio";
  t.header = {"setting", "ratio", "max penetration [m]", "final penetration [m]", "sinking after 2 s [m]", "sink over 5 s [m]",
              "max |v| after 2 s [m/s]", "max |angle| [rad]", "holds"};
  bool pass = false, extreme_pass = true;
  DataFile data{"mass_ratio", {"setting", "ratio", "max_penetration", "final_penetration", "sinking_after_2s", "sink",
                               "max_speed_after_2s", "max_angle", "holds"}, {}};
  for (const Setting& s : solverSettings()) {
    for (double ratio : {1.0, 10.0, 100.0, 1000.0, 1e4, 1e5, 1e6}) {
      World w(s.def);
      box(w, 10, 1, Vec2(0, -0.5), true);
      const BodyId lower = box(w, 1, 1, Vec2(0, 0.5), false, 1.0);
      const BodyId upper = box(w, 1, 1, Vec2(0, 1.5), false, ratio);
      const RestFigures f = runRest(w, {lower, upper}, upper, 5.0);
      const bool holds = f.finite && f.max_pen < 0.01 && std::abs(f.top_drop_settled) < 1e-3 && f.speed_after_settle < 1e-3 &&
                         f.max_angle < 1e-3;
      t.rows.push_back({s.name, fmt(ratio) + ":1", fmt(f.max_pen), fmt(f.final_pen), fmt(f.top_drop_settled), fmt(f.top_sink),
                        fmt(f.speed_after_settle), fmt(f.max_angle), f.finite ? yesNo(holds) : "no (non-finite)"});
      data.rows.push_back({s.name, fmt(ratio, 10), fmt(f.max_pen, 10), fmt(f.final_pen, 10), fmt(f.top_drop_settled, 10),
                           fmt(f.top_sink, 10), fmt(f.speed_after_settle, 10), fmt(f.max_angle, 10),
                           f.finite ? yesNo(holds) : "no (non-finite)"});
      if (s.name == "default") {
        const std::string key = "ratio_" + fmt(ratio);
        r.figures.push_back({key + "_max_penetration", f.max_pen, "m", ""});
        r.figures.push_back({key + "_sinking_after_2s", f.top_drop_settled, "m", ""});
        r.figures.push_back({key + "_sink", f.top_sink, "m", ""});
        if (ratio >= 1000.0) {
          const bool ok = f.finite && f.top_sink <= 0.01 && f.max_pen < 0.01;
          extreme_pass &= ok;
          if (!ok)
            r.notes.push_back(fmt(ratio) + ":1 with default settings: sink " + fmt(f.top_sink) + " m, max penetration " +
                              fmt(f.max_pen) + " m" + (f.finite ? "" : ", non-finite"));
        }
        if (ratio == 100.0) {
          pass = holds;
          if (!holds)
            r.notes.push_back("100:1 with default settings: max penetration " + fmt(f.max_pen) + " m, sinking " +
                              fmt(f.top_drop_settled) + " m, max |v| after 2 s " + fmt(f.speed_after_settle) + " m/s");
        }
      }
    }
  }
  r.tables.push_back(t);
  r.pass = pass && extreme_pass;

  Picture p{.name = "mass_ratio", .data = "mass_ratio",
              .title = "A 1 kg box under a heavier one on the ground: sink over 5 s at dt = 1/60",
              .xlabel = "mass ratio (upper box : 1 kg)", .ylabel = "sink of the upper box [m]", .key = "inside left top"};
  static const char* const colors[] = {"#1f77b4", "#2ca02c", "#9467bd", "#d62728", "#ff7f0e", "#8c564b"};
  const std::vector<Setting> settings = solverSettings();
  for (size_t i = 0; i < settings.size(); ++i)
    p.series.push_back({settings[i].name, "ratio", "sink", {{"setting", settings[i].name}}, colors[i % std::size(colors)],
                        i == 0 ? 7 : 6 + 2 * static_cast<int>(i), true, i == 0 ? 1 : 2});
  p.marks.push_back({"gate: sink ≤ 1 cm from 1000:1 to 1e6:1 (default settings)", 0.01, false, 1000.0, 1e6, "#d62728"});
  r.data.push_back(std::move(data));
  r.pictures.push_back(std::move(p));
  return r;
}

namespace {

CaseResult standing(const std::string& name, const std::string& title, const std::string& what, bool quick,
                    const std::function<std::vector<BodyId>(World&)>& build) {
  CaseResult r;
  const double seconds = quick ? 5.0 : 30.0;
  r.name = name;
  r.title = title;
  r.rule = what + ", default settings, " + fmt(seconds) + " s at dt = 1/60. PASS if it stands: no box moves more than "
           "1 cm sideways, the top box sinks less than 1 mm after t = 2 s, and no box moves faster than 1 cm/s in the "
           "last second (jitter), with the default settings (sleeping on); the same figures with sleeping off are "
           "reported";
  const auto run = [&](bool sleeping) {
    WorldDef def;
    def.sleeping = sleeping;
    World w(def);
    box(w, 60, 1, Vec2(0, -0.5), true);
    const std::vector<BodyId> bodies = build(w);
    return runRest(w, bodies, bodies.back(), seconds);
  };
  const RestFigures f = run(true);
  // Sleeping bodies do not move at all, so the solver's own jitter shows only with sleeping off.
  const RestFigures awake = run(false);
  r.figures = {{"max_sideways_drift", f.max_horizontal, "m", ""},
               {"top_sinking_after_2s", f.top_drop_settled, "m", ""},
               {"top_drop_total", f.top_drop_total, "m", ""},
               {"jitter_last_second", f.jitter_last_second, "m/s", ""},
               {"max_penetration", f.max_pen, "m", ""},
               {"final_penetration", f.final_pen, "m", ""},
               {"max_angle", f.max_angle, "rad", ""},
               {"first_drift_over_1cm", f.first_drift_time < 0 ? kNaN : f.first_drift_time, "s",
                f.first_drift_time < 0 ? "never" : ""},
               {"sleeping_off_max_sideways_drift", awake.max_horizontal, "m", ""},
               {"sleeping_off_top_sinking_after_2s", awake.top_drop_settled, "m", ""},
               {"sleeping_off_jitter_last_second", awake.jitter_last_second, "m/s", ""},
               {"sleeping_off_max_penetration", awake.max_pen, "m", ""}};
  r.pass = f.finite && f.max_horizontal <= 0.01 && f.top_drop_settled < 1e-3 && f.jitter_last_second <= 0.01;
  if (!r.pass)
    r.notes.push_back("sideways drift " + fmt(f.max_horizontal) + " m, sinking after 2 s " + fmt(f.top_drop_settled) +
                      " m, jitter " + fmt(f.jitter_last_second) + " m/s" + (f.finite ? "" : ", non-finite state"));
  return r;
}

}  // namespace

CaseResult tallStack(const Options& options) {
  const bool quick = options.quick;
  return standing("tall_stack", "Tall stack of 20 boxes", "20 boxes of 1×1 m, 1 kg each, stacked on static ground", quick,
                  [](World& w) {
                    std::vector<BodyId> b;
                    for (int i = 0; i < 20; ++i) b.push_back(box(w, 1, 1, Vec2(0, 0.5 + i)));
                    return b;
                  });
}

CaseResult pyramid(const Options& options) {
  const bool quick = options.quick;
  return standing("pyramid", "Pyramid of base 20 (210 boxes)", "a pyramid of 210 boxes of 1×1 m (base 20) on static ground",
                  quick, [](World& w) {
                    std::vector<BodyId> b;
                    constexpr int base = 20;
                    for (int row = 0; row < base; ++row)
                      for (int i = 0; i < base - row; ++i)
                        b.push_back(box(w, 1, 1, Vec2((i - (base - row - 1) / 2.0) * 1.0, 0.5 + row)));
                    return b;
                  });
}

// S8: a small fast disc against a thin static wall.
CaseResult fastBodies(const Options&) {
  CaseResult r;
  r.name = "fast_bodies";
  r.title = "Fast bodies against a thin static wall (S8)";
  r.rule = "a disc of radius 0.1 m from x = 0.8 m at 100 and 500 m/s, no gravity, toward a static wall 0.1 m thick "
           "centred at x = 5 m, 0.5 s at dt = 1/60 (discrete detection is only sure up to 18 m/s). PASS if the disc's "
           "centre never gets past x = 5 m at either speed (default settings; with continuous collision off reported)";
  Table t;
  t.title = "per speed";
  t.header = {"speed [m/s]", "max x of the centre [m]", "final x [m]", "final vx [m/s]", "touched the wall", "passed through"};
  bool pass = true;
  for (const bool continuous : {true, false})
  for (double speed : {100.0, 500.0}) {
    WorldDef def;
    def.continuous = continuous;
    World w(def);
    w.setGravity(Vec2::Zero());
    box(w, 0.1, 2, Vec2(5, 0), true);
    BodyDef d;
    d.shape = makeCircle(0.1);
    d.position = Vec2(0.8, 0);
    d.velocity = Vec2(speed, 0);
    const BodyId disc = w.createBody(d);
    double max_x = 0.8;
    bool touched = false;
    for (int n = 0; n < 30; ++n) {
      w.step(kDt);
      max_x = std::max(max_x, w.body(disc).center.x());
      touched |= !w.contacts().empty();
    }
    const Body& b = w.body(disc);
    const bool through = !(max_x <= 5.0);
    t.rows.push_back({fmt(speed) + (continuous ? "" : " (continuous off, reported)"), fmt(max_x), fmt(b.center.x()),
                      fmt(b.velocity.x()), yesNo(touched), yesNo(through)});
    if (!continuous) continue;
    pass &= !through;
    r.figures.push_back({"max_x_at_" + fmt(speed), max_x, "m", ""});
    if (through) r.notes.push_back("at " + fmt(speed) + " m/s the disc tunnels through the wall (max x " + fmt(max_x) + " m)");
  }
  r.tables.push_back(t);
  r.pass = pass;
  return r;
}

// Boxes spawned overlapping by half must separate without being launched.
CaseResult deepOverlap(const Options&) {
  CaseResult r;
  r.name = "deep_overlap";
  r.title = "Deep overlap: boxes spawned half inside each other";
  r.rule = "1×1 m boxes on static ground, 3 s at dt = 1/60, in three set-ups: two boxes side by side overlapping by "
           "half their width; a box half sunk into the ground; three boxes stacked, each half inside the one below. "
           "PASS if in each the largest speed any box reaches stays at or below 3 m/s (Box2D's push-out speed "
           "limit) and the overlap left at the end is under 1 cm";
  Table t;
  t.title = "per set-up";
  t.header = {"set-up", "largest speed [m/s]", "final penetration [m]", "max displacement [m]"};
  bool pass = true;
  const std::vector<std::pair<std::string, std::function<std::vector<BodyId>(World&)>>> setups = {
      {"side by side", [](World& w) { return std::vector<BodyId>{box(w, 1, 1, Vec2(-0.25, 0.5)), box(w, 1, 1, Vec2(0.25, 0.5))}; }},
      {"half sunk into the ground", [](World& w) { return std::vector<BodyId>{box(w, 1, 1, Vec2(0, 0.0))}; }},
      {"stacked, half inside", [](World& w) {
         return std::vector<BodyId>{box(w, 1, 1, Vec2(0, 0.5)), box(w, 1, 1, Vec2(0, 1.0)), box(w, 1, 1, Vec2(0, 1.5))};
       }}};
  double worst_speed = 0;
  for (const auto& [setup, build] : setups)
  for (const bool sleeping : {true, false}) {
    const std::string name = setup + (sleeping ? "" : " (sleeping off, reported)");
    WorldDef def;
    def.sleeping = sleeping;
    World w(def);
    box(w, 20, 1, Vec2(0, -0.5), true);
    const std::vector<BodyId> bodies = build(w);
    std::vector<Vec2> start;
    for (const BodyId id : bodies) start.push_back(w.body(id).center);
    double speed = 0, moved = 0;
    bool finite = true;
    for (int n = 0; n < 180; ++n) {
      w.step(kDt);
      if (!healthy(w, bodies)) {
        finite = false;
        break;
      }
      speed = std::max(speed, maxSpeed(w));
      for (size_t i = 0; i < bodies.size(); ++i) moved = std::max(moved, (w.body(bodies[i]).center - start[i]).norm());
    }
    const double pen = penetration(w);
    const bool ok = finite && speed <= 3.0 && pen < 0.01;
    if (!sleeping) {
      t.rows.push_back({name, fmt(speed), fmt(pen), fmt(moved)});
      continue;
    }
    worst_speed = std::max(worst_speed, speed);
    pass &= ok;
    t.rows.push_back({name, fmt(speed), fmt(pen), fmt(moved)});
    if (!ok) r.notes.push_back(name + ": largest speed " + fmt(speed) + " m/s, final penetration " + fmt(pen) + " m" + (finite ? "" : ", non-finite"));
  }
  r.figures.push_back({"largest_speed", worst_speed, "m/s", ""});
  r.tables.push_back(t);
  r.pass = pass;
  return r;
}

// Small and large bodies, a density ratio of 1e6, and a scene far from the origin.
CaseResult scale(const Options& options) {
  const bool quick = options.quick;
  CaseResult r;
  r.name = "scale";
  r.title = "Scale: 1 cm and 1 km bodies, density ratio 1e6, 1e5 m from the origin (S10)";
  r.rule = "default settings, dt = 1/60. A 1 cm box and a 1 km box resting on static ground for 3 s: PASS if each ends "
           "resting (its height within 10 % of its size of the resting height, speed in the last second under 1 % of its size per second). A "
           "box of density 1 resting on one of density 1e6 (1×1 m), and the reverse: PASS if each holds (penetration "
           "under 1 cm, the upper box sinks at most 1 cm in 5 s, at rest after 2 s). A scene (stack, sliding box, disc on a spring) translated by "
           "(1e5, 1e5) m: PASS if every position, less the offset, matches the untranslated run to 1e-6 m over 5 s";
  Table t;
  t.title = "per set-up";
  t.header = {"set-up", "figure", "value", "pass"};
  bool pass = true;
  const auto resting = [&](const std::string& label, double size) {
    World w;
    box(w, 3 * size, size, Vec2(0, -size / 2), true);
    const BodyId b = box(w, size, size, Vec2(0, size / 2));
    double offset_end = 0, speed_last = 0;
    bool finite = true;
    for (int n = 1; n <= 180; ++n) {
      w.step(kDt);
      if (!healthy(w, {b})) {
        finite = false;
        break;
      }
      if (n > 120) speed_last = std::max(speed_last, w.body(b).velocity.norm());
    }
    offset_end = std::abs(w.body(b).center.y() - size / 2);  // resting means neither sunk nor lifted
    const bool ok = finite && offset_end < 0.1 * size && speed_last < 0.01 * size;
    pass &= ok;
    t.rows.push_back({label, "|height − resting height| at the end / size", fmt(offset_end / size), yesNo(ok)});
    t.rows.push_back({label, "max speed in the last second / size [1/s]", fmt(speed_last / size), ""});
    r.figures.push_back({label.substr(0, label.find(' ')) + "_offset_per_size", offset_end / size, "", ""});
  };
  resting("1cm box", 0.01);
  resting("1km box", 1000.0);

  for (const auto& [label, key, lower, upper] : {std::tuple{"density 1 on 1e6", "light_on_heavy", 1e6, 1.0},
                                                   std::tuple{"density 1e6 on 1", "heavy_on_light", 1.0, 1e6}}) {
    World w;
    box(w, 10, 1, Vec2(0, -0.5), true);
    const BodyId a = box(w, 1, 1, Vec2(0, 0.5), false, std::nullopt, lower);
    const BodyId b = box(w, 1, 1, Vec2(0, 1.5), false, std::nullopt, upper);
    const RestFigures f = runRest(w, {a, b}, b, 5.0);
    const bool ok = f.finite && f.max_pen < 0.01 && f.top_sink <= 0.01 && f.speed_after_settle < 1e-3;
    pass &= ok;
    t.rows.push_back({label, "max penetration [m]", fmt(f.max_pen), yesNo(ok)});
    t.rows.push_back({label, "sink of the upper box over 5 s [m]", fmt(f.top_sink), ""});
    t.rows.push_back({label, "max |v| after 2 s [m/s]", fmt(f.speed_after_settle), ""});
    r.figures.push_back({std::string(key) + "_max_penetration", f.max_pen, "m", ""});
    r.figures.push_back({std::string(key) + "_sink", f.top_sink, "m", ""});
  }

  // Translation invariance.
  const auto build = [](World& w, Vec2 o) {
    std::vector<BodyId> b;
    box(w, 20, 1, o + Vec2(0, -0.5), true);
    b.push_back(box(w, 1, 1, o + Vec2(0, 0.5)));
    b.push_back(box(w, 1, 1, o + Vec2(0, 1.5)));
    BodyDef s;
    s.shape = makeBox(0.5, 0.5);
    s.position = o + Vec2(-6, 0.25);
    s.velocity = Vec2(5, 0);
    b.push_back(w.createBody(s));
    BodyDef d;
    d.shape = makeCircle(0.3);
    d.position = o + Vec2(5, 3);
    b.push_back(w.createBody(d));
    SpringDef sp;
    sp.a = b.back();
    sp.anchor = o + Vec2(4, 5);
    sp.stiffness = 30;
    w.addSpring(sp);
    return b;
  };
  const Vec2 offset(1e5, 1e5);
  World near, far;
  const auto bn = build(near, Vec2::Zero()), bf = build(far, offset);
  double worst = 0;
  const long steps = quick ? 120 : 300;
  for (long n = 0; n < steps; ++n) {
    near.step(kDt);
    far.step(kDt);
    for (size_t i = 0; i < bn.size(); ++i)
      worst = std::max(worst, ((far.body(bf[i]).center - offset) - near.body(bn[i]).center).norm());
  }
  const bool same = worst <= 1e-6;
  pass &= same;
  t.rows.push_back({"translated by (1e5, 1e5) m", "max |Δposition| [m]", fmt(worst), yesNo(same)});
  r.figures.push_back({"translation_max_deviation", worst, "m", ""});
  r.tables.push_back(t);
  r.pass = pass;
  if (!pass) r.notes.push_back("see the table: a set-up marked 'no' failed");
  return r;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> list = {
      {"stiff_spring_thresholds", "largest stable k per integrator; textbook thresholds (S2–S4)", "", stiffSpringThresholds},
      {"stiff_spring_implicit", "k = 1e6 N/m at 60 Hz stays finite, energy never increasing (S1)", "", stiffSpringImplicit},
      {"damper_sign", "dampers never flip a velocity's sign, whatever b·dt/m (S5)", "", damperSign},
      {"damper_monotone", "dampers never make a speed grow, whatever b·dt/m (S5)", "", damperMonotone},
      {"critical_damper", "critically damped spring at ωh = 0.9 (S6)", "", criticalDamper},
      {"mass_ratio", "1 kg box under 1 kg to 1e6 kg (S7)", "", massRatio},
      {"tall_stack", "20 boxes standing: drift and jitter", "", tallStack},
      {"pyramid", "pyramid of base 20 standing: drift and jitter", "", pyramid},
      {"fast_bodies", "0.1 m disc at 100 and 500 m/s against a 0.1 m wall (S8)", "", fastBodies},
      {"deep_overlap", "boxes spawned half-overlapping separate without flying apart", "", deepOverlap},
      {"long_runs", "spring and Kepler orbit for 1e5 steps: energy drift and trend (S9)", "", longRuns},
      {"scale", "1 cm and 1 km bodies, density ratio 1e6, far from the origin (S10)", "", scale},
      {"frame_rate", "frame times 1/30, 1/60, 1/144 through the fixed-step loop (S11)", "", frameRate},
      {"joint_chain", "30 links of 0.5 m, 1 kg released horizontally: stretch, pin gaps", "", jointChain},
      {"joint_heavy_load", "100 kg box on 10 links of 1 kg (100:1): stretch", "", jointHeavyLoad},
      {"joint_whirl", "20-link chain whirled at 6 rad/s: stretch, pin gaps, energy", "", jointWhirl},
      {"joint_long_chains", "chains of 100 to 10 000 links released horizontally: pin gaps",
       "3000 and 10 000 links over 5 s (quick: 10 000 over 0.25 s); minutes", jointLongChains},
  };
  return list;
}

}  // namespace rigidlab::app::stability

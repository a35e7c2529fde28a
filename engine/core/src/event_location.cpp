// The step's time line: where inside a step something happens that the integrator must not step
// over, and the integration cut there (docs/design/thesis.md §13 future work: "RK4 with collision handling in
// its sub-steps"). Two kinds of event, one loop:
//   scheduled  a time-limited force ends (docs/design/thesis.md §6): known before the step, so every body's
//              step is split there and the force acts for exactly its duration. Without the split
//              every integrator, RK4 included, is first order on such forces (docs/design/accuracy.md §3.7).
//   located    an impact (WorldDef::impacts = Located, in the islands impact_rule.cpp picks): the
//              earliest time in an interval at which a pair's gap reaches zero, found on the
//              integrator's own dense output (dense_output.cpp), a kinematic body's along its
//              straight line (it moves at a constant velocity within the step), by a deterministic root search
//              (impact_search.cpp). The bodies of the islands involved are integrated again from
//              the start of their piece exactly to that time, the impact is resolved there with
//              every touching point of those bodies at once (impact_solve.cpp), and their
//              integration continues from it to the end of the interval; their other pairs are
//              searched again along the new piece. Without this, a step that ends within 2 cm of
//              a floor treats the contact as touching and the bounce is late by h − 2 (t_c − t_n):
//              collisions make any integrator first order (docs/design/accuracy.md §3.12).
// Every body is first integrated over the scheduled intervals exactly as before (so islands that
// are not located, piles and stacks, give the same bits); a located island without an impact keeps
// that result.
//
// What is not an event: a pair touching at the start of its window (resting or persistent contact,
// or a pair just resolved), which the contact solver handles at the end of the step; a pair
// resolved once in the step is not an event again in it (a bounce that ends in contact stays in
// contact; impact_solve.cpp turns approaches below the restitution threshold into resting contact,
// so a decaying bounce ends instead of bouncing ever more often). Impacts within 1e-12 of the
// interval of each other are simultaneous and resolved together, with every located body touching
// the bodies involved. At most kMaxImpactsPerStep impacts are located in a step; past that the rest
// of the step is left to the contact solver.
#include <algorithm>
#include <cmath>
#include <limits>

#include "impact.h"
#include "manifold.h"
#include "mechanism_step.h"
#include "stages.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

constexpr int kMaxImpactsPerStep = 64;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

PathState stateOf(const Body& b) { return {b.center, b.angle, b.velocity, b.angular_velocity}; }

void restore(Body& b, const PathState& s) {
  b.center = s.c;
  b.angle = s.a;
  b.velocity = s.v;
  b.angular_velocity = s.w;
  WorldImpl::syncTransform(b);
}

uint64_t pairKey(uint32_t shape_a, uint32_t shape_b) { return uint64_t{shape_a} << 32 | shape_b; }

// The largest distance of the body's solid shapes from its centre of mass [m].
double reachOf(const WorldImpl& w, const Body& b) {
  double r = 0.0;
  for (ShapeId s : b.shapes)
    if (!w.shapes[s.index].sensor) r = std::max(r, maxExtent(w.shapes[s.index].geometry));
  return r + b.local_center.norm();
}

// One step's event loop over the located bodies.
class Timeline {
 public:
  explicit Timeline(WorldImpl& w) : w_(w), im_(w.impact) {}

  void run() {
    const size_t n = w_.bodies.size();
    im_.mask.assign(n, 0);
    im_.piece_start.resize(n);
    im_.path.resize(n);
    im_.reach.resize(n);
    im_.involved.assign(im_.mover_first.size() - 1, 0);
    im_.mover_t0.assign(im_.mover_first.size() - 1, 0.0);
    im_.resolved.clear();
    for (uint32_t i : im_.bodies) im_.reach[i] = reachOf(w_, w_.bodies[i]);
    collectObstacles();
    const bool single = im_.intervals.size() == 1;
    if (!single)
      for (uint32_t i : im_.bodies) restore(w_.bodies[i], {w_.start_center[i], w_.start_angle[i], w_.start_velocity[i],
                                                            w_.start_angular_velocity[i]});
    for (const ImpactScratch::Interval& interval : im_.intervals) {
      start_ = interval.start;
      t0_ = interval.t0;
      end_ = interval.t0 + interval.h;
      simultaneous_ = 1e-12 * interval.h;
      for (uint32_t m = 0; m + 1 < im_.mover_first.size(); ++m) {
        if (single) {
          // Integrated already by the pass over every body: the piece runs from the step's start.
          im_.mover_t0[m] = interval.t0;
          for (uint32_t i : bodiesOf(m)) {
            im_.piece_start[i] = {w_.start_center[i], w_.start_angle[i], w_.start_velocity[i], w_.start_angular_velocity[i]};
            makePathOf(i);
          }
        } else {
          startPiece(m, interval.t0);
        }
      }
      im_.pairs.clear();
      for (uint32_t i : im_.bodies) addPairs(i, [&](uint32_t j) { return j > i; });
      for (ImpactPair& p : im_.pairs) p.time = search(p);
      locate();
    }
    w_.stats.impact_searches += evaluations_;
  }

 private:
  struct Span {
    const uint32_t* first;
    const uint32_t* last;
    const uint32_t* begin() const { return first; }
    const uint32_t* end() const { return last; }
  };
  Span bodiesOf(uint32_t m) const {
    return {im_.mover_bodies.data() + im_.mover_first[m], im_.mover_bodies.data() + im_.mover_first[m + 1]};
  }
  int32_t moverOf(uint32_t body) const { return im_.located[body] ? im_.mover[body] : -1; }
  // Simulation time of a time t after the start of the step: the interval's own start time plus the
  // offset, so that a piece starting at the interval's start sees the forces the first pass saw.
  double clock(double t) const { return t == t0_ ? start_ : start_ + (t - t0_); }

  void makePathOf(uint32_t i) {
    const Body& b = w_.bodies[i];
    const uint32_t m = static_cast<uint32_t>(im_.mover[i]);
    const double scale = b.center.cwiseAbs().maxCoeff() + im_.reach[i];
    im_.path[i] = makePath(w_.def.integrator, im_.piece_start[i], stateOf(b), im_.mover_t0[m], end_ - im_.mover_t0[m],
                           im_.reach[i], touchTolerance(scale));
  }

  // Integrates the bodies of mover m from `from` to the end of the interval, as a new piece.
  void startPiece(uint32_t m, double from) {
    im_.mover_t0[m] = from;
    for (uint32_t i : bodiesOf(m)) {
      im_.piece_start[i] = stateOf(w_.bodies[i]);
      im_.mask[i] = 1;
    }
    if (end_ > from) integrateInterval(w_, clock(from), end_ - from, im_.mask.data());
    for (uint32_t i : bodiesOf(m)) {
      im_.mask[i] = 0;
      makePathOf(i);
    }
  }

  // Puts the bodies of mover m back at the start of their piece and integrates them to `to`.
  void advanceTo(uint32_t m, double to) {
    for (uint32_t i : bodiesOf(m)) {
      restore(w_.bodies[i], im_.piece_start[i]);
      im_.mask[i] = 1;
    }
    if (to > im_.mover_t0[m]) integrateInterval(w_, clock(im_.mover_t0[m]), to - im_.mover_t0[m], im_.mask.data());
    for (uint32_t i : bodiesOf(m)) im_.mask[i] = 0;
  }

  // The shapes the located bodies may hit besides one another's: static shapes where they are, and
  // kinematic shapes along their paths. A kinematic body moves by its velocity alone, constant over
  // the step (integrator.cpp moveKinematicBodies: c += h v, θ += h ω), so its path over the whole
  // step is the straight line c(t) = c₀ + t v, θ(t) = θ₀ + t ω, which explicit Euler's dense output
  // is exactly (dense_output.cpp). The impact rule needs nothing else: a kinematic body has infinite
  // mass (inv_mass = inv_inertia = 0), so impact_solve.cpp's relative velocity at the contact,
  // v_B + ω_B × r_B − v_A − ω_A × r_A, with the kinematic body's velocity and lever arm at the impact,
  // gives v' = v − (1 + e) ((v − v_k) · n) n and the friction rule of a static obstacle.
  void collectObstacles() {
    im_.obstacles.clear();
    im_.obstacle_boxes.clear();
    if (w_.kinematic_bodies > 0) {
      const double step = im_.intervals.back().t0 + im_.intervals.back().h;
      for (uint32_t k = 0; k < w_.bodies.size(); ++k) {
        if (!w_.isMovingKinematic(k)) continue;
        const Body& b = w_.bodies[k];
        const double reach = reachOf(w_, b);
        const PathState start{b.center, b.angle, b.velocity, b.angular_velocity};
        const PathState end{b.center + step * b.velocity, b.angle + step * b.angular_velocity, b.velocity,
                            b.angular_velocity};
        im_.path[k] = makePath(Integrator::ExplicitEuler, start, end, 0.0, step, reach,
                               touchTolerance(b.center.cwiseAbs().maxCoeff() + reach));
      }
    }
    for (uint32_t s = 0; s < w_.shapes.size(); ++s) {
      if (!w_.shape_alive[s] || w_.shapes[s].sensor) continue;
      const Body& b = w_.bodyOf(s);
      if (b.isDynamic() || !b.enabled) continue;
      im_.obstacles.push_back(s);
      const uint32_t k = w_.shapes[s].body.index;
      im_.obstacle_boxes.push_back(w_.isMovingKinematic(k) ? im_.path[k].box : computeAabb(w_.shapes[s].geometry, b.xf));
    }
  }

  void addPair(uint32_t s1, uint32_t s2) {
    if (!locatablePair(w_, s1, s2)) return;
    ImpactPair p;
    p.shape_a = std::min(s1, s2);
    p.shape_b = std::max(s1, s2);
    p.a = w_.shapes[p.shape_a].body.index;
    p.b = w_.shapes[p.shape_b].body.index;
    p.time = kInfinity;
    im_.pairs.push_back(p);
  }

  // The pairs of body i's shapes with the static and kinematic shapes and with the located bodies j that `take`
  // accepts, whose boxes along their pieces meet.
  template <typename Take>
  void addPairs(uint32_t i, Take take) {
    const Body& b = w_.bodies[i];
    const Aabb& box = im_.path[i].box;
    for (size_t k = 0; k < im_.obstacles.size(); ++k) {
      if (!box.overlaps(im_.obstacle_boxes[k])) continue;
      for (ShapeId s : b.shapes) addPair(s.index, im_.obstacles[k]);
    }
    for (uint32_t j : im_.bodies) {
      if (j == i || !take(j) || !box.overlaps(im_.path[j].box)) continue;
      for (ShapeId s : b.shapes)
        for (ShapeId t : w_.bodies[j].shapes) addPair(s.index, t.index);
    }
  }

  // A shape as the search sees it: a located body's along its path, unless `now` (placed where its
  // body is); a moving kinematic body's along its path; any other body's where it is.
  MovingShape moving(uint32_t shape, bool now) const {
    MovingShape m;
    const Body& b = w_.bodyOf(shape);
    m.shape = &w_.shapes[shape].geometry;
    m.local_center = b.local_center;
    m.fixed = b.xf;
    const uint32_t body = w_.shapes[shape].body.index;
    if (im_.located[body] ? !now : w_.isMovingKinematic(body)) m.path = &im_.path[body];
    return m;
  }

  // Where body `body` is at time t, the moment of an impact: a moving kinematic body along its path,
  // any other where it is (the involved located bodies have been integrated to t).
  void placeAt(uint32_t body, double t, Transform& xf, Vec2& center) const {
    const Body& b = w_.bodies[body];
    if (w_.isMovingKinematic(body)) {
      const BodyPath& path = im_.path[body];
      center = path.center(path.s(t));
      xf = transformAt(b.local_center, center, path.angle(path.s(t)));
      return;
    }
    xf = b.xf;
    center = b.center;
  }

  double scaleOf(const ImpactPair& p) const {
    return std::max(w_.bodies[p.a].center.cwiseAbs().maxCoeff(), w_.bodies[p.b].center.cwiseAbs().maxCoeff());
  }

  // The pair's earliest contact in what is left of the interval, or +∞.
  double search(const ImpactPair& p) {
    if (std::find(im_.resolved.begin(), im_.resolved.end(), pairKey(p.shape_a, p.shape_b)) != im_.resolved.end())
      return kInfinity;
    double t_lo = 0.0;
    for (uint32_t body : {p.a, p.b})
      if (im_.located[body]) t_lo = std::max(t_lo, im_.mover_t0[im_.mover[body]]);
    const MovingShape a = moving(p.shape_a, false), b = moving(p.shape_b, false);
    const double tolerance = touchTolerance(scaleOf(p));
    ++evaluations_;
    if (gapAt(a, b, t_lo) <= tolerance) return kInfinity;  // in contact: not an event
    if (const auto t = earliestContact(a, b, t_lo, end_, evaluations_)) return *t;
    // Touching (within the tolerance) just as the interval ends: the impact is now, not in the next
    // step, which would find the pair in contact and leave it to the contact solver.
    ++evaluations_;
    return gapAt(a, b, end_) <= tolerance ? end_ : kInfinity;
  }

  void involve(uint32_t m, double t) {
    if (im_.involved[m]) return;
    im_.involved[m] = 1;
    advanceTo(m, t);
  }
  bool isInvolved(uint32_t body) const {
    const int32_t m = moverOf(body);
    return m >= 0 && im_.involved[m];
  }

  void locate() {
    for (int impacts = 0; impacts < kMaxImpactsPerStep; ++impacts) {
      double t = kInfinity;
      for (const ImpactPair& p : im_.pairs) t = std::min(t, p.time);
      if (!(t < kInfinity)) return;
      // The movers of every pair touching now, integrated to the impact.
      for (const ImpactPair& p : im_.pairs)
        if (p.time <= t + simultaneous_)
          for (uint32_t body : {p.a, p.b})
            if (moverOf(body) >= 0) involve(static_cast<uint32_t>(moverOf(body)), t);
      // With the located bodies they touch at that moment.
      for (bool grown = true; grown;) {
        grown = false;
        for (const ImpactPair& p : im_.pairs) {
          const bool ia = isInvolved(p.a), ib = isInvolved(p.b);
          if (ia == ib || moverOf(ia ? p.b : p.a) < 0) continue;
          if (gapAt(moving(p.shape_a, ia), moving(p.shape_b, ib), t) > touchTolerance(scaleOf(p))) continue;
          involve(static_cast<uint32_t>(moverOf(ia ? p.b : p.a)), t);
          grown = true;
        }
      }
      resolve(t);
      // New pieces from the impact, and their pairs searched again.
      for (uint32_t m = 0; m < im_.involved.size(); ++m)
        if (im_.involved[m]) startPiece(m, t);
      size_t kept = 0;
      for (size_t k = 0; k < im_.pairs.size(); ++k)
        if (!isInvolved(im_.pairs[k].a) && !isInvolved(im_.pairs[k].b)) im_.pairs[kept++] = im_.pairs[k];
      im_.pairs.resize(kept);
      for (uint32_t i : im_.bodies)
        if (isInvolved(i)) addPairs(i, [&](uint32_t j) { return !isInvolved(j) || j > i; });
      for (size_t k = kept; k < im_.pairs.size(); ++k) im_.pairs[k].time = search(im_.pairs[k]);
      std::fill(im_.involved.begin(), im_.involved.end(), 0);
    }
  }

  // The impact at time t: every touching point of the involved bodies, solved together.
  void resolve(double t) {
    auto& points = im_.points;
    points.clear();
    const size_t first_log = im_.log.size();
    for (uint32_t k = 0; k < im_.pairs.size(); ++k) {
      ImpactPair& p = im_.pairs[k];
      const bool event = p.time <= t + simultaneous_;
      const bool in_a = isInvolved(p.a) || !w_.bodies[p.a].isDynamic(), in_b = isInvolved(p.b) || !w_.bodies[p.b].isDynamic();
      if (!in_a || !in_b) continue;
      const BodyShape &sa = w_.shapes[p.shape_a], &sb = w_.shapes[p.shape_b];
      Transform xa, xb;
      Vec2 ca, cb;
      placeAt(p.a, t, xa, ca);
      placeAt(p.b, t, xb, cb);
      const double tolerance = touchTolerance(scaleOf(p));
      const double gap = separationLowerBound(sa.geometry, xa, sb.geometry, xb);
      if (event) im_.resolved.push_back(pairKey(p.shape_a, p.shape_b));
      if (!event && gap > tolerance) continue;
      const Manifold m = collideShapes(sa.geometry, xa, sb.geometry, xb, std::max(gap, 0.0) + w_.def.contact_margin);
      if (m.count == 0) continue;
      double deepest = m.points[0].separation;
      for (int i = 1; i < m.count; ++i) deepest = std::min(deepest, m.points[i].separation);
      if (!event) im_.resolved.push_back(pairKey(p.shape_a, p.shape_b));
      LocatedImpact& log = im_.log.emplace_back();
      log.shape_a = p.shape_a;
      log.shape_b = p.shape_b;
      log.a = p.a;
      log.b = p.b;
      log.time = t;
      log.normal = m.normal;
      for (int i = 0; i < m.count; ++i) {
        if (m.points[i].separation > std::max(deepest, 0.0) + tolerance) continue;  // not touching yet
        ImpactPoint& q = points.emplace_back();
        q.a = p.a;
        q.b = p.b;
        q.normal = m.normal;
        q.ra = m.points[i].point - ca;
        q.rb = m.points[i].point - cb;
        q.restitution = std::max(sa.material.restitution, sb.material.restitution);
        q.friction = std::sqrt(sa.material.friction * sb.material.friction);
        q.static_friction = std::sqrt(sa.material.static_friction * sb.material.static_friction);
        q.pair = static_cast<uint32_t>(im_.log.size() - 1);
        log.points[log.count++] = m.points[i].point;
      }
    }
    resolveImpact(w_, points);
    for (size_t k = first_log; k < im_.log.size(); ++k) im_.log[k].separating = true;
    for (const ImpactPoint& q : points) {
      LocatedImpact& log = im_.log[q.pair];
      log.approach_speed = std::max(log.approach_speed, q.approach);
      log.normal_impulse += q.normal_impulse;
      log.tangent_impulse += q.tangent_impulse;
      const Body &a = w_.bodies[q.a], &b = w_.bodies[q.b];
      const Vec2 v = b.velocity + cross(b.angular_velocity, q.rb) - a.velocity - cross(a.angular_velocity, q.ra);
      if (!(v.dot(q.normal) > 0.0)) log.separating = false;
    }
    // Pairs that touched without an impulse (already parting) had no impact.
    size_t kept = first_log;
    for (size_t k = first_log; k < im_.log.size(); ++k)
      if (im_.log[k].normal_impulse > 0.0) im_.log[kept++] = im_.log[k];
    im_.log.resize(kept);
    w_.stats.impacts_located += static_cast<int>(kept - first_log);
  }

  WorldImpl& w_;
  ImpactScratch& im_;
  double start_ = 0.0, t0_ = 0.0;  // the current interval's start: simulation time, after the step began [s]
  double end_ = 0.0;           // of the current interval, after the start of the step [s]
  double simultaneous_ = 0.0;  // impacts this close in time are one [s]
  int evaluations_ = 0;
};

}  // namespace

void integrate(WorldImpl& w, const StepContext& ctx) {
  const double dt = ctx.dt;
  beginIntegration(w);
  chooseLocatedBodies(w);
  chooseMechanisms(w, ctx);
  // Scheduled events: the end times of forces that run out inside the step. Without a split the
  // interval is exactly dt (not t_end − t_begin, which rounds differently).
  const double t_begin = w.clock.t, eps = 1e-9 * dt;
  w.breakpoints.clear();
  for (const ForceEntry& f : w.forces)
    if (f.alive && f.expires_at > t_begin + eps && f.expires_at < t_begin + dt - eps) w.breakpoints.push_back(f.expires_at);
  std::sort(w.breakpoints.begin(), w.breakpoints.end());
  auto& intervals = w.impact.intervals;
  intervals.clear();
  double t = t_begin, done = 0.0;
  for (double stop : w.breakpoints) {
    if (stop - t <= eps) continue;
    integrateInterval(w, t, stop - t, nullptr);
    intervals.push_back({t, done, stop - t});
    done += stop - t;
    t = stop;
  }
  integrateInterval(w, t, dt - done, nullptr);
  intervals.push_back({t, done, dt - done});
  w.impact.log.clear();
  // Located events: the impacts of the located islands.
  if (!w.impact.bodies.empty()) Timeline(w).run();
  moveKinematicBodies(w, dt);
}

void settleLocatedContacts(WorldImpl& w) {
  const ImpactScratch& im = w.impact;
  if (im.bodies.empty()) return;
  // A located pair that is not touching at the end of the step: its impact, if it comes, is found
  // in the next step (a speculative contact would stop the bodies at the surface before it).
  for (size_t k = 0; k < w.contacts.size(); ++k) {
    const Contact& c = w.contacts[k];
    const bool la = im.located[c.a], lb = im.located[c.b];
    if (!(la || lb) || !(la || !w.bodies[c.a].isDynamic()) || !(lb || !w.bodies[c.b].isDynamic())) continue;
    if (!locatablePair(w, c.shape_a, c.shape_b)) continue;
    const double scale = std::max(w.bodies[c.a].center.cwiseAbs().maxCoeff(), w.bodies[c.b].center.cwiseAbs().maxCoeff());
    bool touching = false;
    for (int p = 0; p < c.count; ++p) touching |= c.points[p].separation <= touchTolerance(scale);
    if (!touching) w.contact_keys[k].disabled = true;
  }
  locatedImpactEvents(w);
}

}  // namespace rigidlab

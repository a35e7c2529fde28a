// Located impacts (WorldDef::impacts = Located): the pieces the step's event loop is made of.
//
//   impact_rule.cpp     which bodies get located impacts this step (the per-island rule)
//   dense_output.cpp    each integrator's own continuous extension of a step (BodyPath)
//   impact_search.cpp   the earliest time two shapes touch along their paths (a root of the gap)
//   impact_solve.cpp    the impulses of an impact, every touching point of the bodies at once
//   event_location.cpp  the step's time line: force end times and impacts, one loop for both
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "rigidlab/world.h"

namespace rigidlab {

struct WorldImpl;

// The motion of one body over a piece [t0, t0 + h] of a step, as the integrator's own dense output
// in s = (t − t0)/h ∈ [0, 1]: centre c(s) = p0 + p1 s + p2 s² + p3 s³, angle θ(s) likewise
// (dense_output.cpp says which polynomial each integrator gives). t0 is measured from the start of
// the step, so that times inside a step keep their precision late in a long run.
struct BodyPath {
  double t0 = 0.0, h = 0.0;
  Vec2 c[4] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  double a[4] = {0.0, 0.0, 0.0, 0.0};
  // Bound on how fast any point of the body moves, per unit of s: max |c'(s)| + reach · max |θ'(s)|
  // over [0, 1], from the Bernstein coefficients of the derivatives (a polynomial lies in the hull of
  // its Bernstein coefficients). reach: the largest distance of the body's solid shapes from its
  // centre of mass.
  double speed = 0.0;
  Aabb box;  // holds every shape of the body along the whole piece

  double s(double t) const { return h > 0.0 ? (t - t0) / h : 1.0; }
  Vec2 center(double s) const { return c[0] + s * (c[1] + s * (c[2] + s * c[3])); }
  double angle(double s) const { return a[0] + s * (a[1] + s * (a[2] + s * a[3])); }
  Vec2 velocity(double s) const { return (c[1] + s * (2.0 * c[2] + 3.0 * s * c[3])) / h; }
  double angularVelocity(double s) const { return (a[1] + s * (2.0 * a[2] + 3.0 * s * a[3])) / h; }
};

// A body's state: centre of mass, angle, velocity, angular velocity.
struct PathState {
  Vec2 c = Vec2::Zero();
  double a = 0.0;
  Vec2 v = Vec2::Zero();
  double w = 0.0;
};

// The dense output of `integrator` for a piece that went from `start` to `end` in time h, starting
// t0 after the step began; reach as in BodyPath::speed, margin added around the box.
BodyPath makePath(Integrator integrator, const PathState& start, const PathState& end, double t0, double h,
                  double reach, double margin);

// The transform of a body (local centre of mass `local_center`) at centre c and angle θ.
inline Transform transformAt(const Vec2& local_center, const Vec2& c, double angle) {
  Transform xf{Vec2::Zero(), Rot::fromAngle(angle)};
  xf.p = c - xf.q.apply(local_center);
  return xf;
}

// A shape on the move for the search: its geometry and its body's path (nullptr: the body does not
// move during the step, and `fixed` places it). A moving kinematic body's path is its straight line
// over the whole step (t0 = 0).
struct MovingShape {
  const Shape* shape = nullptr;
  const BodyPath* path = nullptr;
  Vec2 local_center = Vec2::Zero();
  Transform fixed;
  Transform at(double t) const;
};

// Gap within which two shapes count as touching [m]: 1e-9 m, widened far from the origin where a
// coordinate's last bits are worth more (64 units in the last place of `scale`, the largest
// coordinate involved).
double touchTolerance(double scale);

// The earliest time in [t_lo, t_hi] at which the two shapes touch (gap ≤ 0), given that they do not
// at t_lo; none if they do not touch before t_hi. `evaluations` counts the gap evaluations.
std::optional<double> earliestContact(const MovingShape& a, const MovingShape& b, double t_lo, double t_hi,
                                      int& evaluations);

// The gap between the two shapes at time t (separationLowerBound: exact with a circle, the
// separating-axis separation of two polygons; its sign is exact).
double gapAt(const MovingShape& a, const MovingShape& b, double t);

// One contact point of an impact: the bodies' slots, the point's normal (unit, A → B) and its lever
// arms from the centres of mass, and the pair's combined material.
struct ImpactPoint {
  uint32_t a = 0, b = 0;
  Vec2 normal = Vec2::Zero();
  Vec2 ra = Vec2::Zero(), rb = Vec2::Zero();
  double restitution = 0.0, friction = 0.0, static_friction = 0.0;
  uint32_t pair = 0;  // index of the pair it belongs to (for reports)
  // Solved: the closing speed before the impact (−v_n, > 0 approaching) and the impulses [N·s].
  double approach = 0.0, normal_impulse = 0.0, tangent_impulse = 0.0;
  // Working values of the solve: effective masses, the target normal velocity, the friction used.
  double normal_mass = 0.0, tangent_mass = 0.0, target = 0.0, mu = 0.0;
};

// Resolves an impact (impact_solve.cpp): changes the velocities of the bodies of `points` so that
// every point ends with v_n' ≥ −e v_n (Newton's law where the approach is faster than the
// restitution threshold, v_n' ≥ 0 otherwise) with normal impulses ≥ 0, and friction impulses within
// the Coulomb cone μ P_n, all points at once.
void resolveImpact(WorldImpl& w, std::vector<ImpactPoint>& points);

// An impact located in the step, for the contact events and the stats.
struct LocatedImpact {
  uint32_t shape_a = 0, shape_b = 0, a = 0, b = 0;  // slots; shape_a < shape_b
  double time = 0.0;          // after the start of the step [s]
  Vec2 normal = Vec2::Zero();
  int count = 0;
  Vec2 points[2] = {Vec2::Zero(), Vec2::Zero()};
  double approach_speed = 0.0;  // closing speed at the impact [m/s]
  double normal_impulse = 0.0, tangent_impulse = 0.0;
  bool separating = false;      // the shapes move apart after it (a bounce), not into resting contact
};

// A pair the event loop watches: a shape of a located body and a static or kinematic shape or a
// shape of another located body.
struct ImpactPair {
  uint32_t shape_a = 0, shape_b = 0;  // slots, shape_a < shape_b
  uint32_t a = 0, b = 0;              // body slots of shape_a and shape_b
  double time = 0.0;                  // its earliest contact in the current interval, or +∞
};

// The event loop's state, reused from step to step (WorldImpl::impact).
struct ImpactScratch {
  std::vector<char> located;        // per body slot: its impacts are located this step
  std::vector<uint32_t> bodies;     // the located slots, ascending
  std::vector<int32_t> mover;       // per body slot: its mover (bodies integrated together), or −1
  std::vector<uint32_t> mover_first;  // per mover: where its bodies start in mover_bodies (+ end)
  std::vector<uint32_t> mover_bodies;
  std::vector<double> mover_t0;     // per mover: start of its current piece, after the step began [s]
  std::vector<char> mask;           // per body slot: integrate this one (integrateInterval)
  std::vector<PathState> piece_start;  // per body slot: state at the start of its current piece
  std::vector<BodyPath> path;       // per body slot: the located bodies' and the moving kinematic bodies'
  std::vector<double> reach;        // per body slot
  std::vector<uint32_t> obstacles;  // static and kinematic shape slots that may be hit
  std::vector<Aabb> obstacle_boxes; // where they are, along the step for a moving kinematic one
  std::vector<ImpactPair> pairs;
  std::vector<uint64_t> resolved;   // shape pairs resolved in this step: not events again in it
  std::vector<char> involved;       // per mover: takes part in the current impact
  std::vector<ImpactPoint> points;
  std::vector<LocatedImpact> log;   // this step's
  struct Interval {
    double start;  // simulation time at its start [s], as the integration of every body used it
    double t0, h;  // its start after the start of the step, and its length [s]
  };
  std::vector<Interval> intervals;  // the step cut at force end times
  // Union–find scratch of the rule (impact_rule.cpp).
  std::vector<uint32_t> parent, island_bodies;
  std::vector<char> island_blocked;
};

// impact_rule.cpp: fills located, bodies and the movers for this step (empty with PerStep).
void chooseLocatedBodies(WorldImpl& w);
// True if the shape pair may have located impacts (solid shapes that collide, no one-way or
// pre-solve flag: those decide per step).
bool locatablePair(const WorldImpl& w, uint32_t shape_a, uint32_t shape_b);

}  // namespace rigidlab

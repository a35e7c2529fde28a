// Distance between convex shapes: GJK (E. Gilbert, D. Johnson, S. Keerthi 1988) in the 2D form of
// E. Catto, "Computing Distance", GDC 2010 (Box2D's b2Distance), and the closest points of two
// segments (C. Ericson, Real-Time Collision Detection, 5.1.9). Pure functions, no allocation.
#pragma once

#include "rigidlab/math.h"

namespace rigidlab {

// A convex point set (the core of a shape: a circle's centre, a capsule's two ends, a polygon's
// corners) plus a radius. Both proxies of a query are in the same (world) frame.
struct DistanceProxy {
  const Vec2* points = nullptr;
  int count = 0;
  double radius = 0.0;
};

struct DistanceResult {
  Vec2 point_a = Vec2::Zero();  // closest point of A's core [m]
  Vec2 point_b = Vec2::Zero();  // closest point of B's core
  double distance = 0.0;        // between the cores, radii not subtracted; 0 if they overlap
  // The closest features: `simplex` points, each a pair of indices into A's and B's points. One:
  // a vertex of each; two: a vertex of one and an edge of the other (or an edge of each).
  int simplex = 0;
  int index_a[3] = {0, 0, 0}, index_b[3] = {0, 0, 0};
};

DistanceResult shapeDistance(const DistanceProxy& a, const DistanceProxy& b);

struct SegmentDistance {
  Vec2 closest1 = Vec2::Zero(), closest2 = Vec2::Zero();
  double fraction1 = 0.0, fraction2 = 0.0;  // along p1 → q1 and p2 → q2, in [0, 1]
  double distance_squared = 0.0;
};
// Closest points of the segments p1–q1 and p2–q2 (either may be a point).
SegmentDistance segmentDistance(const Vec2& p1, const Vec2& q1, const Vec2& p2, const Vec2& q2);

}  // namespace rigidlab

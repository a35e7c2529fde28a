// GJK distance and segment distance (distance.h).
//
// GJK searches the Minkowski difference B − A for its point closest to the origin with a simplex of
// one to three support points w = b_j − a_i. Each iteration (1) reduces the simplex to the smallest
// sub-simplex whose convex hull holds the point closest to the origin (Voronoi regions, solved with
// barycentric coordinates), (2) asks each shape for its support point along the search direction
// towards the origin, and (3) stops when the new point is already in the simplex (no progress: the
// closest point is found) or the simplex holds the origin (overlap).
#include "distance.h"

#include <algorithm>
#include <cmath>

namespace rigidlab {
namespace {

struct SimplexVertex {
  Vec2 wa, wb, w;  // support points of A and B, and w = wb − wa
  double a;        // barycentric coordinate of the closest point
  int ia, ib;
};

struct Simplex {
  SimplexVertex v[3];
  int count = 0;

  // Closest point to the origin on the segment v0–v1 (a region of the segment or an end).
  void solve2() {
    const Vec2 w1 = v[0].w, w2 = v[1].w, e12 = w2 - w1;
    const double d12_2 = -w1.dot(e12);  // w1 region: the origin is behind w1
    if (d12_2 <= 0.0) {
      v[0].a = 1.0;
      count = 1;
      return;
    }
    const double d12_1 = w2.dot(e12);  // w2 region
    if (d12_1 <= 0.0) {
      v[1].a = 1.0;
      count = 1;
      v[0] = v[1];
      return;
    }
    const double inv = 1.0 / (d12_1 + d12_2);
    v[0].a = d12_1 * inv;
    v[1].a = d12_2 * inv;
    count = 2;
  }

  // The same on the triangle v0 v1 v2: vertex, edge or inside regions.
  void solve3() {
    const Vec2 w1 = v[0].w, w2 = v[1].w, w3 = v[2].w;
    const Vec2 e12 = w2 - w1, e13 = w3 - w1, e23 = w3 - w2;
    const double d12_1 = w2.dot(e12), d12_2 = -w1.dot(e12);
    const double d13_1 = w3.dot(e13), d13_2 = -w1.dot(e13);
    const double d23_1 = w3.dot(e23), d23_2 = -w2.dot(e23);
    const double n123 = cross(e12, e13);
    const double d123_1 = n123 * cross(w2, w3), d123_2 = n123 * cross(w3, w1), d123_3 = n123 * cross(w1, w2);
    if (d12_2 <= 0.0 && d13_2 <= 0.0) {  // w1
      v[0].a = 1.0;
      count = 1;
    } else if (d12_1 > 0.0 && d12_2 > 0.0 && d123_3 <= 0.0) {  // e12
      const double inv = 1.0 / (d12_1 + d12_2);
      v[0].a = d12_1 * inv;
      v[1].a = d12_2 * inv;
      count = 2;
    } else if (d13_1 > 0.0 && d13_2 > 0.0 && d123_2 <= 0.0) {  // e13
      const double inv = 1.0 / (d13_1 + d13_2);
      v[0].a = d13_1 * inv;
      v[2].a = d13_2 * inv;
      count = 2;
      v[1] = v[2];
    } else if (d12_1 <= 0.0 && d23_2 <= 0.0) {  // w2
      v[1].a = 1.0;
      count = 1;
      v[0] = v[1];
    } else if (d13_1 <= 0.0 && d23_1 <= 0.0) {  // w3
      v[2].a = 1.0;
      count = 1;
      v[0] = v[2];
    } else if (d23_1 > 0.0 && d23_2 > 0.0 && d123_1 <= 0.0) {  // e23
      const double inv = 1.0 / (d23_1 + d23_2);
      v[1].a = d23_1 * inv;
      v[2].a = d23_2 * inv;
      count = 2;
      v[0] = v[2];
    } else {  // inside: the shapes overlap
      const double inv = 1.0 / (d123_1 + d123_2 + d123_3);
      v[0].a = d123_1 * inv;
      v[1].a = d123_2 * inv;
      v[2].a = d123_3 * inv;
      count = 3;
    }
  }

  // Towards the origin from the simplex.
  Vec2 searchDirection() const {
    if (count == 1) return -v[0].w;
    const Vec2 e12 = v[1].w - v[0].w;
    return cross(e12, -v[0].w) > 0.0 ? cross(1.0, e12) : cross(e12, 1.0);  // the side the origin is on
  }
};

int support(const DistanceProxy& p, const Vec2& d) {
  int best = 0;
  double value = p.points[0].dot(d);
  for (int i = 1; i < p.count; ++i) {
    const double x = p.points[i].dot(d);
    if (x > value) {
      best = i;
      value = x;
    }
  }
  return best;
}

}  // namespace

DistanceResult shapeDistance(const DistanceProxy& a, const DistanceProxy& b) {
  Simplex s;
  s.count = 1;
  s.v[0] = {a.points[0], b.points[0], b.points[0] - a.points[0], 1.0, 0, 0};
  constexpr int kMaxIterations = 30;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    int saved_a[3], saved_b[3];
    const int saved = s.count;
    for (int i = 0; i < saved; ++i) {
      saved_a[i] = s.v[i].ia;
      saved_b[i] = s.v[i].ib;
    }
    if (s.count == 2) s.solve2();
    if (s.count == 3) s.solve3();
    if (s.count == 3) break;  // the origin is inside: overlap
    const Vec2 d = s.searchDirection();
    if (d.squaredNorm() < 1e-300) break;  // the origin is on the simplex: touching
    SimplexVertex& nv = s.v[s.count];
    nv.ia = support(a, -d);
    nv.ib = support(b, d);
    nv.wa = a.points[nv.ia];
    nv.wb = b.points[nv.ib];
    nv.w = nv.wb - nv.wa;
    nv.a = 0.0;
    bool duplicate = false;  // no progress: the closest point is found
    for (int i = 0; i < saved; ++i)
      if (nv.ia == saved_a[i] && nv.ib == saved_b[i]) duplicate = true;
    if (duplicate) break;
    ++s.count;
  }
  DistanceResult r;
  r.simplex = s.count;
  for (int i = 0; i < s.count; ++i) {
    r.point_a += s.v[i].a * s.v[i].wa;
    r.point_b += s.v[i].a * s.v[i].wb;
    r.index_a[i] = s.v[i].ia;
    r.index_b[i] = s.v[i].ib;
  }
  if (s.count == 3) {
    r.point_b = r.point_a;
    r.distance = 0.0;
  } else {
    r.distance = (r.point_b - r.point_a).norm();
  }
  return r;
}

SegmentDistance segmentDistance(const Vec2& p1, const Vec2& q1, const Vec2& p2, const Vec2& q2) {
  SegmentDistance r;
  const Vec2 d1 = q1 - p1, d2 = q2 - p2, rr = p1 - p2;
  const double dd1 = d1.dot(d1), dd2 = d2.dot(d2), rd1 = rr.dot(d1), rd2 = rr.dot(d2);
  constexpr double kEpsSqr = 1e-30;
  double f1 = 0.0, f2 = 0.0;
  if (dd1 < kEpsSqr || dd2 < kEpsSqr) {
    if (dd1 >= kEpsSqr) f1 = std::clamp(-rd1 / dd1, 0.0, 1.0);  // segment 2 is a point
    if (dd2 >= kEpsSqr) f2 = std::clamp(rd2 / dd2, 0.0, 1.0);   // segment 1 is a point
  } else {
    const double d12 = d1.dot(d2), denom = dd1 * dd2 - d12 * d12;
    f1 = denom != 0.0 ? std::clamp((d12 * rd2 - rd1 * dd2) / denom, 0.0, 1.0) : 0.0;  // 0 when parallel
    f2 = (d12 * f1 + rd2) / dd2;
    // Clamping f2 moves the closest point of segment 2 to an end: find segment 1's again.
    if (f2 < 0.0) {
      f2 = 0.0;
      f1 = std::clamp(-rd1 / dd1, 0.0, 1.0);
    } else if (f2 > 1.0) {
      f2 = 1.0;
      f1 = std::clamp((d12 - rd1) / dd1, 0.0, 1.0);
    }
  }
  r.closest1 = p1 + f1 * d1;
  r.closest2 = p2 + f2 * d2;
  r.fraction1 = f1;
  r.fraction2 = f2;
  r.distance_squared = (r.closest2 - r.closest1).squaredNorm();
  return r;
}

}  // namespace rigidlab

// Queries on one placed shape (shape_query.h).
#include "shape_query.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "distance.h"

namespace rigidlab {
namespace {

// The ray against a circle of centre c and radius r: |p + t d − c| = r, the smaller root.
std::optional<ShapeRayHit> rayCircle(const Vec2& c, double r, const Vec2& p1, const Vec2& d, double max_fraction) {
  const Vec2 s = p1 - c;
  const double b = s.dot(d), cc = s.dot(s) - r * r, dd = d.dot(d);
  if (cc <= 0.0 || dd == 0.0) return std::nullopt;  // starts inside (or no direction)
  const double disc = b * b - dd * cc;
  if (disc < 0.0) return std::nullopt;
  const double t = (-b - std::sqrt(disc)) / dd;
  if (t < 0.0 || t > max_fraction) return std::nullopt;
  ShapeRayHit h;
  h.fraction = t;
  h.point = p1 + t * d;
  h.normal = (h.point - c).normalized();
  return h;
}

// The ray against a convex polygon (world vertices, counter-clockwise): the entering fraction of the
// clipped segment (Box2D's b2RayCastPolygon).
std::optional<ShapeRayHit> rayPolygon(const Vec2* v, const Vec2* n, int count, const Vec2& p1, const Vec2& d,
                                      double max_fraction) {
  double lower = 0.0, upper = max_fraction;
  int index = -1;
  for (int i = 0; i < count; ++i) {
    // p1 + t d is inside edge i where n · (p1 + t d − v) ≤ 0.
    const double numerator = n[i].dot(v[i] - p1), denominator = n[i].dot(d);
    if (denominator == 0.0) {
      if (numerator < 0.0) return std::nullopt;  // parallel and outside
    } else if (denominator < 0.0 && numerator < lower * denominator) {
      lower = numerator / denominator;  // entering
      index = i;
    } else if (denominator > 0.0 && numerator < upper * denominator) {
      upper = numerator / denominator;  // leaving
    }
    if (upper < lower) return std::nullopt;
  }
  if (index < 0) return std::nullopt;  // starts inside
  ShapeRayHit h;
  h.fraction = lower;
  h.point = p1 + lower * d;
  h.normal = n[index];
  return h;
}

// The ray against the segment a–b (two-sided unless `front_only`).
std::optional<ShapeRayHit> raySegment(const Vec2& a, const Vec2& b, bool front_only, const Vec2& p1, const Vec2& d,
                                      double max_fraction) {
  const Vec2 e = b - a;
  Vec2 normal = Vec2(e.y(), -e.x()).normalized();  // right of a → b: the front
  const double denominator = normal.dot(d);
  if (denominator == 0.0) return std::nullopt;
  if (front_only && denominator > 0.0) return std::nullopt;  // from behind
  const double t = normal.dot(a - p1) / denominator;
  if (t < 0.0 || t > max_fraction) return std::nullopt;
  const Vec2 q = p1 + t * d;
  const double s = (q - a).dot(e) / e.dot(e);
  if (s < 0.0 || s > 1.0) return std::nullopt;
  if (denominator > 0.0) normal = -normal;
  return ShapeRayHit{t, q, normal};
}

// The ray against a capsule: its two end discs and its two sides, the first hit of them.
std::optional<ShapeRayHit> rayCapsule(const Vec2& a, const Vec2& b, double r, const Vec2& p1, const Vec2& d,
                                      double max_fraction) {
  // Starting inside: no hit.
  const Vec2 e = b - a;
  const double s0 = std::clamp((p1 - a).dot(e) / e.dot(e), 0.0, 1.0);
  if ((p1 - (a + s0 * e)).squaredNorm() <= r * r) return std::nullopt;
  std::optional<ShapeRayHit> best;
  const auto take = [&](const std::optional<ShapeRayHit>& h) {
    if (h && (!best || h->fraction < best->fraction)) best = h;
  };
  take(rayCircle(a, r, p1, d, max_fraction));
  take(rayCircle(b, r, p1, d, max_fraction));
  const Vec2 side = Vec2(e.y(), -e.x()).normalized() * r;
  take(raySegment(a + side, b + side, true, p1, d, max_fraction));
  take(raySegment(b - side, a - side, true, p1, d, max_fraction));
  return best;
}

struct Core {
  Vec2 points[kMaxPolygonVertices];
  Vec2 normals[kMaxPolygonVertices];
  int count = 0;
  double radius = 0.0;
};

Core place(const Shape& s, const Transform& xf) {
  Core c;
  if (s.type == ShapeType::Circle) {
    c.points[0] = xf.apply(s.center);
    c.count = 1;
  } else {
    for (size_t i = 0; i < s.vertices.size(); ++i) {
      c.points[c.count] = xf.apply(s.vertices[i]);
      c.normals[c.count++] = xf.q.apply(s.normals[i]);
    }
  }
  c.radius = s.radius;
  return c;
}

}  // namespace

std::optional<ShapeRayHit> rayCastShape(const Shape& shape, const Transform& xf, const Vec2& p1, const Vec2& p2,
                                        double max_fraction) {
  const Vec2 d = p2 - p1;
  const Core c = place(shape, xf);
  switch (shape.type) {
    case ShapeType::Circle: return rayCircle(c.points[0], shape.radius, p1, d, max_fraction);
    case ShapeType::Polygon: return rayPolygon(c.points, c.normals, c.count, p1, d, max_fraction);
    case ShapeType::Capsule: return rayCapsule(c.points[0], c.points[1], shape.radius, p1, d, max_fraction);
    case ShapeType::Segment: return raySegment(c.points[0], c.points[1], false, p1, d, max_fraction);
    case ShapeType::ChainSegment: return raySegment(c.points[0], c.points[1], true, p1, d, max_fraction);
  }
  return std::nullopt;
}

double shapeDistance(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, Vec2* on_a, Vec2* on_b) {
  const Core ca = place(a, xa), cb = place(b, xb);
  const DistanceResult r = rigidlab::shapeDistance({ca.points, ca.count, 0.0}, {cb.points, cb.count, 0.0});
  const double gap = r.distance - ca.radius - cb.radius;
  if (on_a || on_b) {
    const Vec2 u = r.distance > 1e-12 ? Vec2((r.point_b - r.point_a) / r.distance) : Vec2::Zero();
    if (on_a) *on_a = r.point_a + ca.radius * u;
    if (on_b) *on_b = r.point_b - cb.radius * u;
  }
  return std::max(gap, 0.0);
}

bool shapesOverlap(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  const Core ca = place(a, xa), cb = place(b, xb);
  const DistanceResult r = rigidlab::shapeDistance({ca.points, ca.count, 0.0}, {cb.points, cb.count, 0.0});
  return r.distance <= ca.radius + cb.radius;
}

std::optional<ShapeRayHit> shapeCastShape(const Shape& moving, const Transform& xf, const Vec2& translation,
                                          const Shape& target, const Transform& target_xf) {
  // Conservative advancement along the translation: the gap cannot close faster than |Δ| per unit
  // of t, so t may advance by gap / |Δ| (a translation has no rotation to bound).
  const double length = translation.norm();
  constexpr double kTarget = 1e-7;  // [m]: close enough to call it contact
  double t = 0.0;
  for (int iteration = 0; iteration < 64; ++iteration) {
    Transform at = xf;
    at.p += t * translation;
    Vec2 on_moving, on_target;
    const double gap = shapeDistance(moving, at, target, target_xf, &on_moving, &on_target);
    if (gap <= kTarget) {
      if (iteration == 0 && gap == 0.0) return ShapeRayHit{0.0, on_target, Vec2::Zero()};  // overlapping at the start
      ShapeRayHit h;
      h.fraction = t;
      h.point = on_target;
      const Vec2 n = on_moving - on_target;
      h.normal = n.norm() > 1e-12 ? Vec2(n.normalized()) : Vec2(-translation / length);
      return h;
    }
    if (length == 0.0) return std::nullopt;
    t += gap / length;
    if (t > 1.0) return std::nullopt;
  }
  return std::nullopt;
}

double projectedWidth(const Shape& shape, const Transform& xf, const Vec2& direction) {
  const Core c = place(shape, xf);
  const Vec2 p(-direction.y(), direction.x());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int i = 0; i < c.count; ++i) {
    lo = std::min(lo, p.dot(c.points[i]));
    hi = std::max(hi, p.dot(c.points[i]));
  }
  return hi - lo + 2.0 * c.radius;
}

}  // namespace rigidlab

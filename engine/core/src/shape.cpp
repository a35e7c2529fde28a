// Shape construction, validation and mass properties. See shape.h for the polygon input policy.
#include "rigidlab/portable_math.h"
#include "rigidlab/shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rigidlab/error.h"

namespace rigidlab {
namespace {

std::string vertexField(int index) { return "vertices[" + std::to_string(index + 1) + "]"; }  // 1-based, as in Lua

double computeExtent(const Shape& shape) {
  if (shape.type == ShapeType::Circle) return shape.center.norm() + shape.radius;
  double r = 0.0;
  for (const Vec2& v : shape.vertices) r = std::max(r, v.norm());
  return r + shape.radius;  // capsules: the rounding; 0 for the others
}

// Shapes are computed with the squares of their coordinates (lengths, normals, extents) and their
// moments of inertia with fourth powers: a size at which those overflow is refused, naming the
// input, rather than left to become ∞ or a zero normal (or refused later in other words).
bool squareFinite(const Vec2& v) { return isFinite(v) && std::isfinite(v.squaredNorm()); }

// The area and moment of inertia at density 1 must be finite: `field` and `value` are the size that
// made them overflow.
void requireFiniteMass(const Shape& s, const std::string& field, const std::string& value) {
  const MassData m = computeMass(s, 1.0);
  if (!std::isfinite(m.area) || !std::isfinite(m.inertia))
    throw InputError(field, field + " " + value + " makes the " + shapeTypeName(s.type) +
                                " too large: its area or moment of inertia overflows (area " + formatNumber(m.area) +
                                " m², moment of inertia " + formatNumber(m.inertia) + " m⁴)");
}

// A two-cornered shape (capsule, segment, chain segment): end points and the two side normals.
Shape makeTwoPoint(ShapeType type, const Vec2& a, const Vec2& b, double radius) {
  requireFinite("a", a);
  requireFinite("b", b);
  const Vec2 d = b - a;
  if (!squareFinite(d))
    throw InputError("b", "b is too far from a: the length from a = " + formatVec(a) + " to b = " + formatVec(b) +
                              " overflows");
  requireNearOrigin("a", a);
  requireNearOrigin("b", b);
  // The normal of a → b must be computable: a and b further apart than round-off of their size.
  const double size = std::max({a.norm(), b.norm(), 1e-300});
  if (!(d.norm() > 1e-9 * size))
    throw InputError("b", "b must differ from a, got a = " + formatVec(a) + " and b = " + formatVec(b));
  Shape s;
  s.type = type;
  s.radius = radius;
  s.vertices = {a, b};
  const Vec2 n = Vec2(d.y(), -d.x()).normalized();  // right of a → b
  s.normals = {n, -n};
  s.extent = computeExtent(s);
  s.inradius = radius;
  if (!std::isfinite(s.extent)) throw InputError("radius", "radius " + formatNumber(radius) + " puts the shape out of range");
  return s;
}

void computeNormals(Shape& s) {
  s.extent = computeExtent(s);
  const size_t n = s.vertices.size();
  s.normals.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec2 edge = s.vertices[(i + 1) % n] - s.vertices[i];
    s.normals[i] = Vec2(edge.y(), -edge.x()).normalized();  // right of a CCW edge = outward
  }
  const Vec2 centroid = computeMass(s, 1.0).center;
  s.inradius = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i) s.inradius = std::min(s.inradius, s.normals[i].dot(s.vertices[i] - centroid));
}

}  // namespace

void requireNearOrigin(const std::string& field, const Vec2& p) {
  if (!squareFinite(p))
    throw InputError(field, field + " " + formatVec(p) +
                                " is too far from the body's origin: its distance overflows (a shape's points "
                                "must lie within about 1e154 m of it)");
}

Shape makeCircle(double radius, const Vec2& center) {
  Shape s;
  s.type = ShapeType::Circle;
  s.radius = requirePositive("radius", radius);
  s.center = requireFinite("center", center);
  requireNearOrigin("center", s.center);
  s.extent = computeExtent(s);
  s.inradius = s.radius;
  requireFiniteMass(s, "radius", formatNumber(radius));
  if (!std::isfinite(s.extent)) throw InputError("center", "center " + formatVec(center) + " puts the circle out of range");
  return s;
}

Shape makePolygon(std::span<const Vec2> points) {
  const int n = static_cast<int>(points.size());
  if (n < 3) throw InputError("vertices", "vertices needs at least 3 points, got " + std::to_string(n));
  if (n > kMaxPolygonVertices)
    throw InputError("vertices", "vertices has " + std::to_string(n) + " points, at most " +
                                     std::to_string(kMaxPolygonVertices) + " are allowed");
  for (int i = 0; i < n; ++i) requireFinite(vertexField(i), points[i]);
  for (int i = 0; i < n; ++i) requireNearOrigin(vertexField(i), points[i]);

  // Tolerances scale with the polygon so that 1 cm and 1 km shapes are treated alike.
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (!squareFinite(hi - lo))
    throw InputError("vertices", "vertices span too far: the size of the outline from " + formatVec(lo) + " to " +
                                     formatVec(hi) + " overflows");
  const double extent = (hi - lo).norm();
  const double tol = 1e-9 * extent;

  // Merge duplicates, remembering each kept point's input index for error messages.
  std::vector<Vec2> v;
  std::vector<int> origin;
  for (int i = 0; i < n; ++i) {
    const bool dup = std::any_of(v.begin(), v.end(), [&](const Vec2& q) { return (q - points[i]).norm() <= tol; });
    if (!dup) {
      v.push_back(points[i]);
      origin.push_back(i);
    }
  }
  if (v.size() < 3)
    throw InputError("vertices", "vertices has only " + std::to_string(v.size()) +
                                     " distinct points, a polygon needs 3");

  // Enforce counter-clockwise order (positive signed area, docs/design/thesis.md §3).
  double area2 = 0.0;
  for (size_t i = 0; i < v.size(); ++i) area2 += cross(v[i] - v[0], v[(i + 1) % v.size()] - v[0]);
  if (area2 < 0) {
    std::reverse(v.begin(), v.end());
    std::reverse(origin.begin(), origin.end());
  }

  // Drop collinear points: a vertex within `tol` of the line through its neighbours.
  for (bool changed = true; changed && v.size() >= 3;) {
    changed = false;
    for (size_t i = 0; i < v.size(); ++i) {
      const Vec2& a = v[(i + v.size() - 1) % v.size()];
      const Vec2& b = v[i];
      const Vec2& c = v[(i + 1) % v.size()];
      const double len = (c - a).norm();
      if (len == 0.0 || std::abs(cross(c - a, b - a)) / len <= tol) {
        v.erase(v.begin() + static_cast<long>(i));
        origin.erase(origin.begin() + static_cast<long>(i));
        changed = true;
        break;
      }
    }
  }
  if (v.size() < 3) throw InputError("vertices", "vertices are collinear: the polygon has zero area");

  // Convexity: every corner must turn left, and the outline must go around exactly once.
  double turning = 0.0;
  const size_t m = v.size();
  for (size_t i = 0; i < m; ++i) {
    const Vec2 e0 = v[(i + 1) % m] - v[i];
    const Vec2 e1 = v[(i + 2) % m] - v[(i + 1) % m];
    const double c = cross(e0, e1);
    if (c <= 0) {
      const int bad = origin[(i + 1) % m];
      throw InputError(vertexField(bad), "polygon is not convex: it turns clockwise at " + vertexField(bad) + " " +
                                             formatVec(points[bad]) + " (split concave shapes into convex pieces)");
    }
    turning += portableAtan2(c, e0.dot(e1));
  }
  if (turning > 2.0 * std::numbers::pi + 1e-6)
    throw InputError("vertices", "polygon outline crosses itself (it winds around " +
                                     std::to_string(static_cast<int>(std::lround(turning / (2 * std::numbers::pi)))) +
                                     " times)");

  Shape s;
  s.type = ShapeType::Polygon;
  s.vertices = std::move(v);
  requireFiniteMass(s, "vertices", "spanning " + formatVec(lo) + " to " + formatVec(hi));
  computeNormals(s);
  return s;
}

Shape makeCapsule(const Vec2& a, const Vec2& b, double radius) {
  Shape s = makeTwoPoint(ShapeType::Capsule, a, b, requirePositive("radius", radius));
  requireFiniteMass(s, "radius", formatNumber(radius));
  return s;
}

Shape makeSegment(const Vec2& a, const Vec2& b) { return makeTwoPoint(ShapeType::Segment, a, b, 0.0); }

Shape makeChainSegment(const Vec2& ghost1, const Vec2& a, const Vec2& b, const Vec2& ghost2) {
  Shape s = makeTwoPoint(ShapeType::ChainSegment, a, b, 0.0);
  s.ghost1 = requireFinite("ghost1", ghost1);
  s.ghost2 = requireFinite("ghost2", ghost2);
  return s;
}

Shape transformShape(const Shape& shape, const Vec2& offset, double angle) {
  requireFinite("offset", offset);
  const Transform xf{offset, Rot::fromAngle(requireFinite("angle", angle))};
  Shape s = shape;
  s.center = xf.apply(shape.center);
  for (Vec2& v : s.vertices) v = xf.apply(v);
  for (Vec2& n : s.normals) n = xf.q.apply(n);
  s.ghost1 = xf.apply(shape.ghost1);
  s.ghost2 = xf.apply(shape.ghost2);
  s.extent = computeExtent(s);
  if (!squareFinite(s.center) || !std::all_of(s.vertices.begin(), s.vertices.end(), squareFinite) ||
      !std::isfinite(s.extent) || !std::isfinite(computeMass(s, 1.0).inertia))
    throw InputError("offset", "offset " + formatVec(offset) + " puts the shape out of range");
  return s;
}

const char* shapeTypeName(ShapeType t) {
  switch (t) {
    case ShapeType::Circle: return "circle";
    case ShapeType::Polygon: return "polygon";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::Segment: return "segment";
    case ShapeType::ChainSegment: return "chain_segment";
  }
  return "?";
}

bool shouldCollide(const Filter& a, const Filter& b) {
  if (a.group == b.group && a.group != 0) return a.group > 0;
  return (a.category & b.mask) != 0 && (b.category & a.mask) != 0;
}

Shape makeBox(double width, double height, const Vec2& center, double angle) {
  const double hx = 0.5 * requirePositive("width", width);
  const double hy = 0.5 * requirePositive("height", height);
  // A sliver thinner than this merges its corners in the polygon check (tolerance 1e-9 of the
  // extent): say which side is too thin instead of reporting two "distinct points".
  constexpr double kMinAspect = 1e-8;
  if (hx < kMinAspect * hy)
    throw InputError("width", "width must be at least " + formatNumber(kMinAspect) + " × height (" +
                                  formatNumber(height) + "), got " + formatNumber(width));
  if (hy < kMinAspect * hx)
    throw InputError("height", "height must be at least " + formatNumber(kMinAspect) + " × width (" +
                                   formatNumber(width) + "), got " + formatNumber(height));
  requireFinite("center", center);
  const Rot q = Rot::fromAngle(requireFinite("angle", angle));
  Shape s;
  s.type = ShapeType::Polygon;
  for (const Vec2& corner : {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)})
    s.vertices.push_back(center + q.apply(corner));
  // The longer side is the one that made it too large.
  const std::string side = width >= height ? "width" : "height";
  const double size = std::max(width, height);
  if (!std::all_of(s.vertices.begin(), s.vertices.end(), squareFinite))
    throw InputError(side, side + " " + formatNumber(size) + " makes the box too large: its corners' distances overflow");
  requireFiniteMass(s, side, formatNumber(size));
  computeNormals(s);
  return s;
}

MassData computeMass(const Shape& shape, double density) {
  MassData md;
  if (shape.type == ShapeType::Circle) {
    // Disc: A = πR², I = ½ m R² about its centre (docs/design/thesis.md §1).
    md.area = std::numbers::pi * shape.radius * shape.radius;
    md.mass = density * md.area;
    md.center = shape.center;
    md.inertia = 0.5 * md.mass * shape.radius * shape.radius;
    return md;
  }
  if (!hasArea(shape.type)) {  // segments: no area, no mass; the centre is the midpoint
    md.center = 0.5 * (shape.vertices[0] + shape.vertices[1]);
    return md;
  }
  if (shape.type == ShapeType::Capsule) {
    // A rectangle of length l and width 2r plus two half discs at its ends. About the centre:
    //   rectangle       m_r (l² + 4r²) / 12
    //   half discs      each ½ m_h r² about its flat side's middle; its centroid is 4r/(3π) from
    //                   there, so moving it to the capsule's centre (h = l/2 further) adds, both
    //                   together (m_c = 2 m_h): m_c (½ r² + h² + 2 h · 4r/(3π))
    const double r = shape.radius, l = (shape.vertices[1] - shape.vertices[0]).norm(), h = 0.5 * l;
    const double m_rect = density * 2.0 * r * l, m_disc = density * std::numbers::pi * r * r;
    const double lc = 4.0 * r / (3.0 * std::numbers::pi);
    md.area = 2.0 * r * l + std::numbers::pi * r * r;
    md.mass = m_rect + m_disc;
    md.center = 0.5 * (shape.vertices[0] + shape.vertices[1]);
    md.inertia = m_rect * (l * l + 4.0 * r * r) / 12.0 + m_disc * (0.5 * r * r + h * h + 2.0 * h * lc);
    return md;
  }
  // Polygon centroid (docs/design/thesis.md §3), summed relative to vertex 0 for precision far from the origin:
  //   A = ½ Σ (x_i y_{i+1} − x_{i+1} y_i)
  //   C = 1/(6A) Σ (p_i + p_{i+1}) (x_i y_{i+1} − x_{i+1} y_i)
  const std::vector<Vec2>& v = shape.vertices;
  const size_t n = v.size();
  const Vec2 ref = v[0];
  double area2 = 0.0;
  Vec2 c = Vec2::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 p0 = v[i] - ref, p1 = v[(i + 1) % n] - ref;
    const double w = cross(p0, p1);
    area2 += w;
    c += (p0 + p1) * w;
  }
  md.area = 0.5 * area2;
  md.center = ref + c / (3.0 * area2);  // 1/(6A) = 1/(3·2A)
  md.mass = density * md.area;
  // Inertia about the centroid (docs/design/thesis.md §3), p_i relative to the centroid:
  //   I = (m/6) Σ |p_{i+1} × p_i| (p_{i+1}·p_{i+1} + p_{i+1}·p_i + p_i·p_i) / Σ |p_{i+1} × p_i|
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 p0 = v[i] - md.center, p1 = v[(i + 1) % n] - md.center;
    const double w = std::abs(cross(p1, p0));
    num += w * (p1.dot(p1) + p1.dot(p0) + p0.dot(p0));
    den += w;
  }
  md.inertia = md.mass / 6.0 * num / den;
  return md;
}

Aabb computeAabb(const Shape& shape, const Transform& xf) {
  if (shape.type == ShapeType::Circle) {
    const Vec2 c = xf.apply(shape.center);
    const Vec2 r(shape.radius, shape.radius);
    return {c - r, c + r};
  }
  Aabb box{xf.apply(shape.vertices[0]), xf.apply(shape.vertices[0])};
  for (size_t i = 1; i < shape.vertices.size(); ++i) {
    const Vec2 p = xf.apply(shape.vertices[i]);
    box.lower = box.lower.cwiseMin(p);
    box.upper = box.upper.cwiseMax(p);
  }
  if (shape.radius > 0.0) {  // capsules
    box.lower -= Vec2::Constant(shape.radius);
    box.upper += Vec2::Constant(shape.radius);
  }
  return box;
}

bool containsPoint(const Shape& shape, const Transform& xf, const Vec2& p) {
  const Vec2 local = xf.applyInverse(p);
  if (shape.type == ShapeType::Circle) return (local - shape.center).norm() <= shape.radius;
  if (!hasArea(shape.type)) return false;
  if (shape.type == ShapeType::Capsule) {
    const Vec2 a = shape.vertices[0], d = shape.vertices[1] - a;
    const double t = std::clamp((local - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (local - (a + t * d)).norm() <= shape.radius;
  }
  const size_t n = shape.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = shape.vertices[i];
    const Vec2& b = shape.vertices[(i + 1) % n];
    if (cross(b - a, local - a) < 0) return false;
  }
  return true;
}

double maxExtent(const Shape& shape) { return shape.extent > 0.0 ? shape.extent : computeExtent(shape); }

}  // namespace rigidlab

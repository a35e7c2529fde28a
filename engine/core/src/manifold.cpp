// Narrow-phase contact generation. See manifold.h for conventions.
#include "manifold.h"

#include <algorithm>
#include <limits>

#include "distance.h"

namespace rigidlab {
namespace {

// Feature ids. Circle pairs use 0. Polygon–circle: the edge index (face region) or kVertexBit | the
// vertex index (corner region). Polygon–polygon: vertex of A | vertex of B << 8, the two vertices
// at the point's end of the reference and incident edges (Box2D v3's ids). They do not depend on
// which polygon gives the reference face: two boxes pressed face to face, whose separations along
// either face normal are equal but for a tilt, swap that role back and forth between steps, and
// ids that changed with it lost the point's warm start at every swap (measured: a pyramid of base
// 20 swapped on 1 % of its contact-steps; with those ids the top of large_pyramid at 4 sub-steps
// sank 9 % further, docs/performance.md).
constexpr uint32_t kVertexBit = 0x100;

uint32_t polygonId(int vertex_a, int vertex_b) {
  return static_cast<uint32_t>(vertex_a) | static_cast<uint32_t>(vertex_b) << 8;
}

int next(int i, size_t n) { return (i + 1) % static_cast<int>(n); }
int next(int i, int n) { return i + 1 == n ? 0 : i + 1; }

// Largest separation of `b` from an edge of `a`: for each edge normal of a, the distance of b's
// deepest vertex from that edge's line. Stops at the first axis that separates the shapes by more
// than `margin` (no contact then).
double findMaxSeparation(const WorldPolygon& a, const WorldPolygon& b, int& edge, double margin) {
  double best = -std::numeric_limits<double>::infinity();
  edge = 0;
  const auto consider = [&](int i, double si) {  // true: stop here
    if (si > best) {
      best = si;
      edge = i;
      return best > margin;
    }
    return false;
  };
  const Vec2* n = a.normals;
  if (a.count == 4 && n[2] == -n[0] && n[3] == -n[1]) {
    // A box (any quadrilateral with opposite sides parallel): the deepest vertex along −n is the
    // one furthest along n, so one walk over b gives all four axes, min(−d) being exactly −max(d).
    // Same values, same order, same early stop as the general loop below, for half the products:
    // this test is most of the narrow phase in a pile of boxes.
    const double n0x = n[0].x(), n0y = n[0].y(), n1x = n[1].x(), n1y = n[1].y();
    double lo0 = std::numeric_limits<double>::infinity(), lo1 = lo0, hi0 = -lo0, hi1 = -lo0;
    for (int j = 0; j < b.count; ++j) {
      const double d0 = n0x * b.vertices[j].x() + n0y * b.vertices[j].y();
      const double d1 = n1x * b.vertices[j].x() + n1y * b.vertices[j].y();
      lo0 = std::min(lo0, d0);
      hi0 = std::max(hi0, d0);
      lo1 = std::min(lo1, d1);
      hi1 = std::max(hi1, d1);
    }
    const auto offset = [&](int i) { return n[i].x() * a.vertices[i].x() + n[i].y() * a.vertices[i].y(); };
    if (consider(0, lo0 - offset(0)) || consider(1, lo1 - offset(1)) || consider(2, -hi0 - offset(2))) return best;
    consider(3, -hi1 - offset(3));
    return best;
  }
  for (int i = 0; i < a.count; ++i) {
    const double nx = n[i].x(), ny = n[i].y();
    double si = std::numeric_limits<double>::infinity();
    for (int j = 0; j < b.count; ++j) si = std::min(si, nx * b.vertices[j].x() + ny * b.vertices[j].y());
    if (consider(i, si - (nx * a.vertices[i].x() + ny * a.vertices[i].y()))) break;
  }
  return best;
}

// Two doubles side by side (GCC vector extensions: one SSE2 instruction on x86-64, NEON on
// AArch64). Each lane is computed as the scalar code computes it, so the results are the same bits.
typedef double Lanes2 __attribute__((vector_size(16)));
inline Lanes2 splat(double x) { return Lanes2{x, x}; }

// findMaxSeparation for two boxes (WorldPolygon::box), the same values without the early stop: the
// separations along a's normals 0 and 1 in one pair of lanes and along 2 and 3 (−0 and −1: the
// deepest corner along −n is the furthest along n) in the other, then the first largest. Stopping
// at the first separation above the margin only ever returned one above it too, and the caller
// then wants no more than that.
double boxMaxSeparation(const WorldPolygon& a, const WorldPolygon& b, int& edge) {
  const Vec2 *n = a.normals, *v = a.vertices;
  const Lanes2 nx{n[0].x(), n[1].x()}, ny{n[0].y(), n[1].y()};
  Lanes2 lo = splat(std::numeric_limits<double>::infinity()), hi = -lo;
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j) {
    const Lanes2 d = nx * splat(b.vertices[j].x()) + ny * splat(b.vertices[j].y());
    lo = d < lo ? d : lo;  // std::min(lo, d)
    hi = hi < d ? d : hi;  // std::max(hi, d)
  }
  const Lanes2 s01 = lo - (nx * Lanes2{v[0].x(), v[1].x()} + ny * Lanes2{v[0].y(), v[1].y()});
  const Lanes2 s23 = -hi - (Lanes2{n[2].x(), n[3].x()} * Lanes2{v[2].x(), v[3].x()} +
                            Lanes2{n[2].y(), n[3].y()} * Lanes2{v[2].y(), v[3].y()});
  const double s[4] = {s01[0], s01[1], s23[0], s23[1]};
  double best = -std::numeric_limits<double>::infinity();
  edge = 0;
#pragma GCC unroll 4
  for (int i = 0; i < 4; ++i)
    if (s[i] > best) {
      best = s[i];
      edge = i;
    }
  return best;
}

// Clips the segment p[0]–p[1] to the half-plane n·x ≤ offset; false if it lies wholly outside.
// Inlined: as a lambda GCC called it out of line, a few percent of a pile's narrow phase.
[[gnu::always_inline]] inline bool clipSegment(Vec2 p[2], const Vec2& plane_normal, double offset) {
  const double d0 = plane_normal.dot(p[0]) - offset, d1 = plane_normal.dot(p[1]) - offset;
  if (d0 > 0.0 && d1 > 0.0) return false;
  if (d0 > 0.0) p[0] = p[0] + (p[1] - p[0]) * (d0 / (d0 - d1));
  else if (d1 > 0.0) p[1] = p[1] + (p[0] - p[1]) * (d1 / (d1 - d0));
  return true;
}

Manifold toWorld(Manifold m, const Transform& xf) {
  m.normal = xf.q.apply(m.normal);
  for (int i = 0; i < m.count; ++i) m.points[i].point = xf.apply(m.points[i].point);
  return m;
}

}  // namespace

Manifold collideCircleCentres(const Vec2& ca, double ra, const Vec2& cb, double rb, double margin) {
  Manifold m;
  const Vec2 d = cb - ca;
  const double dist = d.norm();
  const double separation = dist - ra - rb;
  if (separation > margin) return m;
  // Contact on the line of centres (docs/design/thesis.md §7); coincident centres push apart along +y.
  m.normal = dist > 0.0 ? Vec2(d / dist) : Vec2(0.0, 1.0);
  const Vec2 pa = ca + ra * m.normal, pb = cb - rb * m.normal;
  m.points[0] = {0.5 * (pa + pb), separation, 0};
  m.count = 1;
  return m;
}

Manifold collideCircles(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double margin) {
  return collideCircleCentres(xa.apply(a.center), a.radius, xb.apply(b.center), b.radius, margin);
}

Manifold collidePolygonAndCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                                 double margin) {
  // Closest point of the polygon's boundary to the circle's centre (docs/design/thesis.md §7 ClosestEdgePoint),
  // in the polygon's frame.
  Manifold m;
  const Vec2 c = xa.applyInverse(xb.apply(b.center));
  const double r = b.radius;
  const size_t n = a.vertices.size();
  int edge = 0;
  double face_sep = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i) {
    const double s = a.normals[i].dot(c - a.vertices[i]);
    if (s > face_sep) {
      face_sep = s;
      edge = static_cast<int>(i);
    }
  }
  if (face_sep > r + margin) return m;

  const Vec2& v1 = a.vertices[edge];
  const Vec2& v2 = a.vertices[next(edge, n)];
  Vec2 normal = a.normals[edge];
  Vec2 on_polygon;  // closest boundary point
  uint32_t id = static_cast<uint32_t>(edge);
  if (face_sep > 0.0 && (c - v1).dot(v2 - v1) < 0.0) {  // corner region of v1
    on_polygon = v1;
    id = kVertexBit | static_cast<uint32_t>(edge);
  } else if (face_sep > 0.0 && (c - v2).dot(v1 - v2) < 0.0) {  // corner region of v2
    on_polygon = v2;
    id = kVertexBit | static_cast<uint32_t>(next(edge, n));
  } else {  // face region, or the centre is inside the polygon: push out through the nearest face
    on_polygon = c - face_sep * normal;
  }
  double separation;
  if (id & kVertexBit) {
    const Vec2 d = c - on_polygon;
    const double dist = d.norm();  // > 0: face_sep > 0 in a corner region
    separation = dist - r;
    if (separation > margin) return m;
    normal = d / dist;
  } else {
    separation = face_sep - r;
  }
  const Vec2 on_circle = c - r * normal;
  m.normal = normal;
  m.points[0] = {0.5 * (on_polygon + on_circle), separation, id};
  m.count = 1;
  return toWorld(m, xa);
}

Manifold collidePolygons(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double margin) {
  Vec2 va[kMaxPolygonVertices], na[kMaxPolygonVertices], vb[kMaxPolygonVertices], nb[kMaxPolygonVertices];
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    va[i] = xa.apply(a.vertices[i]);
    na[i] = xa.q.apply(a.normals[i]);
  }
  for (size_t i = 0; i < b.vertices.size(); ++i) {
    vb[i] = xb.apply(b.vertices[i]);
    nb[i] = xb.q.apply(b.normals[i]);
  }
  return collidePolygons(WorldPolygon{va, na, static_cast<int>(a.vertices.size()), false, maxExtent(a)},
                         WorldPolygon{vb, nb, static_cast<int>(b.vertices.size()), false, maxExtent(b)}, margin);
}

bool polygonAxes(const WorldPolygon& a, const WorldPolygon& b, double margin, PolygonAxes& axes) {
  int edge_a = 0, edge_b = 0;
  const bool boxes = a.box && b.box;
  const double sep_a = boxes ? boxMaxSeparation(a, b, edge_a) : findMaxSeparation(a, b, edge_a, margin);
  if (sep_a > margin) return false;
  const double sep_b = boxes ? boxMaxSeparation(b, a, edge_b) : findMaxSeparation(b, a, edge_b, margin);
  if (sep_b > margin) return false;

  // Reference face: the axis of least penetration, preferring A unless B's is clearly better, so
  // the choice does not flip between steps on nearly equal values (a flip would change feature ids).
  const double tol = 5e-4 * std::min(a.extent, b.extent);
  axes.flip = sep_b > sep_a + tol;
  const WorldPolygon& ref = axes.flip ? b : a;
  const WorldPolygon& inc = axes.flip ? a : b;
  axes.ref_edge = axes.flip ? edge_b : edge_a;

  // Incident edge: the edge of `inc` whose normal is most anti-parallel to the reference normal,
  // the first of equals. A box's normals 2 and 3 are those of 0 and 1 negated, and so are their
  // products with the reference normal: two products give all four.
  const Vec2& ref_normal = ref.normals[axes.ref_edge];
  int inc_edge = 0;
  double min_dot = std::numeric_limits<double>::infinity();
  const auto consider = [&](int i, double d) {
    if (d < min_dot) {
      min_dot = d;
      inc_edge = i;
    }
  };
  if (inc.box) {
    const double d0 = ref_normal.dot(inc.normals[0]), d1 = ref_normal.dot(inc.normals[1]);
    consider(0, d0);
    consider(1, d1);
    consider(2, -d0);
    consider(3, -d1);
  } else {
    for (int i = 0; i < inc.count; ++i) consider(i, ref_normal.dot(inc.normals[i]));
  }
  axes.inc_edge = inc_edge;
  return true;
}

void clipPolygons(const WorldPolygon& a, const WorldPolygon& b, const PolygonAxes& axes, const Vec2& tangent, double margin,
                  Manifold& m) {
  m.count = 0;
  const WorldPolygon& ref = axes.flip ? b : a;
  const WorldPolygon& inc = axes.flip ? a : b;
  const int ref_edge = axes.ref_edge, inc_edge = axes.inc_edge;
  // Clip the incident edge to the side planes of the reference edge.
  const Vec2& r1 = ref.vertices[ref_edge];
  const Vec2& r2 = ref.vertices[next(ref_edge, ref.count)];
  const Vec2 normal(tangent.y(), -tangent.x());  // outward for a counter-clockwise polygon
  Vec2 p[2] = {inc.vertices[inc_edge], inc.vertices[next(inc_edge, inc.count)]};
  if (!clipSegment(p, -tangent, -tangent.dot(r1)) || !clipSegment(p, tangent, tangent.dot(r2))) return;

  const double front = normal.dot(r1);
  m.normal = axes.flip ? Vec2(-normal) : normal;
  for (int slot = 0; slot < 2; ++slot) {
    const double separation = normal.dot(p[slot]) - front;
    if (separation <= margin) {
      // The incident edge runs against the reference edge: its start (slot 0) lies at the
      // reference edge's end, its end at the reference edge's start.
      const int ref_vertex = slot == 0 ? next(ref_edge, ref.count) : ref_edge;
      const int inc_vertex = slot == 0 ? inc_edge : next(inc_edge, inc.count);
      // Midway between the incident point and its projection on the reference face.
      m.points[m.count++] = {p[slot] - 0.5 * separation * normal, separation,
                             axes.flip ? polygonId(inc_vertex, ref_vertex) : polygonId(ref_vertex, inc_vertex)};
    }
  }
}

Manifold collidePolygons(const WorldPolygon& a, const WorldPolygon& b, double margin) {
  Manifold m;
  PolygonAxes axes;
  if (polygonAxes(a, b, margin, axes)) clipPolygons(a, b, axes, edgeDirection(axes.flip ? b : a, axes.ref_edge), margin, m);
  return m;
}

namespace {

// The core of a shape as GJK sees it (distance.h): points in world coordinates and a radius.
struct Core {
  Vec2 points[kMaxPolygonVertices];
  int count = 0;
  double radius = 0.0;
};

Core coreOf(const Shape& s, const Transform& xf) {
  Core c;
  if (s.type == ShapeType::Circle) {
    c.points[0] = xf.apply(s.center);
    c.count = 1;
  } else {
    for (const Vec2& v : s.vertices) c.points[c.count++] = xf.apply(v);
  }
  c.radius = s.radius;
  return c;
}

}  // namespace

double separationLowerBound(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  constexpr double kAll = std::numeric_limits<double>::infinity();
  const auto plain = [](const Shape& s) { return s.type == ShapeType::Circle || s.type == ShapeType::Polygon; };
  if (!plain(a) || !plain(b)) {
    // Capsules and segments: the exact distance of the cores less the radii.
    const Core ca = coreOf(a, xa), cb = coreOf(b, xb);
    return shapeDistance({ca.points, ca.count, 0.0}, {cb.points, cb.count, 0.0}).distance - ca.radius - cb.radius;
  }
  if (a.type == ShapeType::Polygon && b.type == ShapeType::Polygon) {
    Vec2 va[kMaxPolygonVertices], na[kMaxPolygonVertices], vb[kMaxPolygonVertices], nb[kMaxPolygonVertices];
    for (size_t i = 0; i < a.vertices.size(); ++i) {
      va[i] = xa.apply(a.vertices[i]);
      na[i] = xa.q.apply(a.normals[i]);
    }
    for (size_t i = 0; i < b.vertices.size(); ++i) {
      vb[i] = xb.apply(b.vertices[i]);
      nb[i] = xb.q.apply(b.normals[i]);
    }
    const WorldPolygon pa{va, na, static_cast<int>(a.vertices.size()), false, a.extent};
    const WorldPolygon pb{vb, nb, static_cast<int>(b.vertices.size()), false, b.extent};
    int edge;
    return std::max(findMaxSeparation(pa, pb, edge, kAll), findMaxSeparation(pb, pa, edge, kAll));
  }
  const Manifold m = collideShapes(a, xa, b, xb, kAll);  // with a circle: one point, the exact distance
  return m.count > 0 ? m.points[0].separation : kAll;
}

Manifold collideShapes(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double margin) {
  Vec2 va[kMaxPolygonVertices], na[kMaxPolygonVertices], vb[kMaxPolygonVertices], nb[kMaxPolygonVertices];
  const auto place = [](const Shape& s, const Transform& xf, Vec2* v, Vec2* n) {
    for (size_t i = 0; i < s.vertices.size(); ++i) {
      v[i] = xf.apply(s.vertices[i]);
      n[i] = xf.q.apply(s.normals[i]);
    }
    return PlacedShape{WorldPolygon{v, n, static_cast<int>(s.vertices.size()), false, maxExtent(s)}, &s, &xf};
  };
  return collide(place(a, xa, va, na), place(b, xb, vb, nb), margin);
}

// --- Dispatch on the two kinds.

namespace {

Manifold none(const PlacedShape&, const PlacedShape&, double) { return {}; }
Manifold circleCircle(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collideCircles(*a.shape, *a.xf, *b.shape, *b.xf, margin);
}
Manifold polygonCircle(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collidePolygonAndCircle(*a.shape, *a.xf, *b.shape, *b.xf, margin);
}
Manifold polygonPolygon(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collidePolygons(a.poly, b.poly, margin);
}
// a: capsule or segment (a rounded segment of radius a.shape->radius).
Manifold roundCircle(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collideSegmentAndCircle(a.poly.vertices[0], a.poly.vertices[1], a.shape->radius, b.xf->apply(b.shape->center),
                                 b.shape->radius, margin);
}
Manifold roundPolygon(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collideRoundPolygons(a.poly, a.shape->radius, b.poly, 0.0, margin);
}
Manifold roundRound(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collideRoundSegments(a.poly.vertices[0], a.poly.vertices[1], a.shape->radius, b.poly.vertices[0],
                              b.poly.vertices[1], b.shape->radius, margin);
}
// a: chain segment; b: circle, or polygon or capsule (a polygon rounded by its radius).
Manifold chainCircle(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collideChainAndCircle(a.xf->apply(a.shape->ghost1), a.poly.vertices[0], a.poly.vertices[1],
                               a.xf->apply(a.shape->ghost2), b.xf->apply(b.shape->center), b.shape->radius, margin);
}
Manifold chainPolygon(const PlacedShape& a, const PlacedShape& b, double margin) {
  return collideChainAndPolygon(a.xf->apply(a.shape->ghost1), a.poly.vertices[0], a.poly.vertices[1],
                                a.xf->apply(a.shape->ghost2), b.poly, b.shape->radius, margin);
}
// The pair the other way round: B against A, with the normal turned to point from A to B.
template <CollideFn F>
Manifold swapped(const PlacedShape& a, const PlacedShape& b, double margin) {
  Manifold m = F(b, a, margin);
  m.normal = -m.normal;
  return m;
}

}  // namespace

// Segments and chains belong to static or kinematic bodies, which do not collide with each other.
const CollideFn kCollideTable[kShapeTypes][kShapeTypes] = {
    //          circle                 polygon                capsule                segment              chain segment
    /* circle */ {circleCircle, swapped<polygonCircle>, swapped<roundCircle>, swapped<roundCircle>, swapped<chainCircle>},
    /* polygon*/ {polygonCircle, polygonPolygon, swapped<roundPolygon>, swapped<roundPolygon>, swapped<chainPolygon>},
    /* capsule*/ {roundCircle, roundPolygon, roundRound, roundRound, swapped<chainPolygon>},
    /* segment*/ {roundCircle, roundPolygon, roundRound, none, none},
    /* chain  */ {chainCircle, chainPolygon, chainPolygon, none, none},
};

}  // namespace rigidlab

// Narrow phase (docs/design/thesis.md §7): pure functions per shape pair. No world access, no allocation.
//
// A manifold holds up to two points. Its normal is a unit vector from shape A to shape B. Each
// point lies midway between the two surfaces and carries the separation along the normal
// (negative = penetration depth) and a feature id: the same id on consecutive steps means the same
// pair of features (edges, vertices) touch, so a solver can carry impulses across steps.
//
// Polygon–polygon uses the separating-axis test with reference-face clipping (E. Catto, "Contact
// Manifolds", GDC 2007; Box2D b2CollidePolygons) rather than the thesis's vertex-in-polygon test:
// it finds the same deepest points and the two ends of an edge–edge contact (the thesis's
// EdgeEdgeCollision), and it is robust when no vertex lies inside the other polygon.
#pragma once

#include <cstdint>

#include "rigidlab/shape.h"

namespace rigidlab {

struct ManifoldPoint {
  Vec2 point = Vec2::Zero();  // world, midway between the surfaces [m]
  double separation = 0.0;    // along the normal [m]; < 0 overlap
  uint32_t id = 0;            // feature id
};

struct Manifold {
  Vec2 normal = Vec2::Zero();  // unit, A → B
  ManifoldPoint points[2];
  int count = 0;
};

// A polygon already placed in the world: its vertices and outward normals in world coordinates.
// The step transforms each body's polygon once (broad_phase.cpp) and every pair it is in reads it.
struct WorldPolygon {
  const Vec2* vertices;
  const Vec2* normals;
  int count;
  // Four corners with opposite sides parallel (isBox), which a pair of polygons tests on two axes
  // each instead of four. False is always correct (the general test finds the same values), only slower.
  bool box;
  double extent;  // Shape::extent
};

// A box in the sense of WorldPolygon::box: normals[2] == −normals[0] and normals[3] == −normals[1].
inline bool isBox(const Vec2* normals, int count) {
  return count == 4 && normals[2] == -normals[0] && normals[3] == -normals[1];
}

// A shape placed in the world for the narrow phase: its geometry (body coordinates), the body's
// transform, and for the kinds with corners (polygon, capsule, segment, chain segment) those
// corners and normals in world coordinates (placed once per step by the broad phase).
struct PlacedShape {
  WorldPolygon poly;  // not set for circles
  const Shape* shape;
  const Transform* xf;
};

// The manifold of any two shapes: dispatches on the two kinds (a table with one function per pair
// of kinds, Box2D v3's b2Contact registers). Pairs that cannot meet (two segments of static or
// kinematic bodies) give no points.
using CollideFn = Manifold (*)(const PlacedShape&, const PlacedShape&, double);
extern const CollideFn kCollideTable[kShapeTypes][kShapeTypes];  // [kind of a][kind of b]
inline Manifold collide(const PlacedShape& a, const PlacedShape& b, double margin) {
  return kCollideTable[static_cast<int>(a.shape->type)][static_cast<int>(b.shape->type)](a, b, margin);
}

// Points are reported when their separation is ≤ margin (margin 0: touching or overlapping).
// Two circles by their centres in the world and radii (the narrow phase has the centres placed).
Manifold collideCircleCentres(const Vec2& ca, double ra, const Vec2& cb, double rb, double margin);
Manifold collideCircles(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double margin);
Manifold collidePolygonAndCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double margin);
Manifold collidePolygons(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double margin);
Manifold collidePolygons(const WorldPolygon& a, const WorldPolygon& b, double margin);
// The same in three steps, collidePolygons being clipPolygons(a, b, axes, edgeDirection(the
// reference polygon, axes.ref_edge), margin, m) after polygonAxes. The narrow phase runs each step
// over a block of pairs in turn, so that the square root and division of a reference edge's
// direction overlap other pairs' work instead of holding up their own pair's clipping.
struct PolygonAxes {
  int ref_edge = 0, inc_edge = 0;  // of the reference polygon (b if flip, else a) and the other
  bool flip = false;
};
// The separating-axis test and the choice of reference and incident edges; false when an axis
// separates the polygons by more than margin (no points).
bool polygonAxes(const WorldPolygon& a, const WorldPolygon& b, double margin, PolygonAxes& axes);
// The unit direction of edge i of a counter-clockwise polygon (its start to its end).
inline Vec2 edgeDirection(const WorldPolygon& p, int i) {
  return (p.vertices[i + 1 == p.count ? 0 : i + 1] - p.vertices[i]).normalized();
}
// The incident edge clipped to the reference edge, whose direction is `tangent`, into m: its count,
// and its normal and points up to the count (the rest of m is left as it was).
void clipPolygons(const WorldPolygon& a, const WorldPolygon& b, const PolygonAxes& axes, const Vec2& tangent, double margin,
                  Manifold& m);
// A lower bound of the distance between two shapes (negative when they overlap): exact for pairs
// with a circle; for two polygons the largest separation along their face normals (the separating
// axis test), which never exceeds the true distance. Used by continuous collision detection.
double separationLowerBound(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb);
// Dispatches on the shape types (the shapes placed by the transforms); a circle–polygon pair is
// solved as polygon–circle and flipped.
Manifold collideShapes(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double margin);

// The kinds with a rounded segment (capsule; segment and chain segment with radius 0), in world
// coordinates: manifold_round.cpp.
// Capsule or segment a (radius ra) against a circle of centre c and radius rb.
Manifold collideSegmentAndCircle(const Vec2& p, const Vec2& q, double ra, const Vec2& c, double rb, double margin);
// Two rounded segments.
Manifold collideRoundSegments(const Vec2& p1, const Vec2& q1, double ra, const Vec2& p2, const Vec2& q2, double rb,
                              double margin);
// Two convex polygons rounded by ra and rb (a capsule or segment is a two-cornered polygon).
Manifold collideRoundPolygons(const WorldPolygon& a, double ra, const WorldPolygon& b, double rb, double margin);
// A chain segment (one-sided, with ghost vertices; manifold_chain.cpp) against a circle, or against
// a polygon rounded by `radius` (capsules too). Points are in world coordinates.
Manifold collideChainAndCircle(const Vec2& ghost1, const Vec2& p1, const Vec2& p2, const Vec2& ghost2, const Vec2& c,
                               double r, double margin);
Manifold collideChainAndPolygon(const Vec2& ghost1, const Vec2& p1, const Vec2& p2, const Vec2& ghost2,
                                const WorldPolygon& b, double radius, double margin);

}  // namespace rigidlab

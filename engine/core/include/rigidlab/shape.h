// Shapes: circles and convex polygons in body coordinates (origin.md §3, "Bodies").
//
// Polygon input policy (decided here, documented in README "Shapes"):
// - every coordinate must be finite; 3 to kMaxPolygonVertices points;
// - exact or near duplicates (closer than 1e-9 of the polygon's extent) are merged;
// - collinear points (a vertex on the straight line between its neighbours) are dropped;
// - clockwise input is reversed, so vertices are always counter-clockwise;
// - a concave or self-intersecting outline is REJECTED with the index of the offending vertex, not
//   silently replaced by its convex hull: a hull would simulate a different body than the one the
//   user drew. Split concave outlines into convex pieces (one body each).
// - what is left must have positive area.
#pragma once

#include <span>
#include <vector>

#include "rigidlab/math.h"

namespace rigidlab {

inline constexpr int kMaxPolygonVertices = 32;

enum class ShapeType { Circle, Polygon };

struct Shape {
  ShapeType type = ShapeType::Circle;
  double radius = 0.0;               // circle radius [m]
  Vec2 center = Vec2::Zero();        // circle centre in body coordinates [m]
  std::vector<Vec2> vertices;        // polygon corners, counter-clockwise, body coordinates [m]
  std::vector<Vec2> normals;         // outward unit normal of edge i = vertices[i] → vertices[i+1]
  double extent = 0.0;               // largest distance from the body origin to the shape [m] (cached)
  double inradius = 0.0;             // radius of the largest disc about the centroid inside it [m] (cached)
};

// Mass properties of a shape of uniform density.
struct MassData {
  double area = 0.0;               // m²
  double mass = 0.0;               // kg
  Vec2 center = Vec2::Zero();      // centre of mass in body coordinates [m]
  double inertia = 0.0;            // moment of inertia about `center` [kg·m²]
};

// Throws InputError naming the field ("radius", "center", "vertices[3]", ...) and the bad value.
Shape makeCircle(double radius, const Vec2& center = Vec2::Zero());
Shape makePolygon(std::span<const Vec2> points);
// An axis-aligned box of the given full width and height, centred on `center` and turned by `angle`.
Shape makeBox(double width, double height, const Vec2& center = Vec2::Zero(), double angle = 0.0);

// Area, centroid and inertia (origin.md §3: polygon centroid, inertia about the centroid; disc ½mR²).
MassData computeMass(const Shape& shape, double density);
// Bounding box of the shape placed by `xf`.
Aabb computeAabb(const Shape& shape, const Transform& xf);
// Point-in-shape test (origin.md §7): circle |P − T| ≤ R; convex CCW polygon cross(B − A, P − A) ≥ 0
// for every edge AB. `p` is in world coordinates.
bool containsPoint(const Shape& shape, const Transform& xf, const Vec2& p);
// Largest distance from the body origin to any point of the shape (for rotation bounds, CCD).
double maxExtent(const Shape& shape);

}  // namespace rigidlab

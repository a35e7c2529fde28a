// Shapes (docs/physics.md "Shapes"): the geometry of a body, in body coordinates, and what a world
// attaches to it (material, collision filter, sensor flag).
//
// Kinds:
//   circle        a disc: centre and radius
//   polygon       convex, 3 to kMaxPolygonVertices corners, counter-clockwise (a box is one)
//   capsule       the points within `radius` of the segment a–b: exact mass and inertia
//   segment       a line segment a–b, no area: static and kinematic bodies only
//   chain segment one segment of a chain (a polyline of a static body, World::createChain), with
//                 the neighbouring points ("ghost vertices") so that a body sliding along the chain
//                 never catches on the joint between two segments. One-sided: it collides only with
//                 what lies to the right of the direction a → b (Box2D's convention).
//
// Polygon input policy (decided here, documented in docs/lua-api.md "Shapes"):
// - every coordinate must be finite; 3 to kMaxPolygonVertices points;
// - exact or near duplicates (closer than 1e-9 of the polygon's extent) are merged;
// - collinear points (a vertex on the straight line between its neighbours) are dropped;
// - clockwise input is reversed, so vertices are always counter-clockwise;
// - a concave or self-intersecting outline is REJECTED with the index of the offending vertex, not
//   silently replaced by its convex hull: a hull would simulate a different body than the one the
//   user drew. A concave outline is a compound body of convex pieces (decomposeConcave).
// - what is left must have positive area.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rigidlab/math.h"

namespace rigidlab {

inline constexpr int kMaxPolygonVertices = 32;

enum class ShapeType : uint8_t { Circle, Polygon, Capsule, Segment, ChainSegment };
inline constexpr int kShapeTypes = 5;

// Geometry in body coordinates.
struct Shape {
  ShapeType type = ShapeType::Circle;
  double radius = 0.0;               // circle and capsule radius [m]; 0 for the others
  double extent = 0.0;               // largest distance from the body origin to the shape [m] (cached)
  double inradius = 0.0;             // radius of the largest disc about the centroid inside it [m] (cached)
  Vec2 center = Vec2::Zero();        // circle centre [m]
  // Polygon: corners, counter-clockwise. Capsule, segment, chain segment: the two end points a, b.
  std::vector<Vec2> vertices;
  // Polygon: outward unit normal of edge i = vertices[i] → vertices[i+1]. Capsule, segment, chain
  // segment: the right-hand normal n of a → b and −n (the two sides of a two-cornered polygon).
  std::vector<Vec2> normals;
  Vec2 ghost1 = Vec2::Zero();        // chain segment: the chain's point before a
  Vec2 ghost2 = Vec2::Zero();        // chain segment: the chain's point after b
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
// The points within `radius` > 0 of the segment a–b (a ≠ b).
Shape makeCapsule(const Vec2& a, const Vec2& b, double radius);
Shape makeSegment(const Vec2& a, const Vec2& b);
// Segment a–b of a chain whose previous point is ghost1 and next point ghost2.
Shape makeChainSegment(const Vec2& ghost1, const Vec2& a, const Vec2& b, const Vec2& ghost2);
// Shapes are computed with the squares of their coordinates (lengths, normals, extents): a point
// whose square overflows (about 1e154 m from the body's origin) is refused, InputError naming
// `field` ("vertices[3]", "points[2]") and the point.
void requireNearOrigin(const std::string& field, const Vec2& p);
// The shape moved by `offset` and turned by `angle` about the body origin (offset and angle of a
// shape in body coordinates).
Shape transformShape(const Shape& shape, const Vec2& offset, double angle);

// A concave (or convex) simple outline as convex pieces of at most kMaxPolygonVertices corners
// (ear clipping, then merging neighbours while the union stays convex: Hertel–Mehlhorn). Throws
// InputError for fewer than 3 points, a self-intersecting outline or zero area.
std::vector<std::vector<Vec2>> decomposeConcave(std::span<const Vec2> outline);

// Area, centroid and inertia (docs/design/thesis.md §3: polygon centroid, inertia about the centroid; disc ½mR²;
// capsule: rectangle plus two half discs, with the parallel-axis theorem). Segments have no area.
MassData computeMass(const Shape& shape, double density);
// Bounding box of the shape placed by `xf`.
Aabb computeAabb(const Shape& shape, const Transform& xf);
// Point-in-shape test (docs/design/thesis.md §7): circle |P − T| ≤ R; convex CCW polygon cross(B − A, P − A) ≥ 0
// for every edge AB; capsule: distance to the segment ≤ R. Segments contain no point. `p` is world.
bool containsPoint(const Shape& shape, const Transform& xf, const Vec2& p);
// Largest distance from the body origin to any point of the shape (for rotation bounds, CCD).
double maxExtent(const Shape& shape);
// True for the kinds without area (segment, chain segment), which only static and kinematic bodies
// may have.
inline bool hasArea(ShapeType t) { return t != ShapeType::Segment && t != ShapeType::ChainSegment; }
const char* shapeTypeName(ShapeType t);  // "circle", "polygon", "capsule", "segment", "chain_segment"

// Surface material. When two shapes touch, their values combine as (docs/physics.md "Materials"):
//   restitution  e  = max(e_A, e_B)            a bouncy ball bounces on any floor
//   friction     μ  = sqrt(μ_A · μ_B)          for both dynamic and static friction;
//                                               a frictionless shape slides on anything
struct Material {
  double restitution = 0.0;      // Newton's coefficient, 0 (plastic) … 1 (elastic)
  double friction = 0.6;         // dynamic (sliding) friction coefficient f_d ≥ 0
  double static_friction = 0.6;  // static friction coefficient f_s ≥ 0 (holds up to f_s·F_n)
};

// Collision filtering (Box2D's rule). Two shapes collide when
//   group_A == group_B != 0:  group_A > 0 (always collide), group_A < 0 (never)
//   otherwise:                (category_A & mask_B) != 0 and (category_B & mask_A) != 0
struct Filter {
  uint64_t category = 1;              // the categories this shape belongs to (bits)
  uint64_t mask = ~uint64_t{0};       // the categories it collides with
  int32_t group = 0;                  // see above; 0: no group
  friend bool operator==(const Filter&, const Filter&) = default;
};
bool shouldCollide(const Filter& a, const Filter& b);

// A shape handle: slot index plus generation (see BodyId).
struct ShapeId {
  uint32_t index = UINT32_MAX;
  uint32_t generation = 0;

  bool isNull() const { return index == UINT32_MAX; }
  friend bool operator==(const ShapeId&, const ShapeId&) = default;
};

// Everything needed to attach a shape to a body (World::createShape).
struct ShapeDef {
  Shape shape;                     // in body coordinates: makeCircle / makeBox / ... / transformShape
  double density = 1.0;            // [kg/m²] > 0 (ignored for shapes without area)
  Material material;
  Filter filter;
  // A sensor collides with nothing: it reports the shapes that overlap it (events, World::sensorOverlaps).
  bool sensor = false;
  // Events (World::contactEvents): this shape's contacts beginning and ending; impacts of at least
  // hit_speed [m/s] (the closing speed at the contact) as hit events.
  bool contact_events = false;
  bool hit_events = false;
  double hit_speed = 1.0;
  // A one-way platform: the unit normal, in body coordinates, of the side that other shapes stand
  // on. Coming from the other side (or moving along the normal, or still inside), they pass
  // through: the contact is disabled until it ends.
  std::optional<Vec2> one_way;
  // The world's pre-solve callback (World::setPreSolve) is asked about this shape's contacts.
  bool pre_solve = false;
  // Surface motion (a conveyor belt, a tank's track) [m/s]: the surface moves along itself at this
  // speed, clockwise around the shape (Box2D v3's convention: a floor's top runs towards +x for a
  // positive speed), and friction drags what touches it towards that speed. Two touching shapes'
  // speeds add.
  double tangent_speed = 0.0;
  // Rolling resistance (Box2D v3's): a contact resists the relative turning of its bodies with a
  // torque of at most c · r · N, c the larger of the two shapes' coefficients (≥ 0, usually ≤ 1),
  // r the larger of their radii (circles and capsules; 0 for the others) and N the normal force.
  // A disc rolling on a floor slows at c g m r² / (I + m r²): ⅔ c g for a uniform disc.
  double rolling_resistance = 0.0;
};

}  // namespace rigidlab

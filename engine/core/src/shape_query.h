// Queries on one shape placed in the world (shape_query.cpp): ray casts, overlap tests, the time of
// impact of a moving shape, the closest point, the width a shape shows to a direction. Pure
// functions of the geometry, used by the world's queries (world_query.cpp) and sensors.
#pragma once

#include <optional>

#include "rigidlab/shape.h"

namespace rigidlab {

struct ShapeRayHit {
  double fraction = 0.0;        // along p1 → p2
  Vec2 point = Vec2::Zero();    // world
  Vec2 normal = Vec2::Zero();   // the surface's outward unit normal there
};

// The first point where the segment p1 → p2 (up to max_fraction of it) enters the shape. A ray that
// starts inside a shape does not hit it; a chain segment is hit from its front side only.
std::optional<ShapeRayHit> rayCastShape(const Shape& shape, const Transform& xf, const Vec2& p1, const Vec2& p2,
                                        double max_fraction);
// Do the two placed shapes overlap (touching counts)?
bool shapesOverlap(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb);
// Distance between the placed shapes' surfaces (0 when they overlap), and the closest points.
double shapeDistance(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, Vec2* on_a = nullptr,
                     Vec2* on_b = nullptr);
// The first fraction t ∈ [0, 1] of the translation at which `moving` (placed by xf, then moved by
// t · translation) touches `target`; the hit point and the target's normal there.
std::optional<ShapeRayHit> shapeCastShape(const Shape& moving, const Transform& xf, const Vec2& translation,
                                          const Shape& target, const Transform& target_xf);
// The length of the shape's outline facing `direction` (unit): the width of its projection on the
// perpendicular. An explosion pushes a shape in proportion to it.
double projectedWidth(const Shape& shape, const Transform& xf, const Vec2& direction);

}  // namespace rigidlab

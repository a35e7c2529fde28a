// Math vocabulary of the core: Eigen types plus the few 2D operations Eigen does not name.
// SI units everywhere (metre, kilogram, second, radian); angles are counter-clockwise positive.
#pragma once

#include "rigidlab/portable_math.h"
#include <Eigen/Core>
#include <cmath>

namespace rigidlab {

using Vec2 = Eigen::Vector2d;
using Mat22 = Eigen::Matrix2d;

// 2D cross products (docs/design/thesis.md §1: torque τ = r × F is a scalar in 2D).
// vector × vector → scalar: the z component of the 3D cross product.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
// scalar × vector → vector: ω × r for an angular velocity ω about z, i.e. ω·perp(r).
inline Vec2 cross(double s, const Vec2& v) { return Vec2(-s * v.y(), s * v.x()); }
// vector × scalar → vector: v × s = −(s × v).
inline Vec2 cross(const Vec2& v, double s) { return Vec2(s * v.y(), -s * v.x()); }
// Counter-clockwise perpendicular, (x, y) → (−y, x).
inline Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

inline bool isFinite(double x) { return std::isfinite(x); }
inline bool isFinite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// A rotation stored as cosine and sine, so rotating a point costs four multiplies and no trig.
struct Rot {
  double c = 1.0;
  double s = 0.0;

  // Portable (portable_math.h): the same bits on every machine, unlike the C library's.
  static Rot fromAngle(double angle) {
    Rot q;
    portableSinCos(angle, q.s, q.c);
    return q;
  }
  Vec2 apply(const Vec2& v) const { return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y()); }
  Vec2 applyInverse(const Vec2& v) const { return Vec2(c * v.x() + s * v.y(), -s * v.x() + c * v.y()); }
  Mat22 matrix() const { return (Mat22() << c, -s, s, c).finished(); }
};

// A rigid transform: body coordinates → world coordinates, x_world = p + q·x_local.
struct Transform {
  Vec2 p = Vec2::Zero();
  Rot q;

  Vec2 apply(const Vec2& local) const { return p + q.apply(local); }
  Vec2 applyInverse(const Vec2& world) const { return q.applyInverse(world - p); }
};

// Axis-aligned bounding box.
struct Aabb {
  Vec2 lower = Vec2::Zero();
  Vec2 upper = Vec2::Zero();

  bool overlaps(const Aabb& o) const {
    return lower.x() <= o.upper.x() && o.lower.x() <= upper.x() && lower.y() <= o.upper.y() &&
           o.lower.y() <= upper.y();
  }
  bool contains(const Vec2& p) const {
    return lower.x() <= p.x() && p.x() <= upper.x() && lower.y() <= p.y() && p.y() <= upper.y();
  }
};

}  // namespace rigidlab

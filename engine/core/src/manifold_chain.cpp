// Narrow phase for chain segments (shape.h): one-sided segments that know their neighbours, so that
// a body sliding over the joint between two segments of a chain never catches on it.
//
// Why ghost vertices: a box sliding over two flush segments touches the corner where they meet;
// taken alone, that corner gives a contact normal tilted against the motion, and the box trips
// (a box at 8 m/s over 60 flush boxes: |v_y| 1.86 m/s at the seams). Knowing the neighbours, each
// segment admits only normals that the chain's surface really has (E. Catto, "Ghost Collisions",
// 2020; Box2D v3's b2CollideChainSegment*):
// - normals towards a convex neighbour are admitted while they lie between the two segments'
//   normals (the rounded corner), and beyond that the neighbour owns the contact (skip);
// - normals towards a concave neighbour are snapped to this segment's normal (the corner is a
//   dent, not a bump);
// - the surface faces the right of a → b: a body wholly behind it (and behind the convex
//   neighbours) does not collide.
// An open chain's end segments have no neighbour at their free ends (ghost = the end point): there
// every normal is admitted, as at the end of a plain segment.
#include <algorithm>
#include <cmath>
#include <limits>

#include "distance.h"
#include "manifold.h"

namespace rigidlab {
namespace {

constexpr double kLinearSlop = 0.005;
constexpr double kConvexTolerance = 0.01;  // sine of the smallest turn that counts as convex
constexpr double kSinTolerance = 0.01;

uint32_t pairId(int a, int b) { return static_cast<uint32_t>(a) << 8 | static_cast<uint32_t>(b); }
Vec2 rightPerp(const Vec2& v) { return Vec2(v.y(), -v.x()); }

enum class NormalType { Skip, Admit, Snap };

struct ChainParams {
  Vec2 edge1;             // unit, a → b
  Vec2 normal0, normal2;  // neighbours' normals
  bool free1, free2;      // no neighbour at a / at b
  bool convex1, convex2;  // the neighbour at a / b turns away (a convex corner)
};

// Where on the Gauss map the normal falls (see the file comment).
NormalType classify(const ChainParams& p, const Vec2& normal) {
  if (normal.dot(p.edge1) <= 0.0) {  // towards a
    if (p.free1) return NormalType::Admit;
    if (!p.convex1) return NormalType::Snap;
    return cross(normal, p.normal0) > kSinTolerance ? NormalType::Skip : NormalType::Admit;
  }
  if (p.free2) return NormalType::Admit;
  if (!p.convex2) return NormalType::Snap;
  return cross(p.normal2, normal) > kSinTolerance ? NormalType::Skip : NormalType::Admit;
}

// Clips segment b1–b2 (running against a1–a2) to a1–a2 and returns both ends as points.
Manifold clipSegments(const Vec2& a1, const Vec2& a2, const Vec2& b1, const Vec2& b2, const Vec2& normal, double ra, double rb,
                      uint32_t id1, uint32_t id2, double margin) {
  Manifold m;
  const Vec2 tangent = cross(1.0, normal);
  const double lower1 = 0.0, upper1 = (a2 - a1).dot(tangent);
  const double upper2 = (b1 - a1).dot(tangent), lower2 = (b2 - a1).dot(tangent);
  if (upper2 < lower1 || upper1 < lower2) return m;
  constexpr double kEps = 1e-12;
  const Vec2 v_lower = lower2 < lower1 && upper2 - lower2 > kEps ? Vec2(b2 + (b1 - b2) * ((lower1 - lower2) / (upper2 - lower2))) : b2;
  const Vec2 v_upper = upper2 > upper1 && upper2 - lower2 > kEps ? Vec2(b2 + (b1 - b2) * ((upper1 - lower2) / (upper2 - lower2))) : b1;
  const double s_lower = (v_lower - a1).dot(normal), s_upper = (v_upper - a1).dot(normal);
  const double radius = ra + rb;
  m.normal = normal;
  if (s_lower - radius <= margin) m.points[m.count++] = {v_lower + 0.5 * (ra - rb - s_lower) * normal, s_lower - radius, id1};
  if (s_upper - radius <= margin) m.points[m.count++] = {v_upper + 0.5 * (ra - rb - s_upper) * normal, s_upper - radius, id2};
  return m;
}

Manifold flipped(Manifold m) {
  m.normal = -m.normal;
  return m;
}

}  // namespace

Manifold collideChainAndCircle(const Vec2& ghost1, const Vec2& p1, const Vec2& p2, const Vec2& ghost2, const Vec2& c,
                               double r, double margin) {
  Manifold m;
  const Vec2 e = p2 - p1;
  if (rightPerp(e).dot(c - p1) < 0.0) return m;  // behind: one-sided
  const double u = e.dot(p2 - c), v = e.dot(c - p1);  // barycentric coordinates (times |e|²)
  Vec2 closest;
  uint32_t id = 0;
  if (v <= 0.0) {
    // Before a: in the region of the previous segment, which owns the contact.
    if (ghost1 != p1 && (p1 - ghost1).dot(c - p1) <= 0.0) return m;
    closest = p1;
    id = 1;
  } else if (u <= 0.0) {
    if (ghost2 != p2 && (ghost2 - p2).dot(c - p2) > 0.0) return m;
    closest = p2;
    id = 2;
  } else {
    closest = (u * p1 + v * p2) / e.dot(e);
  }
  const Vec2 d = c - closest;
  const double dist = d.norm();
  const double separation = dist - r;
  if (separation > margin) return m;
  const Vec2 n = dist > 1e-12 ? Vec2(d / dist) : rightPerp(e).normalized();
  m.normal = n;
  m.points[0] = {0.5 * (closest + (c - r * n)), separation, id};
  m.count = 1;
  return m;
}

Manifold collideChainAndPolygon(const Vec2& ghost1, const Vec2& p1, const Vec2& p2, const Vec2& ghost2,
                                const WorldPolygon& b, double radius, double margin) {
  Manifold m;
  const int count = b.count;
  const Vec2* vertices = b.vertices;
  const Vec2* normals = b.normals;
  Vec2 centroid = Vec2::Zero();
  for (int i = 0; i < count; ++i) centroid += vertices[i];
  centroid /= count;

  ChainParams params;
  params.edge1 = (p2 - p1).normalized();
  params.free1 = ghost1 == p1;
  params.free2 = ghost2 == p2;
  const Vec2 edge0 = params.free1 ? params.edge1 : Vec2((p1 - ghost1).normalized());
  const Vec2 edge2 = params.free2 ? params.edge1 : Vec2((ghost2 - p2).normalized());
  params.normal0 = rightPerp(edge0);
  params.normal2 = rightPerp(edge2);
  params.convex1 = !params.free1 && cross(edge0, params.edge1) >= kConvexTolerance;
  params.convex2 = !params.free2 && cross(params.edge1, edge2) >= kConvexTolerance;
  const Vec2 normal1 = rightPerp(params.edge1);

  // Wholly behind this segment and its convex neighbours: no collision (one-sided).
  const bool behind1 = normal1.dot(centroid - p1) < 0.0;
  const bool behind0 = params.convex1 ? params.normal0.dot(centroid - p1) < 0.0 : true;
  const bool behind2 = params.convex2 ? params.normal2.dot(centroid - p2) < 0.0 : true;
  if (behind1 && behind0 && behind2) return m;

  const Vec2 segment[2] = {p1, p2};
  const DistanceResult gjk = shapeDistance({segment, 2, 0.0}, {vertices, count, 0.0});
  if (gjk.distance > radius + margin) return m;

  // Neighbours' normals, snapped to this segment's where the corner is concave (or free).
  const Vec2 n0 = params.convex1 ? params.normal0 : normal1;
  const Vec2 n2 = params.convex2 ? params.normal2 : normal1;
  int incident_index = -1, incident_normal = -1;

  if (!behind1 && gjk.distance > 0.1 * kLinearSlop) {
    // Apart: the closest features decide (two corners, or a corner and an edge).
    if (gjk.simplex == 1) {
      const Vec2 pa = gjk.point_a, pb = gjk.point_b;
      const Vec2 normal = (pb - pa).normalized();
      const NormalType type = classify(params, normal);
      if (type == NormalType::Skip) return m;
      if (type == NormalType::Admit) {
        m.normal = normal;
        m.points[0] = {pa + 0.5 * (gjk.distance - radius) * normal, gjk.distance - radius,
                       pairId(gjk.index_a[0], gjk.index_b[0])};
        m.count = gjk.distance - radius <= margin ? 1 : 0;
        return m;
      }
      incident_index = gjk.index_b[0];  // snap: the segment's normal decides below
    } else {
      const int ia1 = gjk.index_a[0], ia2 = gjk.index_a[1], ib1 = gjk.index_b[0], ib2 = gjk.index_b[1];
      if (ia1 == ia2) {
        // A corner of the segment against an edge of the polygon: that edge's normal, the one most
        // aligned with the direction between the closest points.
        const Vec2 towards_a = gjk.point_a - gjk.point_b;
        const int ib = towards_a.dot(normals[ib1]) > towards_a.dot(normals[ib2]) ? ib1 : ib2;
        const Vec2 normal_b = normals[ib];
        const NormalType type = classify(params, -normal_b);
        if (type == NormalType::Skip) return m;
        if (type == NormalType::Admit) {
          const int e1 = ib, e2 = ib < count - 1 ? ib + 1 : 0;
          const Vec2 b1 = vertices[e1], b2 = vertices[e2];
          // The segment's end nearer the polygon edge: if the neighbour there faces the edge more
          // squarely, the neighbour owns the contact.
          const double d1 = normal_b.dot(p1 - b1), d2 = normal_b.dot(p2 - b1);
          if (d1 < d2 ? n0.dot(normal_b) < normal1.dot(normal_b) : n2.dot(normal_b) < normal1.dot(normal_b)) return m;
          return flipped(clipSegments(b1, b2, p1, p2, normal_b, radius, 0.0, pairId(e1, 1), pairId(e2, 0), margin));
        }
        incident_normal = ib;
      } else {
        // Both features are edges (parallel): the polygon corner deeper along the segment normal.
        const double d1 = normal1.dot(vertices[ib1] - p1), d2 = normal1.dot(vertices[ib2] - p2);
        incident_index = d1 < d2 ? ib1 : ib2;
      }
    }
  } else {
    // Overlapping (or behind the segment's own line but in front of a neighbour's): separating
    // axis test over this segment's normal, its convex neighbours' normals and the polygon's
    // admitted normals.
    double edge_separation = std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; ++i) {
      const double s = normal1.dot(vertices[i] - p1);
      if (s < edge_separation) {
        edge_separation = s;
        incident_index = i;
      }
    }
    const auto neighbourSeparation = [&](const Vec2& n, const Vec2& origin) {
      double s = std::numeric_limits<double>::infinity();
      for (int i = 0; i < count; ++i) s = std::min(s, n.dot(vertices[i] - origin));
      return s;
    };
    if (params.convex1) {
      const double s0 = neighbourSeparation(params.normal0, p1);
      if (s0 > edge_separation) {
        edge_separation = s0;
        incident_index = -1;  // the neighbour owns the separating axis
      }
    }
    if (params.convex2) {
      const double s2 = neighbourSeparation(params.normal2, p2);
      if (s2 > edge_separation) {
        edge_separation = s2;
        incident_index = -1;
      }
    }
    double polygon_separation = -std::numeric_limits<double>::infinity();
    int reference = -1;
    for (int i = 0; i < count; ++i) {
      if (classify(params, -normals[i]) != NormalType::Admit) continue;
      const double s = std::min(normals[i].dot(p2 - vertices[i]), normals[i].dot(p1 - vertices[i]));
      if (s > polygon_separation) {
        polygon_separation = s;
        reference = i;
      }
    }
    if (polygon_separation > edge_separation) {
      const int e1 = reference, e2 = reference < count - 1 ? reference + 1 : 0;
      const Vec2 n = normals[e1];
      const double d1 = n.dot(p1 - vertices[e1]), d2 = n.dot(p2 - vertices[e1]);
      if (d1 < d2 ? n0.dot(n) < normal1.dot(n) : n2.dot(n) < normal1.dot(n)) return m;
      return flipped(clipSegments(vertices[e1], vertices[e2], p1, p2, n, radius, 0.0, pairId(e1, 1), pairId(e2, 0), margin));
    }
    if (incident_index == -1) return m;
  }

  // The segment's normal is the axis: clip the polygon's incident edge (next to the deepest corner,
  // most anti-parallel to the normal) to the segment.
  int e1, e2;
  if (incident_normal != -1) {
    e1 = incident_normal;
    e2 = e1 < count - 1 ? e1 + 1 : 0;
  } else {
    const int i2 = incident_index, i1 = i2 > 0 ? i2 - 1 : count - 1;
    if (normal1.dot(normals[i1]) < normal1.dot(normals[i2])) {
      e1 = i1;
      e2 = i2;
    } else {
      e1 = i2;
      e2 = i2 < count - 1 ? i2 + 1 : 0;
    }
  }
  return clipSegments(p1, p2, vertices[e1], vertices[e2], normal1, 0.0, radius, pairId(0, e2) | 0x10000u,
                      pairId(1, e1) | 0x10000u, margin);
}

}  // namespace rigidlab

// Narrow phase for rounded shapes: capsules (a segment with a radius), segments (radius 0) and
// polygons against them, in world coordinates. See manifold.h for the conventions (normal A → B,
// points midway between the surfaces, separation < 0 overlap, feature ids).
//
// A capsule is the set of points within r of its core segment, so the distance between two rounded
// shapes is the distance between their cores minus the radii; the contact normal is the direction
// between the closest core points, and a contact point sits midway between the two surfaces:
//   c_A = p_A + r_A n,  c_B = p_B − r_B n,  point = (c_A + c_B)/2,  separation = |p_B − p_A| − r_A − r_B.
// Where two cores are parallel and overlap along their length (a capsule lying on a box), one point
// is not enough to hold it still: the incident core edge is clipped to the reference edge's ends
// and both ends become points (E. Catto, "Contact Manifolds", GDC 2007; Box2D v3 manifold.c).
#include <algorithm>
#include <cmath>
#include <limits>

#include "distance.h"
#include "manifold.h"

namespace rigidlab {
namespace {

constexpr double kLinearSlop = 0.005;  // [m] the tolerance below which cores count as touching

uint32_t pairId(int a, int b) { return static_cast<uint32_t>(a) << 8 | static_cast<uint32_t>(b); }

Vec2 safeNormal(const Vec2& d, const Vec2& fallback) {
  const double len = d.norm();
  return len > 1e-12 ? Vec2(d / len) : fallback;
}

// One point from the closest core points pa (on A) and pb (on B).
Manifold onePoint(const Vec2& pa, double ra, const Vec2& pb, double rb, const Vec2& fallback_normal, uint32_t id,
                  double margin) {
  Manifold m;
  const Vec2 d = pb - pa;
  const double dist = d.norm();
  const double separation = dist - ra - rb;
  if (separation > margin) return m;
  const Vec2 n = dist > 1e-12 ? Vec2(d / dist) : fallback_normal;
  const Vec2 ca = pa + ra * n, cb = pb - rb * n;
  m.normal = n;
  m.points[0] = {0.5 * (ca + cb), separation, id};
  m.count = 1;
  return m;
}

// Largest separation of b's corners from a's edges (no early stop), and the edge.
double maxSeparation(const WorldPolygon& a, const WorldPolygon& b, int& edge) {
  double best = -std::numeric_limits<double>::infinity();
  edge = 0;
  for (int i = 0; i < a.count; ++i) {
    double si = std::numeric_limits<double>::infinity();
    for (int j = 0; j < b.count; ++j) si = std::min(si, a.normals[i].dot(b.vertices[j] - a.vertices[i]));
    if (si > best) {
      best = si;
      edge = i;
    }
  }
  return best;
}

// Clips the incident edge of `inc` to the reference edge of `ref` (both rounded) and keeps the ends
// within `margin`. `flip`: ref is B, so the normal is reversed to point from A to B.
Manifold clipEdges(const WorldPolygon& ref, double r_ref, int ref_edge, const WorldPolygon& inc, double r_inc, int inc_edge,
                   bool flip, double margin) {
  Manifold m;
  const int i11 = ref_edge, i12 = ref_edge + 1 < ref.count ? ref_edge + 1 : 0;
  const int i21 = inc_edge, i22 = inc_edge + 1 < inc.count ? inc_edge + 1 : 0;
  const Vec2 normal = ref.normals[i11];
  const Vec2 v11 = ref.vertices[i11], v12 = ref.vertices[i12];
  const Vec2 v21 = inc.vertices[i21], v22 = inc.vertices[i22];
  const Vec2 tangent = cross(1.0, normal);  // along v11 → v12
  const double lower1 = 0.0, upper1 = (v12 - v11).dot(tangent);
  // The incident edge runs against the tangent (both polygons counter-clockwise).
  const double upper2 = (v21 - v11).dot(tangent), lower2 = (v22 - v11).dot(tangent);
  if (upper2 < lower1 || upper1 < lower2) return m;  // no overlap along the edge
  constexpr double kEps = 1e-12;
  const Vec2 v_lower = lower2 < lower1 && upper2 - lower2 > kEps ? Vec2(v22 + (v21 - v22) * ((lower1 - lower2) / (upper2 - lower2))) : v22;
  const Vec2 v_upper = upper2 > upper1 && upper2 - lower2 > kEps ? Vec2(v22 + (v21 - v22) * ((upper1 - lower2) / (upper2 - lower2))) : v21;
  const double s_lower = (v_lower - v11).dot(normal), s_upper = (v_upper - v11).dot(normal);
  const double radius = r_ref + r_inc;
  // Midway between the surfaces: the incident point moved towards the reference face by half the gap.
  const Vec2 p_lower = v_lower + 0.5 * (r_ref - r_inc - s_lower) * normal;
  const Vec2 p_upper = v_upper + 0.5 * (r_ref - r_inc - s_upper) * normal;
  m.normal = flip ? Vec2(-normal) : normal;
  const auto add = [&](const Vec2& p, double s, uint32_t id) {
    if (s - radius <= margin) m.points[m.count++] = {p, s - radius, id};
  };
  if (!flip) {
    add(p_lower, s_lower, pairId(i11, i22));
    add(p_upper, s_upper, pairId(i12, i21));
  } else {
    add(p_upper, s_upper, pairId(i21, i12));
    add(p_lower, s_lower, pairId(i22, i11));
  }
  return m;
}

}  // namespace

Manifold collideSegmentAndCircle(const Vec2& p, const Vec2& q, double ra, const Vec2& c, double rb, double margin) {
  // Closest point of the core segment to the circle's centre: an end, or the foot of the
  // perpendicular, from s = (c − p)·e / e·e.
  const Vec2 e = q - p;
  const double s1 = (c - p).dot(e), s2 = (q - c).dot(e);
  Vec2 closest;
  uint32_t id = 0;
  if (s1 < 0.0) {
    closest = p;
    id = 1;
  } else if (s2 < 0.0) {
    closest = q;
    id = 2;
  } else {
    closest = p + (s1 / e.dot(e)) * e;
  }
  // A centre on the core itself: push out along the segment's right-hand normal.
  const Vec2 side = safeNormal(Vec2(e.y(), -e.x()), Vec2(0.0, 1.0));
  return onePoint(closest, ra, c, rb, side, id, margin);
}

Manifold collideRoundSegments(const Vec2& p1, const Vec2& q1, double ra, const Vec2& p2, const Vec2& q2, double rb,
                              double margin) {
  const SegmentDistance sd = segmentDistance(p1, q1, p2, q2);
  const double radius = ra + rb;
  const double max_distance = radius + margin;
  Manifold m;
  if (sd.distance_squared > max_distance * max_distance) return m;
  const double distance = std::sqrt(sd.distance_squared);
  const Vec2 d1 = q1 - p1, d2 = q2 - p2;
  const double length1 = d1.norm(), length2 = d2.norm();
  const Vec2 u1 = d1 / length1, u2 = d2 / length2;

  // Do the cores overlap along each other (each projects inside the other)? Then try two points.
  const double fp2 = (p2 - p1).dot(u1), fq2 = (q2 - p1).dot(u1);
  const bool outside_a = (fp2 <= 0.0 && fq2 <= 0.0) || (fp2 >= length1 && fq2 >= length1);
  const double fp1 = (p1 - p2).dot(u2), fq1 = (q1 - p2).dot(u2);
  const bool outside_b = (fp1 <= 0.0 && fq1 <= 0.0) || (fp1 >= length2 && fq1 >= length2);
  if (!outside_a && !outside_b) {
    // Reference edge by the separating axis test over the two side normals of each core.
    const auto sideSeparation = [](const Vec2& origin, const Vec2& u, const Vec2& x, const Vec2& y, Vec2& normal) {
      normal = cross(1.0, u);  // left of u
      const double s1 = (x - origin).dot(normal), s2 = (y - origin).dot(normal);
      const double pos = std::min(s1, s2), neg = std::min(-s1, -s2);
      if (pos > neg) return pos;
      normal = -normal;
      return neg;
    };
    Vec2 na, nb;
    const double sa = sideSeparation(p1, u1, p2, q2, na), sb = sideSeparation(p2, u2, p1, q1, nb);
    // Biased towards A so that nearly equal values do not swap the reference between steps.
    const bool ref_a = sa + 0.1 * kLinearSlop >= sb;
    const Vec2 &rp = ref_a ? p1 : p2, &iq = ref_a ? q2 : q1, &ip = ref_a ? p2 : p1;
    const double ref_length = ref_a ? length1 : length2;
    const double fp = ref_a ? fp2 : fp1, fq = ref_a ? fq2 : fq1;
    const Vec2 normal = ref_a ? na : nb;
    const double r_ref = ref_a ? ra : rb, r_inc = ref_a ? rb : ra;
    // Clip the incident core to the reference core's ends (fractions along the reference axis).
    Vec2 cp = ip, cq = iq;
    if (fp < 0.0 && fq > 0.0) cp = ip + (iq - ip) * ((0.0 - fp) / (fq - fp));
    else if (fq < 0.0 && fp > 0.0) cq = iq + (ip - iq) * ((0.0 - fq) / (fp - fq));
    if (fp > ref_length && fq < ref_length) cp = ip + (iq - ip) * ((fp - ref_length) / (fp - fq));
    else if (fq > ref_length && fp < ref_length) cq = iq + (ip - iq) * ((fq - ref_length) / (fq - fp));
    const double sp = (cp - rp).dot(normal), sq = (cq - rp).dot(normal);
    // Only when the clipped ends are about as close as the closest points: otherwise the cores
    // cross at an angle and one point is right.
    if (sp <= distance + kLinearSlop || sq <= distance + kLinearSlop) {
      m.normal = ref_a ? normal : Vec2(-normal);
      const auto add = [&](const Vec2& c, double s, uint32_t id) {
        if (s - radius <= margin) m.points[m.count++] = {c + 0.5 * (r_ref - r_inc - s) * normal, s - radius, id};
      };
      add(cp, sp, ref_a ? pairId(0, 0) : pairId(0, 0) | 0x10000u);
      add(cq, sq, ref_a ? pairId(0, 1) : pairId(1, 0) | 0x10000u);
      if (m.count > 0) return m;
    }
  }
  // One point from the closest points of the cores.
  const Vec2 fallback = cross(1.0, u1);
  const uint32_t id = pairId(sd.fraction1 == 0.0 ? 0 : 1, sd.fraction2 == 0.0 ? 0 : 1) | 0x20000u;
  return onePoint(sd.closest1, ra, sd.closest2, rb, fallback, id, margin);
}

Manifold collideRoundPolygons(const WorldPolygon& a, double ra, const WorldPolygon& b, double rb, double margin) {
  Manifold m;
  int edge_a = 0, edge_b = 0;
  const double sep_a = maxSeparation(a, b, edge_a), sep_b = maxSeparation(b, a, edge_b);
  const double radius = ra + rb;
  if (sep_a > margin + radius || sep_b > margin + radius) return m;
  // Reference face: the axis of least penetration, preferring A unless B's is clearly better.
  const bool flip = sep_b > sep_a + 0.1 * kLinearSlop;
  const WorldPolygon& ref = flip ? b : a;
  const WorldPolygon& inc = flip ? a : b;
  const int ref_edge = flip ? edge_b : edge_a;
  int inc_edge = 0;
  double min_dot = std::numeric_limits<double>::infinity();
  for (int i = 0; i < inc.count; ++i) {
    const double d = ref.normals[ref_edge].dot(inc.normals[i]);
    if (d < min_dot) {
      min_dot = d;
      inc_edge = i;
    }
  }
  const double r_ref = flip ? rb : ra, r_inc = flip ? ra : rb;
  if (std::max(sep_a, sep_b) <= 0.1 * kLinearSlop) return clipEdges(ref, r_ref, ref_edge, inc, r_inc, inc_edge, flip, margin);

  // The cores are apart: the closest features may be two corners (vertex–vertex), where clipping
  // would put the points too far; compare with the closest points of the two edges.
  const int i11 = ref_edge, i12 = ref_edge + 1 < ref.count ? ref_edge + 1 : 0;
  const int i21 = inc_edge, i22 = inc_edge + 1 < inc.count ? inc_edge + 1 : 0;
  const Vec2 v11 = ref.vertices[i11], v12 = ref.vertices[i12], v21 = inc.vertices[i21], v22 = inc.vertices[i22];
  const SegmentDistance sd = segmentDistance(v11, v12, v21, v22);
  const double distance = std::sqrt(sd.distance_squared);
  if (distance - radius > margin) return m;
  m = clipEdges(ref, r_ref, ref_edge, inc, r_inc, inc_edge, flip, margin);
  double min_separation = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.count; ++i) min_separation = std::min(min_separation, m.points[i].separation);
  const bool at_corners = (sd.fraction1 == 0.0 || sd.fraction1 == 1.0) && (sd.fraction2 == 0.0 || sd.fraction2 == 1.0);
  if ((m.count == 0 || distance - radius + 0.1 * kLinearSlop < min_separation) && at_corners) {
    const int ia = sd.fraction1 == 0.0 ? i11 : i12, ib = sd.fraction2 == 0.0 ? i21 : i22;
    const Vec2 fallback = ref.normals[ref_edge];
    // Closest points are on ref (A unless flipped): keep the normal pointing from A to B.
    m = flip ? onePoint(sd.closest2, r_inc, sd.closest1, r_ref, -fallback, pairId(ib, ia) | 0x30000u, margin)
             : onePoint(sd.closest1, r_ref, sd.closest2, r_inc, fallback, pairId(ia, ib) | 0x30000u, margin);
  }
  return m;
}

}  // namespace rigidlab

// A simple (concave or convex) outline split into convex pieces, for compound bodies drawn as one
// outline (shape.h decomposeConcave).
//
//   1. clean: merge near-duplicate points, drop collinear ones, make it counter-clockwise;
//   2. refuse self-intersecting outlines (two non-adjacent edges that meet);
//   3. ear clipping: a convex corner whose triangle holds no other point is cut off, until one
//      triangle is left (every simple polygon has two ears: Meisters' theorem);
//   4. Hertel–Mehlhorn: remove diagonals between neighbouring pieces while the union stays convex
//      and within kMaxPolygonVertices corners. The result has at most four times the minimum number
//      of convex pieces, usually close to it.
// Points are indices into the cleaned outline throughout, so the pieces share corners exactly.
#include <algorithm>
#include <cmath>
#include <string>

#include "rigidlab/error.h"
#include "rigidlab/shape.h"

namespace rigidlab {
namespace {

constexpr size_t kMaxOutlinePoints = 1024;  // ear clipping is O(n³) at worst

double orient(const Vec2& a, const Vec2& b, const Vec2& c) { return cross(b - a, c - a); }

bool segmentsIntersect(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const double d1 = orient(q1, q2, p1), d2 = orient(q1, q2, p2), d3 = orient(p1, p2, q1), d4 = orient(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  const auto onSegment = [](const Vec2& a, const Vec2& b, const Vec2& p) {
    return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
           p.y() <= std::max(a.y(), b.y());
  };
  return (d1 == 0 && onSegment(q1, q2, p1)) || (d2 == 0 && onSegment(q1, q2, p2)) || (d3 == 0 && onSegment(p1, p2, q1)) ||
         (d4 == 0 && onSegment(p1, p2, q2));
}

// Strictly inside the counter-clockwise triangle abc, or on its edges.
bool inTriangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0;
}

bool convexPiece(const std::vector<Vec2>& pts, const std::vector<int>& piece) {
  const size_t n = piece.size();
  for (size_t i = 0; i < n; ++i)
    if (orient(pts[piece[i]], pts[piece[(i + 1) % n]], pts[piece[(i + 2) % n]]) < 0) return false;
  return true;
}

}  // namespace

std::vector<std::vector<Vec2>> decomposeConcave(std::span<const Vec2> outline) {
  const size_t n0 = outline.size();
  if (n0 < 3) throw InputError("vertices", "vertices needs at least 3 points, got " + std::to_string(n0));
  if (n0 > kMaxOutlinePoints)
    throw InputError("vertices", "vertices has " + std::to_string(n0) + " points, at most " +
                                     std::to_string(kMaxOutlinePoints) + " are allowed for a concave outline");
  Vec2 lo = outline[0], hi = outline[0];
  for (size_t i = 0; i < n0; ++i) {
    requireFinite("vertices[" + std::to_string(i + 1) + "]", outline[i]);
    lo = lo.cwiseMin(outline[i]);
    hi = hi.cwiseMax(outline[i]);
  }
  // The squares of the coordinates must not overflow (makePolygon's rule, shape.cpp).
  for (size_t i = 0; i < n0; ++i) requireNearOrigin("vertices[" + std::to_string(i + 1) + "]", outline[i]);
  if (!isFinite(hi - lo) || !std::isfinite((hi - lo).squaredNorm()))
    throw InputError("vertices", "vertices span too far: the size of the outline from " + formatVec(lo) + " to " +
                                     formatVec(hi) + " overflows");
  const double tol = 1e-9 * (hi - lo).norm();

  // 1. Clean.
  std::vector<Vec2> pts;
  for (size_t i = 0; i < n0; ++i)
    if (pts.empty() || (outline[i] - pts.back()).norm() > tol) pts.push_back(outline[i]);
  while (pts.size() > 1 && (pts.front() - pts.back()).norm() <= tol) pts.pop_back();
  for (bool changed = true; changed && pts.size() >= 3;) {
    changed = false;
    for (size_t i = 0; i < pts.size(); ++i) {
      const Vec2& a = pts[(i + pts.size() - 1) % pts.size()];
      const Vec2& c = pts[(i + 1) % pts.size()];
      const double len = (c - a).norm();
      if (len == 0.0 || std::abs(orient(a, pts[i], c)) / len <= tol) {
        pts.erase(pts.begin() + static_cast<long>(i));
        changed = true;
        break;
      }
    }
  }
  if (pts.size() < 3) throw InputError("vertices", "vertices are collinear: the outline has zero area");
  double area2 = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) area2 += cross(pts[i] - pts[0], pts[(i + 1) % pts.size()] - pts[0]);
  if (area2 < 0) std::reverse(pts.begin(), pts.end());
  const size_t n = pts.size();

  // 2. Simple?
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segmentsIntersect(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n]))
        throw InputError("vertices", "outline crosses itself: edge " + std::to_string(i + 1) + " meets edge " +
                                         std::to_string(j + 1));
    }

  // 3. Ear clipping.
  std::vector<int> ring(n);
  for (size_t i = 0; i < n; ++i) ring[i] = static_cast<int>(i);
  std::vector<std::vector<int>> pieces;
  while (ring.size() > 3) {
    const size_t m = ring.size();
    bool cut = false;
    for (size_t i = 0; i < m && !cut; ++i) {
      const int ia = ring[(i + m - 1) % m], ib = ring[i], ic = ring[(i + 1) % m];
      if (orient(pts[ia], pts[ib], pts[ic]) <= 0) continue;  // reflex or flat corner
      bool empty = true;
      for (int k : ring)
        if (k != ia && k != ib && k != ic && inTriangle(pts[k], pts[ia], pts[ib], pts[ic])) {
          empty = false;
          break;
        }
      if (!empty) continue;
      pieces.push_back({ia, ib, ic});
      ring.erase(ring.begin() + static_cast<long>(i));
      cut = true;
    }
    if (!cut) throw InputError("vertices", "outline could not be split into convex pieces (is it simple?)");
  }
  pieces.push_back(ring);

  // 4. Merge neighbours across their shared edge while convex.
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t p = 0; p < pieces.size() && !merged; ++p)
      for (size_t q = p + 1; q < pieces.size() && !merged; ++q) {
        const auto& P = pieces[p];
        const auto& Q = pieces[q];
        if (P.size() + Q.size() - 2 > static_cast<size_t>(kMaxPolygonVertices)) continue;
        // A shared edge runs u → v in P and v → u in Q (both counter-clockwise).
        for (size_t i = 0; i < P.size() && !merged; ++i) {
          const int u = P[i], v = P[(i + 1) % P.size()];
          for (size_t j = 0; j < Q.size(); ++j) {
            if (Q[j] != v || Q[(j + 1) % Q.size()] != u) continue;
            std::vector<int> joined;  // P from v round to u, then Q's corners between u and v
            for (size_t k = 0; k < P.size(); ++k) joined.push_back(P[(i + 1 + k) % P.size()]);
            for (size_t k = 2; k < Q.size(); ++k) joined.push_back(Q[(j + k) % Q.size()]);
            if (convexPiece(pts, joined)) {
              pieces[p] = std::move(joined);
              pieces.erase(pieces.begin() + static_cast<long>(q));
              merged = true;
            }
            break;
          }
        }
      }
  }

  std::vector<std::vector<Vec2>> out;
  for (const auto& piece : pieces) {
    std::vector<Vec2> poly;
    for (int k : piece) poly.push_back(pts[k]);
    out.push_back(std::move(poly));
  }
  return out;
}

}  // namespace rigidlab

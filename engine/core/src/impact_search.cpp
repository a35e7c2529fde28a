// The earliest time two shapes touch along their bodies' paths (dense_output.cpp): the first root
// of the gap g(t) (manifold.cpp separationLowerBound: the distance with a circle or a capsule, the
// separating-axis separation of two polygons, which never exceeds their distance and is ≤ 0 exactly
// when they touch).
//
// A bound L on |g'| comes from the paths: no point of a body moves faster than its path's speed
// bound, so the distance of two shapes changes at most at the sum of the two. Hence on an interval
// [l, r] with g(l), g(r) > 0,
//   min g ≥ (g(l) + g(r) − L (r − l)) / 2,
// and when that is positive the shapes cannot touch in [l, r] (the interval is cleared; the
// separating-axis value is a lower bound of the distance, so the test holds with it too). The search
// walks the window from the left, halving every interval it cannot clear, down to a leaf of 1/64 of
// the window:
//   - a leaf whose right end has g ≤ 0 brackets the earliest root (every interval to its left was
//     cleared); the regula falsi with the Illinois modification (M. Dowell, P. Jarratt, BIT 11, 1971)
//     refines it to a fixed tolerance, 1e-14 of the window, keeping the bracket;
//   - a leaf with both ends > 0 that cannot be cleared may hide a graze (the shapes touch and part
//     between two evaluations): golden-section search for the gap's minimum inside it, and a
//     minimum ≤ 0 brackets a root with the leaf's left end.
// Everything is evaluated at fixed points of the window, so the result depends only on the paths:
// deterministic. A window needs about 25 evaluations near an impact and 2 (its ends) far from one.
#include <algorithm>
#include <cmath>
#include <limits>

#include "impact.h"
#include "manifold.h"

namespace rigidlab {

Transform MovingShape::at(double t) const {
  if (!path) return fixed;
  const double s = path->s(t);
  return transformAt(local_center, path->center(s), path->angle(s));
}

double gapAt(const MovingShape& a, const MovingShape& b, double t) {
  return separationLowerBound(*a.shape, a.at(t), *b.shape, b.at(t));
}

double touchTolerance(double scale) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  return 1e-9 + 64.0 * kEps * std::abs(scale);
}

namespace {

constexpr int kLeafDepth = 6;         // leaves are 1/64 of the window
constexpr double kRootTolerance = 1e-14;  // bracket width at which the root counts as found, in window units
constexpr int kMaxRefinements = 100;
constexpr int kGoldenSteps = 24;      // shrink a leaf by 0.618^24 ≈ 1e-5 looking for a graze

// Regula falsi with the Illinois modification on [l, r], g(l) > 0 ≥ g(r); returns a point with
// g ≤ 0 within kRootTolerance of the root (the bracket's right end).
template <typename Gap>
double refine(Gap& g, double l, double gl, double r, double gr) {
  int side = 0;  // which end was kept last: halve its value if kept twice (Illinois)
  for (int i = 0; i < kMaxRefinements && r - l > kRootTolerance; ++i) {
    double m = r - gr * (r - l) / (gr - gl);
    if (!(m > l && m < r)) m = 0.5 * (l + r);  // round-off at the bracket's ends: bisect
    const double gm = g(m);
    if (gm <= 0.0) {
      r = m, gr = gm;
      if (side == -1) gl *= 0.5;
      side = -1;
    } else {
      l = m, gl = gm;
      if (side == 1) gr *= 0.5;
      side = 1;
    }
  }
  return r;
}

}  // namespace

std::optional<double> earliestContact(const MovingShape& a, const MovingShape& b, double t_lo, double t_hi,
                                      int& evaluations) {
  const double width = t_hi - t_lo;
  if (!(width > 0.0)) return std::nullopt;
  const auto g = [&](double u) {
    ++evaluations;
    return gapAt(a, b, u < 1.0 ? t_lo + u * width : t_hi);
  };
  // Bound of |dg/du|: each path's speed is per unit of its own s.
  double lipschitz = 0.0;
  for (const MovingShape* m : {&a, &b})
    if (m->path && m->path->h > 0.0) lipschitz += m->path->speed * (width / m->path->h);

  double l = 0.0, gl = g(0.0);
  if (gl <= 0.0) return t_lo;  // touching already (the caller leaves such pairs to the contact solver)
  // Right ends of the intervals still to visit, nearest last.
  struct End {
    double u, g;
    int depth;
  };
  End stack[kLeafDepth + 2];
  int top = 0;
  double r = 1.0, gr = g(1.0);
  int depth = 0;
  for (;;) {
    bool cleared = gr > 0.0 && gl + gr - lipschitz * (r - l) > 0.0;
    if (!cleared && depth >= kLeafDepth) {
      if (gr <= 0.0) return t_lo + refine(g, l, gl, r, gr) * width;
      // Both ends apart, yet the bound cannot exclude a touch in between: look for the minimum.
      constexpr double kInvPhi = 0.6180339887498949;
      double x0 = l, x3 = r;
      double x1 = x3 - kInvPhi * (x3 - x0), x2 = x0 + kInvPhi * (x3 - x0);
      double g1 = g(x1), g2 = g(x2);
      for (int i = 0; i < kGoldenSteps && g1 > 0.0 && g2 > 0.0; ++i) {
        if (g1 < g2) {
          x3 = x2, x2 = x1, g2 = g1;
          x1 = x3 - kInvPhi * (x3 - x0);
          g1 = g(x1);
        } else {
          x0 = x1, x1 = x2, g1 = g2;
          x2 = x0 + kInvPhi * (x3 - x0);
          g2 = g(x2);
        }
      }
      if (g1 <= 0.0) return t_lo + refine(g, l, gl, x1, g1) * width;
      if (g2 <= 0.0) return t_lo + refine(g, l, gl, x2, g2) * width;
      cleared = true;  // no touch found down to 1e-5 of the leaf: a miss
    }
    if (cleared) {
      if (top == 0) return std::nullopt;
      l = r, gl = gr;
      --top;
      r = stack[top].u, gr = stack[top].g, depth = stack[top].depth;
      continue;
    }
    // Split: visit the left half first.
    const double m = 0.5 * (l + r);
    stack[top++] = {r, gr, depth + 1};
    r = m, gr = g(m), ++depth;
  }
}

}  // namespace rigidlab

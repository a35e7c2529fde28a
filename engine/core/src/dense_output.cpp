// Dense output: where a body is at any time inside a piece of a step, from the piece's two end
// states, as the integrator itself would put it. The event loop (event_location.cpp) looks for
// impacts along these paths, then integrates to the impact with the integrator proper.
//
// With h the piece's length, s = (t − t0)/h, start (c₀, v₀), end (c₁, v₁), Δ = c₁ − c₀:
//   RK4                  the cubic Hermite interpolant of the two ends and their derivatives
//                          c(s) = c₀ + h v₀ s + (3Δ − 2h v₀ − h v₁) s² + (h v₀ + h v₁ − 2Δ) s³
//                        (E. Hairer, S. P. Nørsett, G. Wanner, Solving ODEs I, II.6: RK4's free
//                        interpolant; its error is O(h⁴), a quadratic path (constant force) it
//                        reproduces exactly)
//   explicit Euler       c(s) = c₀ + s Δ: the method's own step of length s h (c += s h v₀)
//   semi-implicit and    c(s) = c₀ + s h v₀ + s² (Δ − h v₀): the method's own step of length s h,
//   implicit Euler         c += s h (v₀ + s h a), since Δ − h v₀ = h² a
// The angle follows the same polynomial with θ and ω. For the Euler methods a piece integrated to
// s h by the method lands exactly on its path, so an impact found on the path is an impact of the
// integrated state; for RK4 the two differ by the interpolant's O(h⁵) local error.
#include <algorithm>
#include <cmath>

#include "impact.h"

namespace rigidlab {
namespace {

// Bound of |p'(s)| on [0, 1] for p(s) = p0 + p1 s + p2 s² + p3 s³: p' = p1 + 2 p2 s + 3 p3 s² has the
// Bernstein coefficients p1, p1 + p2, p1 + 2 p2 + 3 p3, and lies in their hull.
template <typename T, typename Norm>
double derivativeBound(const T* p, Norm norm) {
  return std::max({norm(p[1]), norm(T(p[1] + p[2])), norm(T(p[1] + 2.0 * p[2] + 3.0 * p[3]))});
}

}  // namespace

BodyPath makePath(Integrator integrator, const PathState& start, const PathState& end, double t0, double h,
                  double reach, double margin) {
  BodyPath p;
  p.t0 = t0;
  p.h = h;
  const Vec2 d = end.c - start.c;
  const double da = end.a - start.a;
  p.c[0] = start.c;
  p.a[0] = start.a;
  switch (integrator) {
    case Integrator::RungeKutta4: {
      const Vec2 m0 = h * start.v, m1 = h * end.v;
      const double n0 = h * start.w, n1 = h * end.w;
      p.c[1] = m0;
      p.c[2] = 3.0 * d - 2.0 * m0 - m1;
      p.c[3] = m0 + m1 - 2.0 * d;
      p.a[1] = n0;
      p.a[2] = 3.0 * da - 2.0 * n0 - n1;
      p.a[3] = n0 + n1 - 2.0 * da;
      break;
    }
    case Integrator::ExplicitEuler:
      p.c[1] = d;
      p.a[1] = da;
      break;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitEuler:
      p.c[1] = h * start.v;
      p.c[2] = d - h * start.v;
      p.a[1] = h * start.w;
      p.a[2] = da - h * start.w;
      break;
  }
  p.speed = derivativeBound(p.c, [](const Vec2& v) { return v.norm(); }) +
            reach * derivativeBound(p.a, [](double x) { return std::abs(x); });
  // The centre's path lies in the hull of the cubic's Bernstein control points.
  const Vec2 b[4] = {p.c[0], p.c[0] + p.c[1] / 3.0, p.c[0] + (2.0 * p.c[1] + p.c[2]) / 3.0,
                     p.c[0] + p.c[1] + p.c[2] + p.c[3]};
  p.box.lower = p.box.upper = b[0];
  for (const Vec2& q : b) {
    p.box.lower = p.box.lower.cwiseMin(q);
    p.box.upper = p.box.upper.cwiseMax(q);
  }
  const Vec2 grow = Vec2::Constant(reach + margin);
  p.box.lower -= grow;
  p.box.upper += grow;
  return p;
}

}  // namespace rigidlab

// Narrow phase (docs/design/thesis.md §7): every shape pair in every configuration, normals from A to B,
// depths, point positions and feature ids.
#include <doctest/doctest.h>

#include <numbers>

#include "manifold.h"
#include "rigidlab/shape.h"

using namespace rigidlab;
using doctest::Approx;

namespace {
Transform at(double x, double y, double angle = 0.0) { return {Vec2(x, y), Rot::fromAngle(angle)}; }
}  // namespace

TEST_CASE("circle–circle") {
  const Shape a = makeCircle(1.0), b = makeCircle(0.5);
  SUBCASE("separated") { CHECK(collideShapes(a, at(0, 0), b, at(1.6, 0), 0.0).count == 0); }
  SUBCASE("touching") {
    const Manifold m = collideShapes(a, at(0, 0), b, at(1.5, 0), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.points[0].separation == Approx(0.0));
    CHECK(m.points[0].point.x() == Approx(1.0));
  }
  SUBCASE("overlapping on a diagonal: normal A→B, point midway between the surfaces") {
    const double d = 1.2 / std::sqrt(2.0);
    const Manifold m = collideShapes(a, at(0, 0), b, at(d, d), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(std::sqrt(0.5)));
    CHECK(m.normal.y() == Approx(std::sqrt(0.5)));
    CHECK(m.points[0].separation == Approx(-0.3));
    CHECK(m.points[0].point.norm() == Approx(0.85));  // surfaces at 1.0 and 0.7 from A's centre
  }
  SUBCASE("swapping A and B flips the normal") {
    const Manifold m = collideShapes(b, at(1.2, 0), a, at(0, 0), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(-1.0));
  }
  SUBCASE("coincident centres separate along +y") {
    const Manifold m = collideShapes(a, at(3, 3), b, at(3, 3), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(-1.5));
  }
}

TEST_CASE("polygon–circle") {
  const Shape box = makeBox(2.0, 2.0), disc = makeCircle(0.5);
  SUBCASE("separated, face region") { CHECK(collideShapes(box, at(0, 0), disc, at(1.6, 0), 0.0).count == 0); }
  SUBCASE("separated, corner region (inside the face slab test, outside the corner circle)") {
    CHECK(collideShapes(box, at(0, 0), disc, at(1.4, 1.4), 0.0).count == 0);
  }
  SUBCASE("touching a face") {
    const Manifold m = collideShapes(box, at(0, 0), disc, at(1.5, 0), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.points[0].separation == Approx(0.0));
  }
  SUBCASE("overlapping a face") {
    const Manifold m = collideShapes(box, at(0, 0), disc, at(1.3, 0.2), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(1.0));
    CHECK(m.normal.y() == Approx(0.0));
    CHECK(m.points[0].separation == Approx(-0.2));
    CHECK(m.points[0].point.x() == Approx(0.9));  // between the face (1.0) and the circle (0.8)
    CHECK(m.points[0].point.y() == Approx(0.2));
  }
  SUBCASE("overlapping a corner: normal from the corner to the centre") {
    const Manifold m = collideShapes(box, at(0, 0), disc, at(1.3, 1.3), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(std::sqrt(0.5)));
    CHECK(m.normal.y() == Approx(std::sqrt(0.5)));
    CHECK(m.points[0].separation == Approx(0.3 * std::sqrt(2.0) - 0.5));
  }
  SUBCASE("circle centre inside the polygon: pushed out through the nearest face") {
    const Manifold m = collideShapes(box, at(0, 0), disc, at(0.1, -0.8), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(-1.0));
    CHECK(m.points[0].separation == Approx(-0.2 - 0.5));
  }
  SUBCASE("circle as A: the normal still points from A to B") {
    const Manifold m = collideShapes(disc, at(1.3, 0.2), box, at(0, 0), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(-1.0));
    CHECK(m.points[0].separation == Approx(-0.2));
  }
  SUBCASE("rotated polygon") {
    const Manifold m = collideShapes(box, at(0, 0, std::numbers::pi / 2), disc, at(0, 1.4), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(-0.1));
  }
}

TEST_CASE("polygon–polygon") {
  const Shape box = makeBox(2.0, 2.0);
  SUBCASE("separated") { CHECK(collideShapes(box, at(0, 0), box, at(0.5, 2.1), 0.0).count == 0); }
  SUBCASE("separated along a diagonal axis") {
    CHECK(collideShapes(box, at(0, 0), box, at(2.05, 2.05, std::numbers::pi / 4), 0.0).count == 0);
  }
  SUBCASE("touching face to face: two points at zero separation") {
    const Manifold m = collideShapes(box, at(0, 0), box, at(0.5, 2.0), 0.0);
    REQUIRE(m.count == 2);
    CHECK(m.points[0].separation == Approx(0.0));
    CHECK(m.points[1].separation == Approx(0.0));
  }
  SUBCASE("edge–edge: two points at the ends of the contact segment") {
    const Manifold m = collideShapes(box, at(0, 0), box, at(1.5, 1.9), 0.0);
    REQUIRE(m.count == 2);
    CHECK(m.normal.x() == Approx(0.0));
    CHECK(m.normal.y() == Approx(1.0));
    double xs[2] = {m.points[0].point.x(), m.points[1].point.x()};
    if (xs[0] > xs[1]) std::swap(xs[0], xs[1]);
    CHECK(xs[0] == Approx(0.5));  // the overlap of the two top/bottom edges is x ∈ [0.5, 1]
    CHECK(xs[1] == Approx(1.0));
    for (int i = 0; i < 2; ++i) {
      CHECK(m.points[i].separation == Approx(-0.1));
      CHECK(m.points[i].point.y() == Approx(0.95));
    }
    CHECK(m.points[0].id != m.points[1].id);
  }
  SUBCASE("vertex–edge: one point at the penetrating corner") {
    // A square turned 45° whose lowest corner is 0.05 below the top face of the lower box.
    const double half_diag = std::sqrt(2.0);
    const Manifold m = collideShapes(box, at(0, 0), box, at(0.3, 1.0 + half_diag - 0.05, std::numbers::pi / 4), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(-0.05));
    CHECK(m.points[0].point.x() == Approx(0.3));
    CHECK(m.points[0].point.y() == Approx(0.975));
  }
  SUBCASE("swapping A and B flips the normal, keeps the depths") {
    const Manifold m = collideShapes(box, at(1.5, 1.9), box, at(0, 0), 0.0);
    REQUIRE(m.count == 2);
    CHECK(m.normal.y() == Approx(-1.0));
    CHECK(m.points[0].separation == Approx(-0.1));
  }
  SUBCASE("feature ids are stable while the same features touch") {
    const Manifold m1 = collideShapes(box, at(0, 0), box, at(1.5, 1.9), 0.0);
    const Manifold m2 = collideShapes(box, at(0, 0), box, at(1.45, 1.92, 0.01), 0.0);
    REQUIRE(m1.count == 2);
    REQUIRE(m2.count == 2);
    CHECK(m1.points[0].id == m2.points[0].id);
    CHECK(m1.points[1].id == m2.points[1].id);
  }
  SUBCASE("feature ids do not depend on which box gives the reference face") {
    // B on A, overlapping half a face. Turned by +1 mrad, A's top face is the axis of least
    // penetration (normal exactly +y); turned by −1 mrad, B's bottom face is, by 1.5 mm, more
    // than the tolerance (the normal is B's, tilted). The same two corners touch either way.
    const Manifold by_a = collideShapes(box, at(0, 0), box, at(1.5, 1.9, 0.001), 0.0);
    const Manifold by_b = collideShapes(box, at(0, 0), box, at(1.5, 1.9, -0.001), 0.0);
    REQUIRE(by_a.count == 2);
    REQUIRE(by_b.count == 2);
    CHECK(by_a.normal.x() == 0.0);
    CHECK(by_b.normal.x() == Approx(0.001).epsilon(1e-3));
    // The point at each end (left: B's corner over A, right: A's corner under B) keeps its id.
    const auto leftFirst = [](const Manifold& m) {
      return m.points[0].point.x() < m.points[1].point.x() ? std::pair(m.points[0].id, m.points[1].id)
                                                            : std::pair(m.points[1].id, m.points[0].id);
    };
    CHECK(leftFirst(by_a) == leftFirst(by_b));
    CHECK(leftFirst(by_a).first != leftFirst(by_a).second);
  }
  SUBCASE("small box deep inside a large one: pushed out through the nearest face") {
    const Manifold m = collideShapes(makeBox(10, 10), at(0, 0), makeBox(1, 1), at(4.2, 0), 0.0);
    REQUIRE(m.count == 2);
    CHECK(m.normal.x() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(-1.3));  // 5 − (4.2 − 0.5)
  }
  SUBCASE("triangle against box") {
    const std::vector<Vec2> tri = {{-1, 0}, {1, 0}, {0, 1}};
    const Manifold m = collideShapes(box, at(0, 0), makePolygon(tri), at(0, 0.9), 0.0);
    REQUIRE(m.count == 2);
    CHECK(m.normal.y() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(-0.1));
  }
}

// --- Rounded shapes and chains.

TEST_CASE("capsule–circle: the closest point of the core segment, minus both radii") {
  const Shape cap = makeCapsule({-1, 0}, {1, 0}, 0.25), disc = makeCircle(0.5);
  SUBCASE("beside the middle") {
    const Manifold m = collideShapes(cap, at(0, 0), disc, at(0.3, 0.7), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(0.7 - 0.75));
    CHECK(m.points[0].point.y() == Approx(0.5 * (0.25 + 0.2)));  // midway between the surfaces
  }
  SUBCASE("past an end: a rounded end") {
    const Manifold m = collideShapes(cap, at(0, 0), disc, at(1.5, 0.3), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(0.5 / std::hypot(0.5, 0.3)));
    CHECK(m.points[0].separation == Approx(std::hypot(0.5, 0.3) - 0.75));
  }
  SUBCASE("circle first: the normal still points from A to B") {
    const Manifold m = collideShapes(disc, at(0.3, 0.7), cap, at(0, 0), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(-1.0));
  }
}

TEST_CASE("capsule–capsule: parallel overlap gives two points, crossing gives one") {
  const Shape a = makeCapsule({-1, 0}, {1, 0}, 0.2), b = makeCapsule({-0.5, 0}, {0.5, 0}, 0.2);
  SUBCASE("lying on top, shifted") {
    const Manifold m = collideShapes(a, at(0, 0), b, at(0.8, 0.38), 0.0);
    REQUIRE(m.count == 2);
    CHECK(m.normal.y() == Approx(1.0));
    for (int i = 0; i < 2; ++i) CHECK(m.points[i].separation == Approx(-0.02));
    // b's core 0.3 … 1.3 clipped to a's 1.0 end: points at x = 0.3 and x = 1.0.
    const double x0 = std::min(m.points[0].point.x(), m.points[1].point.x());
    const double x1 = std::max(m.points[0].point.x(), m.points[1].point.x());
    CHECK(x0 == Approx(0.3));
    CHECK(x1 == Approx(1.0));
  }
  SUBCASE("crossed at right angles: one point") {
    // b's core runs up from (0.2, 0.1): 0.1 from a's core, both radii 0.2.
    const Manifold m = collideShapes(a, at(0, 0), b, at(0.2, 0.6, std::numbers::pi / 2), 0.01);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(-0.3));
    CHECK(m.points[0].point.x() == Approx(0.2));
  }
}

TEST_CASE("polygon–capsule and segment–polygon: a capsule lying on a box has two points") {
  const Shape box = makeBox(4, 1), cap = makeCapsule({-1, 0}, {1, 0}, 0.25);
  const Manifold m = collideShapes(box, at(0, 0), cap, at(0.5, 0.74), 0.0);
  REQUIRE(m.count == 2);
  CHECK(m.normal.y() == Approx(1.0));
  for (int i = 0; i < 2; ++i) CHECK(m.points[i].separation == Approx(-0.01));
  // A box resting on a ground segment.
  const Shape ground = makeSegment({-5, 0}, {5, 0});
  const Shape small = makeBox(1, 1);
  const Manifold g = collideShapes(ground, at(0, 0), small, at(0, 0.49), 0.0);
  REQUIRE(g.count == 2);
  CHECK(std::abs(g.normal.y()) == Approx(1.0));
  for (int i = 0; i < 2; ++i) CHECK(g.points[i].separation == Approx(-0.01));
  // Separated by more than the margin: nothing; within it: speculative points.
  CHECK(collideShapes(box, at(0, 0), cap, at(0, 0.8), 0.0).count == 0);
  CHECK(collideShapes(box, at(0, 0), cap, at(0, 0.8), 0.1).count == 2);
  // A capsule's rounded end near a box corner: one point along the line between core and corner.
  const Manifold c = collideShapes(box, at(0, 0), makeCapsule({0, 0}, {1, 0}, 0.1), at(2.2, 0.7), 0.5);
  REQUIRE(c.count == 1);
  CHECK(c.normal.x() == Approx(std::sqrt(0.5)));
  CHECK(c.points[0].separation == Approx(std::hypot(0.2, 0.2) - 0.1));
}

TEST_CASE("chain segment–circle: one-sided, and a joint between flush segments gives one contact") {
  // Ground listed from right to left: the surface faces up.
  const Shape left = makeChainSegment({2, 0}, {0, 0}, {-2, 0}, {-2, 0});
  const Shape right = makeChainSegment({2, 0}, {2, 0}, {0, 0}, {-2, 0});
  const Shape ball = makeCircle(0.5);
  SUBCASE("above: a contact with normal down from the chain to the ball, i.e. up") {
    const Manifold m = collideShapes(left, at(0, 0), ball, at(-1, 0.45), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.y() == Approx(1.0));
    CHECK(m.points[0].separation == Approx(-0.05));
  }
  SUBCASE("below (behind): nothing") { CHECK(collideShapes(left, at(0, 0), ball, at(-1, -0.45), 0.0).count == 0); }
  SUBCASE("just right of the joint: only the right segment answers") {
    const int from_left = collideShapes(left, at(0, 0), ball, at(0.01, 0.45), 0.0).count;
    const int from_right = collideShapes(right, at(0, 0), ball, at(0.01, 0.45), 0.0).count;
    CHECK(from_left + from_right == 1);
    CHECK(from_right == 1);
  }
  SUBCASE("a free end of an open chain collides like a segment end") {
    const Manifold m = collideShapes(left, at(0, 0), ball, at(-2.3, 0.3), 0.0);
    REQUIRE(m.count == 1);
    CHECK(m.normal.x() == Approx(-0.3 / std::hypot(0.3, 0.3)));
  }
}

TEST_CASE("chain segment–polygon: a box over the joint of flush segments gets only upward normals") {
  const Shape left = makeChainSegment({2, 0}, {0, 0}, {-2, 0}, {-2, 0});
  const Shape right = makeChainSegment({2, 0}, {2, 0}, {0, 0}, {-2, 0});
  const Shape box = makeBox(1, 1);
  for (double x : {-0.6, -0.5, -0.2, 0.0, 0.3, 0.5, 0.55}) {
    CAPTURE(x);
    int points = 0;
    for (const Shape* s : {&left, &right}) {
      const Manifold m = collideShapes(*s, at(0, 0), box, at(x, 0.49), 0.0);
      for (int i = 0; i < m.count; ++i) {
        CHECK(m.normal.y() == Approx(1.0));
        CHECK(m.points[i].separation == Approx(-0.01));
        ++points;
      }
    }
    CHECK(points >= 2);
  }
  // Behind the chain: nothing.
  CHECK(collideShapes(left, at(0, 0), box, at(-1, -0.49), 0.0).count == 0);
  // A capsule lying on the chain: two points.
  const Manifold c = collideShapes(left, at(0, 0), makeCapsule({-0.5, 0}, {0.5, 0}, 0.2), at(-1, 0.19), 0.0);
  CHECK(c.count == 2);
}

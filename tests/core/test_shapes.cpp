// Shapes: mass properties against hand-computed values, and polygon input validation.
#include <doctest/doctest.h>

#include <numbers>
#include <vector>

#include "rigidlab/error.h"
#include "rigidlab/shape.h"
#include "test_util.h"

using namespace rigidlab;
using std::numbers::pi;

TEST_CASE("circle mass properties: A = πR², I = ½ m R² about its centre") {
  const MassData md = computeMass(makeCircle(2.0, Vec2(1.0, -3.0)), 1.5);
  CHECK(md.area == doctest::Approx(4.0 * pi).epsilon(1e-15));
  CHECK(md.mass == doctest::Approx(6.0 * pi).epsilon(1e-15));
  CHECK(md.inertia == doctest::Approx(0.5 * 6.0 * pi * 4.0).epsilon(1e-15));
  CHECK(md.center.x() == 1.0);
  CHECK(md.center.y() == -3.0);
}

TEST_CASE("box mass properties: I = m (w² + h²) / 12") {
  const MassData md = computeMass(makeBox(2.0, 1.0, Vec2(0.5, 0.25)), 3.0);
  CHECK(md.area == doctest::Approx(2.0).epsilon(1e-15));
  CHECK(md.mass == doctest::Approx(6.0).epsilon(1e-15));
  CHECK(md.inertia == doctest::Approx(6.0 * (4.0 + 1.0) / 12.0).epsilon(1e-14));
  CHECK(md.center.x() == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(md.center.y() == doctest::Approx(0.25).epsilon(1e-15));
}

TEST_CASE("rotated box has the same inertia about its centre") {
  const MassData md = computeMass(makeBox(2.0, 1.0, Vec2::Zero(), 0.7), 1.0);
  CHECK(md.inertia == doctest::Approx(2.0 * 5.0 / 12.0).epsilon(1e-14));
  CHECK(std::abs(md.center.x()) < 1e-15);
}

TEST_CASE("right triangle: centroid at the mean of the corners, I = m (a² + b²) / 18") {
  const std::vector<Vec2> pts = {{0, 0}, {1, 0}, {0, 1}};
  const MassData md = computeMass(makePolygon(pts), 1.0);
  CHECK(md.area == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(md.center.x() == doctest::Approx(1.0 / 3.0).epsilon(1e-15));
  CHECK(md.center.y() == doctest::Approx(1.0 / 3.0).epsilon(1e-15));
  CHECK(md.inertia == doctest::Approx(0.5 * 2.0 / 18.0).epsilon(1e-14));
}

TEST_CASE("irregular convex pentagon against an independent triangle-fan computation") {
  // Reference computed with exact rational arithmetic by splitting into triangles from vertex 0
  // (area 16, centroid (2, 5/3), polar moment about the centroid 404/9 at density 1).
  const std::vector<Vec2> pts = {{0, 0}, {4, 0}, {5, 2}, {2, 4}, {-1, 2}};
  const MassData md = computeMass(makePolygon(pts), 2.0);
  CHECK(md.area == doctest::Approx(16.0).epsilon(1e-14));
  CHECK(md.mass == doctest::Approx(32.0).epsilon(1e-14));
  CHECK(md.center.x() == doctest::Approx(2.0).epsilon(1e-14));
  CHECK(md.center.y() == doctest::Approx(5.0 / 3.0).epsilon(1e-14));
  CHECK(md.inertia == doctest::Approx(2.0 * 404.0 / 9.0).epsilon(1e-13));
}

TEST_CASE("mass properties far from the origin keep their precision") {
  std::vector<Vec2> pts = {{0, 0}, {4, 0}, {5, 2}, {2, 4}, {-1, 2}};
  for (Vec2& p : pts) p += Vec2(1e5, -1e5);
  const MassData md = computeMass(makePolygon(pts), 1.0);
  CHECK(md.area == doctest::Approx(16.0).epsilon(1e-12));
  CHECK(md.center.x() == doctest::Approx(1e5 + 2.0).epsilon(1e-15));
  CHECK(md.inertia == doctest::Approx(404.0 / 9.0).epsilon(1e-9));
}

TEST_CASE("polygon normalisation: clockwise input is reversed, duplicates and collinear points dropped") {
  SUBCASE("clockwise square becomes counter-clockwise") {
    const std::vector<Vec2> cw = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    const Shape s = makePolygon(cw);
    REQUIRE(s.vertices.size() == 4);
    double area2 = 0;
    for (size_t i = 0; i < 4; ++i) area2 += cross(s.vertices[i], s.vertices[(i + 1) % 4]);
    CHECK(area2 == doctest::Approx(2.0));
    for (const Vec2& n : s.normals) CHECK(n.norm() == doctest::Approx(1.0));
  }
  SUBCASE("a repeated corner and a point in the middle of an edge are removed") {
    const std::vector<Vec2> pts = {{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {1, 1}, {0, 1}};
    const Shape s = makePolygon(pts);
    CHECK(s.vertices.size() == 4);
    CHECK(computeMass(s, 1.0).area == doctest::Approx(1.0));
  }
  SUBCASE("outward normals") {
    const Shape s = makeBox(2, 2);
    CHECK(s.normals[0].y() == doctest::Approx(-1.0));  // bottom edge
    CHECK(s.normals[1].x() == doctest::Approx(1.0));   // right edge
  }
}

TEST_CASE("rejected shapes name the field and the offending value") {
  CHECK_THROWS_WITH_AS(makeCircle(-1.0), "radius must be > 0, got -1", InputError);
  CHECK_THROWS_WITH_AS(makeCircle(0.0), "radius must be > 0, got 0", InputError);
  CHECK_THROWS_WITH_AS(makeCircle(NAN), "radius must be > 0, got nan", InputError);
  CHECK_THROWS_WITH_AS(makeCircle(1.0, Vec2(INFINITY, 0)), "center must be finite, got (inf, 0)", InputError);
  CHECK_THROWS_WITH_AS(makeBox(0.0, 1.0), "width must be > 0, got 0", InputError);
  CHECK_THROWS_WITH_AS(makeBox(1.0, -2.5), "height must be > 0, got -2.5", InputError);

  const auto polygonError = [](std::vector<Vec2> pts) { return test::errorOf([&] { makePolygon(pts); }); };
  CHECK(polygonError({{0, 0}, {1, 0}}) == "vertices needs at least 3 points, got 2");
  CHECK(polygonError({{0, 0}, {1, NAN}, {0, 1}}) == "vertices[2] must be finite, got (1, nan)");
  CHECK(polygonError({{0, 0}, {1, 1}, {2, 2}, {3, 3}}) == "vertices are collinear: the polygon has zero area");
  CHECK(polygonError({{0, 0}, {0, 0}, {1, 1}}) == "vertices has only 2 distinct points, a polygon needs 3");
  // An L-shaped outline turns clockwise at its inner corner, input vertex 4.
  CHECK(polygonError({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}) ==
        "polygon is not convex: it turns clockwise at vertices[4] (1, 1) (split concave shapes into convex pieces)");
  // A pentagram turns left at every corner but winds around twice.
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i) star.push_back({std::cos(4 * pi * i / 5), std::sin(4 * pi * i / 5)});
  CHECK(polygonError(star) == "polygon outline crosses itself (it winds around 2 times)");
  std::vector<Vec2> many;
  for (int i = 0; i < 33; ++i) many.push_back({std::cos(2 * pi * i / 33), std::sin(2 * pi * i / 33)});
  CHECK(polygonError(many) == "vertices has 33 points, at most 32 are allowed");

  try {
    makePolygon(std::vector<Vec2>{{0, 0}, {1, NAN}, {0, 1}});
  } catch (const InputError& e) {
    CHECK(e.field() == "vertices[2]");
  }
}

TEST_CASE("point in shape (docs/design/thesis.md §7)") {
  const Transform xf{Vec2(2, 1), Rot::fromAngle(pi / 2)};
  const Shape box = makeBox(2, 1);  // after a quarter turn: 1 wide, 2 tall around (2, 1)
  CHECK(containsPoint(box, xf, Vec2(2.4, 1.9)));
  CHECK_FALSE(containsPoint(box, xf, Vec2(2.6, 1.0)));
  CHECK(containsPoint(box, xf, Vec2(2.5, 1.0)));  // on the boundary counts as inside
  const Shape disc = makeCircle(0.5, Vec2(1, 0));
  CHECK(containsPoint(disc, xf, Vec2(2.0, 2.4)));  // centre at (2, 2) after the turn
  CHECK_FALSE(containsPoint(disc, xf, Vec2(2.0, 2.6)));
}

TEST_CASE("bounding boxes follow the transform") {
  const Aabb box = computeAabb(makeBox(2, 1), {Vec2(1, 1), Rot::fromAngle(pi / 2)});
  CHECK(box.lower.x() == doctest::Approx(0.5));
  CHECK(box.upper.x() == doctest::Approx(1.5));
  CHECK(box.lower.y() == doctest::Approx(0.0));
  CHECK(box.upper.y() == doctest::Approx(2.0));
  const Aabb disc = computeAabb(makeCircle(0.5, Vec2(1, 0)), {Vec2(0, 0), Rot::fromAngle(pi)});
  CHECK(disc.lower.x() == doctest::Approx(-1.5));
  CHECK(disc.upper.x() == doctest::Approx(-0.5));
}

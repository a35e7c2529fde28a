// Portable trigonometry (rigidlab/portable_math.h): accurate to about one unit in the last place,
// C's special cases, and the same bits everywhere (fixed outputs, written as hexadecimal doubles:
// a build that fused a multiply–add or called the C library would change some of them).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include "rigidlab/portable_math.h"

using namespace rigidlab;

namespace {

// |got − exact| in units in the last place of the double nearest exact.
double ulps(double got, long double exact) {
  const double e = static_cast<double>(exact);
  const double unit = std::nextafter(std::fabs(e), INFINITY) - std::fabs(e);
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / unit);
}

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("portable math: sin, cos, atan and atan2 within 1.5 units in the last place of long double's") {
  std::mt19937_64 random(7);
  double sin_worst = 0.0, cos_worst = 0.0, atan_worst = 0.0, atan2_worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double range = i % 3 == 0 ? 1.0 : i % 3 == 1 ? 30.0 : 5e5;
    const double x = std::uniform_real_distribution<double>(-range, range)(random);
    double s = 0.0, c = 0.0;
    portableSinCos(x, s, c);
    REQUIRE(same(s, portableSin(x)));
    REQUIRE(same(c, portableCos(x)));
    sin_worst = std::max(sin_worst, ulps(s, sinl(x)));
    cos_worst = std::max(cos_worst, ulps(c, cosl(x)));
    const double t = std::uniform_real_distribution<double>(-40.0, 40.0)(random);
    atan_worst = std::max(atan_worst, ulps(portableAtan(t), atanl(t)));
    double y = std::uniform_real_distribution<double>(-3.0, 3.0)(random);
    if (i % 7 == 0) y *= 1e-7;
    const double xx = std::uniform_real_distribution<double>(-3.0, 3.0)(random);
    atan2_worst = std::max(atan2_worst, ulps(portableAtan2(y, xx), atan2l(y, xx)));
  }
  MESSAGE("worst: sin " << sin_worst << ", cos " << cos_worst << ", atan " << atan_worst << ", atan2 " << atan2_worst << " ulp");
  CHECK(sin_worst < 1.0);
  CHECK(cos_worst < 1.0);
  CHECK(atan_worst < 1.5);
  CHECK(atan2_worst < 1.5);
}

TEST_CASE("portable math: C's special cases") {
  CHECK(same(portableSin(0.0), 0.0));
  CHECK(same(portableSin(-0.0), -0.0));
  CHECK(same(portableCos(0.0), 1.0));
  CHECK(same(portableAtan(-0.0), -0.0));
  for (double x : {INFINITY, -INFINITY, NAN}) {
    CHECK(std::isnan(portableSin(x)));
    CHECK(std::isnan(portableCos(x)));
  }
  CHECK(same(portableAtan(INFINITY), std::atan(static_cast<double>(INFINITY))));
  // atan2's signed zeros and infinities: exactly C's values.
  const double special[][2] = {{0.0, 0.0},  {-0.0, 0.0},     {0.0, -0.0},       {-0.0, -0.0},       {1.0, 0.0},
                               {-1.0, 0.0}, {1.0, -0.0},     {0.0, -1.0},       {-0.0, -1.0},       {0.0, 1.0},
                               {INFINITY, INFINITY}, {-INFINITY, -INFINITY}, {INFINITY, -INFINITY}, {1.0, INFINITY},
                               {1.0, -INFINITY},     {-1.0, -INFINITY},      {INFINITY, 1.0},       {-INFINITY, -5.0}};
  for (const auto& p : special) {
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    CHECK(same(portableAtan2(p[0], p[1]), std::atan2(p[0], p[1])));
  }
  CHECK(std::isnan(portableAtan2(NAN, 1.0)));
  CHECK(std::isnan(portableAtan2(1.0, NAN)));
  // The quadrants.
  CHECK(portableAtan2(1.0, 1.0) == doctest::Approx(M_PI / 4).epsilon(1e-15));
  CHECK(portableAtan2(1.0, -1.0) == doctest::Approx(3 * M_PI / 4).epsilon(1e-15));
  CHECK(portableAtan2(-1.0, -1.0) == doctest::Approx(-3 * M_PI / 4).epsilon(1e-15));
  CHECK(portableAtan2(-1.0, 1.0) == doctest::Approx(-M_PI / 4).epsilon(1e-15));
}

TEST_CASE("portable math: fixed bits") {
  // The outputs of this build, which every machine must reproduce.
  struct Case {
    double x, sin, cos, atan;
  };
  const Case cases[] = {
      {0x1p-1, 0x1.eaee8744b05fp-2, 0x1.c1528065b7d5p-1, 0x1.dac670561bb4fp-2},
      {0x1p+0, 0x1.aed548f090ceep-1, 0x1.14a280fb5068cp-1, 0x1.921fb54442d18p-1},
      {-0x1p+1, -0x1.d18f6ead1b446p-1, -0x1.aa22657537205p-2, -0x1.1b6e192ebbe44p+0},
      {0x1.921f9f01b866ep+1, 0x1.6428a6aa44cdp-19, -0x1.fffffffff842p-1, 0x1.433b8619a690ap+0},
      {0x1.4p+3, -0x1.1689ef5f34f52p-1, -0x1.ad9ac890c6b1fp-1, 0x1.789bd2c160053p+0},
      {-0x1.91p+6, 0x1.1bf00980dc35cp-2, 0x1.ebec72ba6b0ecp-1, -0x1.8f92010a9ab6dp+0},
      {0x1.81cd6c8b43958p+13, -0x1.687d5890974a5p-1, 0x1.6b94c3bbe24b8p-1, 0x1.921a664fe1dc4p+0},
      {0x1.e848p+19, -0x1.6664b2568d867p-2, 0x1.df9df9906d32cp-1, 0x1.921fa47d4b30dp+0},
      {0x1.2599ed7c6fbd2p-14, 0x1.2599ed7869ea7p-14, 0x1.ffffffeaf464ap-1, 0x1.2599ed746417bp-14},
      {0x1.921fb323ae5afp-1, 0x1.6a09e4e6e03c8p-1, 0x1.6a09e7e9073b8p-1, 0x1.54e04ab4ffb0ep-1},
  };
  for (const Case& k : cases) {
    CAPTURE(k.x);
    CHECK(same(portableSin(k.x), k.sin));
    CHECK(same(portableCos(k.x), k.cos));
    CHECK(same(portableAtan(k.x), k.atan));
  }
  CHECK(same(portableAtan2(-0.3, -2.5), -0x1.82d642d289d64p+1));
}

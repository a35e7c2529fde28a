// Sine, cosine and arctangent from + − × ÷ only (portable_math.h).
//
// sin and cos: x = k·π/2 + r with |r| ≤ π/4 (Cody and Waite's reduction: π/2 in three parts of
// which the first two have 33 significant bits, so k·part is exact for |k| < 2¹⁹), then the Taylor
// series of sin r to r¹⁷ and of cos r to r¹⁸: on |r| ≤ π/4 the first omitted terms are below
// 10⁻¹⁹ of the result, far under its last bit. cos r = 1 − r²/2 + r⁴·q is summed as
// w + ((1 − w) − r²/2 + r⁴·q) with w = 1 − r²/2, which recovers the bits the first subtraction
// rounds away.
//
// atan: for t = |x| ≤ 1, the nearest of c = 0, 1/4, 3/8, …, 1 and atan t = atan c + atan u with
// u = (t − c)/(1 + c·t), |u| ≤ 3/16 (the addition formula of the arctangent); atan u by its series
// to u²⁵ (omitted terms below 10⁻¹⁹ of it); atan c as a double and its remainder (both from a
// 80-digit evaluation). For t > 1, atan t = π/2 − atan(1/t).
//
// The constants are the doubles nearest to the exact values (the series' rational coefficients,
// π and atan(k/8) to 80 digits), written in hexadecimal so that no decimal conversion intervenes.
#include "rigidlab/portable_math.h"

#include <cmath>

namespace rigidlab {
namespace {

constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
constexpr double kPio2Part1 = 0x1.921fb54400000p+0;  // 33 bits
constexpr double kPio2Part2 = 0x1.0b4611a600000p-34;  // the next 33 bits
constexpr double kPio2Part3 = 0x1.3198a2e037073p-69;  // the rest, to 53 bits
constexpr double kPio2Hi = 0x1.921fb54442d18p+0, kPio2Lo = 0x1.1a62633145c07p-54;
constexpr double kPiHi = 0x1.921fb54442d18p+1, kPiLo = 0x1.1a62633145c07p-53;
constexpr double kTwoPi = 0x1.921fb54442d18p+2;
constexpr double kLargest = 0x1.8p+19;  // |k| below 2¹⁹·1.5: k·part 1 and k·part 2 exact

// (−1)ⁿ/(2n+1)! for n = 1 … 8.
constexpr double kSin[8] = {-0x1.5555555555555p-3,  0x1.1111111111111p-7,  -0x1.a01a01a01a01ap-13, 0x1.71de3a556c734p-19,
                            -0x1.ae64567f544e4p-26, 0x1.6124613a86d09p-33, -0x1.ae7f3e733b81fp-41, 0x1.952c77030ad4ap-49};
// (−1)ⁿ/(2n)! for n = 2 … 9.
constexpr double kCos[8] = {0x1.5555555555555p-5,  -0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-16,  -0x1.27e4fb7789f5cp-22,
                            0x1.1eed8eff8d898p-29, -0x1.93974a8c07c9dp-37, 0x1.ae7f3e733b81fp-45, -0x1.6827863b97d97p-53};
// (−1)ⁿ/(2n+1) for n = 1 … 12.
constexpr double kAtan[12] = {-0x1.5555555555555p-2, 0x1.999999999999ap-3,  -0x1.2492492492492p-3, 0x1.c71c71c71c71cp-4,
                              -0x1.745d1745d1746p-4, 0x1.3b13b13b13b14p-4, -0x1.1111111111111p-4, 0x1.e1e1e1e1e1e1ep-5,
                              -0x1.af286bca1af28p-5, 0x1.8618618618618p-5,  -0x1.642c8590b2164p-5, 0x1.47ae147ae147bp-5};
// atan(k/8) for k = 0 … 8: the nearest double and what is left of the exact value.
constexpr double kAtanHi[9] = {0.0,
                               0x1.fd5ba9aac2f6ep-4,
                               0x1.f5b75f92c80ddp-3,
                               0x1.6f61941e4def1p-2,
                               0x1.dac670561bb4fp-2,
                               0x1.1e00babdefeb4p-1,
                               0x1.4978fa3269ee1p-1,
                               0x1.700a7c5784634p-1,
                               0x1.921fb54442d18p-1};
constexpr double kAtanLo[9] = {0.0,
                               -0x1.cd37686760c17p-59,
                               0x1.8ab6e3cf7afbdp-57,
                               -0x1.c63aae6f6e918p-56,
                               0x1.a2b7f222f65e2p-56,
                               -0x1.928df287a668fp-58,
                               0x1.2419a87f2a458p-56,
                               -0x1.8c34d25aadef6p-56,
                               0x1.1a62633145c07p-55};

// The integer nearest v, |v| < 2⁵¹: adding 1.5·2⁵² leaves no bits below the units, so the sum
// rounds v to an integer (to even on a tie, as nearbyint in the default rounding mode), and the
// subtraction is exact. An inline add and subtract where nearbyint is a library call without SSE4.1.
inline double nearestInteger(double v) {
  constexpr double kShift = 0x1.8p52;
  return (v + kShift) - kShift;
}

// sin(r + e) and cos(r + e) for |r| ≤ π/4 (a little more after rounding) and e the reduction's
// tail, |e| ≤ one unit in the last place of r: sin(r + e) ≈ sin r + e·(1 − r²/2) and
// cos(r + e) ≈ cos r − e·r, to far below the last place.
double sinKernel(double r, double e) {
  const double z = r * r;
  double p = kSin[7];
  for (int i = 6; i >= 0; --i) p = p * z + kSin[i];
  return r + (r * (z * p) + e * (1.0 - 0.5 * z));
}

double cosKernel(double r, double e) {
  const double z = r * r;
  double q = kCos[7];
  for (int i = 6; i >= 0; --i) q = q * z + kCos[i];
  const double half = 0.5 * z;
  const double w = 1.0 - half;
  return w + ((((1.0 - w) - half) + z * (z * q)) - e * r);
}

// x = k·π/2 + r + e: returns r, its tail e and the quadrant k mod 4. x finite. x − k·part 1 and
// k·part 2 are exact; their difference is rounded and what rounding dropped is kept in the tail
// (Knuth's two-sum), with the third part's product.
double reduce(double x, double& e, int& quadrant) {
  e = 0.0;
  quadrant = 0;
  if (std::fabs(x) <= 0x1.921fb54442d18p-1) return x;  // |x| ≤ π/4: nothing to reduce
  if (std::fabs(x) * kTwoOverPi >= kLargest) x = std::fmod(x, kTwoPi);  // exact, by the double nearest 2π
  const double k = nearestInteger(x * kTwoOverPi);
  const double y = x - k * kPio2Part1, w = k * kPio2Part2;
  const double t = y - w;
  const double v = t - y;
  const double tail = ((y - (t - v)) - (w + v)) - k * kPio2Part3;
  const double r = t + tail;
  e = (t - r) + tail;
  quadrant = static_cast<int>(static_cast<long long>(k) & 3);
  return r;
}

// atan t for 0 ≤ t ≤ 1.
double atanUnit(double t) {
  int k = static_cast<int>(nearestInteger(t * 8.0));
  if (k == 1) k = 0;  // below 3/16 directly: with c = 1/8 the rounding of u would be as large as the result's last bit
  const double c = k * 0.125;
  const double u = (t - c) / (1.0 + c * t);
  const double z = u * u;
  double p = kAtan[11];
  for (int i = 10; i >= 0; --i) p = p * z + kAtan[i];
  return kAtanHi[k] + (kAtanLo[k] + (u + u * (z * p)));
}

// atan t for t ≥ 0 (t may be +∞).
double atanPositive(double t) {
  if (t <= 1.0) return atanUnit(t);
  return kPio2Hi - (atanUnit(1.0 / t) - kPio2Lo);
}

}  // namespace

void portableSinCos(double x, double& s, double& c) {
  if (!std::isfinite(x)) {
    s = c = x - x;  // NaN, as sin and cos of ±∞ and NaN are
    return;
  }
  if (std::fabs(x) < 0x1p-27) {  // as portableSin and portableCos
    s = x;
    c = cosKernel(x, 0.0);
    return;
  }
  int quadrant = 0;
  double e = 0.0;
  const double r = reduce(x, e, quadrant);
  const double sr = sinKernel(r, e), cr = cosKernel(r, e);
  switch (quadrant) {  // sin(r + kπ/2), cos(r + kπ/2)
    case 0: s = sr; c = cr; break;
    case 1: s = cr; c = -sr; break;
    case 2: s = -sr; c = -cr; break;
    default: s = -cr; c = sr; break;
  }
}

double portableSin(double x) {
  if (!std::isfinite(x)) return x - x;
  if (std::fabs(x) < 0x1p-27) return x;  // x³/6 is below half of x's last bit (and −0 stays −0)
  int quadrant = 0;
  double e = 0.0;
  const double r = reduce(x, e, quadrant);
  switch (quadrant) {
    case 0: return sinKernel(r, e);
    case 1: return cosKernel(r, e);
    case 2: return -sinKernel(r, e);
    default: return -cosKernel(r, e);
  }
}

double portableCos(double x) {
  if (!std::isfinite(x)) return x - x;
  int quadrant = 0;
  double e = 0.0;
  const double r = reduce(x, e, quadrant);
  switch (quadrant) {
    case 0: return cosKernel(r, e);
    case 1: return -sinKernel(r, e);
    case 2: return -cosKernel(r, e);
    default: return sinKernel(r, e);
  }
}

double portableAtan(double x) {
  if (std::isnan(x)) return x;
  const double a = atanPositive(std::fabs(x));
  return std::signbit(x) ? -a : a;
}

double portableAtan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  const double ax = std::fabs(x), ay = std::fabs(y);
  double a;
  if (ay == 0.0) {
    a = std::signbit(x) ? kPiHi : 0.0;  // atan2(±0, −0 or x < 0) = ±π, atan2(±0, +0 or x > 0) = ±0
  } else if (std::isinf(ax) && std::isinf(ay)) {
    a = std::signbit(x) ? 0.75 * kPiHi : 0.25 * kPiHi;
  } else if (std::isinf(ax)) {
    a = std::signbit(x) ? kPiHi : 0.0;
  } else if (ax == 0.0 || std::isinf(ay)) {
    a = kPio2Hi;
  } else {
    // The smaller over the larger, so the quotient is at most 1 and never overflows.
    a = ay <= ax ? atanUnit(ay / ax) : kPio2Hi - (atanUnit(ax / ay) - kPio2Lo);
    if (std::signbit(x)) a = kPiHi - (a - kPiLo);
  }
  return std::signbit(y) ? -a : a;
}

}  // namespace rigidlab

#include "rigidlab/error.h"

#include <charconv>
#include <cmath>

namespace rigidlab {

std::string formatNumber(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);  // shortest round-trip representation
  return ec == std::errc() ? std::string(buf, end) : std::to_string(x);
}

std::string formatVec(const Vec2& v) { return "(" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ")"; }

double requireFinite(const std::string& field, double x) {
  if (!std::isfinite(x)) throw InputError(field, field + " must be finite, got " + formatNumber(x));
  return x;
}

Vec2 requireFinite(const std::string& field, const Vec2& v) {
  if (!isFinite(v)) throw InputError(field, field + " must be finite, got " + formatVec(v));
  return v;
}

double requirePositive(const std::string& field, double x) {
  if (!(std::isfinite(x) && x > 0)) throw InputError(field, field + " must be > 0, got " + formatNumber(x));
  return x;
}

double requireNonNegative(const std::string& field, double x) {
  if (!(std::isfinite(x) && x >= 0)) throw InputError(field, field + " must be >= 0, got " + formatNumber(x));
  return x;
}

}  // namespace rigidlab

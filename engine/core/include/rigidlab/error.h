// Rejected input. Every public constructor of the core validates what it is given (in release
// builds too) and throws InputError on a bad value, so a NaN, a negative size or a degenerate
// polygon never reaches the simulation. The message names the field and the offending value,
// e.g. "radius must be > 0, got -1"; `field` holds the field name alone so that a binding layer
// (the Lua scene loader) can prefix its own function name and source location.
#pragma once

#include <stdexcept>
#include <string>

#include "rigidlab/math.h"

namespace rigidlab {

class InputError : public std::invalid_argument {
 public:
  InputError(std::string field, const std::string& message)
      : std::invalid_argument(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// Formats a number the way error messages show it: shortest round-trip form ("0.1", "-1", "nan",
// "inf").
std::string formatNumber(double x);
std::string formatVec(const Vec2& v);  // "(x, y)"

// Throws InputError("<field> must be finite, got <x>") unless x is finite; returns x.
double requireFinite(const std::string& field, double x);
Vec2 requireFinite(const std::string& field, const Vec2& v);
// Throws unless x is finite and > 0 ("<field> must be > 0, got <x>").
double requirePositive(const std::string& field, double x);
// Throws unless x is finite and >= 0.
double requireNonNegative(const std::string& field, double x);

}  // namespace rigidlab

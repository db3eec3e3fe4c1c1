#pragma once
// Floats on a double wall, from the definition: for points stored exactly on a wall or just below.

#include <cmath>
#include <limits>

namespace eco::test {

/// The least float f with double(f) >= w.
inline float first_float_at_or_above(double w) {
  float f = float(w);
  while (double(f) < w) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  while (double(std::nextafter(f, -std::numeric_limits<float>::infinity())) >= w) {
    f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  }
  return f;
}

}  // namespace eco::test

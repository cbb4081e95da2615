// Small inline helpers of the colloid force terms: minimum-image separations and the
// conversion of a force component to the fixed point in which all colloid forces are summed.
#pragma once

#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"

#include <array>
#include <cmath>
#include <cstdint>

namespace narrows::colloids {

// Minimum image of a separation along a periodic axis of length L.
inline double minimum_image(double d, double L) {
  if (d > 0.5 * L)
    return d - L;
  if (d < -0.5 * L)
    return d + L;
  return d;
}

// i modulo n in [0, n) (the periodic index of an unwrapped cell): one comparison each way for
// an index within a period of [0, n), as the cells around a colloid are; a division otherwise.
inline int wrap_index(int i, int n) {
  if (i < 0)
    i += n;
  else if (i >= n)
    i -= n;
  if (i < 0 || i >= n) [[unlikely]]
    i = ((i % n) + n) % n;
  return i;
}

// The separation a - b of two points (minimum image along the periodic axes) into d; returns
// its square.
template <int D, bool WallsY>
inline double separation(const double *a, const double *b, const std::array<double, 3> &L,
                         double *d) {
  double r2 = 0.0;
  for (int k = 0; k < D; ++k) {
    d[k] = a[k] - b[k];
    if (!(WallsY && k == 1))
      d[k] = minimum_image(d[k], L[k]);
    r2 += d[k] * d[k];
  }
  return r2;
}

// A force component in fixed point; refuses values the 64-bit sums cannot hold.
[[noreturn]] void fixed_range_error(double f); // invariant_error naming f (forces.cpp)

inline std::int64_t to_fixed(double f) {
  if (!(std::abs(f) < fixed::max_magnitude)) [[unlikely]]
    fixed_range_error(f);
  return fixed::from_double(f);
}

} // namespace narrows::colloids

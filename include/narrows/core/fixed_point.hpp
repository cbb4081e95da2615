// 64-bit fixed-point numbers for sums whose result must not depend on the order of terms
// (cell momenta, angular momenta, global momentum): integer addition is associative, so a
// sum is bitwise the same whatever order particles arrive in, on any number of ranks.
#pragma once

#include <cmath>
#include <cstdint>
#if defined(__SSE2__) && defined(__x86_64__)
#include <emmintrin.h>
#endif

namespace narrows::fixed {

// 40 fractional bits: resolution 9.1e-13, range of one sum +-8.4e6. A cell sum of n
// velocities of size |v| needs n|v| < 8e6, far above what an MPCD fluid reaches (the
// invariant check refuses |v| > max_speed).
inline constexpr int frac_bits = 40;
inline constexpr double scale = 0x1p40;
inline constexpr double inv_scale = 0x1p-40;
inline constexpr double max_magnitude = 0x1p22; // half the range, for range checks

// Round to nearest-even (the default rounding mode). On x86-64 this is one cvtsd2si
// instruction; std::llrint is an out-of-line libm call unless -fno-math-errno, and it sits in
// the hottest loops (binning, cell sums).
inline std::int64_t from_double(double v) {
#if defined(__SSE2__) && defined(__x86_64__)
  return _mm_cvtsd_si64(_mm_set_sd(v * scale));
#else
  return std::llrint(v * scale);
#endif
}
inline double to_double(std::int64_t f) { return static_cast<double>(f) * inv_scale; }

} // namespace narrows::fixed

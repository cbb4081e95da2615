// 64-bit fixed-point numbers for sums whose result must not depend on the order of terms
// (cell momenta, angular momenta, global momentum): integer addition is associative, so a
// sum is bitwise the same whatever order particles arrive in, on any number of ranks.
#pragma once

#include <cmath>
#include <cstdint>

namespace narrows::fixed {

// 40 fractional bits: resolution 9.1e-13, range of one sum +-8.4e6. A cell sum of n
// velocities of size |v| needs n|v| < 8e6, far above what an MPCD fluid reaches (the
// invariant check refuses |v| > max_speed).
inline constexpr int frac_bits = 40;
inline constexpr double scale = 0x1p40;
inline constexpr double inv_scale = 0x1p-40;
inline constexpr double max_magnitude = 0x1p22; // half the range, for range checks

// Round to nearest (the current rounding mode: nearest-even by default).
inline std::int64_t from_double(double v) { return std::llrint(v * scale); }
inline double to_double(std::int64_t f) { return static_cast<double>(f) * inv_scale; }

} // namespace narrows::fixed

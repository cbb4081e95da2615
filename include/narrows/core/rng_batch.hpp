// Counter-based Gaussians for many ids at once: the Philox4x32-10 blocks of a batch of ids and
// their Box-Muller transform, as plain loops over fixed-size arrays that the compiler
// vectorises (rng.hpp draws one block at a time, with libm's scalar log and sincos).
#pragma once

#include "narrows/core/rng.hpp"

#include <cstddef>
#include <cstdint>

namespace narrows::rng {

// Ids per call: a multiple of every vector width, so every id takes the same (vector) path
// and its deviates do not depend on where in an array it sits.
inline constexpr std::size_t batch = 64;

// The blocks draw(seed, purpose, step, id[j]) for j < batch, word k in w[k][j]; bitwise the
// same as rng::draw.
void draw_batch(std::uint64_t seed, Purpose purpose, std::uint64_t step, const std::uint64_t *id,
                std::uint32_t (*w)[batch]);

// The same by the plain loop (the path without AVX-512; exposed to test both paths).
void draw_batch_plain(std::uint64_t seed, Purpose purpose, std::uint64_t step,
                      const std::uint64_t *id, std::uint32_t (*w)[batch]);

// Standard normal deviates of those blocks by Box-Muller, both deviates of every pair used:
// g[0], g[1] from words 0 and 1 (radius from word 0, angle from word 1, as rng::gaussian2),
// and with count = 4 also g[2], g[3] from words 2 and 3 (as rng::gaussian4). The logarithm,
// sine and cosine are polynomial (fdlibm's kernels), within a few ulp of libm's: the deviates
// agree with gaussian4's to ~1e-15 of their radius, not bitwise.
void gaussian_batch(std::uint64_t seed, Purpose purpose, std::uint64_t step,
                    const std::uint64_t *id, int count, double (*g)[batch]);

// The transform alone, on word arrays (exposed for the accuracy tests): -2 ln(open01(a)) and
// sin, cos of 2 pi open01(b), then g0 = r cos, g1 = r sin with r = sqrt(-2 ln u).
void box_muller_batch(const std::uint32_t *a, const std::uint32_t *b, double *g0, double *g1);

} // namespace narrows::rng

// Counter-based random numbers: Philox4x32-10 known answers, purity of rng::draw, the ranges
// of the uniform conversions, and the moments of the Box-Muller Gaussians.
#include "narrows/core/rng.hpp"
#include "narrows/core/rng_batch.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>

namespace {

using namespace narrows;
using rng::Block;

// Known-answer vectors of Random123 (kat_vectors, philox4x32 10 rounds).
TEST(RngPhilox, KnownAnswerZero) {
  const Block got = rng::philox4x32_10({0, 0, 0, 0}, {0, 0});
  const Block want = {0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u};
  EXPECT_EQ(got, want);
}

TEST(RngPhilox, KnownAnswerAllOnes) {
  const Block got = rng::philox4x32_10({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu},
                                       {0xffffffffu, 0xffffffffu});
  const Block want = {0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu};
  EXPECT_EQ(got, want);
}

TEST(RngPhilox, KnownAnswerPi) {
  const Block got = rng::philox4x32_10({0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u},
                                       {0xa4093822u, 0x299f31d0u});
  const Block want = {0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u};
  EXPECT_EQ(got, want);
}

TEST(RngDraw, PureFunctionOfArguments) {
  const std::uint64_t seeds[] = {0, 1, 0x123456789abcdefull, ~0ull};
  const std::uint64_t steps[] = {0, 7, 0xffffffffull, 0x100000000ull, 0xabcdef12345ull};
  const std::uint64_t ids[] = {0, 3, 0xffffffffull, 0x100000000ull, ~0ull};
  for (auto seed : seeds)
    for (auto step : steps)
      for (auto id : ids) {
        const Block a = rng::draw(seed, rng::Purpose::test, step, id);
        // Interleave other draws: no hidden state may leak into the next call.
        (void)rng::draw(seed + 1, rng::Purpose::srd_rotation, step + 1, id + 1);
        const Block b = rng::draw(seed, rng::Purpose::test, step, id);
        EXPECT_EQ(a, b) << "seed " << seed << " step " << step << " id " << id;
      }
}

TEST(RngDraw, EveryArgumentChangesTheBlock) {
  const std::uint64_t seed = 0x0123456789abcdefull, step = 0x0000123487654321ull,
                      id = 0x00fedcba98765432ull;
  const Block base = rng::draw(seed, rng::Purpose::test, step, id);
  // Flip every bit of the seed and the id, and every bit of the step the counter holds.
  for (int b = 0; b < 64; ++b) {
    EXPECT_NE(rng::draw(seed ^ (1ull << b), rng::Purpose::test, step, id), base)
        << "seed bit " << b;
    EXPECT_NE(rng::draw(seed, rng::Purpose::test, step, id ^ (1ull << b)), base) << "id bit " << b;
  }
  // The counter keeps 56 bits of the step (32 low + 24 next to the purpose), see rng.hpp.
  for (int b = 0; b < 56; ++b)
    EXPECT_NE(rng::draw(seed, rng::Purpose::test, step ^ (1ull << b), id), base)
        << "step bit " << b;
  // Step bits above 32 matter: steps 1 and 1 + 2^32 must not share a stream.
  EXPECT_NE(rng::draw(seed, rng::Purpose::test, 1, id),
            rng::draw(seed, rng::Purpose::test, 1 + (1ull << 32), id));
  const rng::Purpose purposes[] = {rng::Purpose::grid_shift,     rng::Purpose::srd_rotation,
                                   rng::Purpose::at_gaussian,    rng::Purpose::random_maxwell,
                                   rng::Purpose::random_permute, rng::Purpose::init_position,
                                   rng::Purpose::init_velocity};
  for (auto p : purposes)
    EXPECT_NE(rng::draw(seed, p, step, id), base) << "purpose " << static_cast<int>(p);
  for (auto p : purposes)
    for (auto q : purposes)
      if (p != q) {
        EXPECT_NE(rng::draw(seed, p, step, id), rng::draw(seed, q, step, id));
      }
}

TEST(RngDraw, MatchesPhiloxWithDocumentedCounterLayout) {
  const std::uint64_t seed = 0x1122334455667788ull, step = 0x00abcdef01234567ull,
                      id = 0x99aabbccddeeff00ull;
  const Block want = rng::philox4x32_10(
      {0xddeeff00u, 0x99aabbccu, 0x01234567u, (15u << 24) | 0xabcdefu}, {0x55667788u, 0x11223344u});
  EXPECT_EQ(rng::draw(seed, rng::Purpose::test, step, id), want);
}

TEST(RngUniform, Open01StrictlyInside) {
  const double lo = rng::open01(0u), hi = rng::open01(0xffffffffu);
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_EQ(lo, 0x1p-33);
  EXPECT_EQ(hi, 1.0 - 0x1p-33);
  EXPECT_GT(std::log(lo), -24.0); // finite log for Box-Muller
  EXPECT_LT(rng::open01(0x7fffffffu), 0.5);
  EXPECT_GT(rng::open01(0x80000000u), 0.5);
}

TEST(RngUniform, Uniform53HalfOpen) {
  EXPECT_EQ(rng::uniform53(0u, 0u), 0.0);
  EXPECT_LT(rng::uniform53(0xffffffffu, 0xffffffffu), 1.0);
  EXPECT_EQ(rng::uniform53(0xffffffffu, 0xffffffffu), 1.0 - 0x1p-53);
  // All 53 bits reach the result: the lowest from lo's top bit block, the highest from hi.
  EXPECT_EQ(rng::uniform53(0u, 1u << 11), 0x1p-53);
  EXPECT_EQ(rng::uniform53(0u, (1u << 11) - 1), 0.0);
  EXPECT_EQ(rng::uniform53(1u, 0u), 0x1p-32);
  EXPECT_EQ(rng::uniform53(0x80000000u, 0u), 0.5);
  for (std::uint64_t i = 0; i < 100000; ++i) {
    const Block b = rng::draw(5, rng::Purpose::test, 0, i);
    const double u = rng::uniform53(b[0], b[1]);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    const double o = rng::open01(b[2]);
    ASSERT_GT(o, 0.0);
    ASSERT_LT(o, 1.0);
  }
}

TEST(RngGaussian, MomentsOfOneMillionDraws) {
  // 250000 blocks x 4 deviates = 1e6 standard normal draws.
  const std::uint64_t blocks = 250000;
  const double N = 4.0 * blocks;
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  double c01 = 0, c02 = 0, c13 = 0;
  for (std::uint64_t i = 0; i < blocks; ++i) {
    const auto g = rng::gaussian4(rng::draw(2024, rng::Purpose::test, 3, i));
    for (double x : g) {
      ASSERT_TRUE(std::isfinite(x));
      s1 += x;
      s2 += x * x;
      s3 += x * x * x;
      s4 += x * x * x * x;
    }
    c01 += g[0] * g[1];
    c02 += g[0] * g[2];
    c13 += g[1] * g[3];
  }
  const double mean = s1 / N;
  const double var = s2 / N - mean * mean;
  const double skew = s3 / N;
  const double kurt = (s4 / N) / (var * var);
  // sigma of the sample mean of N(0,1): 1/sqrt(N) = 1e-3.
  EXPECT_LT(std::abs(mean), 5.0 / std::sqrt(N));
  // sigma of the sample variance: sqrt(Var(x^2)/N) = sqrt(2/N) = 1.41e-3.
  EXPECT_LT(std::abs(var - 1.0), 5.0 * std::sqrt(2.0 / N));
  // sigma of the third moment: sqrt(E x^6 / N) = sqrt(15/N) = 3.9e-3.
  EXPECT_LT(std::abs(skew), 5.0 * std::sqrt(15.0 / N));
  // sigma of the sample kurtosis of a normal: sqrt(24/N) = 4.9e-3.
  EXPECT_LT(std::abs(kurt - 3.0), 5.0 * std::sqrt(24.0 / N));
  // The four deviates of a block are uncorrelated; sigma of each mean product: 1/sqrt(blocks).
  const double nb = static_cast<double>(blocks);
  EXPECT_LT(std::abs(c01 / nb), 5.0 / std::sqrt(nb));
  EXPECT_LT(std::abs(c02 / nb), 5.0 / std::sqrt(nb));
  EXPECT_LT(std::abs(c13 / nb), 5.0 / std::sqrt(nb));
}

TEST(RngGaussian, TailsMatchNormal) {
  // Fraction beyond |x| > 2: 0.0455003; binomial sigma sqrt(p(1-p)/N) = 2.1e-4 for N = 1e6.
  const std::uint64_t blocks = 250000;
  const double N = 4.0 * blocks;
  double beyond = 0;
  for (std::uint64_t i = 0; i < blocks; ++i)
    for (double x : rng::gaussian4(rng::draw(99, rng::Purpose::test, 0, i)))
      beyond += std::abs(x) > 2.0;
  const double p = 0.04550026389635842;
  EXPECT_LT(std::abs(beyond / N - p), 5.0 * std::sqrt(p * (1 - p) / N));
}

} // namespace

TEST(Gaussian, TwoAreTheFirstTwoOfFour) {
  for (std::uint64_t id = 0; id < 1000; ++id) {
    const auto b = narrows::rng::draw(3, narrows::rng::Purpose::test, 1, id);
    const auto four = narrows::rng::gaussian4(b);
    const auto two = narrows::rng::gaussian2(b);
    ASSERT_EQ(two[0], four[0]);
    ASSERT_EQ(two[1], four[1]);
  }
}

// Batched draws (core/rng_batch.hpp): the same blocks as rng::draw on both code paths, Gaussians
// within rounding of libm's Box-Muller, and Gaussian moments and tails.
namespace {

using narrows::rng::batch;

std::array<std::uint64_t, batch> scattered_ids(std::uint64_t first) {
  std::array<std::uint64_t, batch> ids;
  for (std::size_t j = 0; j < batch; ++j) // scattered, some above 2^32, one all ones
    ids[j] = (first + j) * 0x9E3779B97F4A7C15ull >> (j % 3 == 0 ? 0 : 20);
  ids[batch / 2] = ~0ull;
  return ids;
}

TEST(RngBatch, BlocksAreRngDrawOnBothPaths) {
  using namespace narrows;
  alignas(64) std::uint32_t w[4][batch], p[4][batch];
  const std::uint64_t seeds[] = {0, 1, 0x123456789abcdefull, ~0ull};
  const std::uint64_t steps[] = {0, 7, 0xffffffffull, 0x100000000ull, 0xabcdef12345ull};
  for (auto seed : seeds)
    for (auto step : steps)
      for (auto purpose : {rng::Purpose::at_gaussian, rng::Purpose::test}) {
        const auto ids = scattered_ids(seed ^ step);
        rng::draw_batch(seed, purpose, step, ids.data(), w);
        rng::draw_batch_plain(seed, purpose, step, ids.data(), p);
        for (std::size_t j = 0; j < batch; ++j) {
          const rng::Block b = rng::draw(seed, purpose, step, ids[j]);
          for (int k = 0; k < 4; ++k) {
            ASSERT_EQ(w[k][j], b[k]) << "seed " << seed << " step " << step << " id " << ids[j];
            ASSERT_EQ(p[k][j], b[k]) << "plain loop, seed " << seed << " id " << ids[j];
          }
        }
      }
}

// The deviates of an id do not depend on its position in a batch or on its neighbours.
TEST(RngBatch, DeviatesDoNotDependOnPosition) {
  using namespace narrows;
  const auto ids = scattered_ids(5);
  alignas(64) double a[4][batch], b[4][batch];
  rng::gaussian_batch(11, rng::Purpose::at_gaussian, 3, ids.data(), 4, a);
  std::array<std::uint64_t, batch> turned;
  for (std::size_t j = 0; j < batch; ++j)
    turned[j] = ids[(j + 13) % batch];
  rng::gaussian_batch(11, rng::Purpose::at_gaussian, 3, turned.data(), 4, b);
  for (std::size_t j = 0; j < batch; ++j)
    for (int k = 0; k < 4; ++k)
      ASSERT_EQ(b[k][j], a[k][(j + 13) % batch]) << "position " << j << " deviate " << k;
  // count = 2 gives the first two of count = 4.
  rng::gaussian_batch(11, rng::Purpose::at_gaussian, 3, ids.data(), 2, b);
  for (std::size_t j = 0; j < batch; ++j)
    for (int k = 0; k < 2; ++k)
      ASSERT_EQ(b[k][j], a[k][j]);
}

// The polynomial log, sin and cos against libm (rng::gaussian4): every deviate within 2e-15 of
// its pair's radius (libm and fdlibm's kernels are each within ~1 ulp; the radius reaches 6.7,
// so this is a few ulp). Also at the edge words: u = open01(0), open01(2^32 - 1), and angles
// at the quadrant boundaries, where the integer reduction switches quadrant.
TEST(RngBatch, GaussiansAgreeWithLibmBoxMuller) {
  using namespace narrows;
  double worst = 0;
  alignas(64) double g[4][batch];
  alignas(64) std::uint32_t w[4][batch];
  for (std::uint64_t first = 0; first < 400000; first += batch) {
    const auto ids = scattered_ids(first);
    rng::draw_batch(77, rng::Purpose::test, 9, ids.data(), w);
    rng::gaussian_batch(77, rng::Purpose::test, 9, ids.data(), 4, g);
    for (std::size_t j = 0; j < batch; ++j) {
      const auto want = rng::gaussian4({w[0][j], w[1][j], w[2][j], w[3][j]});
      for (int k = 0; k < 4; ++k) {
        const double radius = std::hypot(want[k & 2], want[(k & 2) + 1]);
        worst = std::max(worst, std::abs(g[k][j] - want[k]) / radius);
      }
    }
  }
  EXPECT_LT(worst, 2e-15);
  const std::uint32_t edges[] = {0u,          1u,          0x1fffffffu, 0x20000000u, 0x3fffffffu,
                                 0x40000000u, 0x5fffffffu, 0x60000000u, 0x9fffffffu, 0xa0000000u,
                                 0xdfffffffu, 0xe0000000u, 0xfffffffeu, 0xffffffffu};
  alignas(64) std::uint32_t a[batch], b[batch];
  alignas(64) double g0[batch], g1[batch];
  constexpr std::size_t ne = std::size(edges);
  for (std::size_t j = 0; j < batch; ++j) {
    a[j] = edges[j % ne];
    b[j] = edges[(j / ne + 3 * j) % ne];
  }
  rng::box_muller_batch(a, b, g0, g1);
  for (std::size_t j = 0; j < batch; ++j) {
    const auto want = rng::gaussian2({a[j], b[j], 0u, 0u});
    const double radius = std::hypot(want[0], want[1]);
    EXPECT_LE(std::abs(g0[j] - want[0]), 2e-15 * radius) << "words " << a[j] << " " << b[j];
    EXPECT_LE(std::abs(g1[j] - want[1]), 2e-15 * radius) << "words " << a[j] << " " << b[j];
  }
}

// Moments up to the 4th and tails of 1e6 batched deviates, with the sigmas of
// RngGaussian.MomentsOfOneMillionDraws; the tails beyond 2, 3 and 4 sigma within 5 binomial
// sigmas; deviates of one pair and of the two pairs uncorrelated.
TEST(RngBatch, GaussianMomentsAndTails) {
  using namespace narrows;
  const std::size_t rounds = 250000 / batch + 1;
  const double N = 4.0 * rounds * batch, nb = static_cast<double>(rounds * batch);
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0, c01 = 0, c02 = 0, c23 = 0;
  double beyond[3] = {0, 0, 0};
  alignas(64) double g[4][batch];
  std::array<std::uint64_t, batch> ids;
  for (std::size_t r = 0; r < rounds; ++r) {
    for (std::size_t j = 0; j < batch; ++j)
      ids[j] = r * batch + j;
    rng::gaussian_batch(2024, rng::Purpose::at_gaussian, 3, ids.data(), 4, g);
    for (std::size_t j = 0; j < batch; ++j) {
      for (int k = 0; k < 4; ++k) {
        const double x = g[k][j];
        ASSERT_TRUE(std::isfinite(x));
        s1 += x;
        s2 += x * x;
        s3 += x * x * x;
        s4 += x * x * x * x;
        for (int t = 0; t < 3; ++t)
          beyond[t] += std::abs(x) > 2.0 + t;
      }
      c01 += g[0][j] * g[1][j];
      c02 += g[0][j] * g[2][j];
      c23 += g[2][j] * g[3][j];
    }
  }
  const double mean = s1 / N, var = s2 / N - mean * mean;
  EXPECT_LT(std::abs(mean), 5.0 / std::sqrt(N));
  EXPECT_LT(std::abs(var - 1.0), 5.0 * std::sqrt(2.0 / N));
  EXPECT_LT(std::abs(s3 / N), 5.0 * std::sqrt(15.0 / N));
  EXPECT_LT(std::abs((s4 / N) / (var * var) - 3.0), 5.0 * std::sqrt(24.0 / N));
  EXPECT_LT(std::abs(c01 / nb), 5.0 / std::sqrt(nb));
  EXPECT_LT(std::abs(c02 / nb), 5.0 / std::sqrt(nb));
  EXPECT_LT(std::abs(c23 / nb), 5.0 / std::sqrt(nb));
  const double p[3] = {0.04550026389635842, 0.0026997960632601866, 6.334248366623996e-05};
  for (int t = 0; t < 3; ++t)
    EXPECT_LT(std::abs(beyond[t] / N - p[t]), 5.0 * std::sqrt(p[t] * (1 - p[t]) / N))
        << "fraction beyond " << 2 + t << ": " << beyond[t] / N << ", normal " << p[t];
}

} // namespace

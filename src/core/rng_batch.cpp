// Batched Philox4x32-10 and Box-Muller (see rng_batch.hpp). Compiled with -fno-math-errno
// (CMakeLists.txt) so that std::sqrt is one vector instruction; nothing here reads errno.
#include "narrows/core/rng_batch.hpp"

#include "narrows/core/trig_kernels.hpp"

#include <bit>
#include <cmath>
#ifdef __AVX512F__
#include <immintrin.h>
#endif

namespace narrows::rng {

namespace {

// Random123's Philox4x32 constants (philox.h: PHILOX_M4x32_0/1, PHILOX_W32_0/1).
constexpr std::uint32_t M0 = 0xD2511F53u, M1 = 0xCD9E8D57u;
constexpr std::uint32_t W0 = 0x9E3779B9u, W1 = 0xBB67AE85u;

// ln(u) for u in (0, 1), normal: fdlibm's e_log.c without its special cases. u = 2^e m with
// m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s), s = (m - 1) / (m + 1), by a minimax
// polynomial in s^2 (error < 2^-58.45); the result is within 1 ulp.
inline double log_open01(double u) {
  constexpr double Lg1 = 6.666666666666735130e-01, Lg2 = 3.999999999940941908e-01,
                   Lg3 = 2.857142874366239149e-01, Lg4 = 2.222219843214978396e-01,
                   Lg5 = 1.818357216161805012e-01, Lg6 = 1.531383769920937332e-01,
                   Lg7 = 1.479819860511658591e-01;
  constexpr double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(u);
  const std::int64_t e0 = static_cast<std::int64_t>(bits >> 52) - 1023;
  const double m0 = std::bit_cast<double>((bits & 0x000fffffffffffffull) | 0x3ff0000000000000ull);
  const bool big = m0 > 1.4142135623730951; // selects of constants only: no branch, vectorises
  const double m = m0 * (big ? 0.5 : 1.0);
  const double k = static_cast<double>(e0) + (big ? 1.0 : 0.0);
  const double f = m - 1.0;
  const double s = f / (2.0 + f), z = s * s, w = z * z;
  const double t1 = w * (Lg2 + w * (Lg4 + w * Lg6));
  const double t2 = z * (Lg1 + w * (Lg3 + w * (Lg5 + w * Lg7)));
  const double R = t2 + t1, hfsq = 0.5 * f * f;
  return k * ln2_hi - ((hfsq - (s * (hfsq + R) + k * ln2_lo)) - f);
}

// sin and cos of 2 pi (b + 1/2) 2^-32 (= 2 pi open01(b)). The quadrant q = round(4 t) and the
// remainder r = t - q/4 in [-1/8, 1/8] come exactly from the integer b; fdlibm's k_sin.c and
// k_cos.c kernels (minimax on [-pi/4, pi/4], error < 2^-58) give sin and cos of 2 pi r, which
// the quadrant swaps and negates.
inline void sincos_2pi_open01(std::uint32_t b, double &sine, double &cosine) {
  constexpr double two_pi = 6.283185307179586;
  const std::uint32_t q = ((b + 0x20000000u) >> 30) & 3u;  // b + 2^29 wraps: quadrant 4 = 0
  const auto d = static_cast<std::int32_t>(b - (q << 30)); // in [-2^29, 2^29)
  const double x = two_pi * ((static_cast<double>(d) + 0.5) * 0x1p-32);
  double s, c;
  trig::kernel_sincos(x, s, c);
  trig::to_quadrant(q, s, c, sine, cosine);
}

// The counter words that do not depend on the id (rng::draw's layout: {id lo, id hi, step lo,
// purpose << 24 | step bits 32-55}) and the key of each of the ten rounds.
struct Keys {
  std::uint32_t c2, c3, k0[10], k1[10];
};
inline Keys keys(std::uint64_t seed, Purpose purpose, std::uint64_t step) {
  Keys k;
  k.c2 = static_cast<std::uint32_t>(step);
  k.c3 = (static_cast<std::uint32_t>(purpose) << 24) |
         static_cast<std::uint32_t>((step >> 32) & 0xFFFFFFu);
  k.k0[0] = static_cast<std::uint32_t>(seed);
  k.k1[0] = static_cast<std::uint32_t>(seed >> 32);
  for (int r = 1; r < 10; ++r) {
    k.k0[r] = k.k0[r - 1] + W0;
    k.k1[r] = k.k1[r - 1] + W1;
  }
  return k;
}

} // namespace

void draw_batch_plain(std::uint64_t seed, Purpose purpose, std::uint64_t step,
                      const std::uint64_t *id, std::uint32_t (*w)[batch]) {
  const Keys k = keys(seed, purpose, step);
  for (std::size_t j = 0; j < batch; ++j) {
    std::uint32_t x0 = static_cast<std::uint32_t>(id[j]),
                  x1 = static_cast<std::uint32_t>(id[j] >> 32);
    std::uint32_t x2 = k.c2, x3 = k.c3;
    for (int r = 0; r < 10; ++r) { // one Philox round: two 32 x 32 -> 64 bit products
      const std::uint64_t p0 = static_cast<std::uint64_t>(M0) * x0;
      const std::uint64_t p1 = static_cast<std::uint64_t>(M1) * x2;
      const std::uint32_t y0 = static_cast<std::uint32_t>(p1 >> 32) ^ x1 ^ k.k0[r];
      const std::uint32_t y2 = static_cast<std::uint32_t>(p0 >> 32) ^ x3 ^ k.k1[r];
      x1 = static_cast<std::uint32_t>(p1);
      x3 = static_cast<std::uint32_t>(p0);
      x0 = y0;
      x2 = y2;
    }
    w[0][j] = x0;
    w[1][j] = x1;
    w[2][j] = x2;
    w[3][j] = x3;
  }
}

void draw_batch(std::uint64_t seed, Purpose purpose, std::uint64_t step, const std::uint64_t *id,
                std::uint32_t (*w)[batch]) {
#ifdef __AVX512F__
  // Eight ids per register, one per 64-bit lane whose low half holds the 32-bit word: the
  // lane multiply (vpmuludq) reads only low halves, so the high halves may hold junk and no
  // masking is needed until the words are stored. (The plain loop vectorises with 32-bit
  // lanes and spends most of its instructions moving between the two layouts: ~4x slower.)
  const Keys k = keys(seed, purpose, step);
  const __m512i m0 = _mm512_set1_epi64(M0), m1 = _mm512_set1_epi64(M1);
  const __m512i c2 = _mm512_set1_epi64(k.c2), c3 = _mm512_set1_epi64(k.c3);
  __m512i k0[10], k1[10];
  for (int r = 0; r < 10; ++r) {
    k0[r] = _mm512_set1_epi64(k.k0[r]);
    k1[r] = _mm512_set1_epi64(k.k1[r]);
  }
  for (std::size_t j = 0; j < batch; j += 8) {
    __m512i x0 = _mm512_loadu_si512(id + j);
    __m512i x1 = _mm512_srli_epi64(x0, 32), x2 = c2, x3 = c3;
    for (int r = 0; r < 10; ++r) {
      const __m512i p0 = _mm512_mul_epu32(x0, m0), p1 = _mm512_mul_epu32(x2, m1);
      // 0x96: three-way xor
      x0 = _mm512_ternarylogic_epi64(_mm512_srli_epi64(p1, 32), x1, k0[r], 0x96);
      x2 = _mm512_ternarylogic_epi64(_mm512_srli_epi64(p0, 32), x3, k1[r], 0x96);
      x1 = p1;
      x3 = p0;
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(&w[0][j]), _mm512_cvtepi64_epi32(x0));
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(&w[1][j]), _mm512_cvtepi64_epi32(x1));
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(&w[2][j]), _mm512_cvtepi64_epi32(x2));
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(&w[3][j]), _mm512_cvtepi64_epi32(x3));
  }
#else
  draw_batch_plain(seed, purpose, step, id, w);
#endif
}

void box_muller_batch(const std::uint32_t *a, const std::uint32_t *b, double *g0, double *g1) {
  for (std::size_t j = 0; j < batch; ++j) {
    const double r = std::sqrt(-2.0 * log_open01(open01(a[j])));
    double s, c;
    sincos_2pi_open01(b[j], s, c);
    g0[j] = r * c;
    g1[j] = r * s;
  }
}

void gaussian_batch(std::uint64_t seed, Purpose purpose, std::uint64_t step,
                    const std::uint64_t *id, int count, double (*g)[batch]) {
  alignas(64) std::uint32_t w[4][batch];
  draw_batch(seed, purpose, step, id, w);
  box_muller_batch(w[0], w[1], g[0], g[1]);
  if (count == 4)
    box_muller_batch(w[2], w[3], g[2], g[3]);
}

} // namespace narrows::rng

// Propagation and collision of one row of the FHP lattice: portable loop and AVX-512 VBMI.
#include "narrows/engines/lgca/fhp_update.hpp"

#ifdef __AVX512VBMI__
#include <immintrin.h>
#endif

namespace narrows::lgca {

bool vbmi_kernel() {
#ifdef __AVX512VBMI__
  return true;
#else
  return false;
#endif
}

void update_row_portable(const RowUpdate &r) {
  const int o = r.odd;
  for (int x = 0; x < r.n; ++x) {
    const unsigned in = (r.here[x - 1] & 0x01u) | (r.below[x - 1 + o] & 0x02u) |
                        (r.below[x + o] & 0x04u) | (r.here[x + 1] & 0x08u) |
                        (r.above[x + o] & 0x10u) | (r.above[x - 1 + o] & 0x20u) |
                        (r.here[x] & 0x40u);
    // Index arithmetic, not branches: the chirality bit is random, a branch on it would be
    // mispredicted half of the time.
    const unsigned chir = (r.chirality[x >> 6] >> (x & 63)) & 1u;
    const std::uint8_t s = r.table[chir << 7 | in];
    r.out[x] = r.solid != nullptr && r.solid[x] ? r.bounce[in] : s;
  }
}

#ifdef __AVX512VBMI__
void update_row_vbmi(const RowUpdate &r) {
  const int o = r.odd;
  const __m512i t0a = _mm512_loadu_si512(r.table), t0b = _mm512_loadu_si512(r.table + 64);
  const __m512i t1a = _mm512_loadu_si512(r.table + 128), t1b = _mm512_loadu_si512(r.table + 192);
  const __m512i ba = _mm512_loadu_si512(r.bounce), bb = _mm512_loadu_si512(r.bounce + 64);
  const auto bit = [](unsigned b) { return _mm512_set1_epi8(static_cast<char>(b)); };
  const __m512i m0 = bit(0x01), m1 = bit(0x02), m2 = bit(0x04), m3 = bit(0x08), m4 = bit(0x10),
                m5 = bit(0x20), m6 = bit(0x40);
  for (int x = 0; x < r.n; x += 64) {
    const int left = r.n - x;
    const __mmask64 k = left >= 64 ? ~__mmask64{0} : (__mmask64{1} << left) - 1;
    const auto ld = [k](const std::uint8_t *p) { return _mm512_maskz_loadu_epi8(k, p); };
    // Ternary logic 0xF8 = a | (b & c): OR in one masked link per load.
    __m512i in = _mm512_and_si512(ld(r.here + x - 1), m0);
    in = _mm512_ternarylogic_epi64(in, ld(r.below + x - 1 + o), m1, 0xF8);
    in = _mm512_ternarylogic_epi64(in, ld(r.below + x + o), m2, 0xF8);
    in = _mm512_ternarylogic_epi64(in, ld(r.here + x + 1), m3, 0xF8);
    in = _mm512_ternarylogic_epi64(in, ld(r.above + x + o), m4, 0xF8);
    in = _mm512_ternarylogic_epi64(in, ld(r.above + x - 1 + o), m5, 0xF8);
    in = _mm512_ternarylogic_epi64(in, ld(r.here + x), m6, 0xF8);
    const __m512i s0 = _mm512_permutex2var_epi8(t0a, in, t0b);
    const __m512i s1 = _mm512_permutex2var_epi8(t1a, in, t1b);
    const __mmask64 chir = r.chirality[x >> 6];
    __m512i s = _mm512_mask_blend_epi8(chir, s0, s1);
    if (r.solid != nullptr) {
      const __mmask64 solid = _mm512_test_epi8_mask(ld(r.solid + x), ld(r.solid + x));
      if (solid)
        s = _mm512_mask_blend_epi8(solid, s, _mm512_permutex2var_epi8(ba, in, bb));
    }
    _mm512_mask_storeu_epi8(r.out + x, k, s);
  }
}
#endif

} // namespace narrows::lgca

// Linear springs with Coulomb friction between colloids and with the walls
// (Kanehl (thesis) §4.2.3).
#include "narrows/colloids/springs.hpp"

#include "narrows/colloids/colloid_pairs.hpp"
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#if defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512BW__) && defined(__AVX512VL__)
// GCC 12's AVX-512 headers leave a dummy operand undefined on purpose (GCC bug 105593).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif

namespace narrows::colloids {

namespace {

// Rows in the pair list standing for the walls (partner ids wall_low_id, wall_high_id).
constexpr std::uint32_t wall_low_row = ~std::uint32_t{0}, wall_high_row = wall_low_row - 1;

// The 2D path of SpringContacts::forces: the same operations in the same order as its generic
// (3D) loop, written with scalars and selects so that they vectorise (the generic loop's small
// arrays keep it scalar). The hits of a block of slots: slot, rows i and j (j = i for a wall),
// kind (0 pair, 1 lower wall, 2 upper wall), what the touch test found of the geometry (d = x_j
// - x_i with its minimum image, |d|^2, r_i + r_j or a wall's overlap, and the lever arms r_i
// and r_j, 0 for a wall), and the spring.
struct Hits2 {
  std::uint64_t *slot, *i, *j;
  std::int64_t *kind;
  double *d[2], *r2, *reach, *r[2], *xi[2];
};

// The slots' side of the touch test: with `update`, whether each slot touches, and its spring
// dropped (zeroed) if it does not (a touching slot's goes to the hits first).
struct Slots2 {
  double *xi[2];
  std::uint8_t *touch;
  bool update;
};

// One slot's touch test (the scalar form of touching_2d's vector body): written at hits[nh],
// which grows only if the slot touches.
template <bool WallsY>
inline std::size_t touch_slot_2d(const Colloids &c, std::uint64_t i, std::uint32_t p, std::size_t q,
                                 const Slots2 &slots, const std::array<double, 3> &L,
                                 const Hits2 &hit, std::size_t nh) {
  const double *x0 = c.x[0].data(), *x1 = c.x[1].data(), *rad = c.radius.data();
  const bool wall = WallsY && p >= wall_high_row, low = p == wall_low_row;
  const std::uint64_t j = wall ? i : p;
  double d0 = x0[j] - x0[i], d1 = x1[j] - x1[i]; // from i towards j
  d0 = minimum_image(d0, L[0]);
  if constexpr (!WallsY)
    d1 = minimum_image(d1, L[1]);
  double r2 = 0.0;
  r2 += d0 * d0;
  r2 += d1 * d1;
  const double ri = rad[i], rj = rad[j], R = ri + rj, y = x1[i];
  const double wall_delta = low ? ri - y : y + ri - L[1];
  const bool touch = wall ? wall_delta > 0.0 : r2 < R * R;
  hit.slot[nh] = q;
  hit.i[nh] = i;
  hit.j[nh] = j;
  hit.kind[nh] = wall ? (low ? 1 : 2) : 0;
  hit.d[0][nh] = d0;
  hit.d[1][nh] = d1;
  hit.r2[nh] = r2;
  hit.reach[nh] = wall ? wall_delta : R;
  hit.r[0][nh] = ri;
  hit.r[1][nh] = wall ? 0.0 : rj;
  for (int k = 0; k < 2; ++k) {
    hit.xi[k][nh] = slots.xi[k][q];
    if (slots.update)
      slots.xi[k][q] = touch ? slots.xi[k][q] : 0.0;
  }
  if (slots.update)
    slots.touch[q] = touch;
  return nh + touch;
}

// The slots q0 <= q < q1 that touch now (a colloid pair closer than r_i + r_j, or a colloid
// over a wall), in slot order, into hit (room for q1 - q0 + 8); returns their number. Whether
// a slot touches is a coin toss in a dense packing: no branch per slot. With AVX-512 eight
// slots at a time (gathers, and the touching lanes compressed to the front); the same
// operations, so the same bits, as touch_slot_2d, which does the rest.
template <bool WallsY>
std::size_t touching_2d(const Colloids &c, const std::uint32_t *pi, const std::uint32_t *pj,
                        std::size_t q0, std::size_t q1, const Slots2 &slots,
                        const std::array<double, 3> &L, const Hits2 &hit) {
  std::size_t nh = 0, q = q0;
#if defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512BW__) && defined(__AVX512VL__)
  const double *x0 = c.x[0].data(), *x1 = c.x[1].data(), *rad = c.radius.data();
  const __m512d L0 = _mm512_set1_pd(L[0]), L1 = _mm512_set1_pd(L[1]);
  const __m512d up0 = _mm512_set1_pd(0.5 * L[0]), down0 = _mm512_set1_pd(-(0.5 * L[0]));
  const __m512d up1 = _mm512_set1_pd(0.5 * L[1]), down1 = _mm512_set1_pd(-(0.5 * L[1]));
  const __m512d zero = _mm512_setzero_pd();
  const __m512i lane = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
  const auto image = [](__m512d d, __m512d length, __m512d up, __m512d down) {
    const __mmask8 over = _mm512_cmp_pd_mask(d, up, _CMP_GT_OQ);
    const __mmask8 under = _mm512_cmp_pd_mask(d, down, _CMP_LT_OQ);
    d = _mm512_mask_sub_pd(d, over, d, length);
    return _mm512_mask_add_pd(d, under, d, length);
  };
  for (; q + 8 <= q1; q += 8) {
    const __m512i i =
        _mm512_cvtepu32_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i *>(pi + q)));
    const __m512i p =
        _mm512_cvtepu32_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i *>(pj + q)));
    __mmask8 wall = 0, low = 0;
    if constexpr (WallsY) {
      wall = _mm512_cmpge_epu64_mask(p, _mm512_set1_epi64(wall_high_row));
      low = _mm512_cmpeq_epu64_mask(p, _mm512_set1_epi64(wall_low_row));
    }
    const __m512i j = _mm512_mask_blend_epi64(wall, p, i);
    const __m512d xi0 = _mm512_i64gather_pd(i, x0, 8), xj0 = _mm512_i64gather_pd(j, x0, 8);
    const __m512d y = _mm512_i64gather_pd(i, x1, 8), xj1 = _mm512_i64gather_pd(j, x1, 8);
    const __m512d ri = _mm512_i64gather_pd(i, rad, 8), rj = _mm512_i64gather_pd(j, rad, 8);
    const __m512d d0 = image(_mm512_sub_pd(xj0, xi0), L0, up0, down0);
    __m512d d1 = _mm512_sub_pd(xj1, y);
    if constexpr (!WallsY)
      d1 = image(d1, L1, up1, down1);
    const __m512d r2 = _mm512_add_pd(_mm512_mul_pd(d0, d0), _mm512_mul_pd(d1, d1));
    const __m512d R = _mm512_add_pd(ri, rj);
    const __m512d wall_delta =
        _mm512_mask_blend_pd(low, _mm512_sub_pd(_mm512_add_pd(y, ri), L1), _mm512_sub_pd(ri, y));
    const __mmask8 touch = (_mm512_cmp_pd_mask(r2, _mm512_mul_pd(R, R), _CMP_LT_OQ) & ~wall) |
                           (_mm512_cmp_pd_mask(wall_delta, zero, _CMP_GT_OQ) & wall);
    const __m512i kind = _mm512_mask_blend_epi64(
        wall, _mm512_setzero_si512(),
        _mm512_mask_blend_epi64(low, _mm512_set1_epi64(2), _mm512_set1_epi64(1)));
    const auto put = [&](void *to, __m512i v) {
      _mm512_storeu_si512(to, _mm512_maskz_compress_epi64(touch, v));
    };
    const auto putd = [&](double *to, __m512d v) {
      _mm512_storeu_pd(to, _mm512_maskz_compress_pd(touch, v));
    };
    put(hit.slot + nh, _mm512_add_epi64(_mm512_set1_epi64(static_cast<long long>(q)), lane));
    put(hit.i + nh, i);
    put(hit.j + nh, j);
    put(hit.kind + nh, kind);
    putd(hit.d[0] + nh, d0);
    putd(hit.d[1] + nh, d1);
    putd(hit.r2 + nh, r2);
    putd(hit.reach + nh, _mm512_mask_blend_pd(wall, R, wall_delta));
    putd(hit.r[0] + nh, ri);
    putd(hit.r[1] + nh, _mm512_mask_blend_pd(wall, rj, zero));
    for (int k = 0; k < 2; ++k) {
      putd(hit.xi[k] + nh, _mm512_loadu_pd(slots.xi[k] + q));
      if (slots.update)
        _mm512_mask_storeu_pd(slots.xi[k] + q, static_cast<__mmask8>(~touch), zero);
    }
    if (slots.update) // (one byte per slot, 0 or 1)
      _mm_storel_epi64(reinterpret_cast<__m128i *>(slots.touch + q), _mm_maskz_set1_epi8(touch, 1));
    nh += static_cast<std::size_t>(__builtin_popcount(touch));
  }
#endif
  for (; q < q1; ++q)
    nh = touch_slot_2d<WallsY>(c, pi[q], pj[q], q, slots, L, hit, nh);
  return nh;
}

// The force on i (the opposite on j, unless a wall), and n x F_t (the torque per unit lever
// arm, times r_i on i and r_j on j) of each hit, the spring advanced first when updating, into
// fixed point: force[0..1] the force, force[2] and force[3] the torques on i and j. Returns the
// number of values beyond the fixed-point range or NaN; *over is the largest |value| beyond it
// (0 if there are only NaN).
struct Forces2 {
  std::int64_t *force[4], *slides;
};
template <bool Update>
std::int64_t contacts_2d(const Colloids &c, const Hits2 &hit, const Forces2 &out, std::size_t nh,
                         const SpringParams &p, double step, double *over) {
  const double *v0 = c.v[0].data(), *v1 = c.v[1].data(), *om = c.omega[2].data();
  const double kn = p.kn, kt = p.kt, mu_cc = p.mu_cc, mu_cw = p.mu_cw;
  // (Local pointers: loads through the structs would not be hoisted from the loop.)
  const std::uint64_t *hi = hit.i, *hj = hit.j;
  const std::int64_t *kind = hit.kind;
  const double *sep0 = hit.d[0], *sep1 = hit.d[1], *sep2 = hit.r2, *reach = hit.reach,
               *arm_i = hit.r[0], *arm_j = hit.r[1];
  double *hxi0 = hit.xi[0], *hxi1 = hit.xi[1];
  std::int64_t *f0 = out.force[0], *f1 = out.force[1], *f2 = out.force[2], *f3 = out.force[3],
               *slides = out.slides;
  std::int64_t bad = 0;
  double beyond = 0.0;
#pragma omp simd reduction(+ : bad) reduction(max : beyond)
  for (std::size_t h = 0; h < nh; ++h) {
    const std::uint64_t i = hi[h], j = hj[h]; // j = i for a wall
    const bool wall = kind[h] != 0, low = kind[h] == 1;
    const double ri = arm_i[h], rj = arm_j[h]; // (rj 0 for a wall)
    const double d0 = sep0[h], d1 = sep1[h];
    const double dist = std::sqrt(sep2[h]);
    // (Every sum in the order of the generic loop: the same roundings.)
    const double delta = wall ? reach[h] : reach[h] - dist;
    const double n0 = wall ? 0.0 : (dist > 0.0 ? d0 / dist : 1.0); // on top: along x
    const double n1 = wall ? (low ? -1.0 : 1.0) : (dist > 0.0 ? d1 / dist : 0.0);
    const double mu = wall ? mu_cw : mu_cc;
    const double vj0 = v0[j], vj1 = v1[j], oj = om[j];
    double U0 = v0[i] - (wall ? 0.0 : vj0), U1 = v1[i] - (wall ? 0.0 : vj1);
    const double w = ri * om[i] + (wall ? 0.0 : rj * oj);
    U0 -= w * n1;
    U1 += w * n0;
    double xi0 = hxi0[h], xi1 = hxi1[h];
    bool slid = false;
    if constexpr (Update) {
      double len2 = 0.0, xn = 0.0, un = 0.0, t2 = 0.0;
      len2 += xi0 * xi0;
      xn += xi0 * n0;
      un += U0 * n0;
      len2 += xi1 * xi1;
      xn += xi1 * n1;
      un += U1 * n1;
      const double t0 = xi0 - xn * n0;
      t2 += t0 * t0;
      const double t1 = xi1 - xn * n1;
      t2 += t1 * t1;
      const double f = t2 > 0.0 ? std::sqrt(len2 / t2) : 0.0;
      xi0 = len2 > 0.0 ? t0 * f : xi0;
      xi1 = len2 > 0.0 ? t1 * f : xi1;
      double x2 = 0.0;
      xi0 += (U0 - un * n0) * step;
      x2 += xi0 * xi0;
      xi1 += (U1 - un * n1) * step;
      x2 += xi1 * xi1;
      const double ft = kt * std::sqrt(x2), cap = mu * kn * delta;
      slid = kt != 0.0 && ft > cap;
      const double cut = slid ? cap / ft : 1.0;
      xi0 = slid ? xi0 * cut : xi0; // (k_t = 0: zeroed below; -k_t xi is a zero force)
      xi1 = slid ? xi1 * cut : xi1;
      hxi0[h] = xi0;
      hxi1[h] = xi1;
    }
    slides[h] = slid;
    const double Ft0 = -kt * xi0, Ft1 = -kt * xi1;
    const double torque = n0 * Ft1 - n1 * Ft0;
    const double fx = -kn * delta * n0 + Ft0, fy = -kn * delta * n1 + Ft1;
    const double ti = ri * torque, tj = rj * torque;
    // fixed::from_double's rounding (to nearest, even), written so that it vectorises.
    const double a =
        std::max(std::max(std::abs(fx), std::abs(fy)), std::max(std::abs(ti), std::abs(tj)));
    bad += !(std::abs(fx) < fixed::max_magnitude) + !(std::abs(fy) < fixed::max_magnitude) +
           !(std::abs(ti) < fixed::max_magnitude) + !(std::abs(tj) < fixed::max_magnitude);
    beyond = a > beyond ? a : beyond;
    f0[h] = static_cast<std::int64_t>(std::nearbyint(fx * fixed::scale));
    f1[h] = static_cast<std::int64_t>(std::nearbyint(fy * fixed::scale));
    f2[h] = static_cast<std::int64_t>(std::nearbyint(ti * fixed::scale));
    f3[h] = static_cast<std::int64_t>(std::nearbyint(tj * fixed::scale));
  }
  if (Update && kt == 0.0) // no tangential spring
    for (int k = 0; k < 2; ++k)
      std::fill(hit.xi[k], hit.xi[k] + nh, 0.0);
  *over = beyond >= fixed::max_magnitude ? beyond : 0.0;
  return bad;
}

} // namespace

SpringContacts::SpringContacts(const SpringParams &params, const mpcd::Box &box)
    : params_(params), box_(box), dim_(box.dim) {}

void SpringContacts::compute(const Colloids &c, std::size_t owned, ContactHistory &h, double step) {
  counted_rows_ = owned;
  if (dim_ == 2)
    box_.walls_y ? compute<2, true>(c, owned, h, step) : compute<2, false>(c, owned, h, step);
  else
    box_.walls_y ? compute<3, true>(c, owned, h, step) : compute<3, false>(c, owned, h, step);
}

template <int D, bool WallsY>
void SpringContacts::compute(const Colloids &c, std::size_t owned, ContactHistory &h, double step) {
  if (!pairs_fresh<D, WallsY>(c, owned))
    build_pairs<D, WallsY>(c, owned);
  load_springs(h);
  forces<D, WallsY>(c, step);
  if (step > 0.0)
    store_springs(h);
}

bool SpringContacts::load_springs(const ContactHistory &h) {
  const std::size_t m = slot_owner_.size();
  bool sized = slot_touch_.size() == m;
  for (int k = 0; k < 3; ++k)
    sized = sized && slot_xi_[k].size() == m;
  bool same = sized;
  if (sized) {
    // Usually h is what store_springs made of these slots: the touching ones, in order. Then
    // one pass without branches; it falls through to the general walk when a key differs.
    std::size_t n = 0;
    for (std::size_t q = 0; q < m; ++q)
      n += slot_touch_[q];
    if (n == h.size()) {
      bool differ = false;
      std::size_t r = 0;
      for (std::size_t q = 0; q < m; ++q) {
        const bool touch = slot_touch_[q] != 0;
        const std::size_t at = r < n ? r : 0; // (read, then not used, past the end)
        differ = differ ||
                 (touch && (h.owner[at] != slot_owner_[q] || h.partner[at] != slot_partner_[q]));
        for (int k = 0; k < dim_; ++k) {
          const double xi = touch ? h.xi[k][at] : 0.0;
          same = same &&
                 std::bit_cast<std::uint64_t>(xi) == std::bit_cast<std::uint64_t>(slot_xi_[k][q]);
          slot_xi_[k][q] = xi;
        }
        r += touch;
      }
      if (!differ)
        return same;
      same = false; // (a contact came or went; the slots are partly overwritten)
    }
  }
  // Both in key order: one walk along h.
  for (int k = 0; k < 3; ++k)
    slot_xi_[k].resize(m);
  std::size_t walk = 0;
  for (std::size_t q = 0; q < m; ++q) {
    const std::uint64_t o = slot_owner_[q], p = slot_partner_[q];
    while (walk < h.size() && (h.owner[walk] < o || (h.owner[walk] == o && h.partner[walk] < p)))
      ++walk;
    const bool found = walk < h.size() && h.owner[walk] == o && h.partner[walk] == p;
    for (int k = 0; k < 3; ++k) {
      const double xi = found && k < dim_ ? h.xi[k][walk] : 0.0;
      same =
          same && std::bit_cast<std::uint64_t>(xi) == std::bit_cast<std::uint64_t>(slot_xi_[k][q]);
      slot_xi_[k][q] = xi;
    }
  }
  return same;
}

void SpringContacts::store_springs(ContactHistory &h) const {
  const std::size_t m = slot_owner_.size();
  std::size_t n = 0;
  for (std::size_t q = 0; q < m; ++q)
    n += slot_touch_[q];
  h.dim = dim_;
  h.resize(n + 1); // (+1: every slot is written at the end, which grows only by those that touch)
  std::size_t r = 0;
  for (std::size_t q = 0; q < m; ++q) {
    h.owner[r] = slot_owner_[q];
    h.partner[r] = slot_partner_[q];
    for (int k = 0; k < dim_; ++k)
      h.xi[k][r] = slot_xi_[k][q];
    r += slot_touch_[q];
  }
  h.resize(n);
}

template <bool WallsY> void SpringContacts::forces_2d(const Colloids &c, double step) {
  const ScopedSeconds timed(force_seconds_);
  end_kept_ = false;
  ++evaluations_;
  constexpr int S = 3;
  const std::size_t nc = c.size();
  sums_.assign(nc * S, 0);
  const bool update = step > 0.0;
  const std::size_t m = pair_i_.size();
  if (update)
    slot_touch_.resize(m); // (each written by the touch test)
  // The slots a block at a time, so that the touching ones and their forces stay in the cache
  // between the passes.
  constexpr std::size_t block = 2048, room = block + 8; // (+8: whole vectors stored)
  hits_.resize(room);
  hit_i_.resize(room);
  hit_j_.resize(room);
  hit_kind_.resize(room);
  for (int k = 0; k < 2; ++k) {
    hit_sep_[k].resize(room);
    hit_xi_[k].resize(room);
  }
  hit_sep_[2].resize(room);
  hit_reach_.resize(room);
  for (auto &r : hit_arm_)
    r.resize(room);
  for (auto &f : hit_fixed_)
    f.resize(room);
  hit_slides_.resize(room);
  const Hits2 hit{hits_.data(),
                  hit_i_.data(),
                  hit_j_.data(),
                  hit_kind_.data(),
                  {hit_sep_[0].data(), hit_sep_[1].data()},
                  hit_sep_[2].data(),
                  hit_reach_.data(),
                  {hit_arm_[0].data(), hit_arm_[1].data()},
                  {hit_xi_[0].data(), hit_xi_[1].data()}};
  const Forces2 out{
      {hit_fixed_[0].data(), hit_fixed_[1].data(), hit_fixed_[2].data(), hit_fixed_[3].data()},
      hit_slides_.data()};
  const Slots2 slots{{slot_xi_[0].data(), slot_xi_[1].data()}, slot_touch_.data(), update};
  for (std::size_t q0 = 0; q0 < m; q0 += block) {
    const std::size_t q1 = std::min(m, q0 + block);
    // 1. The slots that touch now, in key order, with their geometry and springs.
    const std::size_t nh =
        touching_2d<WallsY>(c, pair_i_.data(), pair_j_.data(), q0, q1, slots, box_.length, hit);
    // 2. Their springs (advanced when updating) and forces, in fixed point.
    double over = 0.0;
    const std::int64_t bad = update ? contacts_2d<true>(c, hit, out, nh, params_, step, &over)
                                    : contacts_2d<false>(c, hit, out, nh, params_, step, &over);
    if (bad > 0) [[unlikely]]
      fixed_range_error(over > 0.0 ? over : std::numeric_limits<double>::quiet_NaN());
    // 3. Into the sums (exact in any order); a wall's share of the forces goes nowhere.
    std::int64_t nowhere[S];
    std::uint64_t sliding = 0, counted = 0;
    for (std::size_t h = 0; h < nh; ++h) {
      std::int64_t *si = &sums_[hit.i[h] * S];
      std::int64_t *sj = hit.kind[h] != 0 ? nowhere : &sums_[hit.j[h] * S];
      const std::int64_t f0 = out.force[0][h], f1 = out.force[1][h];
      si[0] += f0;
      si[1] += f1;
      si[2] += out.force[2][h];
      sj[0] -= f0;
      sj[1] -= f1;
      sj[2] += out.force[3][h];
      const bool mine = hit.i[h] < counted_rows_; // (a ghost's contact: its owner counts it)
      sliding += mine && out.slides[h] != 0;
      counted += mine;
    }
    if (update) {
      // The advanced springs back to their slots (those of the slots that no longer touch were
      // dropped by the touch test).
      for (std::size_t h = 0; h < nh; ++h) {
        const std::uint64_t q = hit.slot[h];
        slots.xi[0][q] = hit.xi[0][h];
        slots.xi[1][q] = hit.xi[1][h];
      }
      updates_ += counted;
      sliding_ += sliding;
    }
  }
}

template <int D, bool WallsY> void SpringContacts::forces(const Colloids &c, double step) {
  if constexpr (D == 2) {
    forces_2d<WallsY>(c, step);
    return;
  }
  const ScopedSeconds timed(force_seconds_);
  end_kept_ = false;
  ++evaluations_;
  constexpr int S = D == 2 ? 3 : 6, T = D == 2 ? 1 : 3;
  const std::size_t nc = c.size();
  sums_.assign(nc * S, 0);
  const bool update = step > 0.0;
  const SpringParams &p = params_;
  const auto &L = box_.length;
  const std::size_t m = pair_i_.size();
  if (update)
    slot_touch_.assign(m, 0);
  // The slots a block at a time, so that the touching ones and their forces stay in the cache
  // between the passes.
  constexpr std::size_t block = 2048;
  for (std::size_t q0 = 0; q0 < m; q0 += block) {
    const std::size_t q1 = std::min(m, q0 + block);

    // 1. The slots that touch now (a colloid pair closer than r_i + r_j, or a colloid over a
    // wall), in key order.
    // Without branches (whether a slot touches is a coin toss in a dense packing): every slot is
    // written at the end of the hits, which grow only by those that touch.
    hits_.resize(q1 - q0);
    hit_j_.resize(q1 - q0);
    hit_kind_.resize(q1 - q0);
    std::size_t nh = 0;
    for (std::size_t q = q0; q < q1; ++q) {
      const std::size_t i = pair_i_[q];
      const std::uint32_t pj = pair_j_[q];
      const bool wall = WallsY && pj >= wall_high_row, low = pj == wall_low_row;
      const std::size_t j = wall ? i : pj;
      const double ri = c.radius[i], y = c.x[1][i];
      const double xj[3] = {c.x[0][j], c.x[1][j], D == 3 ? c.x[2][j] : 0.0};
      const double xi[3] = {c.x[0][i], y, D == 3 ? c.x[2][i] : 0.0};
      double d[3];
      const double R = ri + c.radius[j], r2 = separation<D, WallsY>(xj, xi, L, d);
      const double wall_delta = low ? ri - y : y + ri - L[1];
      const bool touch = wall ? wall_delta > 0.0 : r2 < R * R;
      hits_[nh] = q;
      hit_j_[nh] = j; // i for a wall (read, then not used)
      hit_kind_[nh] = wall ? (low ? 1 : 2) : 0;
      nh += touch;
    }
    hits_.resize(nh);
    hit_i_.resize(nh);
    for (int k = 0; k < D; ++k)
      hit_xi_[k].resize(nh);
    for (std::size_t h = 0; h < nh; ++h) {
      hit_i_[h] = pair_i_[hits_[h]];
      for (int k = 0; k < D; ++k)
        hit_xi_[k][h] = slot_xi_[k][hits_[h]];
    }
    for (int k = 0; k < D; ++k)
      hit_force_[k].resize(nh);
    for (int k = 0; k < T; ++k)
      hit_torque_[k].resize(nh);
    hit_slides_.resize(nh);

    // 2. Each touching slot's force on i (the opposite on j, unless a wall at rest) and n x F_t
    // (the torque per unit lever arm); the spring is advanced first when updating. A plain loop
    // of the same operations for every contact (walls by selects), vectorised.
    const double *x[3] = {c.x[0].data(), c.x[1].data(), D == 3 ? c.x[2].data() : nullptr};
    const double *v[3] = {c.v[0].data(), c.v[1].data(), D == 3 ? c.v[2].data() : nullptr};
    const double *om[3] = {c.omega[0].data(), c.omega[1].data(), c.omega[2].data()};
    const double *rad = c.radius.data();
    double *sxi[3] = {hit_xi_[0].data(), hit_xi_[1].data(), D == 3 ? hit_xi_[2].data() : nullptr};
    const std::uint64_t *hi = hit_i_.data(), *hj = hit_j_.data();
    const std::int64_t *kind = hit_kind_.data();
    double *hf[3] = {hit_force_[0].data(), hit_force_[1].data(),
                     D == 3 ? hit_force_[2].data() : nullptr};
    double *ht[3] = {hit_torque_[0].data(), T == 3 ? hit_torque_[1].data() : nullptr,
                     T == 3 ? hit_torque_[2].data() : nullptr};
    std::int64_t *slides = hit_slides_.data();
    const double kn = p.kn, kt = p.kt, mu_cc = p.mu_cc, mu_cw = p.mu_cw;
    for (std::size_t h = 0; h < nh; ++h) {
      const std::uint64_t i = hi[h], j = hj[h]; // j = i for a wall
      const bool wall = kind[h] != 0, low = kind[h] == 1;
      const double ri = rad[i], rj_row = rad[j], rj = wall ? 0.0 : rj_row;
      double n[3] = {0.0, 0.0, 0.0}, d[3] = {0.0, 0.0, 0.0}, r2 = 0.0;
      for (int k = 0; k < D; ++k) {
        d[k] = x[k][j] - x[k][i]; // from i towards j
        if (!(WallsY && k == 1))
          d[k] = d[k] > 0.5 * L[k] ? d[k] - L[k] : (d[k] < -0.5 * L[k] ? d[k] + L[k] : d[k]);
        r2 += d[k] * d[k];
      }
      const double dist = std::sqrt(r2);
      const double wall_delta = low ? ri - x[1][i] : x[1][i] + ri - L[1];
      const double delta = wall ? wall_delta : ri + rj - dist;
      for (int k = 0; k < D; ++k)
        n[k] = wall ? (k == 1 ? (low ? -1.0 : 1.0) : 0.0)
                    : (dist > 0.0 ? d[k] / dist : (k == 0 ? 1.0 : 0.0)); // on top: along x
      const double mu = wall ? mu_cw : mu_cc;
      // U = v_i - v_j + (r_i w_i + r_j w_j) x n: the relative velocity of the contact points.
      double U[3] = {0.0, 0.0, 0.0}, w[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < D; ++k) {
        const double vj = v[k][j];
        U[k] = v[k][i] - (wall ? 0.0 : vj);
      }
      for (int k = 0; k < 3; ++k) {
        const double oj = om[k][j];
        w[k] = ri * om[k][i] + (wall ? 0.0 : rj * oj);
      }
      if constexpr (D == 2) {
        U[0] -= w[2] * n[1];
        U[1] += w[2] * n[0];
      } else {
        U[0] += w[1] * n[2] - w[2] * n[1];
        U[1] += w[2] * n[0] - w[0] * n[2];
        U[2] += w[0] * n[1] - w[1] * n[0];
      }
      double xi[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < D; ++k)
        xi[k] = sxi[k][h];
      bool slid = false;
      if (update) {
        // Into the current tangent plane, the same length (eq 4.40).
        double len2 = 0.0, xn = 0.0, un = 0.0;
        for (int k = 0; k < D; ++k) {
          len2 += xi[k] * xi[k];
          xn += xi[k] * n[k];
          un += U[k] * n[k];
        }
        double t2 = 0.0, turned[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < D; ++k) {
          turned[k] = xi[k] - xn * n[k];
          t2 += turned[k] * turned[k];
        }
        const double f = t2 > 0.0 ? std::sqrt(len2 / t2) : 0.0;
        for (int k = 0; k < D; ++k)
          xi[k] = len2 > 0.0 ? turned[k] * f : xi[k];
        // Stretched by the tangential relative velocity (eq 4.39), capped by Coulomb (4.41-4.42).
        double x2 = 0.0;
        for (int k = 0; k < D; ++k) {
          xi[k] += (U[k] - un * n[k]) * step;
          x2 += xi[k] * xi[k];
        }
        const double ft = kt * std::sqrt(x2), cap = mu * kn * delta;
        slid = kt != 0.0 && ft > cap;
        const double cut = slid ? cap / ft : 1.0;
        for (int k = 0; k < D; ++k) {
          xi[k] = kt == 0.0 ? 0.0 : (slid ? xi[k] * cut : xi[k]);
          sxi[k][h] = xi[k];
        }
      }
      slides[h] = slid;
      double Ft[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < D; ++k) {
        Ft[k] = -kt * xi[k];
        hf[k][h] = -kn * delta * n[k] + Ft[k];
      }
      // n x F_t (times r_i on i and r_j on j below).
      if constexpr (D == 2) {
        ht[0][h] = n[0] * Ft[1] - n[1] * Ft[0];
      } else {
        ht[0][h] = n[1] * Ft[2] - n[2] * Ft[1];
        ht[1][h] = n[2] * Ft[0] - n[0] * Ft[2];
        ht[2][h] = n[0] * Ft[1] - n[1] * Ft[0];
      }
    }

    // 3. Into the fixed-point sums (exact in any order).
    std::uint64_t sliding = 0, counted = 0;
    for (std::size_t h = 0; h < nh; ++h) {
      const auto i = static_cast<std::size_t>(hi[h]), j = static_cast<std::size_t>(hj[h]);
      const bool wall = kind[h] != 0;
      std::int64_t *si = &sums_[i * S];
      std::int64_t *sj = wall ? nullptr : &sums_[j * S];
      for (int k = 0; k < D; ++k) {
        const std::int64_t f = to_fixed(hf[k][h]);
        si[k] += f;
        if (sj)
          sj[k] -= f;
      }
      const double ri = rad[i], rj = wall ? 0.0 : rad[j];
      for (int k = 0; k < T; ++k) {
        si[D + k] += to_fixed(ri * ht[k][h]);
        if (sj)
          sj[D + k] += to_fixed(rj * ht[k][h]);
      }
      const bool mine = i < counted_rows_; // (a ghost's contact: its owner counts it)
      sliding += mine && slides[h] != 0;
      counted += mine;
    }
    if (update) {
      // The springs of the block's slots that no longer touch are dropped.
      for (int k = 0; k < D; ++k)
        std::fill(slot_xi_[k].begin() + static_cast<std::ptrdiff_t>(q0),
                  slot_xi_[k].begin() + static_cast<std::ptrdiff_t>(q1), 0.0);
      for (std::size_t h = 0; h < nh; ++h) {
        slot_touch_[hits_[h]] = 1;
        for (int k = 0; k < D; ++k)
          slot_xi_[k][hits_[h]] = hit_xi_[k][h];
      }
      updates_ += counted;
      sliding_ += sliding;
    }
  }
}

template <int D, bool WallsY>
bool SpringContacts::pairs_fresh(const Colloids &c, std::size_t owned, bool same_rows,
                                 std::size_t from, double worst) const {
  const std::size_t nc = c.size();
  if (!built_ || owned != built_owned_ || nc != built_id_.size() ||
      (!same_rows && (c.id != built_id_ || c.radius != built_radius_)))
    return false;
  // The largest displacement since the list was built (a plain loop, vectorised; its rounding
  // only decides when the list is built again, which changes no result).
  for (std::size_t a = from; a < nc; ++a) {
    double r2 = 0.0;
    for (int k = 0; k < D; ++k) {
      double d = c.x[k][a] - built_x_[k][a];
      if (!(WallsY && k == 1)) {
        const double L = box_.length[k];
        d = d > 0.5 * L ? d - L : (d < -0.5 * L ? d + L : d);
      }
      r2 += d * d;
    }
    worst = r2 > worst ? r2 : worst;
  }
  return worst < 0.25 * skin_ * skin_; // (skin / 2)^2
}

template <int D, bool WallsY>
void SpringContacts::build_pairs(const Colloids &c, std::size_t owned) {
  const std::size_t nc = c.size();
  double r_min = nc > 0 ? c.radius[0] : 0.0, r_max = 0.0;
  for (std::size_t a = 0; a < nc; ++a) {
    r_min = std::min(r_min, c.radius[a]);
    r_max = std::max(r_max, c.radius[a]);
  }
  // A skin of 15 % of the smallest radius: colloids move far less than that in an MPCD step.
  skin_ = 0.15 * r_min;
  if (nc > 1 && 2.0 * r_max + skin_ > cell_cut_) {
    cell_cut_ = 2.0 * r_max + skin_;
    cells_.size_for(box_, cell_cut_);
  }
  std::vector<Slot> &slots = build_scratch_;
  slots.clear();
  const auto &L = box_.length;
  // The pair belongs to the rank that owns the colloid of the smaller id (pairs of two ghosts,
  // or whose smaller id is a ghost, are left to their owners).
  if (nc > 1)
    for_each_colloid_pair<D, WallsY>(
        cells_, cell_of_, partners_, c, [&](std::size_t a, std::vector<std::uint32_t> &near) {
          for (const std::uint32_t bb : near) {
            const std::size_t b = bb;
            const std::size_t i = c.id[a] < c.id[b] ? a : b, j = i == a ? b : a;
            if (i >= owned)
              continue;
            const double xj[3] = {c.x[0][j], c.x[1][j], D == 3 ? c.x[2][j] : 0.0};
            const double xi[3] = {c.x[0][i], c.x[1][i], D == 3 ? c.x[2][i] : 0.0};
            double d[3] = {0.0, 0.0, 0.0};
            const double R = c.radius[i] + c.radius[j] + skin_;
            if (separation<D, WallsY>(xj, xi, L, d) >= R * R)
              continue;
            slots.push_back(
                {c.id[i], c.id[j], static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
          }
        });
  if constexpr (WallsY)
    for (std::size_t a = 0; a < owned; ++a) {
      const auto i = static_cast<std::uint32_t>(a);
      if (c.x[1][a] - c.radius[a] < skin_)
        slots.push_back({c.id[a], wall_low_id, i, wall_low_row});
      if (c.x[1][a] + c.radius[a] > L[1] - skin_)
        slots.push_back({c.id[a], wall_high_id, i, wall_high_row});
    }
  std::sort(slots.begin(), slots.end(), [](const Slot &x, const Slot &y) {
    return x.owner < y.owner || (x.owner == y.owner && x.partner < y.partner);
  });
  const std::size_t m = slots.size();
  pair_i_.resize(m);
  pair_j_.resize(m);
  slot_owner_.resize(m);
  slot_partner_.resize(m);
  slot_touch_.assign(m, 0);
  for (std::size_t q = 0; q < m; ++q) {
    pair_i_[q] = slots[q].i;
    pair_j_[q] = slots[q].j;
    slot_owner_[q] = slots[q].owner;
    slot_partner_[q] = slots[q].partner;
  }
  for (int k = 0; k < D; ++k)
    built_x_[k] = c.x[k];
  built_id_ = c.id;
  built_radius_ = c.radius;
  built_owned_ = owned;
  built_ = true;
  ++builds_;
}

template <int D, bool WallsY, bool External, bool Moves>
double SpringContacts::kick_drift(Colloids &c, std::size_t owned, double h, bool twice,
                                  double drift, const double *external) {
  constexpr int S = D == 2 ? 3 : 6, T = D == 2 ? 1 : 3;
  const std::int64_t *s = sums_.data();
  const double *mass = c.mass.data(), *inertia = inertia_.data();
  double *x[3], *v[3], *omega[3];
  const double *built[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = k < D ? c.x[k].data() : nullptr;
    v[k] = k < D ? c.v[k].data() : nullptr;
    built[k] = k < D ? built_x_[k].data() : nullptr;
    omega[k] = c.omega[k].data();
  }
  const auto &L = box_.length;
  rare_axes_.resize(owned);
  std::uint8_t *rare_axes = rare_axes_.data();
  double worst = 0.0;
  std::int64_t rare = 0;
#pragma omp simd reduction(max : worst) reduction(+ : rare)
  for (std::size_t a = 0; a < owned; ++a) {
    double r2 = 0.0;
    int odd_axes = 0;
    for (int k = 0; k < D; ++k) {
      double f = fixed::to_double(s[a * S + k]);
      if constexpr (External)
        f += external[a * D + k];
      const double dv = h * f / mass[a];
      double u = v[k][a] + dv;
      u = twice ? u + dv : u;
      v[k][a] = u;
      if constexpr (Moves) {
        // The drift, wrapped as wrap_periodic does; its rare case (a jump by more than a
        // period) is left to the loop below.
        const double old = x[k][a];
        double to = old + u * drift;
        bool odd = false;
        if (!(WallsY && k == 1)) {
          const double up = to - L[k], down = to + L[k];
          odd = to >= L[k] ? up >= L[k] : to < 0.0 && down < 0.0;
          to = to >= L[k] ? up : (to < 0.0 ? (down >= L[k] ? 0.0 : down) : to);
        }
        odd_axes |= odd << k;
        x[k][a] = odd ? old : to;
        // The displacement since the list was built, as pairs_fresh measures it.
        double d = to - built[k][a];
        if (!(WallsY && k == 1))
          d = d > 0.5 * L[k] ? d - L[k] : (d < -0.5 * L[k] ? d + L[k] : d);
        r2 += d * d;
      }
    }
    for (int k = 0; k < T; ++k) {
      const double dw = h * fixed::to_double(s[a * S + D + k]) / inertia[a];
      double w = omega[D == 2 ? 2 : k][a] + dw;
      w = twice ? w + dw : w;
      omega[D == 2 ? 2 : k][a] = w;
    }
    if constexpr (Moves) {
      rare_axes[a] = static_cast<std::uint8_t>(odd_axes);
      rare += odd_axes != 0;
      worst = r2 > worst ? r2 : worst;
    }
  }
  if (rare > 0) { // (their positions were left as they were)
    for (std::size_t a = 0; a < owned; ++a)
      for (int k = 0; k < D; ++k)
        if (rare_axes[a] >> k & 1)
          x[k][a] = mpcd::wrap_periodic(x[k][a] + v[k][a] * drift, L[k]);
    worst = std::numeric_limits<double>::infinity(); // (the list is built again)
  }
  return worst;
}

void SpringContacts::advance(Colloids &c, std::size_t owned, ContactHistory &h, double dt,
                             const std::vector<double> *external, std::size_t counted) {
  counted_rows_ = std::min(counted, owned);
  if (dim_ == 2)
    box_.walls_y ? advance<2, true>(c, owned, h, dt, external)
                 : advance<2, false>(c, owned, h, dt, external);
  else
    box_.walls_y ? advance<3, true>(c, owned, h, dt, external)
                 : advance<3, false>(c, owned, h, dt, external);
}

template <int D, bool WallsY>
double SpringContacts::kick_drift(Colloids &c, std::size_t owned, double h, bool twice,
                                  double drift, const std::vector<double> *external) {
  const double *ext = external ? external->data() : nullptr;
  if (drift > 0.0)
    return external ? kick_drift<D, WallsY, true, true>(c, owned, h, twice, drift, ext)
                    : kick_drift<D, WallsY, false, true>(c, owned, h, twice, drift, ext);
  return external ? kick_drift<D, WallsY, true, false>(c, owned, h, twice, drift, ext)
                  : kick_drift<D, WallsY, false, false>(c, owned, h, twice, drift, ext);
}

template <int D, bool WallsY>
void SpringContacts::advance(Colloids &c, std::size_t owned, ContactHistory &h, double dt,
                             const std::vector<double> *external) {
  const int n = params_.substeps;
  const double hs = dt / n;
  // The springs live in the list's slots during the step and go back to h at its end (and
  // whenever the list is built again).
  const bool built = !pairs_fresh<D, WallsY>(c, owned);
  if (built)
    build_pairs<D, WallsY>(c, owned);
  const bool springs_kept = load_springs(h);
  inertia_.resize(owned);
  for (std::size_t a = 0; a < owned; ++a)
    inertia_[a] = moment_of_inertia(c, a);
  // The forces the last step ended with: kept from its end when nothing they depend on (the
  // rows, their positions, the springs) has changed since, else computed again. The same bits
  // either way.
  if (!(end_kept_ && !built && springs_kept && same_positions_as_end(c)))
    forces<D, WallsY>(c, 0.0);
  for (int s = 0; s < n; ++s) {
    // The last sub-step's second half kick, this one's first and its drift, in one pass.
    const double moved = kick_drift<D, WallsY>(c, owned, 0.5 * hs, s > 0, hs, external);
    if (!pairs_fresh<D, WallsY>(c, owned, true, owned, moved)) { // (only positions changed)
      if (s > 0)
        store_springs(h); // the contacts of the last sub-step
      build_pairs<D, WallsY>(c, owned);
      load_springs(h);
    }
    forces<D, WallsY>(c, hs);
    if (s == n - 1)
      keep_end(c);
  }
  kick_drift<D, WallsY>(c, owned, 0.5 * hs, false, 0.0, external); // the last half kick
  store_springs(h);
}

void SpringContacts::keep_end(const Colloids &c) {
  for (int k = 0; k < dim_; ++k)
    end_x_[k].assign(c.x[k].begin(), c.x[k].end());
  end_kept_ = true; // (sums_ stays as it is until the next call)
}

bool SpringContacts::same_positions_as_end(const Colloids &c) const {
  for (int k = 0; k < dim_; ++k)
    if (end_x_[k].size() != c.x[k].size() ||
        std::memcmp(end_x_[k].data(), c.x[k].data(), c.x[k].size() * sizeof(double)) != 0)
      return false;
  return true;
}

double SpringContacts::elastic_energy(const Colloids &c, const ContactHistory &h) const {
  double e = 0.0;
  const std::size_t n = c.size();
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      double r2 = 0.0;
      for (int k = 0; k < dim_; ++k) {
        double d = c.x[k][a] - c.x[k][b];
        if (!(k == 1 && box_.walls_y))
          d = minimum_image(d, box_.length[k]);
        r2 += d * d;
      }
      const double delta = c.radius[a] + c.radius[b] - std::sqrt(r2);
      if (delta > 0.0)
        e += 0.5 * params_.kn * delta * delta;
    }
    if (box_.walls_y) {
      const double lo = c.radius[a] - c.x[1][a], hi = c.x[1][a] + c.radius[a] - box_.length[1];
      if (lo > 0.0)
        e += 0.5 * params_.kn * lo * lo;
      if (hi > 0.0)
        e += 0.5 * params_.kn * hi * hi;
    }
  }
  for (std::size_t j = 0; j < h.size(); ++j)
    for (int k = 0; k < dim_; ++k)
      e += 0.5 * params_.kt * h.xi[k][j] * h.xi[k][j];
  return e;
}

} // namespace narrows::colloids

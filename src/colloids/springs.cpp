// Linear springs with Coulomb friction between colloids and with the walls (seed 001 §4.2.3).
#include "narrows/colloids/springs.hpp"

#include "narrows/colloids/colloid_pairs.hpp"
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/mpcd/streaming.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::colloids {

namespace {

// Rows in the pair list standing for the walls (partner ids wall_low_id, wall_high_id).
constexpr std::uint32_t wall_low_row = ~std::uint32_t{0}, wall_high_row = wall_low_row - 1;

// The 2D contacts of SpringContacts::forces (step 2), the same operations in the same order as
// its generic loop, written with scalars and selects so that the compiler vectorises it: the
// generic loop's small arrays keep it scalar. kind: 0 pair, 1 lower wall, 2 upper wall.
struct Hits2 {
  const std::uint64_t *i, *j;
  const std::int64_t *kind;
  double *xi[2], *force[2], *torque;
  std::int64_t *slides;
};

template <bool Update, bool WallsY>
void contacts_2d(const Colloids &c, const Hits2 &hit, std::size_t nh, const SpringParams &p,
                 const std::array<double, 3> &L, double step) {
  const double *x0 = c.x[0].data(), *x1 = c.x[1].data(), *v0 = c.v[0].data(), *v1 = c.v[1].data(),
               *om = c.omega[2].data(), *rad = c.radius.data();
  const double kn = p.kn, kt = p.kt, mu_cc = p.mu_cc, mu_cw = p.mu_cw;
  const double L0 = L[0], L1 = L[1], half0 = 0.5 * L[0], half1 = 0.5 * L[1];
#pragma omp simd
  for (std::size_t h = 0; h < nh; ++h) {
    const std::uint64_t i = hit.i[h], j = hit.j[h]; // j = i for a wall
    const bool wall = hit.kind[h] != 0, low = hit.kind[h] == 1;
    const double ri = rad[i], rj_row = rad[j], rj = wall ? 0.0 : rj_row;
    double d0 = x0[j] - x0[i], d1 = x1[j] - x1[i]; // from i towards j
    d0 = d0 > half0 ? d0 - L0 : (d0 < -half0 ? d0 + L0 : d0);
    if constexpr (!WallsY)
      d1 = d1 > half1 ? d1 - L1 : (d1 < -half1 ? d1 + L1 : d1);
    // (Every sum in the order of the generic loop: the same roundings, fused or not.)
    double r2 = 0.0;
    r2 += d0 * d0;
    r2 += d1 * d1;
    const double dist = std::sqrt(r2);
    const double wall_delta = low ? ri - x1[i] : x1[i] + ri - L1;
    const double delta = wall ? wall_delta : ri + rj - dist;
    const double n0 = wall ? 0.0 : (dist > 0.0 ? d0 / dist : 1.0); // on top: along x
    const double n1 = wall ? (low ? -1.0 : 1.0) : (dist > 0.0 ? d1 / dist : 0.0);
    const double mu = wall ? mu_cw : mu_cc;
    const double vj0 = v0[j], vj1 = v1[j], oj = om[j];
    double U0 = v0[i] - (wall ? 0.0 : vj0), U1 = v1[i] - (wall ? 0.0 : vj1);
    const double w = ri * om[i] + (wall ? 0.0 : rj * oj);
    U0 -= w * n1;
    U1 += w * n0;
    double xi0 = hit.xi[0][h], xi1 = hit.xi[1][h];
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
      hit.xi[0][h] = xi0;
      hit.xi[1][h] = xi1;
    }
    hit.slides[h] = slid;
    const double Ft0 = -kt * xi0, Ft1 = -kt * xi1;
    hit.force[0][h] = -kn * delta * n0 + Ft0;
    hit.force[1][h] = -kn * delta * n1 + Ft1;
    hit.torque[h] = n0 * Ft1 - n1 * Ft0;
  }
  if (Update && kt == 0.0) // no tangential spring
    for (int k = 0; k < 2; ++k)
      std::fill(hit.xi[k], hit.xi[k] + nh, 0.0);
}

} // namespace

SpringContacts::SpringContacts(const SpringParams &params, const mpcd::Box &box)
    : params_(params), box_(box), dim_(box.dim) {}

void SpringContacts::compute(const Colloids &c, std::size_t owned, ContactHistory &h, double step) {
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

void SpringContacts::load_springs(const ContactHistory &h) {
  // Both in key order: one walk along h.
  const std::size_t m = slot_owner_.size();
  for (int k = 0; k < 3; ++k)
    slot_xi_[k].assign(m, 0.0);
  std::size_t walk = 0;
  for (std::size_t q = 0; q < m; ++q) {
    const std::uint64_t o = slot_owner_[q], p = slot_partner_[q];
    while (walk < h.size() && (h.owner[walk] < o || (h.owner[walk] == o && h.partner[walk] < p)))
      ++walk;
    if (walk < h.size() && h.owner[walk] == o && h.partner[walk] == p)
      for (int k = 0; k < dim_; ++k)
        slot_xi_[k][q] = h.xi[k][walk];
  }
}

void SpringContacts::store_springs(ContactHistory &h) const {
  const std::size_t m = slot_owner_.size();
  std::size_t n = 0;
  for (std::size_t q = 0; q < m; ++q)
    n += slot_touch_[q];
  h.dim = dim_;
  h.resize(n);
  std::size_t r = 0;
  for (std::size_t q = 0; q < m; ++q)
    if (slot_touch_[q]) {
      h.owner[r] = slot_owner_[q];
      h.partner[r] = slot_partner_[q];
      for (int k = 0; k < dim_; ++k)
        h.xi[k][r] = slot_xi_[k][q];
      ++r;
    }
}

template <int D, bool WallsY> void SpringContacts::forces(const Colloids &c, double step) {
  const ScopedSeconds timed(force_seconds_);
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
      hits_[nh] = static_cast<std::uint32_t>(q);
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
    if constexpr (D == 2) {
      const Hits2 hits{hi, hj, kind, {sxi[0], sxi[1]}, {hf[0], hf[1]}, ht[0], slides};
      if (update)
        contacts_2d<true, WallsY>(c, hits, nh, p, L, step);
      else
        contacts_2d<false, WallsY>(c, hits, nh, p, L, step);
    } else
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
    std::uint64_t sliding = 0;
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
      sliding += slides[h];
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
      updates_ += nh;
      sliding_ += sliding;
    }
  }
}

template <int D, bool WallsY>
bool SpringContacts::pairs_fresh(const Colloids &c, std::size_t owned, bool same_rows) const {
  const std::size_t nc = c.size();
  if (!built_ || owned != built_owned_ || nc != built_id_.size() ||
      (!same_rows && (c.id != built_id_ || c.radius != built_radius_)))
    return false;
  // The largest displacement since the list was built (a plain loop, vectorised; its rounding
  // only decides when the list is built again, which changes no result).
  double worst = 0.0;
  for (std::size_t a = 0; a < nc; ++a) {
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

void SpringContacts::kick(Colloids &c, std::size_t owned, double h,
                          const std::vector<double> *external) const {
  const int S = stride();
  for (std::size_t a = 0; a < owned; ++a) {
    const std::int64_t *s = &sums_[a * static_cast<std::size_t>(S)];
    const double m = c.mass[a], inertia = inertia_[a];
    for (int k = 0; k < dim_; ++k) {
      double f = fixed::to_double(s[k]);
      if (external)
        f += (*external)[a * static_cast<std::size_t>(dim_) + k];
      c.v[k][a] += h * f / m;
    }
    if (dim_ == 2)
      c.omega[2][a] += h * fixed::to_double(s[2]) / inertia;
    else
      for (int k = 0; k < 3; ++k)
        c.omega[k][a] += h * fixed::to_double(s[3 + k]) / inertia;
  }
}

void SpringContacts::advance(Colloids &c, std::size_t owned, ContactHistory &h, double dt,
                             const SpringHooks *hooks, const std::vector<double> *external) {
  if (dim_ == 2)
    box_.walls_y ? advance<2, true>(c, owned, h, dt, hooks, external)
                 : advance<2, false>(c, owned, h, dt, hooks, external);
  else
    box_.walls_y ? advance<3, true>(c, owned, h, dt, hooks, external)
                 : advance<3, false>(c, owned, h, dt, hooks, external);
}

template <int D, bool WallsY>
void SpringContacts::advance(Colloids &c, std::size_t owned, ContactHistory &h, double dt,
                             const SpringHooks *hooks, const std::vector<double> *external) {
  const int n = params_.substeps;
  const double hs = dt / n;
  // The springs live in the list's slots during the step and go back to h at its end (and
  // whenever the list is built again).
  if (!pairs_fresh<D, WallsY>(c, owned))
    build_pairs<D, WallsY>(c, owned);
  load_springs(h);
  inertia_.resize(owned);
  for (std::size_t a = 0; a < owned; ++a)
    inertia_[a] = moment_of_inertia(c, a);
  forces<D, WallsY>(c, 0.0); // the forces the last step ended with
  if (hooks)
    hooks->reverse(sums_, stride());
  for (int s = 0; s < n; ++s) {
    kick(c, owned, 0.5 * hs, external);
    for (std::size_t a = 0; a < owned; ++a)
      for (int k = 0; k < D; ++k) {
        double x = c.x[k][a] + c.v[k][a] * hs;
        if (!(k == 1 && WallsY))
          x = mpcd::wrap_periodic(x, box_.length[k]);
        c.x[k][a] = x;
      }
    if (hooks)
      hooks->refresh(c);
    if (!pairs_fresh<D, WallsY>(c, owned, true)) { // (only the positions changed)
      if (s > 0)
        store_springs(h); // the contacts of the last sub-step
      build_pairs<D, WallsY>(c, owned);
      load_springs(h);
    }
    forces<D, WallsY>(c, hs);
    if (hooks)
      hooks->reverse(sums_, stride());
    kick(c, owned, 0.5 * hs, external);
  }
  store_springs(h);
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

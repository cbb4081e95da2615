// Linear springs with Coulomb friction between colloids and with the walls (seed 001 §4.2.3).
#include "narrows/colloids/springs.hpp"

#include "narrows/colloids/colloid_pairs.hpp"
#include "narrows/colloids/force_terms.hpp"
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/mpcd/streaming.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::colloids {

namespace {

// One contact of body i with body j (a row, or -1: a wall at rest). n: the unit normal from i
// towards j; delta: the overlap; ri, rj: the lever arms (radii; rj 0 for a wall).
struct Contact {
  std::size_t i;
  long j;
  double n[3];
  double delta, ri, rj, mu;
  std::uint64_t owner, partner;
};

} // namespace

SpringContacts::SpringContacts(const SpringParams &params, const mpcd::Box &box)
    : params_(params), box_(box), dim_(box.dim) {
  next_.dim = dim_;
}

void SpringContacts::compute(const Colloids &c, std::size_t owned, ContactHistory &h, double step) {
  if (dim_ == 2)
    box_.walls_y ? compute<2, true>(c, owned, h, step) : compute<2, false>(c, owned, h, step);
  else
    box_.walls_y ? compute<3, true>(c, owned, h, step) : compute<3, false>(c, owned, h, step);
}

template <int D, bool WallsY>
void SpringContacts::compute(const Colloids &c, std::size_t owned, ContactHistory &h, double step) {
  constexpr int S = D == 2 ? 3 : 6;
  const std::size_t nc = c.size();
  sums_.assign(nc * S, 0);
  const bool update = step > 0.0;
  if (update)
    next_.resize(0);
  const SpringParams &p = params_;

  // The force of one contact on i (and the opposite on j), torques on both; the spring is
  // advanced first when updating.
  const auto add = [&](const Contact &k) {
    double U[3] = {0.0, 0.0, 0.0}, w[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < D; ++d)
      U[d] = c.v[d][k.i] - (k.j >= 0 ? c.v[d][static_cast<std::size_t>(k.j)] : 0.0);
    for (int d = 0; d < 3; ++d)
      w[d] = k.ri * c.omega[d][k.i] +
             (k.j >= 0 ? k.rj * c.omega[d][static_cast<std::size_t>(k.j)] : 0.0);
    // U = v_i - v_j + (r_i w_i + r_j w_j) x n: the relative velocity of the contact points.
    if constexpr (D == 2) {
      U[0] -= w[2] * k.n[1];
      U[1] += w[2] * k.n[0];
    } else {
      U[0] += w[1] * k.n[2] - w[2] * k.n[1];
      U[1] += w[2] * k.n[0] - w[0] * k.n[2];
      U[2] += w[0] * k.n[1] - w[1] * k.n[0];
    }
    double xi[3] = {0.0, 0.0, 0.0};
    const long row = h.find(k.owner, k.partner);
    if (row >= 0)
      for (int d = 0; d < D; ++d)
        xi[d] = h.xi[d][static_cast<std::size_t>(row)];
    if (update) {
      // Into the current tangent plane, the same length (eq 4.40).
      double len2 = 0.0, xn = 0.0, un = 0.0;
      for (int d = 0; d < D; ++d) {
        len2 += xi[d] * xi[d];
        xn += xi[d] * k.n[d];
        un += U[d] * k.n[d];
      }
      if (len2 > 0.0) {
        double t2 = 0.0;
        for (int d = 0; d < D; ++d) {
          xi[d] -= xn * k.n[d];
          t2 += xi[d] * xi[d];
        }
        const double f = t2 > 0.0 ? std::sqrt(len2 / t2) : 0.0;
        for (int d = 0; d < D; ++d)
          xi[d] *= f;
      }
      // Stretched by the tangential relative velocity (eq 4.39), capped by Coulomb (4.41-4.42).
      double x2 = 0.0;
      for (int d = 0; d < D; ++d) {
        xi[d] += (U[d] - un * k.n[d]) * step;
        x2 += xi[d] * xi[d];
      }
      const double ft = p.kt * std::sqrt(x2), cap = k.mu * p.kn * k.delta;
      if (p.kt == 0.0) {
        for (int d = 0; d < D; ++d)
          xi[d] = 0.0;
      } else if (ft > cap) {
        const double f = cap / ft;
        for (int d = 0; d < D; ++d)
          xi[d] *= f;
        ++sliding_;
      }
      const std::size_t m = next_.size();
      next_.resize(m + 1);
      next_.owner[m] = k.owner;
      next_.partner[m] = k.partner;
      for (int d = 0; d < D; ++d)
        next_.xi[d][m] = xi[d];
      ++updates_;
    }
    double F[3] = {0.0, 0.0, 0.0}, Ft[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < D; ++d) {
      Ft[d] = -p.kt * xi[d];
      F[d] = -p.kn * k.delta * k.n[d] + Ft[d];
    }
    std::int64_t *si = &sums_[k.i * S];
    std::int64_t *sj = k.j >= 0 ? &sums_[static_cast<std::size_t>(k.j) * S] : nullptr;
    for (int d = 0; d < D; ++d) {
      const std::int64_t q = to_fixed(F[d]);
      si[d] += q;
      if (sj)
        sj[d] -= q;
    }
    // n x F_t, times r_i on i and r_j on j.
    if constexpr (D == 2) {
      const double t = k.n[0] * Ft[1] - k.n[1] * Ft[0];
      si[2] += to_fixed(k.ri * t);
      if (sj)
        sj[2] += to_fixed(k.rj * t);
    } else {
      const double t[3] = {k.n[1] * Ft[2] - k.n[2] * Ft[1], k.n[2] * Ft[0] - k.n[0] * Ft[2],
                           k.n[0] * Ft[1] - k.n[1] * Ft[0]};
      for (int d = 0; d < 3; ++d) {
        si[3 + d] += to_fixed(k.ri * t[d]);
        if (sj)
          sj[3 + d] += to_fixed(k.rj * t[d]);
      }
    }
  };

  // Pairs from a cell list at least the largest contact distance wide; the pair belongs to the
  // rank that owns the colloid of the smaller id (pairs of two ghosts, or whose smaller id is
  // a ghost, are left to their owners).
  double r_max = 0.0;
  for (std::size_t a = 0; a < nc; ++a)
    r_max = std::max(r_max, c.radius[a]);
  if (nc > 1 && 2.0 * r_max > cell_cut_) {
    cell_cut_ = 2.0 * r_max;
    cells_.size_for(box_, cell_cut_);
  }
  const auto &L = box_.length;
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
            const double r2 = separation<D, WallsY>(xj, xi, L, d); // from i towards j
            const double R = c.radius[i] + c.radius[j];
            if (r2 >= R * R)
              continue;
            const double r = std::sqrt(r2);
            Contact k{i,           static_cast<long>(j), {0.0, 0.0, 0.0}, R - r,
                      c.radius[i], c.radius[j],          p.mu_cc,         c.id[i],
                      c.id[j]};
            if (r > 0.0)
              for (int q = 0; q < D; ++q)
                k.n[q] = d[q] / r;
            else
              k.n[0] = 1.0; // centres on top of each other: push apart along x
            add(k);
          }
        });
  if constexpr (WallsY) {
    for (std::size_t a = 0; a < owned; ++a) {
      const double r = c.radius[a], y = c.x[1][a];
      if (y < r) {
        Contact k{a, -1, {0.0, -1.0, 0.0}, r - y, r, 0.0, p.mu_cw, c.id[a], wall_low_id};
        add(k);
      }
      if (y + r > L[1]) {
        Contact k{a, -1, {0.0, 1.0, 0.0}, y + r - L[1], r, 0.0, p.mu_cw, c.id[a], wall_high_id};
        add(k);
      }
    }
  }
  if (update) {
    next_.sort();
    std::swap(h, next_);
    next_.dim = D;
  }
}

void SpringContacts::kick(Colloids &c, std::size_t owned, double h,
                          const std::vector<double> *external) const {
  const int S = stride();
  for (std::size_t a = 0; a < owned; ++a) {
    const std::int64_t *s = &sums_[a * static_cast<std::size_t>(S)];
    const double m = c.mass[a], inertia = moment_of_inertia(c, a);
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
  const int n = params_.substeps;
  const double hs = dt / n;
  compute(c, owned, h, 0.0); // the forces the last step ended with
  if (hooks)
    hooks->reverse(sums_, stride());
  for (int s = 0; s < n; ++s) {
    kick(c, owned, 0.5 * hs, external);
    for (std::size_t a = 0; a < owned; ++a)
      for (int k = 0; k < dim_; ++k) {
        double x = c.x[k][a] + c.v[k][a] * hs;
        if (!(k == 1 && box_.walls_y))
          x = mpcd::wrap_periodic(x, box_.length[k]);
        c.x[k][a] = x;
      }
    if (hooks)
      hooks->refresh(c);
    compute(c, owned, h, hs);
    if (hooks)
      hooks->reverse(sums_, stride());
    kick(c, owned, 0.5 * hs, external);
  }
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

// Velocity-Verlet sub-steps of colloids and fluid, with forces from a cell list of the fluid.
#include "narrows/colloids/md_coupling.hpp"

#include "narrows/colloids/potentials.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/mpcd/cell_grid.hpp"
#include "narrows/mpcd/streaming.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace narrows::colloids {

namespace {

// Added to each colloid's path over a step when choosing the fluid particles of the sub-steps.
constexpr double path_allowance = 0.25;

// Minimum image of a separation along a periodic axis of length L.
inline double minimum_image(double d, double L) {
  if (d > 0.5 * L)
    return d - L;
  if (d < -0.5 * L)
    return d + L;
  return d;
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

// A pair force component in fixed point; refuses values the 64-bit sums cannot hold.
inline std::int64_t to_fixed(double f) {
  if (!(std::abs(f) < fixed::max_magnitude)) {
    std::ostringstream os;
    os << "colloid force component " << f << " is not finite or beyond the fixed-point range "
       << fixed::max_magnitude
       << " (a particle ran deep into a colloid within one MD step; allowed: a smaller MD "
          "step, i.e. more colloids.md_substeps, or weaker forces)";
    throw invariant_error(os.str());
  }
  return fixed::from_double(f);
}

} // namespace

MdCoupling::MdCoupling(const MdParams &params, const mpcd::Box &box, FluidDrift drift)
    : params_(params), box_(box), dim_(box.dim), drift_(std::move(drift)) {}

void MdCoupling::size_cells(const Colloids &c) {
  // Fluid cells at least the largest WCA cut-off wide, colloid cells at least the largest
  // 48-24 cut-off; the radii are fixed, so this runs once.
  double r_max = 0.0;
  for (const double r : c.radius)
    r_max = std::max(r_max, r);
  if (r_max == cell_radius_)
    return;
  cell_radius_ = r_max;
  const double cut = repulsive_cutoff(6, r_max), cut_cc = repulsive_cutoff(24, 2.0 * r_max);
  std::size_t n = 1, n_cc = 1;
  for (int k = 0; k < dim_; ++k) {
    cells_[k] = std::max(1, static_cast<int>(std::floor(box_.length[k] / cut)));
    inv_cell_[k] = cells_[k] / box_.length[k];
    n *= static_cast<std::size_t>(cells_[k]);
    cc_cells_[k] = std::max(1, static_cast<int>(std::floor(box_.length[k] / cut_cc)));
    cc_inv_cell_[k] = cc_cells_[k] / box_.length[k];
    n_cc *= static_cast<std::size_t>(cc_cells_[k]);
  }
  head_.assign(n, -1);
  cc_head_.assign(n_cc, -1);
}

void MdCoupling::clear_fluid_forces() {
  for (const std::uint32_t i : touched_) {
    fluid_flag_[i] = 0;
    for (int k = 0; k < dim_; ++k)
      fluid_force_[static_cast<std::size_t>(i) * dim_ + k] = 0;
  }
  touched_.clear();
}

void MdCoupling::build_cell_list(const mpcd::Fluid &f) {
  const std::size_t n = f.size();
  std::fill(head_.begin(), head_.end(), -1);
  next_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t cell = 0;
    for (int k = dim_ - 1; k >= 0; --k) {
      const int ck =
          mpcd::clamped_cell(f.x[k][i], inv_cell_[k], cells_[k], "fluid particle", f.id[i], k);
      cell = cell * static_cast<std::size_t>(cells_[k]) + static_cast<std::size_t>(ck);
    }
    next_[i] = head_[cell];
    head_[cell] = static_cast<std::int32_t>(i);
  }
}

template <int D, bool WallsY>
void MdCoupling::select_near(const mpcd::Fluid &f, const Colloids &c) {
  // Uses the cell list of f built by the force evaluation just before.
  const std::size_t n = f.size();
  const double dt = params_.tau * params_.substeps;
  const double half_a_dt2 = 0.5 * params_.fluid_accel * dt * dt;
  const double *X[3] = {f.x[0].data(), f.x[1].data(), D == 3 ? f.x[2].data() : nullptr};
  const double *V[3] = {f.v[0].data(), f.v[1].data(), D == 3 ? f.v[2].data() : nullptr};
  auto reach = [&](std::size_t i) {
    double v2 = 0.0;
    for (int k = 0; k < D; ++k)
      v2 += V[k][i] * V[k][i];
    return std::sqrt(v2) * dt + half_a_dt2;
  };
  double max_reach = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    max_reach = std::max(max_reach, reach(i));
  near_flag_.assign(n, 0);
  near_index_.clear();
  const auto &L = box_.length;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double range = repulsive_cutoff(6, c.radius[a]) + margin_[a];
    const double xc[3] = {c.x[0][a], c.x[1][a], D == 3 ? c.x[2][a] : 0.0};
    // Cells along each axis within range + max_reach of the colloid's cell (all if that covers
    // the axis); along a wall axis clipped at the ends.
    std::array<std::vector<int>, 3> axis;
    for (int k = 0; k < D; ++k) {
      const int nk = cells_[k];
      const int home = mpcd::clamped_cell(c.x[k][a], inv_cell_[k], nk, "colloid", c.id[a], k);
      const int w = static_cast<int>(std::ceil((range + max_reach) * inv_cell_[k]));
      if (2 * w + 1 >= nk) {
        for (int q = 0; q < nk; ++q)
          axis[k].push_back(q);
      } else if (WallsY && k == 1) {
        for (int q = std::max(0, home - w); q <= std::min(nk - 1, home + w); ++q)
          axis[k].push_back(q);
      } else {
        for (int q = home - w; q <= home + w; ++q)
          axis[k].push_back(q < 0 ? q + nk : (q >= nk ? q - nk : q));
      }
    }
    if constexpr (D == 2)
      axis[2] = {0};
    for (const int cz : axis[2])
      for (const int cy : axis[1])
        for (const int cx : axis[0]) {
          const std::size_t cell =
              (static_cast<std::size_t>(cz) * cells_[1] + static_cast<std::size_t>(cy)) *
                  cells_[0] +
              static_cast<std::size_t>(cx);
          for (std::int32_t j = head_[cell]; j >= 0; j = next_[j]) {
            const auto js = static_cast<std::size_t>(j);
            if (near_flag_[js])
              continue;
            const double xj[3] = {X[0][js], X[1][js], D == 3 ? X[2][js] : 0.0};
            double d[3];
            const double r2 = separation<D, WallsY>(xj, xc, L, d);
            const double limit = range + reach(js);
            if (r2 < limit * limit) {
              near_flag_[js] = 1;
              near_index_.push_back(static_cast<std::uint32_t>(j));
            }
          }
        }
  }
}

template <int D, bool WallsY>
void MdCoupling::colloid_pairs(const Colloids &c, PotentialEnergy &energy, bool want_energy) {
  // A cell list of the colloids (cells at least the largest 48-24 cut-off wide): colloid a meets
  // the partners b > a in the cells within one of its own (along an axis of fewer than three
  // cells, all of its cells, so no cell is visited twice and no pair counted twice; along a
  // wall axis the range stops at the walls). The pair forces are rounded to fixed point and
  // summed as integers, so the order of the pairs does not matter; the energy is a sum of
  // doubles, so for it the partners of each a are taken in increasing b, the order of a double
  // loop over a < b.
  const std::size_t nc = c.size();
  const auto &L = box_.length;
  const double eps = params_.epsilon;
  std::fill(cc_head_.begin(), cc_head_.end(), -1);
  cc_next_.resize(nc);
  cc_cell_.resize(nc * D);
  for (std::size_t a = 0; a < nc; ++a) {
    std::size_t cell = 0;
    for (int k = D - 1; k >= 0; --k) {
      const int n = cc_cells_[k];
      const int ck = mpcd::clamped_cell(c.x[k][a], cc_inv_cell_[k], n, "colloid", c.id[a], k);
      cc_cell_[a * D + k] = ck;
      cell = cell * static_cast<std::size_t>(n) + static_cast<std::size_t>(ck);
    }
    cc_next_[a] = cc_head_[cell];
    cc_head_[cell] = static_cast<std::int32_t>(a);
  }
  for (std::size_t a = 0; a < nc; ++a) {
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, home[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      const int n = cc_cells_[k];
      home[k] = cc_cell_[a * D + k];
      if (n < 3) {
        lo[k] = -home[k], hi[k] = n - 1 - home[k];
      } else if (WallsY && k == 1) {
        lo[k] = home[k] > 0 ? -1 : 0, hi[k] = home[k] < n - 1 ? 1 : 0;
      } else {
        lo[k] = -1, hi[k] = 1;
      }
    }
    cc_partners_.clear();
    int off[3] = {0, 0, 0};
    for (off[2] = lo[2]; off[2] <= hi[2]; ++off[2])
      for (off[1] = lo[1]; off[1] <= hi[1]; ++off[1])
        for (off[0] = lo[0]; off[0] <= hi[0]; ++off[0]) {
          std::size_t cell = 0;
          for (int k = D - 1; k >= 0; --k) {
            const int n = cc_cells_[k];
            int ck = home[k] + off[k];
            ck = ck < 0 ? ck + n : (ck >= n ? ck - n : ck);
            cell = cell * static_cast<std::size_t>(n) + static_cast<std::size_t>(ck);
          }
          for (std::int32_t b = cc_head_[cell]; b >= 0; b = cc_next_[b])
            if (static_cast<std::size_t>(b) > a)
              cc_partners_.push_back(static_cast<std::uint32_t>(b));
        }
    if (want_energy)
      std::sort(cc_partners_.begin(), cc_partners_.end());
    const double xa[3] = {c.x[0][a], c.x[1][a], D == 3 ? c.x[2][a] : 0.0};
    for (const std::uint32_t b : cc_partners_) {
      const double xb[3] = {c.x[0][b], c.x[1][b], D == 3 ? c.x[2][b] : 0.0};
      double d[3];
      const double r2 = separation<D, WallsY>(xa, xb, L, d);
      const double scc = c.radius[a] + c.radius[b];
      if (r2 >= std::pow(repulsive_cutoff(24, scc), 2))
        continue;
      const PairTerm t = repulsive_pair<24>(r2, scc * scc, eps);
      energy.colloid_colloid += t.energy;
      for (int k = 0; k < D; ++k) {
        const std::int64_t q = to_fixed(t.f_over_r * d[k]);
        colloid_force_[a * D + k] += q;
        colloid_force_[static_cast<std::size_t>(b) * D + k] -= q;
      }
    }
  }
}

template <int D, bool WallsY>
PotentialEnergy MdCoupling::forces(const mpcd::Fluid &f, const Colloids &c, MPI_Comm comm,
                                   bool want_energy) {
  const std::size_t n = f.size(), nc = c.size();
  // Forces of the previous call are cleared where they were set; arrays grow with the fluid.
  clear_fluid_forces();
  fluid_force_.resize(n * D, 0);
  fluid_flag_.resize(n, 0);
  const auto &L = box_.length;

  size_cells(c);
  build_cell_list(f);
  const double *X[3] = {f.x[0].data(), f.x[1].data(), D == 3 ? f.x[2].data() : nullptr};

  // Colloid-fluid pairs (sigma_cf = r_a): each colloid scans the cells within one cell of its
  // own (all cells of an axis with fewer than three, so none is visited twice).
  PotentialEnergy energy;
  colloid_local_.assign(nc * D, 0);
  const double eps = params_.epsilon;
  for (std::size_t a = 0; a < nc; ++a) {
    const double cut2 = std::pow(repulsive_cutoff(6, c.radius[a]), 2);
    const double s2cf = c.radius[a] * c.radius[a];
    double xc[3] = {0.0, 0.0, 0.0};
    int lo[3], hi[3], home[3];
    for (int k = 0; k < D; ++k) {
      xc[k] = c.x[k][a];
      home[k] = mpcd::clamped_cell(xc[k], inv_cell_[k], cells_[k], "colloid", c.id[a], k);
      const bool periodic = !(WallsY && k == 1);
      if (cells_[k] < 3) {
        lo[k] = 0, hi[k] = cells_[k] - 1, home[k] = 0;
      } else if (periodic) {
        lo[k] = -1, hi[k] = 1;
      } else {
        lo[k] = home[k] > 0 ? -1 : 0, hi[k] = home[k] < cells_[k] - 1 ? 1 : 0;
      }
    }
    int off[3] = {0, 0, 0};
    for (off[2] = D == 3 ? lo[2] : 0; off[2] <= (D == 3 ? hi[2] : 0); ++off[2])
      for (off[1] = lo[1]; off[1] <= hi[1]; ++off[1])
        for (off[0] = lo[0]; off[0] <= hi[0]; ++off[0]) {
          std::size_t cell = 0;
          for (int k = D - 1; k >= 0; --k) {
            int ck = home[k] + off[k];
            ck = ck < 0 ? ck + cells_[k] : (ck >= cells_[k] ? ck - cells_[k] : ck);
            cell = cell * static_cast<std::size_t>(cells_[k]) + static_cast<std::size_t>(ck);
          }
          for (std::int32_t j = head_[cell]; j >= 0; j = next_[j]) {
            const double xj[3] = {X[0][j], X[1][j], D == 3 ? X[2][j] : 0.0};
            double d[3];
            const double r2 = separation<D, WallsY>(xj, xc, L, d);
            if (r2 >= cut2)
              continue;
            const PairTerm t = repulsive_pair<6>(r2, s2cf, eps);
            if (want_energy)
              energy.colloid_fluid += t.energy;
            const auto js = static_cast<std::size_t>(j);
            if (!fluid_flag_[js]) {
              fluid_flag_[js] = 1;
              touched_.push_back(static_cast<std::uint32_t>(j));
            }
            for (int k = 0; k < D; ++k) {
              const std::int64_t q = to_fixed(t.f_over_r * d[k]);
              fluid_force_[js * D + k] += q;
              colloid_local_[a * D + k] -= q;
            }
          }
        }
  }
  colloid_force_.resize(nc * D);
  if (comm == MPI_COMM_NULL) {
    colloid_force_ = colloid_local_;
  } else {
    MPI_Allreduce(colloid_local_.data(), colloid_force_.data(), static_cast<int>(nc * D),
                  MPI_INT64_T, MPI_SUM, comm);
  }
  if (want_energy && comm != MPI_COMM_NULL) {
    double sum = 0.0;
    MPI_Allreduce(&energy.colloid_fluid, &sum, 1, MPI_DOUBLE, MPI_SUM, comm);
    energy.colloid_fluid = sum;
  }

  // Colloid-colloid pairs (sigma_cc = r_a + r_b), wall and gravity: the same on every rank (all
  // hold all colloids).
  colloid_pairs<D, WallsY>(c, energy, want_energy);
  if constexpr (WallsY) {
    for (std::size_t a = 0; a < nc; ++a) {
      const double sw = params_.sigma_wall > 0.0 ? params_.sigma_wall : 2.0 * c.radius[a];
      const double hcut = wall_cutoff(sw), y = c.x[1][a];
      if (!(y > 0.0 && y < L[1])) {
        std::ostringstream os;
        os.precision(17);
        os << "colloid id " << c.id[a] << " is outside the channel at y = " << y
           << " (allowed: 0 < y < " << L[1] << ")";
        throw invariant_error(os.str());
      }
      if (y < hcut) {
        const WallTerm w = wall_term(y, sw, eps, params_.wall_q);
        energy.wall += w.energy;
        colloid_force_[a * D + 1] += to_fixed(w.force);
      }
      if (L[1] - y < hcut) {
        const WallTerm w = wall_term(L[1] - y, sw, eps, params_.wall_q);
        energy.wall += w.energy;
        colloid_force_[a * D + 1] -= to_fixed(w.force);
      }
    }
  }
  for (int k = 0; k < D; ++k)
    if (params_.gravity[k] != 0.0) // the field g of seed 000 (eq 4.4): force M g on each colloid
      for (std::size_t a = 0; a < nc; ++a)
        colloid_force_[a * D + k] += to_fixed(c.mass[a] * params_.gravity[k]);
  return energy;
}

PotentialEnergy MdCoupling::compute_forces(const mpcd::Fluid &fluid, const Colloids &colloids,
                                           MPI_Comm comm, bool want_energy) {
  if (dim_ == 3)
    return box_.walls_y ? forces<3, true>(fluid, colloids, comm, want_energy)
                        : forces<3, false>(fluid, colloids, comm, want_energy);
  return box_.walls_y ? forces<2, true>(fluid, colloids, comm, want_energy)
                      : forces<2, false>(fluid, colloids, comm, want_energy);
}

void MdCoupling::kick(mpcd::Fluid &f, Colloids &c) const {
  // Half a step of the current forces: v += F tau / (2 m), fluid mass 1.
  const double h = 0.5 * params_.tau;
  for (const std::uint32_t i : touched_)
    for (int k = 0; k < dim_; ++k)
      f.v[k][i] += fixed::to_double(fluid_force_[static_cast<std::size_t>(i) * dim_ + k]) * h;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double s = h / c.mass[a];
    for (int k = 0; k < dim_; ++k)
      c.v[k][a] += fixed::to_double(colloid_force_[a * dim_ + k]) * s;
  }
}

void MdCoupling::advance(mpcd::Fluid &fluid, Colloids &colloids, MPI_Comm comm) {
  // Forces depend on positions only, which the collision does not change: they are computed
  // afresh here rather than carried across the migration of the fluid.
  compute_forces(fluid, colloids, comm);
  const double tau = params_.tau, dt = tau * params_.substeps;
  const std::size_t nc = colloids.size();
  margin_.resize(nc);
  for (int k = 0; k < dim_; ++k)
    start_[k] = colloids.x[k];
  for (std::size_t a = 0; a < nc; ++a) {
    double v2 = 0.0, f2 = 0.0;
    for (int k = 0; k < dim_; ++k) {
      v2 += colloids.v[k][a] * colloids.v[k][a];
      const double f = fixed::to_double(colloid_force_[a * dim_ + k]);
      f2 += f * f;
    }
    // Fluid kicks change the force within the step, so a fixed allowance is added to the path
    // the start values give (a thermal colloid moves ~0.01 per step of 0.1).
    margin_[a] = std::sqrt(v2) * dt + std::sqrt(f2) / colloids.mass[a] * dt * dt + path_allowance;
  }
  // The particles that may meet a colloid this step are copied out; everybody streams the
  // whole step, then the copies are integrated with the colloids and written back.
  if (dim_ == 3)
    box_.walls_y ? select_near<3, true>(fluid, colloids) : select_near<3, false>(fluid, colloids);
  else
    box_.walls_y ? select_near<2, true>(fluid, colloids) : select_near<2, false>(fluid, colloids);
  const std::size_t m = near_index_.size();
  near_.dim = dim_;
  near_.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    const std::uint32_t i = near_index_[j];
    for (int k = 0; k < dim_; ++k) {
      near_.x[k][j] = fluid.x[k][i];
      near_.v[k][j] = fluid.v[k][i];
    }
    near_.id[j] = fluid.id[i];
  }
  drift_(fluid, dt);
  compute_forces(near_, colloids, comm); // the same colloid forces: every pair is in near_
  for (int s = 0; s < params_.substeps; ++s) {
    kick(near_, colloids);
    drift_(near_, tau);
    for (std::size_t a = 0; a < nc; ++a)
      for (int k = 0; k < dim_; ++k) {
        double x = colloids.x[k][a] + colloids.v[k][a] * tau;
        if (!(k == 1 && box_.walls_y))
          x = mpcd::wrap_periodic(x, box_.length[k]);
        colloids.x[k][a] = x;
      }
    compute_forces(near_, colloids, comm);
    kick(near_, colloids);
  }
  for (std::size_t j = 0; j < m; ++j) {
    const std::uint32_t i = near_index_[j];
    for (int k = 0; k < dim_; ++k) {
      fluid.x[k][i] = near_.x[k][j];
      fluid.v[k][i] = near_.v[k][j];
    }
  }
  // A colloid that went further than assumed might have met a particle left out.
  for (std::size_t a = 0; a < nc; ++a) {
    double d2 = 0.0;
    for (int k = 0; k < dim_; ++k) {
      double d = colloids.x[k][a] - start_[k][a];
      if (!(k == 1 && box_.walls_y))
        d = minimum_image(d, box_.length[k]);
      d2 += d * d;
    }
    if (std::sqrt(d2) > margin_[a] + 1e-12) {
      std::ostringstream os;
      os << "colloid id " << colloids.id[a] << " moved " << std::sqrt(d2)
         << " in one step, more than the " << margin_[a]
         << " its velocity and force allowed (a sudden force: more colloids.md_substeps or a "
            "smaller fluid.dt)";
      throw invariant_error(os.str());
    }
  }
}

} // namespace narrows::colloids

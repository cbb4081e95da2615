// Ghost copies of colloids owned by other ranks.
#include "narrows/colloids/ghosts.hpp"

#include "narrows/colloids/ownership.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace narrows::colloids {

namespace {

// True if x (in [0, L)) lies within `range` of the interval [lo, hi] on a circle of length L.
bool near_interval(double x, double lo, double hi, double range, double L) {
  const double span = hi - lo;
  if (span + 2.0 * range >= L)
    return true;
  double u = std::fmod(x - lo, L);
  if (u < 0.0)
    u += L;
  return u <= span + range || u >= L - range;
}

} // namespace

ColloidGhosts::ColloidGhosts(const parallel::Slabs &slabs, const mpcd::Box &box)
    : slabs_(slabs), box_(box), exchange_(slabs.comm()) {}

double ColloidGhosts::largest_radius(const Colloids &c) {
  if (r_max_ < 0.0) { // radii never change: once per run
    double mine = 0.0;
    for (const double r : c.radius)
      mine = std::max(mine, r);
    MPI_Allreduce(&mine, &r_max_, 1, MPI_DOUBLE, MPI_MAX, slabs_.comm());
  }
  return r_max_;
}

void ColloidGhosts::add(Colloids &c, std::vector<double> *margin, double own_extent) {
  owned_ = c.size();
  if (!active())
    return;
  const int ranks = slabs_.ranks(), me = slabs_.rank();
  extent_.resize(ranks);
  MPI_Allgather(&own_extent, 1, MPI_DOUBLE, extent_.data(), 1, MPI_DOUBLE, slabs_.comm());
  const double r_max = largest_radius(c), L = box_.length[0];
  list_.clear();
  for (std::size_t a = 0; a < owned_; ++a) {
    const double range = repulsive_cutoff(24, c.radius[a] + r_max) + (margin ? (*margin)[a] : 0.0);
    for (int r = 0; r < ranks; ++r) {
      if (r == me)
        continue;
      const double lo = slabs_.first_column_of(r) - extent_[r];
      const double hi =
          (r + 1 < ranks ? slabs_.first_column_of(r + 1) : slabs_.columns()) + extent_[r];
      if (near_interval(c.x[0][a], lo, hi, range, L)) {
        list_.index.push_back(a);
        list_.dest.push_back(r);
      }
    }
  }
  parallel::SoaView view = parallel::view(table(c), species::ghost);
  if (margin)
    view.reals.push_back(margin);
  halo_ = exchange_.copy(view, list_);
}

void ColloidGhosts::add_for_forces(Colloids &c) { add(c, nullptr, 1.0); }

void ColloidGhosts::add_for_step(Colloids &c, std::vector<double> &margin, double fluid_reach) {
  add_for_step(c, margin, fluid_reach, 0.0);
}

void ColloidGhosts::add_for_step(Colloids &c, std::vector<double> &margin, double fluid_reach,
                                 double more) {
  if (!active()) {
    owned_ = c.size();
    return;
  }
  double own = 0.0, largest = 0.0;
  for (std::size_t a = 0; a < c.size(); ++a)
    own = std::max(own, margin[a]);
  MPI_Allreduce(&own, &largest, 1, MPI_DOUBLE, MPI_MAX, slabs_.comm());
  add(c, &margin, std::max(1.0 + fluid_reach + 2.0 * largest, own) + more);
}

void ColloidGhosts::trusted_rows(const Colloids &c, double depth,
                                 std::vector<std::uint8_t> &flags) const {
  flags.assign(c.size(), 1);
  if (!active())
    return;
  const double lo = slabs_.first_column(), hi = lo + slabs_.local_columns();
  const double range = extent() - depth;
  for (std::size_t a = owned_; a < c.size(); ++a)
    flags[a] = range >= 0.0 && near_interval(c.x[0][a], lo, hi, range, box_.length[0]);
}

void ColloidGhosts::refresh_positions(Colloids &c) {
  if (!active())
    return;
  positions_.clear(); // pointers to the position arrays (no allocation after the first step)
  for (int k = 0; k < c.dim; ++k)
    positions_.push_back(&c.x[k]);
  exchange_.refresh(positions_, list_, owned_);
}

void ColloidGhosts::refresh_motion(Colloids &c) {
  if (!active())
    return;
  motion_.clear();
  for (int k = 0; k < c.dim; ++k)
    motion_.push_back(&c.v[k]);
  for (int k = 0; k < 3; ++k)
    motion_.push_back(&c.omega[k]);
  exchange_.refresh(motion_, list_, owned_);
}

void ColloidGhosts::refresh_state(Colloids &c) {
  if (!active())
    return;
  state_.clear();
  for (int k = 0; k < c.dim; ++k)
    state_.push_back(&c.x[k]);
  for (int k = 0; k < c.dim; ++k)
    state_.push_back(&c.v[k]);
  for (int k = 0; k < 3; ++k)
    state_.push_back(&c.omega[k]);
  exchange_.refresh(state_, list_, owned_);
}

void ColloidGhosts::reverse(std::vector<std::int64_t> &per_row, int k) {
  if (!active())
    return;
  const std::size_t first = owned_ * static_cast<std::size_t>(k);
  ghost_values_.assign(per_row.begin() + static_cast<std::ptrdiff_t>(first), per_row.end());
  std::fill(per_row.begin() + static_cast<std::ptrdiff_t>(first), per_row.end(), 0);
  exchange_.reverse(halo_, ghost_values_, k, per_row);
}

void ColloidGhosts::remove(Colloids &c, std::vector<double> *margin) {
  table(c).resize(owned_);
  if (margin)
    margin->resize(owned_);
}

void ColloidGhosts::check_region(const mpcd::Fluid &near) const {
  if (!active())
    return;
  const int r = slabs_.rank();
  const double lo = slabs_.first_column() - extent_[r];
  const double hi = slabs_.first_column() + slabs_.local_columns() + extent_[r];
  for (std::size_t j = 0; j < near.size(); ++j)
    if (!near_interval(near.x[0][j], lo, hi, 0.0, box_.length[0])) {
      std::ostringstream os;
      os << "fluid particle id " << near.id[j] << " near a colloid ended at x = " << near.x[0][j]
         << ", outside the region [" << lo << ", " << hi
         << "] whose colloids this rank held this step (a colloid it met may have been "
            "missing; allowed: a smaller fluid.dt or more colloids.md_substeps)";
      throw invariant_error(os.str());
    }
}

} // namespace narrows::colloids

// Ghost copies of colloids owned by other ranks.
#include "narrows/colloids/ghosts.hpp"

#include "narrows/colloids/ownership.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/core/error.hpp"
#include "narrows/parallel/message_clock.hpp"

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
    : slabs_(slabs), box_(box), exchange_(slabs.comm()), contact_exchange_(slabs.comm()) {}

double ColloidGhosts::largest_radius(const Colloids &c) {
  if (r_max_ < 0.0) { // radii never change: once per run
    double mine = 0.0;
    for (const double r : c.radius)
      mine = std::max(mine, r);
    MPI_Allreduce(&mine, &r_max_, 1, MPI_DOUBLE, MPI_MAX, slabs_.comm());
  }
  return r_max_;
}

void ColloidGhosts::add(Colloids &c, std::vector<double> *margin, double extent,
                        double largest_margin) {
  owned_ = c.size();
  if (!active())
    return;
  extent_ = extent;
  largest_margin_ = largest_margin;
  const int ranks = slabs_.ranks();
  const double r_max = largest_radius(c), L = box_.length[0];
  // A colloid owned here lies within a column of this slab (the grid shift); it is copied to
  // the ranks whose region [first - e, end + e] comes within its range.
  reach_columns_ = extent + repulsive_cutoff(24, 2.0 * r_max) + largest_margin + 2.0;
  exchange_.set_neighbours(slabs_, reach_columns_, "colloid ghost");
  list_.clear();
  for (std::size_t a = 0; a < owned_; ++a) {
    const double range = repulsive_cutoff(24, c.radius[a] + r_max) + (margin ? (*margin)[a] : 0.0);
    for (const int r : exchange_.neighbours()) {
      const double lo = slabs_.first_column_of(r) - extent;
      const double hi = (r + 1 < ranks ? slabs_.first_column_of(r + 1) : slabs_.columns()) + extent;
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

void ColloidGhosts::add_for_forces(Colloids &c) {
  more_ = 0.0;
  add(c, nullptr, 1.0, 0.0);
}

void ColloidGhosts::add_for_step(Colloids &c, std::vector<double> &margin, double fluid_reach) {
  add_for_step(c, margin, fluid_reach, 0.0);
}

void ColloidGhosts::add_for_step(Colloids &c, std::vector<double> &margin, double fluid_reach,
                                 double more) {
  if (!active()) {
    owned_ = c.size();
    return;
  }
  double own[2] = {0.0, fluid_reach}, all[2] = {0.0, 0.0};
  for (std::size_t a = 0; a < c.size(); ++a)
    own[0] = std::max(own[0], margin[a]);
  {
    const parallel::MessageTimer timed;
    MPI_Allreduce(own, all, 2, MPI_DOUBLE, MPI_MAX, slabs_.comm());
  }
  add_for_step_agreed(c, margin, all[0], all[1], more);
}

void ColloidGhosts::add_for_step_agreed(Colloids &c, std::vector<double> &margin,
                                        double largest_margin, double fluid_reach, double more) {
  if (!active()) {
    owned_ = c.size();
    return;
  }
  more_ = more;
  add(c, &margin, 1.0 + fluid_reach + 2.0 * largest_margin + more, largest_margin);
}

void ColloidGhosts::drop_widening(Colloids &c, std::vector<double> &margin,
                                  const std::array<std::vector<double>, 3> &start) {
  if (!active() || more_ == 0.0)
    return;
  const int ranks = slabs_.ranks(), me = slabs_.rank();
  const double r_max = largest_radius(c), L = box_.length[0], e = extent_ - more_;
  const auto range = [&](std::size_t a) {
    return repulsive_cutoff(24, c.radius[a] + r_max) + margin[a];
  };
  const auto end_of = [&](int r) {
    return r + 1 < ranks ? slabs_.first_column_of(r + 1) : slabs_.columns();
  };
  // The owners' side: the copies that rank r's unwidened region needs (as add() chose them).
  std::vector<int> &to = kept_to_, &from = kept_from_; // (members: no allocation per step)
  to.assign(ranks, 0);
  from.assign(ranks, 0);
  std::size_t kept = 0;
  for (std::size_t j = 0; j < list_.index.size(); ++j) {
    const std::size_t a = list_.index[j];
    const int r = list_.dest[j];
    if (near_interval(start[0][a], slabs_.first_column_of(r) - e, end_of(r) + e, range(a), L)) {
      list_.index[kept] = a;
      list_.dest[kept++] = r;
      ++to[r];
    }
  }
  list_.index.resize(kept);
  list_.dest.resize(kept);
  // This rank's side: its ghosts that its unwidened region needs (the same test, same bits).
  const double lo = slabs_.first_column_of(me) - e, hi = end_of(me) + e;
  std::vector<bool> &keep = keep_;
  keep.assign(c.size(), true);
  kept = 0;
  for (std::size_t g = 0; g < halo_.size(); ++g) {
    const std::size_t a = owned_ + g;
    keep[a] = near_interval(start[0][a], lo, hi, range(a), L);
    if (keep[a]) {
      halo_.source_rank[kept] = halo_.source_rank[g];
      halo_.source_index[kept++] = halo_.source_index[g];
      ++from[halo_.source_rank[g]];
    }
  }
  halo_.source_rank.resize(kept);
  halo_.source_index.resize(kept);
  std::size_t m = 0;
  for (std::size_t a = 0; a < margin.size(); ++a)
    if (keep[a])
      margin[m++] = margin[a];
  margin.resize(m);
  table(c).keep_rows(keep);
  exchange_.keep_copies(to, from);
  more_ = 0.0;
  extent_ = e;
}

void ColloidGhosts::copy_contacts(ContactHistory &h, const Colloids &c) {
  if (!active())
    return;
  // list_ names the owned rows in ascending order (add); the contacts' owners are owned rows.
  contact_list_.clear();
  for (std::size_t j = 0; j < h.size(); ++j) {
    const long a = row_of(c, owned_, h.owner[j]);
    if (a < 0)
      continue;
    const auto first =
        std::lower_bound(list_.index.begin(), list_.index.end(), static_cast<std::size_t>(a));
    for (auto it = first; it != list_.index.end() && *it == static_cast<std::size_t>(a); ++it) {
      contact_list_.index.push_back(j);
      contact_list_.dest.push_back(list_.dest[static_cast<std::size_t>(it - list_.index.begin())]);
    }
  }
  contact_exchange_.set_neighbours(slabs_, reach_columns_, "contact ghost");
  contact_exchange_.copy(parallel::view(table(h), species::migrates), contact_list_);
  h.sort();
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
  const double lo = slabs_.first_column() - extent_;
  const double hi = slabs_.first_column() + slabs_.local_columns() + extent_;
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

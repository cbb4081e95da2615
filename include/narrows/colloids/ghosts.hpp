// Ghost copies of colloids owned by other ranks (issue 16 item 4): every colloid that can
// interact with this rank's fluid or with the colloids it owns is present on it, as an owned
// row or as a ghost row appended after the owned ones. Ghosts are exact copies (the same
// position bits; pair geometry is the minimum image, as on one rank), forces on them go back to
// their owners in fixed point (reverse), so the result is bitwise that of one rank.
//
// Rank r's region is the interval [first_r - e_r, end_r + e_r] along x around its slab of cell
// columns [first_r, end_r); a colloid a is copied to every other rank whose region comes within
// R_a = margin_a + 2^(1/24) (r_a + r_max) of its centre (the 48-24 range to the largest colloid,
// which exceeds the WCA range r_a 2^(1/6), plus the colloid's own path this step). Two uses per
// MPCD step:
//   for forces at the start of a step: e_r = 1 (the fluid of a rank lies within half a cell of
//   its slab after binning on the shifted grid; the owned colloids within it), margins 0;
//   for the whole step: e = 1 + fluid reach + 2 M, where the fluid reach is |v| dt + a dt^2 / 2
//   of the fastest fluid particle of any rank and M the largest margin of any colloid (a fluid
//   particle kicked by a colloid gains at most about twice the colloid's speed).
//   check_region() refuses a near fluid particle that ended outside it.
// e is the same on every rank (the largest of all ranks' needs), so each rank knows every
// region from the slabs: the copies go to the ranks whose slabs come within e + R_max of this
// rank's slab (the Exchange's neighbours, from 1 on each side up to all on thin slabs), and no
// collective is needed beyond the one that agrees on M and the fluid reach.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/parallel/exchange.hpp"
#include "narrows/parallel/slabs.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::colloids {

class ColloidGhosts {
public:
  ColloidGhosts(const parallel::Slabs &slabs, const mpcd::Box &box);

  // False on one rank: then nothing is ever copied and every colloid is owned.
  bool active() const { return slabs_.ranks() > 1; }
  // Rows of c that are owned (the rest are ghosts) since the last add_*.
  std::size_t owned() const { return owned_; }

  // Appends the ghosts for forces at the current positions (collective).
  void add_for_forces(Colloids &c);
  // Appends the ghosts for a whole step; `margin` (one per owned row) grows by the ghosts'
  // margins. `fluid_reach`: the largest path of this rank's fluid this step (collective).
  void add_for_step(Colloids &c, std::vector<double> &margin, double fluid_reach);
  // The ghosts' positions from their owners again (after the owners moved them; collective).
  void refresh_positions(Colloids &c);
  // The ghosts' velocities and angular velocities from their owners again (collective).
  void refresh_motion(Colloids &c);
  // The ghosts' positions, velocities and angular velocities from their owners (collective).
  void refresh_state(Colloids &c);
  // Appends the ghosts for a whole step with this rank's region widened by `more` beyond what
  // add_for_step takes (room for chains of contacts; collective).
  void add_for_step(Colloids &c, std::vector<double> &margin, double fluid_reach, double more);
  // The same with M (`largest_margin`) and the fluid reach already agreed over all ranks (the
  // largest of every rank's; not collective: only the neighbours' messages).
  void add_for_step_agreed(Colloids &c, std::vector<double> &margin, double largest_margin,
                           double fluid_reach, double more);
  // One flag per row of c: owned rows, and ghosts whose centre lies within extent() - depth of
  // this rank's slab (their partners within `depth` are all here).
  void trusted_rows(const Colloids &c, double depth, std::vector<std::uint8_t> &flags) const;
  // e_r of this rank's region since the last add (0 on one rank: the region is the box).
  double extent() const { return active() ? extent_ : 0.0; }
  // M of the last add_for_step (0 after add_for_forces): the largest path of any colloid.
  double largest_margin() const { return largest_margin_; }
  // Adds the per-row values of the ghost rows ([row * k + j]) to their owners' rows on the
  // owning ranks, and zeroes the ghost rows (collective).
  void reverse(std::vector<std::int64_t> &per_row, int k);
  // Appends to h copies of the contacts (springs) of this rank's colloids that were copied as
  // ghosts by the last add, to the same ranks, and sorts h: then each rank holds the springs of
  // every pair whose colloid of the smaller id it holds (ghost shell of the spring contacts).
  // The copies are this step's only: keep_contacts_of(h, c, owned()) drops them.
  void copy_contacts(ContactHistory &h, const Colloids &c);
  // Drops the ghosts (and their copies on the owners' side) that the unwidened region does not
  // need: those a rank would not have got without the widening `more`, decided from the
  // positions `start` of the copy (the same bits on both sides). The rest of the step's
  // messages (impulse sums, refreshes) then go to the near ranks only. `margin` loses the same
  // rows. Not collective.
  void drop_widening(Colloids &c, std::vector<double> &margin,
                     const std::array<std::vector<double>, 3> &start);
  // e minus the widening `more` of the last add_for_step (the region whose ghosts the fluid can
  // meet).
  double base_extent() const { return active() ? extent_ - more_ : 0.0; }
  // Drops the ghost rows (and their margins).
  void remove(Colloids &c, std::vector<double> *margin = nullptr);
  // invariant_error if the near fluid left this rank's region of the step (a colloid it could
  // meet may then have been missing here).
  void check_region(const mpcd::Fluid &near) const;

  // The largest radius of all colloids on all ranks (collective the first time; the radii are
  // fixed for a run); c holds this rank's colloids.
  double largest_radius(const Colloids &c);

  // Bytes this rank sent for colloids (migration not included).
  std::uint64_t bytes_sent() const { return exchange_.bytes_sent(); }

private:
  void add(Colloids &c, std::vector<double> *margin, double extent, double largest_margin);

  parallel::Slabs slabs_;
  mpcd::Box box_;
  parallel::Exchange exchange_;
  std::size_t owned_ = 0;
  double r_max_ = -1.0;         // the largest radius of all colloids (fixed for a run)
  double extent_ = 0.0;         // e of the last add (the same on every rank)
  double largest_margin_ = 0.0; // M of the last add
  double more_ = 0.0;           // the widening of the last add
  double reach_columns_ = 0.0;  // the neighbours' reach of the last add
  parallel::CopyList contact_list_;
  std::vector<int> kept_to_, kept_from_; // (drop_widening's scratch)
  std::vector<bool> keep_;
  parallel::Exchange contact_exchange_;
  parallel::CopyList list_; // owned rows and the ranks they were copied to
  parallel::Halo halo_;     // where each ghost row came from
  std::vector<std::int64_t> ghost_values_;
  std::vector<std::vector<double> *> positions_; // the fields refresh_positions() sends
  std::vector<std::vector<double> *> motion_;    // the fields refresh_motion() sends
  std::vector<std::vector<double> *> state_;     // the fields refresh_state() sends
};

} // namespace narrows::colloids

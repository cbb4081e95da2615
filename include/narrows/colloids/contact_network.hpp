// The contact network of the spring contacts (Kanehl (thesis) §4.2.3, fig 6.3): every contact of
// a contact history with its overlap, normal and tangential force and whether it slides, read
// from the colloids' positions and the springs at the end of a step. For observables and
// trajectories: the history holds each contact once (on the rank of its owner colloid), so a
// network made from gathered colloids and a gathered history counts each contact once, in key
// order, the same on any number of ranks.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/colloids/springs.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include <cstdint>
#include <vector>

namespace narrows::colloids {

// A contact counts as sliding when |F_t| >= (1 - sliding_tolerance) mu |F_n|: a spring cut back
// to the Coulomb cap (springs.cpp) has |F_t| = mu |F_n| up to a few roundings (~1e-15).
inline constexpr double sliding_tolerance = 1e-9;

// One row per contact, in the history's key order (owner, partner).
struct ContactNetwork {
  std::vector<std::uint64_t> owner, partner; // ids; partner wall_low_id / wall_high_id: a wall
  std::vector<double> overlap;               // delta_n > 0
  std::vector<double> scale;         // the radius the overlap is measured in: min(r_i, r_j), or r_i
  std::vector<double> normal;        // |F_n| = k_n delta_n
  std::vector<double> tangential;    // |F_t| = k_t |xi|
  std::vector<std::uint8_t> sliding; // |F_t| at the Coulomb cap mu |F_n| (mu finite, k_t > 0)

  std::size_t size() const { return owner.size(); }
  bool is_wall(std::size_t j) const { return is_wall_id(partner[j]); }
};

// The network of history `h` (every contact, key order) among colloids `c` (every colloid, id
// order), the positions as the spring kernel reads them (minimum image along the periodic axes;
// walls at y = 0 and y = L_y when box.walls_y). A contact whose bodies no longer overlap (none
// at the end of a step) is left out. Throws narrows::Error (other) if a contact names a colloid
// c does not hold.
ContactNetwork contact_network(const Colloids &c, const ContactHistory &h, const mpcd::Box &box,
                               const SpringParams &p);

} // namespace narrows::colloids

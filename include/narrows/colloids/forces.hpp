// The forces on colloids and on the fluid near them (Tabatabaei (2008) §3.3-3.4): a sum of separate
// terms, each its own function and file (force_terms.hpp), all accumulated in 64-bit fixed
// point so that the sum is exact and independent of the order of pairs and of ranks:
//   colloid-fluid WCA (force_colloid_fluid.cpp), colloid-colloid 48-24
//   (force_colloid_colloid.cpp), integrated LJ wall (force_wall.cpp), gravity
//   (force_gravity.cpp).
// Contact forces with per-contact history (springs and friction, Kanehl (thesis) §4.2.3) are not a
// term here: they move no-slip colloids in their own sub-steps (springs.hpp), with their history
// as data of its own that travels with the colloid owning the contact (contact_history.hpp);
// event-driven hard-sphere collisions (hard_spheres.hpp) likewise move no-slip colloids.
//
// Parallel model: colloids are owned by slabs (ownership.hpp); the rows of the colloid arrays
// after the owned ones are ghost copies of other ranks' colloids (ghosts.hpp). Each rank adds
// the forces of its own fluid particles on its owned and ghost colloids, and the ghosts'
// shares go back to their owners (reverse, integers: exact); the colloid-colloid, wall and
// gravity terms are added to the owned rows only, so each force is complete on its owner and
// bitwise the same as on one rank.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::colloids {

// Pair ranges follow each colloid's own radius r_a (Colloids::radius): sigma_cf = r_a,
// sigma_cc = r_a + r_b, and sigma_w = 2 r_a unless sigma_wall is set.
struct ForceParams {
  double epsilon = 1.0;
  double sigma_wall = 0.0, wall_q = 1.0; // used when the box has walls along y; sigma_wall 0: 2 r_a
  std::array<double, 3> gravity{0.0, 0.0, 0.0}; // acceleration: the force on colloid a is M_a g
};

// Potential energy of a configuration, split by interaction (summed over the ranks).
struct PotentialEnergy {
  double colloid_fluid = 0.0, colloid_colloid = 0.0, wall = 0.0;
  double total() const { return colloid_fluid + colloid_colloid + wall; }
};

// A linked cell list over the whole box, cells at least `cut` wide along each axis. A rank's
// particles fill only the cells near its slab: clear() empties just the cells filled since the
// last clear, so a rebuild costs O(particles), not O(cells of the box).
struct CellList {
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> inv_cell{1.0, 1.0, 1.0};
  std::vector<std::int32_t> head, next;
  std::vector<std::size_t> filled; // cells whose head is set
  void size_for(const mpcd::Box &box, double cut);
  void clear() {
    for (const std::size_t c : filled)
      head[c] = -1;
    filled.clear();
  }
  void push(std::size_t cell, std::int32_t i) {
    if (head[cell] < 0)
      filled.push_back(cell);
    next[static_cast<std::size_t>(i)] = head[cell];
    head[cell] = i;
  }
};

// Forces of the colloids on local fluid particles: [i * dim + k] in fixed point, set only for
// the particles listed in `touched` (flag 1), zero elsewhere; cleared where set.
struct FluidForces {
  std::vector<std::int64_t> value;
  std::vector<std::uint8_t> flag;
  std::vector<std::uint32_t> touched;
  void clear(int dim);
};

class ColloidGhosts;

class ForceField {
public:
  ForceField(const ForceParams &params, const mpcd::Box &box);

  // Every term at the current positions (collective over comm): afterwards colloid_force() of
  // the owned rows (those before ghosts->owned(); all without ghosts) and fluid_force() hold
  // the forces. With want_energy, also returns the potential energy, summed over comm.
  // comm = MPI_COMM_NULL and no ghosts: this process alone, without MPI (unit tests).
  PotentialEnergy compute(const mpcd::Fluid &fluid, const Colloids &colloids, ColloidGhosts *ghosts,
                          MPI_Comm comm, bool want_energy = false);
  PotentialEnergy compute(const mpcd::Fluid &fluid, const Colloids &colloids, MPI_Comm comm,
                          bool want_energy = false) {
    return compute(fluid, colloids, nullptr, comm, want_energy);
  }

  // Sizes the cell lists for colloids of radius up to r_max (compute() does so from the rows it
  // is given; a rank that may hold no colloid sizes them for the largest of all).
  void size_cells(double r_max);

  // Total force on (owned) colloid i, component k, in fixed point (fixed_point.hpp).
  std::int64_t colloid_force(std::size_t i, int k) const { return colloid_[i * dim_ + k]; }
  // Force of the colloids on local fluid particle i, component k, in fixed point.
  std::int64_t fluid_force(std::size_t i, int k) const {
    return i < fluid_.flag.size() && fluid_.flag[i] ? fluid_.value[i * dim_ + k] : 0;
  }
  const FluidForces &fluid_forces() const { return fluid_; }
  const std::vector<std::int64_t> &colloid_forces() const { return colloid_; }
  // The cell list of the fluid of the last compute().
  const CellList &fluid_cells() const { return fluid_cells_; }
  const ForceParams &params() const { return params_; }

private:
  template <int D, bool WallsY>
  PotentialEnergy compute(const mpcd::Fluid &f, const Colloids &c, ColloidGhosts *ghosts,
                          MPI_Comm comm, bool want_energy);

  ForceParams params_;
  mpcd::Box box_;
  int dim_;
  double cell_radius_ = -1.0;           // the largest colloid radius the cell lists were sized for
  CellList fluid_cells_;                // cells at least the largest WCA cut-off wide
  CellList colloid_cells_;              // cells at least the largest 48-24 cut-off wide
  std::vector<int> colloid_cell_;       // [a * dim + k]: cell coordinate of colloid a
  std::vector<std::uint32_t> partners_; // scratch of the 48-24 term
  FluidForces fluid_;
  std::vector<std::int64_t> colloid_;
};

} // namespace narrows::colloids

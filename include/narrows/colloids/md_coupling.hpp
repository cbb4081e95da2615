// MD coupling of colloids and fluid (seed 000 §3.4.5): over one collision step dt, k sub-steps
// of velocity Verlet with tau_MD = dt / k for the colloids and the fluid. Forces: colloid-fluid
// WCA, colloid-colloid 48-24, integrated LJ wall, gravity on colloids (potentials.hpp).
//
// Only fluid particles that can come within the WCA cut-off of a colloid during the step take
// part in the sub-steps: a particle is left out when its distance to every colloid exceeds
// r_cut + (its largest possible path |v| dt + |a| dt^2/2) + (the colloid's possible path
// |V| dt + |F|/M dt^2 + 0.25: twice the constant-force value, plus an allowance for the fluid's
// kicks within the step). Those far particles stream the whole
// step at once, exactly (body force, bounce-back walls) with the kernel the pipeline chose once;
// the near ones stream with the same kernel between the velocity-Verlet kicks. After the step
// every colloid's displacement is checked against its assumed path (invariant_error if it went
// further, which would mean a missed pair). Colloid-fluid pairs come from a cell list (cells
// at least the largest WCA cut-off wide, over the whole box): of all local fluid once per step,
// of the near particles every sub-step. Colloid-colloid pairs come from a cell list of the
// colloids (cells at least the largest 48-24 cut-off wide), so many colloids cost O(N).
//
// Parallel model: every rank holds all colloids (they are few: at most a few thousand, and
// each carries d + d + ... words). Each rank adds the forces of its own fluid particles on
// every colloid in 64-bit fixed point; one MPI_Allreduce of those integers gives every rank the
// exact, order-independent total, and every rank integrates every colloid identically. So no
// colloid migrates or needs halo copies, and a run is bitwise the same on any number of ranks.
// Pair forces are rounded to fixed point once and added with opposite signs to both partners,
// so Newton's third law holds exactly.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/mpcd/fluid.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace narrows::colloids {

// Pair ranges follow each colloid's own radius r_a (Colloids::radius): sigma_cf = r_a,
// sigma_cc = r_a + r_b, and sigma_w = 2 r_a unless sigma_wall is set.
struct MdParams {
  double tau = 0.1 / 15; // MD time step
  int substeps = 15;
  double epsilon = 1.0;
  double sigma_wall = 0.0, wall_q = 1.0; // used when the box has walls along y; sigma_wall 0: 2 r_a
  std::array<double, 3> gravity{0.0, 0.0, 0.0}; // acceleration: the force on colloid a is M_a g
  double fluid_accel = 0.0; // largest body-force acceleration of a fluid particle
};

// Streams the fluid by tau (walls and body force exact); chosen once by the pipeline.
using FluidDrift = std::function<void(mpcd::Fluid &, double tau)>;

// Potential energy of a configuration, split by interaction (summed over the ranks).
struct PotentialEnergy {
  double colloid_fluid = 0.0, colloid_colloid = 0.0, wall = 0.0;
  double total() const { return colloid_fluid + colloid_colloid + wall; }
};

class MdCoupling {
public:
  MdCoupling(const MdParams &params, const mpcd::Box &box, FluidDrift drift);

  // One collision step: `substeps` velocity-Verlet steps of fluid and colloids (collective).
  void advance(mpcd::Fluid &fluid, Colloids &colloids, MPI_Comm comm);

  // Forces at the current positions (collective): afterwards colloid_force() and fluid_force()
  // hold them. With want_energy, also returns the potential energy. comm = MPI_COMM_NULL: this
  // process alone, without MPI (unit tests).
  PotentialEnergy compute_forces(const mpcd::Fluid &fluid, const Colloids &colloids, MPI_Comm comm,
                                 bool want_energy = false);

  // Total force on colloid i, component k, in fixed point (fixed_point.hpp).
  std::int64_t colloid_force(std::size_t i, int k) const { return colloid_force_[i * dim_ + k]; }
  // Force of the colloids on local fluid particle i, component k, in fixed point.
  std::int64_t fluid_force(std::size_t i, int k) const {
    return i < fluid_flag_.size() && fluid_flag_[i] ? fluid_force_[i * dim_ + k] : 0;
  }
  const MdParams &params() const { return params_; }

private:
  template <int D, bool WallsY>
  PotentialEnergy forces(const mpcd::Fluid &f, const Colloids &c, MPI_Comm comm, bool want_energy);
  void kick(mpcd::Fluid &fluid, Colloids &colloids) const;
  void clear_fluid_forces();
  template <int D, bool WallsY>
  void colloid_pairs(const Colloids &c, PotentialEnergy &energy, bool want_energy);
  template <int D, bool WallsY> void select_near(const mpcd::Fluid &f, const Colloids &c);
  void build_cell_list(const mpcd::Fluid &f);
  void size_cells(const Colloids &c);

  MdParams params_;
  mpcd::Box box_;
  int dim_;
  FluidDrift drift_;
  double cell_radius_ = -1.0;         // the largest colloid radius the cells were sized for
  std::array<int, 3> cells_{1, 1, 1}; // cell list cells per axis
  std::array<double, 3> inv_cell_{1.0, 1.0, 1.0};
  std::vector<std::int32_t> head_, next_;
  std::array<int, 3> cc_cells_{1, 1, 1}; // colloid cell list: cells per axis
  std::array<double, 3> cc_inv_cell_{1.0, 1.0, 1.0};
  std::vector<std::int32_t> cc_head_, cc_next_;
  std::vector<int> cc_cell_;               // [a * dim + k]: cell coordinate of colloid a
  std::vector<std::uint32_t> cc_partners_; // partners b > a of the colloid at hand
  std::vector<std::int64_t> fluid_force_;  // [i * dim + k], zero unless flagged
  std::vector<std::uint8_t> fluid_flag_;   // 1 if fluid particle i has a force
  std::vector<std::uint32_t> touched_;     // the flagged particles
  std::vector<std::int64_t> colloid_force_, colloid_local_;
  std::vector<double> margin_;            // per colloid: its largest possible path this step
  std::vector<std::uint32_t> near_index_; // local fluid particles taking part in the sub-steps
  std::vector<std::uint8_t> near_flag_;
  mpcd::Fluid near_;                         // their copy during the sub-steps
  std::array<std::vector<double>, 3> start_; // colloid positions at the start of the step
};

} // namespace narrows::colloids

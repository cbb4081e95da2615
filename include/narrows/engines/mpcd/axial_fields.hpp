// The MPCD observable axial_fields (Kanehl (thesis) eq 6.1): in bins of width output.axial_bin
// along x, the colloid area fraction phi(x) (3D: volume fraction) and colloid velocity v(x) from
// the power (Voronoi) cells of the colloids (analysis/axial_fields.hpp), and the fluid's mean
// x-velocity. Written to /observables/axial_fields/{phi, velocity, fluid_velocity} [T][bins], bins
// (x centres), step, time. Each colloid's own fraction phi_i can go with the trajectory frames
// (/particles/colloids/voronoi_fraction).
//
// Bitwise the same on any number of ranks: the colloid fields are computed from all colloids
// gathered in id order (the same input, the same arithmetic, on every rank), and the fluid's
// sums are exact 64-bit fixed-point numbers added as 128-bit integers.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <mpi.h>

#include <cstddef>
#include <string_view>
#include <vector>

namespace narrows::mpcd {

// The name of the per-colloid field in trajectory frames.
inline constexpr std::string_view voronoi_fraction_field = "voronoi_fraction";

struct AxialSample {
  std::vector<double> phi, velocity, fluid_velocity; // [bins]; fluid_velocity on rank 0 only
  std::vector<double> local_fraction;                // phi_i per colloid, in the given order
};

class AxialFields {
public:
  // A box whose x length is a whole number of bins of width `bin` (the scene checks both);
  // throws narrows::Error otherwise.
  AxialFields(const Box &box, double bin);
  std::size_t bins() const { return bins_; }
  const std::vector<double> &centres() const { return centres_; }

  // The colloid fields of `all` (every colloid: MpcdSimulation::gather_colloids).
  AxialSample colloid_fields(const colloids::Colloids &all) const;
  // Collective: the colloid fields and the fluid's mean x-velocity per bin (its particles of
  // every rank; NaN in a bin without any).
  AxialSample sample(const colloids::Colloids &all, const Fluid &fluid, MPI_Comm comm) const;
  // Adds the trajectory field voronoi_fraction, phi_i, to `all` (fresh from gather_colloids,
  // without it).
  void add_local_fraction(colloids::Colloids &all) const;

private:
  Box box_;
  std::size_t bins_ = 0;
  std::vector<double> centres_;
};

} // namespace narrows::mpcd

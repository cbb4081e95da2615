// Observables of the FHP lattice: mass, the shear-wave amplitude, block-averaged fields. All
// sums are integers reduced over ranks, so the numbers are the same on any rank count.
#pragma once

#include "narrows/engines/lgca/fhp_lattice.hpp"

#include <cstdint>
#include <vector>

namespace narrows::lgca {

// Particles on the whole lattice (collective).
std::int64_t total_mass(const FhpLattice &lattice);

// Twice the x momentum summed over the whole lattice (collective): an integer, since
// c_x is a multiple of 1/2.
std::int64_t total_momentum_x2(const FhpLattice &lattice);

// Amplitude A of the mode u_x = A sin(2 pi y / L_y) (y = row sqrt(3)/2, L_y = size_y
// sqrt(3)/2): A = 2 sum_sites j_x sin(2 pi row / size_y) / (sites rho), rho the mean number
// of particles per site (collective; the same value on every rank).
double shear_wave_amplitude(const FhpLattice &lattice);

// Density and velocity averaged over square blocks of `block` sites and over the steps added
// since the last finish().
class FieldAccumulator {
public:
  FieldAccumulator(const FhpLattice &lattice, int block);
  void add(const FhpLattice &lattice);
  // Rank 0 gets density [by][bx] (particles per site) and velocity [by][bx][2] (momentum /
  // mass of the block); other ranks get empty vectors. Returns false when nothing was added.
  bool finish(MPI_Comm comm, std::vector<double> &density, std::vector<double> &velocity);
  int blocks_x() const { return bx_; }
  int blocks_y() const { return by_; }
  int block() const { return block_; }

private:
  int block_ = 1, bx_ = 0, by_ = 0;
  std::int64_t samples_ = 0;
  std::vector<std::int64_t> mass_, jx2_, jy2_; // [by][bx]; momentum in units of 1/2, sqrt3/2
};

} // namespace narrows::lgca

// Moment propagation (van der Hoef & Frenkel eq 11, 13, 14) on the MPI slabs of an FhpLattice: the
// tagged-particle VACF of all particles as starting points, over successive time origins.
//
// Pull form of eq 11: the weight a(r) that arrives at site r is the sum over links i of
// q(r - c_i) s_i(r - c_i), with q = a / rho at the source after its collision (the tagged
// weight split equally over the outgoing particles, the rule for which eq 19 is exact). Sources
// are nearest neighbours, so one halo column of occupations and of q per side is all a slab
// needs. Every site's arithmetic is the same on any number of ranks, and the sum of eq 14 is
// taken per global column and then over columns in order on rank 0: the VACF is bitwise the
// same on any number of ranks.
#pragma once

#include "narrows/engines/lgca/fhp_lattice.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::lgca {

class FhpTagged {
public:
  FhpTagged(const FhpLattice &lattice, int max_lag);

  // Feed the post-collision state of every step in order (the first call, and the call that
  // completes a curve, start a new time origin there). Collective over the lattice's ranks.
  void feed(const FhpLattice &lattice);

  int max_lag() const { return max_lag_; }
  int curves() const { return curves_; }
  // Rank 0: mean over completed curves of the normalised VACF Z(t) = C(t) / C(0) of each curve
  // and its standard error from the spread of the curves (each curve is one time origin);
  // empty on other ranks or before the first curve is complete.
  std::vector<double> mean() const;
  std::vector<double> error() const;
  // Rank 0: mean particle number of the origins (for eq 22).
  double particles() const { return curves_ > 0 ? particle_sum_ / curves_ : 0.0; }

private:
  std::size_t at(int x_local, int y) const {
    return static_cast<std::size_t>(y) * stride_ + 1 + static_cast<std::size_t>(x_local);
  }
  void load(const FhpLattice &lattice);
  void start();
  double correlation() const;

  const parallel::Slabs &slabs_;
  int links_, nx_, ny_, max_lag_;
  std::size_t stride_;
  std::vector<std::uint8_t> occ_;            // post-collision states with halo columns
  std::vector<std::array<double, 2>> a_, q_; // arrived weight; a / rho with halo columns
  std::array<double, 128> ux_{}, uy_{};      // u(s) = sum_i s_i c_i / rho(s)
  std::vector<double> current_, sum_, sum2_;
  double particles_ = 0.0, particle_sum_ = 0.0;
  int lag_ = -1, curves_ = 0, rank_ = 0;
  std::vector<int> counts_, displs_; // columns per rank, for the gather of column sums
};

} // namespace narrows::lgca

// The terms of the colloid forces (forces.hpp), one file each: plain loops over the arrays,
// templated on the dimension D and on walls along y, adding fixed-point forces.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/forces.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <cstdint>
#include <vector>

// Instantiates M(D, WallsY) for the four kernels a pair term is compiled for.
#define NARROWS_FOR_EACH_DIM_AND_WALLS(M) M(2, false) M(2, true) M(3, false) M(3, true)

namespace narrows::colloids {

// Colloid-fluid WCA, phi with n = 6 and sigma_cf = r_a (Tabatabaei (2008) eq 3.42), over the pairs
// the cell list `cells` of the fluid (already built) gives: adds to `on_fluid` and `on_colloids`
// ([a * D + k]). Returns the energy (0 unless want_energy), summed in a fixed loop order.
template <int D, bool WallsY>
double add_colloid_fluid_wca(const CellList &cells, const mpcd::Fluid &f, const Colloids &c,
                             const mpcd::Box &box, double eps, bool want_energy,
                             FluidForces &on_fluid, std::vector<std::int64_t> &on_colloids);

// Colloid-colloid 48-24, n = 24 and sigma_cc = r_a + r_b (Tabatabaei (2008) eq 3.43), from a cell
// list of the colloids (`cells` sized, rebuilt here; `cell_of` and `partners` scratch). Forces go
// to the first `owned` rows only (the rest are ghost copies: ghosts.hpp). The energy is summed
// over the partners b > a of each a in increasing b, the order of a double loop.
template <int D, bool WallsY>
double add_colloid_colloid_4824(CellList &cells, std::vector<int> &cell_of,
                                std::vector<std::uint32_t> &partners, const Colloids &c,
                                std::size_t owned, const mpcd::Box &box, double eps,
                                bool want_energy, std::vector<std::int64_t> &on_colloids);

// Integrated LJ walls at y = 0 and y = L_y (Tabatabaei (2008) eq 3.35-3.37), sigma_w = sigma_wall
// or 2 r_a, on the first `owned` rows; invariant_error for a colloid outside the channel. Returns
// the energy.
template <int D>
double add_wall_lj(const Colloids &c, std::size_t owned, const mpcd::Box &box, double eps,
                   double sigma_wall, double wall_q, std::vector<std::int64_t> &on_colloids);

// Gravity: the force M_a g on the first `owned` rows (the field g of Tabatabaei (2008) eq 4.4).
template <int D>
void add_gravity(const Colloids &c, std::size_t owned, const std::array<double, 3> &g,
                 std::vector<std::int64_t> &on_colloids);

} // namespace narrows::colloids

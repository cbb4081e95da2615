// Fields along the channel (Kanehl (thesis) eq 6.1): the colloid area fraction phi(x) (3D:
// volume fraction) and the colloid velocity v(x), averaged over the cross-section in bins along x,
// from the power (Voronoi) cells of the colloids (power_diagram.hpp).
//
// The local fraction of colloid i is phi_i = V_i / A_i, its area V_i = pi r_i^2 over the area A_i
// of its power cell, and phi(x, y) = phi_i on cell i is the field eq 6.1 averages over y. In a
// bin b of area A_b (width times channel width) the average is the area-weighted mean of phi_i
// over the parts A_ib of the cells lying in the bin:
//   phi_b = sum_i phi_i A_ib / A_b,
// the cross-section average of eq 6.1 integrated over the bin. As the cells tile the channel,
// sum_b phi_b A_b = sum_i phi_i A_i = sum_i V_i: the mean of phi over the channel is exactly
// the colloids' area over the channel's (rather than the disk area lying in a bin, which would
// not be the Voronoi fraction of the thesis and jumps as disks cross bin edges).
// The velocity is the colloid velocity field weighted by colloid material, the same weights:
//   v_b = sum_i phi_i A_ib u_i / sum_i phi_i A_ib,
// so sum_b phi_b v_b A_b = sum_i V_i u_i: the channel average of phi v is the colloids' total
// x-momentum over the channel area times the material density.
#pragma once

#include "narrows/analysis/power_diagram.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace narrows::analysis {

struct ColloidAxialFields {
  std::vector<double> phi, velocity;  // [bins]: phi_b, v_b (NaN where no colloid material)
  std::vector<double> local_fraction; // phi_i per colloid (NaN for a hidden one: no cell)
  PowerCells cells;                   // the clipped power cells
};

// n colloids (centres x, y in the box, radii r, x-velocities u) in the 2D box [0, length[0]) x
// [0, length[1]) (periodic along x; along y periodic if periodic_y, else walls), `bins` equal
// bins along x. Deterministic: sums run over the colloids in the order given.
ColloidAxialFields colloid_axial_fields(std::span<const double> x, std::span<const double> y,
                                        std::span<const double> r, std::span<const double> u,
                                        const Point2 &length, bool periodic_y, std::size_t bins);

// The same in 3D: balls (volume 4/3 pi r^3) in the box [0, length[k]), periodic along x and z
// (and y if periodic_y), power cells as polyhedra; phi is the volume fraction, bins are slabs.
struct ColloidAxialFields3 {
  std::vector<double> phi, velocity, local_fraction;
  PowerCells3 cells;
};
ColloidAxialFields3 colloid_axial_fields_3d(std::span<const double> x, std::span<const double> y,
                                            std::span<const double> z, std::span<const double> r,
                                            std::span<const double> u, const Point3 &length,
                                            bool periodic_y, std::size_t bins);

// The number of bins of width `bin` along a length, or 0 if the length is not a whole number
// of them (to a relative 1e-9).
std::size_t axial_bin_count(double length, double bin);

} // namespace narrows::analysis

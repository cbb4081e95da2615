// A colloid's path over one MPCD step: the ballistic move both couplings use, and the check that
// no owned colloid went further than the margin its ghosts and near fluid were chosen for.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace narrows::colloids {

// x += v t for rows [0, rows) of c, wrapped along the periodic axes.
void move_ballistic(Colloids &c, std::size_t rows, const mpcd::Box &box, double t);

// invariant_error if an owned row a (a < owned) is further than margin[a] + slack from start
// (minimum image): "colloid id I moved D in one step, more than the M <allowed>".
void check_paths(const Colloids &c, std::size_t owned,
                 const std::array<std::vector<double>, 3> &start, const std::vector<double> &margin,
                 const mpcd::Box &box, double slack, const char *allowed);
// The same for rows [from, to) (ghost rows: the message names the copy).
void check_paths(const Colloids &c, std::size_t from, std::size_t to,
                 const std::array<std::vector<double>, 3> &start, const std::vector<double> &margin,
                 const mpcd::Box &box, double slack, const char *allowed);

} // namespace narrows::colloids

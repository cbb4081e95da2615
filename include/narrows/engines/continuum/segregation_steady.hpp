// The steady state of the segregation model (Kanehl (thesis) eq 5.30 with d phi / dt = 0): with
// walls that let no colloid through, every current vanishes, J_i = -(M phi' + b)_i = 0, a
// first-order ODE system phi' = -M^-1 b across the channel (Eigen's LU per step). The profile is
// even in y; it is integrated from the centre to the wall by RK4 with the centre values phi_i(0)
// found by Newton's method so that each kind's mean over the channel is its fraction.
#pragma once

#include "narrows/engines/continuum/segregation_model.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace narrows::continuum {

struct SteadyProfile {
  bool ok = false;
  std::string failure;      // why not, when !ok
  std::size_t kinds = 0;    // n
  double step = 0.0;        // dy of the RK4 grid y_k = k dy, k = 0..steps, on [0, w]
  std::vector<double> phi;  // [steps + 1][n]
  std::vector<double> dphi; // phi' at the same points (y = 0: the limit y -> 0+)
  int iterations = 0;       // Newton steps
  double mass_error = 0.0;  // largest |mean phi_i - fraction_i| at the end
};

// `steps` RK4 steps from the centre to the wall.
SteadyProfile steady_profile(const SegregationModel &model, std::size_t steps);

// phi_i at each y of `ys` in [-w, w] (cubic Hermite between the grid points; row-major
// [ys.size()][n]).
std::vector<double> steady_at(const SteadyProfile &p, const std::vector<double> &ys);

} // namespace narrows::continuum

// Viscosity from a Poiseuille profile (Tabatabaei (2008) eq 3.15, Kanehl (thesis) eq 4.48-4.49):
// walls at y = 0 and y = L, force g along x, steady v_x(y) = g y (L - y) / (2 nu).
#pragma once

#include <vector>

namespace narrows::analysis {

struct PoiseuilleFit {
  double nu = 0.0;            // g / (2 a) for the fitted curvature a
  double wall_velocity = 0;   // fitted v_x at y = 0 and y = L (slip; zero for a no-slip wall)
  double centre_velocity = 0; // fitted v_x at y = L/2
};

// Least-squares fit of v = a q(y) + b to bin averages of v_x, where q is the average of
// y (L - y) over the bin [c - w/2, c + w/2] (= c (L - c) - w^2/12), so bin averaging does
// not bias a. `velocity` holds `dim` components per bin (x first).
PoiseuilleFit fit_poiseuille(const std::vector<double> &centres,
                             const std::vector<double> &velocity, int dim, double bin_width,
                             double L, double g);

} // namespace narrows::analysis

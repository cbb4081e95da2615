// The segregation model's coefficients as curves of the total fraction phi at the scene's
// composition (observable collective_diffusivity): the collective diffusivity of Kanehl (thesis)
// eq 5.23-5.28 (fig 5.3 draws its diagonal in 2D at c_L = c_S, a_L / a_S = 2), the structure
// factor S of eq 5.19-5.22 and the viscosity of eq 5.29. Along the curve each kind keeps its share
// of the scene's total fraction: phi_i = phi f_i with f_i = fraction_i / sum_k fraction_k.
#pragma once

#include "narrows/engines/continuum/segregation_model.hpp"

#include <cstddef>
#include <vector>

namespace narrows::continuum {

// Points of the curves: phi = k phi_M / points, k = 0 .. points - 1 (0 to just below phi_M).
inline constexpr std::size_t segregation_curve_points = 200;

struct SegregationCurves {
  std::vector<double> phi;         // [points] the total fraction
  std::vector<double> value;       // [points][kinds][kinds] D_C^ij / (K_d D_0^i)
  std::vector<double> structure;   // [points] S(phi)
  std::vector<double> viscosity;   // [points] eta / eta_0 (eq 5.29)
  std::vector<double> composition; // [kinds] f_i
  std::vector<double> scale;       // [kinds] K_d D_0^i: D_C^ij = value [ij] scale [i]
};

SegregationCurves segregation_curves(const SegregationModel &model,
                                     std::size_t points = segregation_curve_points);

} // namespace narrows::continuum
